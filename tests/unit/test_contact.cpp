// Multimaterial contact (Nairn 2026 §3.2; docs/theory/contact.md).
// 1. The lumped laws of eq. (18) on hand-made node states (exact arithmetic).
// 2. Issue 5 verification item 1: stick contact between two bodies reproduces the single-field
//    run step by step. Nairn proves the reversion exact for lumped contact and for both FMPM
//    increment methods (§3.2: "Both methods revert exactly to single-material mode with stick
//    contact"), so the bound is round-off: 1e-10 relative to the largest grid speed.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "matpoint/analysis/grid_modes.hpp"
#include "matpoint/core/errors.hpp"
#include "matpoint/explicit/explicit_step.hpp"
#include "matpoint/io/input.hpp"
#include "matpoint/shape/cpdi_stencils.hpp"
#include "matpoint/shape/tensor_bases.hpp"
#include "matpoint/shape/tensor_stencils.hpp"

namespace {

using namespace matpoint;

// --- the laws ---

TEST(ContactLaw, StickAppliesTheWholeChangeEvenWhenSeparating) {
  const ContactLawSpec stick{ContactLaw::Stick, 0.0};
  const Vec<2> dp0(0.3, 0.5), n(0.0, 1.0);  // dp0 . n > 0: separating
  EXPECT_EQ(contact_momentum_change<2>(stick, dp0, n), dp0);
}

TEST(ContactLaw, SeparatingFieldsGetNothing) {
  for (auto law : {ContactLaw::Frictionless, ContactLaw::Coulomb})
    EXPECT_EQ(contact_momentum_change<2>({law, 0.5}, Vec<2>(0.3, 0.5), Vec<2>(0.0, 1.0)), Vec<2>::Zero());
}

TEST(ContactLaw, FrictionlessKeepsOnlyTheNormalPart) {
  const Vec<2> dp =
      contact_momentum_change<2>({ContactLaw::Frictionless, 0.0}, Vec<2>(0.3, -0.5), Vec<2>(0, 1));
  EXPECT_DOUBLE_EQ(dp[0], 0.0);
  EXPECT_DOUBLE_EQ(dp[1], -0.5);
}

TEST(ContactLaw, CoulombSticksBelowAndSlidesAboveMuTimesTheNormalChange) {
  const Vec<2> n(0.0, 1.0);
  // |dp0_t| = 0.3 <= mu |dp0_n| = 0.8 * 0.5: stick, the whole change
  EXPECT_EQ(contact_momentum_change<2>({ContactLaw::Coulomb, 0.8}, Vec<2>(0.3, -0.5), n), Vec<2>(0.3, -0.5));
  // |dp0_t| = 0.3 > 0.2 * 0.5 = 0.1: slide, tangential part mu |dp0_n| along dp0_t
  const Vec<2> slide = contact_momentum_change<2>({ContactLaw::Coulomb, 0.2}, Vec<2>(-0.3, -0.5), n);
  EXPECT_NEAR(slide[0], -0.1, 1e-15);
  EXPECT_NEAR(slide[1], -0.5, 1e-15);
}

// --- stick reproduces the single-field run ---

/// Two touching blocks of one material driven into each other on a slip floor with gravity; the
/// contact object is spliced in by the test.
std::string two_blocks(const std::string& solver, const std::string& contact) {
  return R"({
    "grid": { "dim": 2, "min": [0, 0], "max": [1, 0.5], "cell_size": 0.05 },
    "materials": [ { "name": "m", "model": "neo_hookean", "density": 1000, "E": 1e5, "nu": 0.3 } ],
    "bodies": [
      { "name": "a", "material": "m", "shape": { "type": "box", "min": [0.1, 0], "max": [0.5, 0.2] },
        "velocity": [1, 0.2] },
      { "name": "b", "material": "m", "shape": { "type": "disk", "center": [0.65, 0.2], "radius": 0.15 },
        "velocity": [-1, 0] } ],
    "boundary_conditions": [ { "face": "y-", "type": "slip" } ],
    "loads": { "gravity": [0, -10] },
    "solver": )" +
         solver + R"(,
    "output": { "particles": false, "plots": false })" +
         contact + "}";
}

