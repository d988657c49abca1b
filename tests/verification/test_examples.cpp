// Every example with reference checks passes them as shipped (the regression rerun of Uintah's
// habit, DESIGN.md). The throughput examples (bench-*) have no checks and are skipped, and so are
// the examples whose checked run takes minutes: scripts/verification_table.py runs those
// (docs/verification.md), and the default suite runs a scaled-down version of each.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <string_view>

#include "test_support.hpp"

namespace {

using namespace matpoint;
using namespace matpoint::test;

// 3.5 s of Aulisa & Capodaglio's Test D: about 4 minutes on 2 cores (scaled down in
// tests/verification/test_fe_coupling.cpp). The other two run as shipped in their own tests, which
// check what their inputs check (about 200 s and 70 s of the suite each; not twice):
// ImplicitCantilever.TestBFreeVibrationAtJ2 and ImplicitRollingDisk.TestATable1SoftDiskJ1AndJ2 (J = 1).
constexpr std::array<std::string_view, 3> kLongExamples{"bouncing-disk", "implicit-cantilever",
                                                        "implicit-rolling-disk"};

TEST(Examples, EveryExamplePassesItsChecks) {
  int checked = 0;
  for (const auto& entry : std::filesystem::directory_iterator(MATPOINT_EXAMPLES_DIR)) {
    const std::string name = entry.path().filename().string();
    if (!std::filesystem::exists(entry.path() / "input.json") || name.rfind("bench-", 0) == 0 ||
        std::find(kLongExamples.begin(), kLongExamples.end(), name) != kLongExamples.end())
      continue;
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
