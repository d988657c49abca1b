// Every example with reference checks passes them as shipped (the regression rerun of Uintah's
// habit, DESIGN.md). The throughput examples (bench-*) have no checks and are skipped.
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <filesystem>

namespace {

using namespace matpoint;
using namespace matpoint::test;

TEST(Examples, EveryExamplePassesItsChecks) {
  int checked = 0;
  for (const auto& entry : std::filesystem::directory_iterator(MATPOINT_EXAMPLES_DIR)) {
    const std::string name = entry.path().filename().string();
    if (!std::filesystem::exists(entry.path() / "input.json") || name.rfind("bench-", 0) == 0) continue;
    SCOPED_TRACE(name);
    const Spec spec = load_example(name);
    if (spec.checks.empty()) continue;
    const auto result = run_quietly(spec, "example_" + name);
    ASSERT_EQ(result.exit_code, 0) << result.message;
    for (const auto& check : result.summary["checks"]) EXPECT_TRUE(check["pass"].get<bool>()) << check.dump();
    ++checked;
  }
  EXPECT_GE(checked, 6);
}

}  // namespace