template <class Stencils>
double worst_grid_velocity_difference(const std::string& solver, const std::string& contact, int steps) {
  Simulation<2> single = build_simulation<2>(parse_spec(two_blocks(solver, "")));
  Simulation<2> multi = build_simulation<2>(parse_spec(two_blocks(solver, ",\n\"contact\": " + contact)));
  EXPECT_TRUE(multi.has_contact);
  const double dt = stable_time_step(single);
  ExplicitStepper<2, Stencils> one(single);
  ExplicitStepper<2, FieldStencils<2, Stencils>> two(multi);
  const Index n = single.grid.node_count;
  double worst = 0.0;
  long shared = 0;
  for (int s = 0; s < steps; ++s) {
    one.step(dt);
    two.step(dt);
    double scale = 0.0;
    for (Index i = 0; i < n; ++i) scale = std::max(scale, single.fields.velocity_new[i].norm());
    for (Index i = 0; i < n; ++i) {
      int present = 0;
      for (int f = 0; f < 2; ++f) {
        const Index k = f * n + i;
        if (!(multi.fields.mass[k] > multi.mass_floor)) continue;
        ++present;
        worst =
            std::max(worst, (multi.fields.velocity_new[k] - single.fields.velocity_new[i]).norm() / scale);
      }
      if (present == 2) ++shared;
    }
  }
  EXPECT_GT(shared, steps);  // the bodies do share nodes: contact was exercised
  for (std::size_t p = 0; p < single.particles.size(); ++p)
    EXPECT_NEAR((single.particles.x[p] - multi.particles.x[p]).norm(), 0.0, 1e-12) << "particle " << p;
  return worst;
}

using Linear = TensorStencils<2, LinearBasis>;
using Cpdi = CpdiStencils<2, HatKernel, CpdiDomain::Parallelogram>;
constexpr int kSteps = 60;

TEST(StickContact, FlipReproducesTheSingleFieldRunStepByStep) {
  const std::string solver = R"({ "scheme": "usl", "transfer": "flip", "courant": 0.3, "end_time": 1 })";
  EXPECT_LT(worst_grid_velocity_difference<Linear>(solver, R"({ "law": "stick" })", kSteps), 1e-10);
}

TEST(StickContact, MuslFlipReproducesTheSingleFieldRun) {
  const std::string solver = R"({ "scheme": "musl", "transfer": "flip", "courant": 0.3, "end_time": 1 })";
  EXPECT_LT(worst_grid_velocity_difference<Linear>(solver, R"({ "law": "stick" })", kSteps), 1e-10);
}

TEST(StickContact, FmpmNetReproducesTheSingleFieldRunStepByStep) {
  for (int k : {2, 4, 8}) {
    const std::string solver = R"({ "scheme": "usl", "transfer": "fmpm", "fmpm": { "order": )" +
                               std::to_string(k) + R"( }, "basis": "cpdi1", "courant": 0.2, "end_time": 1 })";
    EXPECT_LT(
        worst_grid_velocity_difference<Cpdi>(solver, R"({ "law": "stick", "fmpm_method": "net" })", kSteps),
        1e-10)
        << "FMPM(" << k << ")";
  }
}

TEST(StickContact, FmpmEvolvingAlsoReproducesTheSingleFieldRun) {
  const std::string solver =
      R"({ "scheme": "usl", "transfer": "fmpm", "fmpm": { "order": 4 }, "basis": "cpdi1", "courant": 0.2, "end_time": 1 })";
  EXPECT_LT(worst_grid_velocity_difference<Cpdi>(solver, R"({ "law": "stick", "fmpm_method": "evolving" })",
                                                 kSteps),
            1e-10);
}

// --- logistic-regression normals: the gap test of the deformed particle extents ---

