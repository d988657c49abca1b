// The granular (c = 0) column beside the cohesive one (examples/soil-column-collapse/granular.json):
// its checks as shipped (mass conserved, at rest at 3 s, run-out and height within 5 % of the
// h/2 run). test_examples.cpp runs every example's input.json; this input is the second one of
// its folder.
#include <gtest/gtest.h>

#include "test_support.hpp"

namespace {

using namespace matpoint;
using namespace matpoint::test;

TEST(SoilColumns, GranularColumnPassesItsChecks) {
  const Spec spec = load_example("soil-column-collapse", "granular.json");
  const auto result = run_quietly(spec, "granular_column");
  ASSERT_EQ(result.exit_code, 0) << result.message;
  ASSERT_EQ(result.summary["checks"].size(), spec.checks.size());
  for (const auto& check : result.summary["checks"]) EXPECT_TRUE(check["pass"].get<bool>()) << check.dump();
}

}  // namespace