/// Largest change of any particle velocity after `steps` steps of two blocks that approach at
/// +/-1 m/s with a gap of half a cell between their particle domains (they share the nodes on
/// x = 0.5 from the start, but their domains meet only at t = 0.0125 s, about 9 steps).
double largest_velocity_change_before_touching(const std::string& normals, int steps) {
  const std::string input = R"({
    "grid": { "dim": 2, "min": [0, 0], "max": [1, 0.5], "cell_size": 0.05 },
    "materials": [ { "name": "m", "model": "neo_hookean", "density": 1000, "E": 1e5, "nu": 0.3 } ],
    "bodies": [
      { "name": "a", "material": "m", "shape": { "type": "box", "min": [0.1, 0.1], "max": [0.5, 0.3] },
        "velocity": [1, 0] },
      { "name": "b", "material": "m", "shape": { "type": "box", "min": [0.525, 0.1], "max": [0.9, 0.3] },
        "velocity": [-1, 0] } ],
    "solver": { "scheme": "usl", "transfer": "flip", "courant": 0.3, "end_time": 1 },
    "output": { "particles": false, "plots": false },
    "contact": { "law": "frictionless", "normals": ")" +
                            normals + R"(" } })";
  Simulation<2> sim = build_simulation<2>(parse_spec(input));
  const auto initial = sim.particles.v;
  const double dt = stable_time_step(sim);
  EXPECT_LT(steps * dt, 0.0125);  // still apart at the end
  ExplicitStepper<2, FieldStencils<2, Linear>> stepper(sim);
  for (int s = 0; s < steps; ++s) stepper.step(dt);
  double largest = 0.0;
  for (std::size_t p = 0; p < initial.size(); ++p)
    largest = std::max(largest, (sim.particles.v[p] - initial[p]).norm());
  return largest;
}

TEST(LogisticContact, BodiesWithAGapBetweenTheirDomainsDoNotTouch) {
  // Nairn 2026 §3.2 step 4: contact needs N_c > 0 and delta_n < 0. Approaching alone (the
  // "average" normal's test) already applies contact on the shared nodes; the regression gap
  // delta_n = 0.5 cell - 2 v t > 0 keeps the rigidly translating blocks untouched: no stress, so
  // every particle velocity stays exactly the initial one.
  EXPECT_EQ(largest_velocity_change_before_touching("logistic_regression", 6), 0.0);
  EXPECT_GT(largest_velocity_change_before_touching("average", 6), 0.1);
}

// --- input errors name the JSON path (exit 2 before any work) ---

/// The paths of the issues parse_spec reports for the two-block input with `contact`.
std::vector<std::string> contact_issue_paths(const std::string& contact,
                                             const std::string& solver = R"({ "end_time": 1 })") {
  try {
    (void)parse_spec(two_blocks(solver, ",\n\"contact\": " + contact));
  } catch (const InputError& e) {
    std::vector<std::string> paths;
    for (const auto& issue : e.issues()) paths.push_back(issue.path);
    return paths;
  }
  return {};
}

TEST(ContactInput, NamesThePathOfEachMistake) {
  using Paths = std::vector<std::string>;
  EXPECT_EQ(contact_issue_paths(R"({ "law": "glue" })"), Paths{"contact.law"});
  EXPECT_EQ(contact_issue_paths(R"({ "law": "coulomb", "friction": -0.1 })"), Paths{"contact.friction"});
  EXPECT_EQ(contact_issue_paths(R"({ "law": "coulomb" })"), Paths{"contact.friction"});
  EXPECT_EQ(contact_issue_paths(R"({ "law": "stick", "friction": 0.3 })"), Paths{"contact.friction"});
  EXPECT_EQ(contact_issue_paths(R"({ "normals": "logistic" })"), Paths{"contact.normals"});
  EXPECT_EQ(contact_issue_paths(R"({ "pairs": [ { "between": ["a", "zz"] } ] })"),
            Paths{"contact.pairs[0].between[1]"});
  EXPECT_EQ(contact_issue_paths(R"({ "pairs": [ { "between": ["a", "a"] } ] })"),
            Paths{"contact.pairs[0].between"});
  EXPECT_EQ(contact_issue_paths(R"({})", R"({ "transfer": "xpic", "end_time": 1 })"), Paths{"contact"});
  EXPECT_EQ(contact_issue_paths(R"({})", R"({ "basis": "cpdi2", "end_time": 1 })"), Paths{"contact"});
  // one field: two bodies of one material grouped by material
  EXPECT_EQ(contact_issue_paths(R"({ "fields": "materials" })"), Paths{"contact"});
  EXPECT_TRUE(contact_issue_paths(R"({ "law": "coulomb", "friction": 0.3, "separation": 0.8 })").empty());
}

TEST(ContactInput, RigidMaterialNeedsContactAndNoElasticConstants) {
  const std::string rigid = R"({
    "grid": { "dim": 2, "min": [0, 0], "max": [1, 0.5], "cell_size": 0.1 },
    "materials": [ { "name": "floor", "model": "rigid", "density": 1000, "E": 5 } ],
    "bodies": [ { "material": "floor", "shape": { "type": "box", "min": [0, 0], "max": [1, 0.1] } } ],
    "solver": { "end_time": 1 } })";
  try {
    (void)parse_spec(rigid);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    ASSERT_EQ(e.issues().size(), 2u);
    EXPECT_EQ(e.issues()[0].path, "materials[0].E");
    EXPECT_EQ(e.issues()[1].path, "contact");
  }
}

}  // namespace

// Grid diagnostics with one velocity field per body (history.csv's checkerboard_velocity,
// grid_rms_velocity, hourglass_energy): every field counts. A checkerboard on field 0 and the same
// state copied into field 1 give the same mass-weighted ratios and twice the hourglass energy; a
// second field at rest halves the checkerboard velocity (it doubles the mass, not the mode).
TEST(ContactDiagnostics, GridModesCountEveryField) {
  const Grid<2> grid(Vec<2>(0, 0), Vec<2>(1, 1), {4, 4}, 0);
  const auto n = static_cast<std::size_t>(grid.node_count);
  std::vector<double> mass(n, 2.0);
  std::vector<Vec<2>> velocity(n);
  for (Index i = 0; i < grid.node_count; ++i) {
    const auto ijk = grid.node_coords(i);
    velocity[i] = Vec<2>((ijk[0] + ijk[1]) % 2 == 0 ? 1.0 : -1.0, 0.0);
  }
  const GridModes one = measure_grid_modes(grid, mass, velocity);
  EXPECT_NEAR(one.checkerboard_velocity, 1.0, 1e-14);
  EXPECT_NEAR(one.rms_velocity, 1.0, 1e-14);
  EXPECT_NEAR(one.hourglass_energy, 0.5 * 2.0 * 16, 1e-12);  // 16 cells, m_c = 2, |g_c| = 1

  std::vector<double> mass2(mass);
  mass2.insert(mass2.end(), mass.begin(), mass.end());
  std::vector<Vec<2>> copied(velocity);
  copied.insert(copied.end(), velocity.begin(), velocity.end());
  const GridModes two = measure_grid_modes(grid, mass2, copied);
  EXPECT_NEAR(two.checkerboard_velocity, 1.0, 1e-14);
  EXPECT_NEAR(two.rms_velocity, 1.0, 1e-14);
  EXPECT_NEAR(two.hourglass_energy, 2 * one.hourglass_energy, 1e-12);

  std::vector<Vec<2>> resting(velocity);
  resting.insert(resting.end(), n, Vec<2>::Zero());
  const GridModes half = measure_grid_modes(grid, mass2, resting);
  EXPECT_NEAR(half.checkerboard_velocity, 0.5, 1e-14);
  EXPECT_NEAR(half.hourglass_energy, one.hourglass_energy, 1e-12);
}
