// Tests of the JSON input reader (src/matpoint/io/input.cpp and io/input/, format in docs/input.md).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "matpoint/core/errors.hpp"
#include "matpoint/explicit/simulation.hpp"
#include "matpoint/io/input.hpp"
#include "matpoint/io/memory_estimate.hpp"

namespace matpoint {
namespace {

using nlohmann::json;

/// A small valid 2-D input: one elastic block in a unit square.
json minimal_input() {
  return json::parse(R"({
    "grid": {"dim": 2, "min": [0, 0], "max": [1, 1], "cell_size": 0.25},
    "materials": [{"name": "steel", "model": "linear_elastic", "density": 1000, "E": 1e6, "nu": 0.3}],
    "bodies": [{"material": "steel", "shape": {"type": "box", "min": [0.25, 0.25], "max": [0.75, 0.75]}}],
    "solver": {"end_time": 1.0}
  })");
}

/// The issues parse_spec reports for `text` (empty when it is accepted).
std::vector<InputIssue> issues_of(const std::string& text) {
  try {
    (void)parse_spec(text);
  } catch (const InputError& e) {
    return e.issues();
  }
  return {};
}

std::vector<InputIssue> issues_of(const json& input) { return issues_of(input.dump()); }

std::string describe(const std::vector<InputIssue>& issues) {
  std::string out;
  for (const auto& issue : issues) out += "\n  " + issue.message();
  return out;
}

TEST(InputReader, MinimalTwoDimensionalInputGetsDefaults) {
  const Spec spec = parse_spec(minimal_input().dump());
  EXPECT_EQ(spec.title, "");
  EXPECT_EQ(spec.grid.dim, 2);
  EXPECT_EQ(spec.grid.cells, (std::array<int, 3>{4, 4, 0}));
  EXPECT_EQ(spec.grid.cell_size, (Triple{0.25, 0.25, 0}));
  EXPECT_EQ(spec.grid.max, (Triple{1, 1, 0}));

  ASSERT_EQ(spec.materials.size(), 1u);
  EXPECT_EQ(spec.materials[0].name, "steel");
  EXPECT_EQ(spec.materials[0].model, MaterialModel::LinearElastic);
  EXPECT_EQ(spec.materials[0].volumetric, NeoHookeanVolumetric::LogJ);

  ASSERT_EQ(spec.bodies.size(), 1u);
  const BodySpec& body = spec.bodies[0];
  EXPECT_EQ(body.name, "body0");
  EXPECT_EQ(body.material, 0);
  EXPECT_EQ(body.shape, BodyShape::Box);
  EXPECT_EQ(body.min, (Triple{0.25, 0.25, 0}));
  EXPECT_EQ(body.particles_per_cell, 2);
  EXPECT_EQ(body.velocity, (Triple{0, 0, 0}));
  EXPECT_FALSE(body.has_sine_velocity);

  EXPECT_TRUE(spec.conditions.empty());
  EXPECT_EQ(spec.loads.gravity, (Triple{0, 0, 0}));

  const SolverSpec& solver = spec.solver;
  EXPECT_EQ(solver.scheme, UpdateScheme::MUSL);
  EXPECT_EQ(solver.transfer, VelocityTransfer::FLIP);
  EXPECT_EQ(solver.position_alpha, 1.0);
  EXPECT_EQ(solver.shape, ShapeKind::BSpline2);  // the user guide's recommended basis
  EXPECT_EQ(solver.deformation_update, DeformationUpdate::Exponential);
  EXPECT_FALSE(solver.dt.has_value());
  EXPECT_EQ(solver.courant, 0.5);
  EXPECT_EQ(solver.end_time, 1.0);
  EXPECT_EQ(solver.max_steps, 0);
  EXPECT_EQ(solver.mass_tolerance, 0.0);  // every node a particle reaches is active (momentum exact)
  ASSERT_TRUE(solver.max_energy_growth.has_value());
  EXPECT_EQ(*solver.max_energy_growth, 1.0);

  EXPECT_EQ(spec.output.every_steps, 0);
  EXPECT_EQ(spec.output.every_time, 0.0);
  EXPECT_TRUE(spec.output.particles);
  EXPECT_TRUE(spec.output.plots);
  EXPECT_TRUE(spec.output.fields.empty());
  EXPECT_TRUE(spec.checks.empty());
  EXPECT_EQ(spec.echo, minimal_input());

  // IMPM's cell quadrature needs the bilinear basis (Gong 2015 §5.3): there the default is linear.
  json impm = minimal_input();
  impm["solver"]["mapping"] = "impm";
  EXPECT_EQ(parse_spec(impm.dump()).solver.shape, ShapeKind::Linear);
}

TEST(InputReader, YoungsModulusAndPoissonRatioGiveLameConstants) {
  const Spec spec = parse_spec(minimal_input().dump());  // E = 1e6, nu = 0.3
  const MaterialSpec& m = spec.materials[0];
  EXPECT_DOUBLE_EQ(m.youngs_modulus, 1e6);
  EXPECT_DOUBLE_EQ(m.poisson_ratio, 0.3);
  EXPECT_NEAR(m.lambda, 576923.07692307692, 1e-6);  // E nu / ((1 + nu)(1 - 2 nu)) = 0.3e6 / 0.52
  EXPECT_NEAR(m.mu, 384615.38461538462, 1e-6);      // E / (2 (1 + nu)) = 1e6 / 2.6
}

TEST(InputReader, LameConstantsGiveYoungsModulusAndPoissonRatio) {
  json input = minimal_input();
  input["materials"][0].erase("E");
  input["materials"][0].erase("nu");
  input["materials"][0]["lambda"] = 2.0;
  input["materials"][0]["mu"] = 1.0;
  const MaterialSpec m = parse_spec(input.dump()).materials[0];
  EXPECT_DOUBLE_EQ(m.lambda, 2.0);
  EXPECT_DOUBLE_EQ(m.mu, 1.0);
  EXPECT_DOUBLE_EQ(m.youngs_modulus, 8.0 / 3.0);  // mu (3 lambda + 2 mu) / (lambda + mu)
  EXPECT_DOUBLE_EQ(m.poisson_ratio, 1.0 / 3.0);   // lambda / (2 (lambda + mu))
}

TEST(InputReader, CommentsAreAllowed) {
  const std::string text = R"(// a unit square
  {
    "title": "commented", /* the title */
    "grid": {"dim": 2, "min": [0, 0], "max": [1, 1], "cell_size": 0.25},  // 4 x 4 cells
    "materials": [{"name": "m", "model": "neo_hookean", "density": 1, "E": 1, "nu": 0.25,
                   "volumetric": "half_j_squared"}],
    "bodies": [{"material": "m", "shape": {"type": "disk", "center": [0.5, 0.5], "radius": 0.25}}],
    "solver": {"end_time": 1}
  })";
  const Spec spec = parse_spec(text);
  EXPECT_EQ(spec.title, "commented");
  EXPECT_EQ(spec.materials[0].model, MaterialModel::NeoHookean);
  EXPECT_EQ(spec.materials[0].volumetric, NeoHookeanVolumetric::HalfJSquared);
  EXPECT_EQ(spec.bodies[0].shape, BodyShape::Disk);
  EXPECT_EQ(spec.echo["title"], "commented");
}

TEST(InputReader, SyntaxErrorIsOneIssueWithItsLine) {
  const auto issues = issues_of(std::string("{\n  \"grid\": {\n    \"dim\": 2,,\n  }\n}"));
  ASSERT_EQ(issues.size(), 1u) << describe(issues);
  EXPECT_EQ(issues[0].path, "(json)");
  EXPECT_NE(issues[0].value.find("line 3"), std::string::npos) << issues[0].value;
  EXPECT_EQ(issues[0].expected, "valid JSON (comments allowed)");
}

// Every piece of the input echoed in a message is cut at 200 characters (docs/input.md), so a
// mistake inside a huge token gives a short message, not the token back.
constexpr std::size_t kEchoLimit = 200;

void expect_short_issues(const std::vector<InputIssue>& issues, std::size_t input_size) {
  ASSERT_FALSE(issues.empty());
  for (const auto& issue : issues) {
    EXPECT_LE(issue.message().size(), 5 * kEchoLimit) << issue.message().substr(0, 1000);
    EXPECT_LT(issue.message().size(), input_size / 100);
  }
}

TEST(InputReader, ParseErrorInsideAHugeNumberIsShort) {
  std::string text = minimal_input().dump();
  const std::string end_time = R"("end_time":1.0)";
  text.replace(text.find(end_time), end_time.size(), R"("end_time":1.)" + std::string(4'000'000, '7') + "x");
  const auto issues = issues_of(text);
  ASSERT_EQ(issues.size(), 1u);
  EXPECT_EQ(issues[0].path, "(json)");
  EXPECT_NE(issues[0].value.find("line 1"), std::string::npos) << issues[0].value.substr(0, 1000);
  expect_short_issues(issues, text.size());
}

TEST(InputReader, UnterminatedCommentIsShort) {
  const std::string text = minimal_input().dump() + "\n/* " + std::string(4'000'000, 'c');
  const auto issues = issues_of(text);
  ASSERT_EQ(issues.size(), 1u);
  EXPECT_NE(issues[0].value.find("comment"), std::string::npos) << issues[0].value.substr(0, 1000);
  expect_short_issues(issues, text.size());
}

TEST(InputReader, HugeUnknownKeyAndValueAreCut) {
  json input = minimal_input();
  input["solver"][std::string(1'000'000, 'k')] = std::string(1'000'000, 'v');
  input["title"] = std::vector<double>(200'000, 1.5);
  const auto issues = issues_of(input);
  ASSERT_EQ(issues.size(), 2u) << describe(issues).substr(0, 2000);
  expect_short_issues(issues, 1'000'000);
}

// A key given in the wrong section is reported where it is, with where it belongs.
TEST(InputReader, MisplacedKeySaysWhereItBelongs) {
  json input = minimal_input();
  input["gravity"] = {0, -9.81};
  input["solver"]["every_steps"] = 10;
  input["bodies"][0]["density"] = 1000;
  input["solver"]["sceme"] = "usl";  // a typo, known nowhere: no hint
  const auto issues = issues_of(input);
  ASSERT_EQ(issues.size(), 4u) << describe(issues);
  std::map<std::string, std::string> expected_of;
  for (const auto& issue : issues) expected_of[issue.path] = issue.expected;
  EXPECT_NE(expected_of["gravity"].find("gravity belongs under loads"), std::string::npos)
      << describe(issues);
  EXPECT_NE(expected_of["solver.every_steps"].find("every_steps belongs under output"), std::string::npos)
      << describe(issues);
  EXPECT_NE(expected_of["bodies[0].density"].find("density belongs under materials[]"), std::string::npos)
      << describe(issues);
  EXPECT_EQ(expected_of["solver.sceme"].find("belongs under"), std::string::npos) << describe(issues);
}

// A body outside the grid: which side and by how much.
TEST(InputReader, BodyOutsideTheGridNamesTheSideAndTheOverhang) {
  json input = minimal_input();
  input["bodies"][0]["shape"] = {{"type", "box"}, {"min", {-0.25, 0.25}}, {"max", {0.75, 1.5}}};
  const auto issues = issues_of(input);
  ASSERT_EQ(issues.size(), 1u) << describe(issues);
  EXPECT_EQ(issues[0].path, "bodies[0].shape");
  EXPECT_NE(issues[0].expected.find("0.25 beyond the x- side (x = -0.25 < grid.min[0] = 0)"),
            std::string::npos)
      << describe(issues);
  EXPECT_NE(issues[0].expected.find("0.5 beyond the y+ side (y = 1.5 > grid.max[1] = 1)"), std::string::npos)
      << describe(issues);
}

TEST(InputReader, RepeatedKeyIsAnIssue) {
  json input = minimal_input();
  std::string text = input.dump();
  const std::string end_time = R"("end_time":1.0)";
  text.replace(text.find(end_time), end_time.size(), end_time + "," + end_time);
  const auto issues = issues_of(text);
  ASSERT_EQ(issues.size(), 1u) << describe(issues);
  EXPECT_EQ(issues[0].path, "solver.end_time");
}

TEST(InputReader, MessageNamesPathValueAndExpectation) {
  json input = minimal_input();
  input["materials"][0]["nu"] = "abc";
  try {
    (void)parse_spec(input.dump());
    FAIL() << "nu = \"abc\" was accepted";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "materials[0].nu: got \"abc\", expected a number in (-1, 0.5)\n");
  }
}

// --- One mistake, one issue at the exact path --------------------------------------------------

struct Mistake {
  std::string name;
  std::function<void(json&)> make;
  std::string path;
  std::string value;  // expected InputIssue::value, when not empty
};

void PrintTo(const Mistake& mistake, std::ostream* out) { *out << mistake.name; }

class InputOneMistake : public testing::TestWithParam<Mistake> {};

TEST_P(InputOneMistake, GivesOneIssueAtItsPath) {
  json input = minimal_input();
  GetParam().make(input);
  const auto issues = issues_of(input);
  ASSERT_EQ(issues.size(), 1u) << describe(issues);
  EXPECT_EQ(issues[0].path, GetParam().path) << describe(issues);
  if (!GetParam().value.empty()) {
    EXPECT_EQ(issues[0].value, GetParam().value);
  }
  EXPECT_FALSE(issues[0].expected.empty());
}

void use_3d_grid(json& j) {
  j["grid"] = json::parse(R"({"dim": 3, "min": [0, 0, 0], "max": [1, 1, 1], "cell_size": 0.25})");
  j["bodies"][0]["shape"] = json::parse(R"({"type": "box", "min": [0, 0, 0], "max": [1, 1, 1]})");
}

const std::vector<Mistake> kMistakes = {
    {"NegativeDensity", [](json& j) { j["materials"][0]["density"] = -1; }, "materials[0].density", "-1"},
    {"PoissonRatioHalf", [](json& j) { j["materials"][0]["nu"] = 0.5; }, "materials[0].nu", "0.5"},
    {"PoissonRatioString", [](json& j) { j["materials"][0]["nu"] = "abc"; }, "materials[0].nu", "\"abc\""},
    {"UnknownSolverKey", [](json& j) { j["solver"]["sceme"] = "usl"; }, "solver.sceme", "\"usl\""},
    {"UnknownTopLevelKey", [](json& j) { j["titel"] = "x"; }, "titel", "\"x\""},
    {"BodyOutsideGrid",
     [](json& j) {
       j["bodies"][0]["shape"]["max"] = {1.5, 0.75};
     },
     "bodies[0].shape", ""},
    {"DiskOutsideGrid",
     [](json& j) {
       j["bodies"][0]["shape"] = json::parse(R"({"type":"disk","center":[0.9,0.5],"radius":0.2})");
     },
     "bodies[0].shape", ""},
    {"DimensionFour", [](json& j) { j["grid"]["dim"] = 4; }, "grid.dim", "4"},
    {"CellSizeNotDividing", [](json& j) { j["grid"]["cell_size"] = 0.3; }, "grid.cell_size", "0.3"},
    {"TooManyCells", [](json& j) { j["grid"]["cell_size"] = 1e-5; }, "grid.cell_size", ""},
    {"GridMaxBelowMin",
     [](json& j) {
       j["grid"]["max"] = {1, 0};
     },
     "grid.max", "[1,0]"},
    {"MissingGrid", [](json& j) { j.erase("grid"); }, "grid", "missing"},
    {"MissingEndTime", [](json& j) { j["solver"].erase("end_time"); }, "solver.end_time", "missing"},
    {"PolygonIn3D",  // a 3-D polygon is a prism along z: without its z range
     [](json& j) {
       use_3d_grid(j);
       j["bodies"][0]["shape"] = json::parse(R"({"type": "polygon", "vertices": [[0, 0], [1, 0], [0, 1]]})");
     },
     "bodies[0].shape.z", "missing"},
    {"PolygonWithoutArea",
     [](json& j) {
       j["bodies"][0]["shape"] =
           json::parse(R"({"type": "polygon", "vertices": [[0, 0], [0.5, 0.5], [1, 1]]})");
     },
     "bodies[0].shape.vertices", ""},
    {"DtAndCourant",
     [](json& j) {
       j["solver"]["dt"] = 1e-3;
       j["solver"]["courant"] = 0.5;
     },
     "solver.courant", "0.5"},
    {"CourantAboveOne", [](json& j) { j["solver"]["courant"] = 1.5; }, "solver.courant", "1.5"},
    {"UnknownMeasure",
     [](json& j) {
       j["checks"] = json::parse(
           R"([{"name": "c", "measure": "energy", "expected": 0, "tolerance": 0.1, "source": "s"}])");
     },
     "checks[0].measure", "\"energy\""},
    {"YoungAndLameMixed", [](json& j) { j["materials"][0]["lambda"] = 1; }, "materials[0].lambda", "1"},
    {"NegativeBulkModulus",
     [](json& j) {
       j["materials"][0] = json::parse(R"({"name": "steel", "model": "linear_elastic", "density": 1,
                                           "lambda": -1, "mu": 1})");
     },
     "materials[0].lambda", "-1"},
    {"VolumetricForLinearElastic", [](json& j) { j["materials"][0]["volumetric"] = "log_j"; },
     "materials[0].volumetric", "\"log_j\""},
    {"DuplicateMaterialName", [](json& j) { j["materials"].push_back(j["materials"][0]); },
     "materials[1].name", "\"steel\""},
    {"UnknownMaterialInBody", [](json& j) { j["bodies"][0]["material"] = "rubber"; }, "bodies[0].material",
     "\"rubber\""},
    {"TooManyParticlesPerCell", [](json& j) { j["bodies"][0]["particles_per_cell"] = 11; },
     "bodies[0].particles_per_cell", "11"},
    {"FractionalParticlesPerCell", [](json& j) { j["bodies"][0]["particles_per_cell"] = 2.5; },
     "bodies[0].particles_per_cell", "2.5"},
    {"VelocityOfWrongLength",
     [](json& j) {
       j["bodies"][0]["velocity"] = {1, 2, 3};
     },
     "bodies[0].velocity", "[1,2,3]"},
    {"GravityString", [](json& j) { j["loads"]["gravity"] = "down"; }, "loads.gravity", "\"down\""},
    {"FlipFractionWithoutBlend", [](json& j) { j["solver"]["flip_fraction"] = 0.9; }, "solver.flip_fraction",
     "0.9"},
    {"UnknownScheme", [](json& j) { j["solver"]["scheme"] = "usx"; }, "solver.scheme", "\"usx\""},
    {"FaceZIn2D",
     [](json& j) { j["boundary_conditions"] = json::parse(R"([{"face": "z-", "type": "fixed"}])"); },
     "boundary_conditions[0].face", "\"z-\""},
    {"FaceAndBox",
     [](json& j) {
       j["boundary_conditions"] =
           json::parse(R"([{"face": "x-", "box": {"min": [0, 0], "max": [0, 1]}, "type": "fixed"}])");
     },
     "boundary_conditions[0].box", ""},
    {"SlipBoxWithoutNormal",
     [](json& j) {
       j["boundary_conditions"] = json::parse(R"([{"box": {"min": [0, 0], "max": [0, 1]}, "type": "slip"}])");
     },
     "boundary_conditions[0].normal", "missing"},
    {"VelocityOnFixedCondition",
     [](json& j) {
       j["boundary_conditions"] = json::parse(R"([{"face": "x-", "type": "fixed", "velocity": [0, 0]}])");
     },
     "boundary_conditions[0].velocity", "[0,0]"},
    {"VelocityAllFree",
     [](json& j) {
       j["boundary_conditions"] =
           json::parse(R"([{"face": "x-", "type": "velocity", "velocity": [null, null]}])");
     },
     "boundary_conditions[0].velocity", "[null,null]"},
    {"TableTimesNotIncreasing",
     [](json& j) {
       j["boundary_conditions"] = json::parse(
           R"([{"face": "x-", "type": "velocity", "velocity": [{"table": [[0, 0], [0, 1]]}, null]}])");
     },
     "boundary_conditions[0].velocity[0].table[1]", "[0,1]"},
    {"UnknownParticleField",
     [](json& j) {
       j["output"]["fields"] = {"velocity", "speed"};
     },
     "output.fields[1]", "\"speed\""},
    {"EveryStepsAndEveryTime",
     [](json& j) {
       j["output"]["every_steps"] = 10;
       j["output"]["every_time"] = 0.1;
     },
     "output.every_time", "0.1"},
    {"PlotsNotBoolean", [](json& j) { j["output"]["plots"] = "yes"; }, "output.plots", "\"yes\""},
    {"EmptyMaterials", [](json& j) { j["materials"] = json::array(); }, "materials", "[]"},
    {"RootNotObject", [](json& j) { j = json::array(); }, "(root)", "[]"},
};

INSTANTIATE_TEST_SUITE_P(InputReader, InputOneMistake, testing::ValuesIn(kMistakes),
                         [](const testing::TestParamInfo<Mistake>& info) { return info.param.name; });

TEST(InputReader, ThreeMistakesGiveExactlyThreeIssues) {
  json input = minimal_input();
  input["materials"][0]["density"] = 0;
  input["solver"]["sceme"] = "usl";
  input["bodies"][0]["shape"]["min"] = {-1, 0.25};
  const auto issues = issues_of(input);
  ASSERT_EQ(issues.size(), 3u) << describe(issues);
  std::vector<std::string> paths;
  for (const auto& issue : issues) paths.push_back(issue.path);
  EXPECT_NE(std::find(paths.begin(), paths.end(), "materials[0].density"), paths.end());
  EXPECT_NE(std::find(paths.begin(), paths.end(), "solver.sceme"), paths.end());
  EXPECT_NE(std::find(paths.begin(), paths.end(), "bodies[0].shape"), paths.end());
}

// --- Valid variants ----------------------------------------------------------------------------

TEST(InputReader, ThreeDimensionalGridWithCellSizeVector) {
  json input = minimal_input();
  use_3d_grid(input);
  input["grid"]["cell_size"] = {0.5, 0.25, 0.125};
  input["loads"]["gravity"] = {0, 0, -9.81};
  const Spec spec = parse_spec(input.dump());
  EXPECT_EQ(spec.grid.dim, 3);
  EXPECT_EQ(spec.grid.cells, (std::array<int, 3>{2, 4, 8}));
  EXPECT_EQ(spec.loads.gravity, (Triple{0, 0, -9.81}));
}

// The basis key was solver.shape (easily confused with bodies[].shape, the geometry): the old
// spelling is refused with a message naming solver.basis.
TEST(InputReader, OldBasisKeyIsRefusedNamingTheNewOne) {
  json input = minimal_input();
  input["solver"]["shape"] = "bspline2";
  const auto issues = issues_of(input);
  ASSERT_EQ(issues.size(), 1u) << describe(issues);
  EXPECT_EQ(issues[0].path, "solver.shape");
  EXPECT_NE(issues[0].expected.find("solver.basis"), std::string::npos) << describe(issues);
  input["solver"].erase("shape");
  input["solver"]["basis"] = "cpdi1";
  EXPECT_EQ(parse_spec(input.dump()).solver.shape, ShapeKind::CPDI1);
}

// A 3-D ball is a "sphere" ("disk" stays accepted in 3-D); a "sphere" in 2-D is refused.
TEST(InputReader, SphereIsTheThreeDimensionalBall) {
  json input = minimal_input();
  use_3d_grid(input);
  input["bodies"][0]["shape"] = {{"type", "sphere"}, {"center", {0.5, 0.5, 0.5}}, {"radius", 0.25}};
  const Spec spec = parse_spec(input.dump());
  EXPECT_EQ(spec.bodies[0].shape, BodyShape::Disk);
  EXPECT_EQ(spec.bodies[0].radius, 0.25);
  json flat = minimal_input();
  flat["bodies"][0]["shape"] = {{"type", "sphere"}, {"center", {0.5, 0.5}}, {"radius", 0.25}};
  const auto issues = issues_of(flat);
  ASSERT_EQ(issues.size(), 1u) << describe(issues);
  EXPECT_EQ(issues[0].path, "bodies[0].shape.type");
}

TEST(InputReader, OneDimensionalBarWithIntervalBody) {
  const Spec spec = parse_spec(R"({
    "grid": {"dim": 1, "min": [0], "max": [25], "cell_size": [1]},
    "materials": [{"name": "bar", "model": "linear_elastic", "density": 1, "E": 100, "nu": 0}],
    "bodies": [{"material": "bar", "shape": {"type": "disk", "center": [12.5], "radius": 12.5},
                "velocity_sine": {"amplitude": [0.1], "wave_vector": [0.0628], "phase": 1.5}}],
    "boundary_conditions": [{"face": "x-", "type": "fixed"}],
    "solver": {"end_time": 10, "courant": 0.1}
  })");
  EXPECT_EQ(spec.grid.dim, 1);
  EXPECT_EQ(spec.grid.cells, (std::array<int, 3>{25, 0, 0}));
  EXPECT_EQ(spec.bodies[0].center, (Triple{12.5, 0, 0}));
  EXPECT_EQ(spec.bodies[0].sine_phase, 1.5);
  EXPECT_EQ(spec.solver.courant, 0.1);
  EXPECT_DOUBLE_EQ(spec.materials[0].lambda, 0.0);
  EXPECT_DOUBLE_EQ(spec.materials[0].mu, 50.0);
}

TEST(InputReader, CellCountWithinRoundOffIsAccepted) {
  json input = minimal_input();
  input["grid"]["max"] = {0.3, 0.3};
  input["grid"]["cell_size"] = 0.1;  // 0.3 / 0.1 = 2.9999999999999996
  input["bodies"][0]["shape"]["min"] = {0.1, 0.1};
  input["bodies"][0]["shape"]["max"] = {0.3, 0.3};
  EXPECT_EQ(parse_spec(input.dump()).grid.cells, (std::array<int, 3>{3, 3, 0}));
}

TEST(InputReader, PolygonBodyAndSineVelocity) {
  json input = minimal_input();
  input["bodies"][0] = json::parse(R"({
    "name": "wedge", "material": "steel", "particles_per_cell": 3, "velocity": [1, 0],
    "shape": {"type": "polygon", "vertices": [[0, 0], [1, 0], [0, 1]]},
    "velocity_sine": {"amplitude": [0.1, 0], "wave_vector": [3.14, 0]}})");
  const BodySpec body = parse_spec(input.dump()).bodies[0];
  EXPECT_EQ(body.name, "wedge");
  EXPECT_EQ(body.shape, BodyShape::Polygon);
  ASSERT_EQ(body.polygon.size(), 3u);
  EXPECT_EQ(body.polygon[1], (std::array<double, 2>{1, 0}));
  EXPECT_EQ(body.particles_per_cell, 3);
  EXPECT_EQ(body.velocity, (Triple{1, 0, 0}));
  EXPECT_TRUE(body.has_sine_velocity);
  EXPECT_EQ(body.sine_amplitude, (Triple{0.1, 0, 0}));
  EXPECT_EQ(body.sine_wave_vector, (Triple{3.14, 0, 0}));
  EXPECT_EQ(body.sine_phase, 0.0);
}

TEST(InputReader, BoundaryConditionsMapToVelocityConditions) {
  json input = minimal_input();
  input["boundary_conditions"] = json::parse(R"([
    {"face": "y-", "type": "fixed"},
    {"face": "x+", "type": "slip"},
    {"box": {"min": [0, 0], "max": [0.25, 1]}, "type": "slip", "normal": "y"},
    {"face": "x-", "type": "velocity", "velocity": [{"table": [[0, 0], [1, 2]]}, 0.5]}
  ])");
  const auto conditions = parse_spec(input.dump()).conditions;
  ASSERT_EQ(conditions.size(), 4u);

  EXPECT_TRUE(conditions[0].on_face);
  EXPECT_EQ(conditions[0].face_axis, 1);
  EXPECT_EQ(conditions[0].face_side, 0);
  EXPECT_EQ(conditions[0].kind, ConditionKind::Fixed);

  EXPECT_EQ(conditions[1].face_axis, 0);
  EXPECT_EQ(conditions[1].face_side, 1);
  EXPECT_EQ(conditions[1].kind, ConditionKind::Slip);
  EXPECT_EQ(conditions[1].normal_axis, 0);  // the face's own axis by default

  EXPECT_FALSE(conditions[2].on_face);
  EXPECT_EQ(conditions[2].box_max, (Triple{0.25, 1, 0}));
  EXPECT_EQ(conditions[2].normal_axis, 1);

  const auto& velocity = conditions[3].velocity;
  EXPECT_EQ(conditions[3].kind, ConditionKind::Velocity);
  ASSERT_TRUE(velocity[0].has_value());
  ASSERT_TRUE(velocity[1].has_value());
  EXPECT_FALSE(velocity[2].has_value());
  EXPECT_EQ(velocity[0]->times, (std::vector<double>{0, 1}));
  EXPECT_DOUBLE_EQ((*velocity[0])(0.25), 0.5);
  EXPECT_TRUE(velocity[1]->times.empty());
  EXPECT_EQ((*velocity[1])(7.0), 0.5);
}

TEST(InputReader, SolverAndOutputOptions) {
  json input = minimal_input();
  input["solver"] = json::parse(R"({"scheme": "musl", "transfer": "blend", "basis": "bspline2",
    "deformation_update": "linear", "dt": 1e-4, "end_time": 2, "max_steps": 1e6, "position_alpha": 0,
    "mass_tolerance": 1e-9})");
  input["output"] = json::parse(R"({"every_time": 0.1, "particles": false, "fields": ["stress", "id"]})");
  const Spec spec = parse_spec(input.dump());
  EXPECT_EQ(spec.solver.scheme, UpdateScheme::MUSL);
  EXPECT_EQ(spec.solver.transfer, VelocityTransfer::Blend);
  EXPECT_EQ(spec.solver.flip_fraction, 0.99);
  EXPECT_EQ(spec.solver.shape, ShapeKind::BSpline2);
  EXPECT_EQ(spec.solver.deformation_update, DeformationUpdate::Linear);
  EXPECT_EQ(spec.solver.dt, 1e-4);
  EXPECT_EQ(spec.solver.max_steps, 1000000);
  EXPECT_EQ(spec.solver.position_alpha, 0.0);
  EXPECT_EQ(spec.solver.mass_tolerance, 1e-9);
  EXPECT_EQ(spec.output.every_time, 0.1);
  EXPECT_FALSE(spec.output.particles);
  EXPECT_TRUE(spec.output.plots);
  EXPECT_EQ(spec.output.fields, (std::vector<std::string>{"stress", "id"}));
}

TEST(InputReader, ChecksAreRead) {
  json input = minimal_input();
  input["checks"] = json::parse(R"([{"name": "energy", "measure": "max_relative_energy_error",
    "expected": 0, "tolerance": 1e-3, "source": "energy conservation"}])");
  const auto checks = parse_spec(input.dump()).checks;
  ASSERT_EQ(checks.size(), 1u);
  EXPECT_EQ(checks[0].measure, "max_relative_energy_error");
  EXPECT_EQ(checks[0].tolerance, 1e-3);
  EXPECT_EQ(checks[0].source, "energy conservation");
}

// --- Files -------------------------------------------------------------------------------------

TEST(InputReader, MissingFileIsAnIssueNamingTheFile) {
  const std::filesystem::path file = std::filesystem::temp_directory_path() / "matpoint_no_such_input.json";
  try {
    (void)load_spec(file);
    FAIL() << "a missing file was accepted";
  } catch (const InputError& e) {
    ASSERT_EQ(e.issues().size(), 1u);
    EXPECT_EQ(e.issues()[0].path, file.string());
  }
}

// A named pipe is refused by its type before it is opened: opening one with no writer blocks.
TEST(InputReader, NamedPipeIsRefusedWithoutWaiting) {
  const std::filesystem::path fifo =
      std::filesystem::temp_directory_path() / ("matpoint_test_fifo_" + std::to_string(::getpid()) + ".json");
  std::filesystem::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  try {
    (void)load_spec(fifo);  // the old reader blocked here forever
    ADD_FAILURE() << "a named pipe was accepted";
  } catch (const InputError& e) {
    ASSERT_EQ(e.issues().size(), 1u);
    EXPECT_EQ(e.issues()[0].path, fifo.string());
    EXPECT_EQ(e.issues()[0].value, "a named pipe");
  }
  std::filesystem::remove(fifo);
}

TEST(InputReader, LoadsAFile) {
  const std::filesystem::path file = std::filesystem::temp_directory_path() /
                                     ("matpoint_test_input_" + std::to_string(::getpid()) + ".json");
  std::ofstream(file) << "// minimal\n" << minimal_input().dump(2);
  EXPECT_EQ(load_spec(file).grid.cells[0], 4);
  std::filesystem::remove(file);
}

#ifdef MATPOINT_TEST_INPUTS_DIR
/// The JSON path a malformed input's first line promises: "// expect PATH: what is wrong".
std::string expected_path(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string first;
  std::getline(in, first);
  const std::string prefix = "// expect ";
  const auto colon = first.find(": ");
  if (!first.starts_with(prefix) || colon == std::string::npos) return {};
  return first.substr(prefix.size(), colon - prefix.size());
}

// Issue 8: every malformed input (types, ranges, missing sections, overlapping and empty bodies, a
// grid too small, wrong units of magnitude) is refused with a message at the JSON path it names,
// by the validator or by the set-up that `matpoint check` and `matpoint run` do before any step.
TEST(InputReader, EveryBadInputFileIsRefusedAtTheExpectedPath) {
  const std::filesystem::path folder = std::filesystem::path(MATPOINT_TEST_INPUTS_DIR) / "bad";
  ASSERT_TRUE(std::filesystem::is_directory(folder)) << folder;
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.path().extension() != ".json") continue;
    ++count;
    SCOPED_TRACE(entry.path().filename().string());
    const std::string path = expected_path(entry.path());
    ASSERT_FALSE(path.empty()) << "first line must be // expect PATH: what is wrong";
    try {
      check_setup(load_spec(entry.path()));
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      std::string paths;
      bool found = false;
      for (const auto& issue : e.issues()) {
        found = found || issue.path == path;
        EXPECT_FALSE(issue.expected.empty());
        paths += issue.message() + "\n";
      }
      EXPECT_TRUE(found) << "expected an issue at " << path << ", got:\n" << paths;
    }
  }
  EXPECT_GE(count, 50);  // issue 8: a corpus of at least 50 malformed inputs
}
#endif

// --- TimeFunction ------------------------------------------------------------------------------

TEST(InputTimeFunction, ConstantWithoutTimes) {
  const TimeFunction f{{}, {2.5}};
  EXPECT_EQ(f(-1.0), 2.5);
  EXPECT_EQ(f(0.0), 2.5);
  EXPECT_EQ(f(1e9), 2.5);
}

TEST(InputTimeFunction, TableInterpolatesLinearlyAndClampsOutside) {
  const TimeFunction f{{0, 1, 3}, {0, 2, -2}};
  EXPECT_EQ(f(-5.0), 0.0);  // before the first row: the first value
  EXPECT_EQ(f(0.0), 0.0);
  EXPECT_DOUBLE_EQ(f(0.5), 1.0);
  EXPECT_EQ(f(1.0), 2.0);
  EXPECT_DOUBLE_EQ(f(2.0), 0.0);
  EXPECT_DOUBLE_EQ(f(2.5), -1.0);
  EXPECT_EQ(f(3.0), -2.0);
  EXPECT_EQ(f(10.0), -2.0);  // after the last row: the last value
}

TEST(InputTimeFunction, SingleRowIsConstant) {
  const TimeFunction f{{1}, {4}};
  EXPECT_EQ(f(0.0), 4.0);
  EXPECT_EQ(f(2.0), 4.0);
}

}  // namespace
}  // namespace matpoint

// --- memory estimate (issue 8: refuse what would be killed for memory) ------------------------

namespace matpoint {
namespace {

TEST(InputMemory, RefusesAProblemLargerThanTheAvailableMemoryWithTheEstimate) {
  const Spec spec = parse_spec(R"({"grid": {"dim": 2, "min": [0, 0], "max": [1, 1], "cell_size": 0.01},
    "materials": [{"name": "m", "model": "linear_elastic", "density": 1, "E": 1, "nu": 0.3}],
    "bodies": [{"material": "m", "shape": {"type": "box", "min": [0, 0], "max": [1, 1]}}],
    "solver": {"end_time": 1}})");
  const MemoryEstimate e = estimate_memory(spec);
  EXPECT_GE(e.particles, 4 * 100 * 100) << "an upper estimate: 2 x 2 particles in each of 100 x 100 cells";
  EXPECT_LE(e.particles, 4 * 102 * 102);
  EXPECT_NO_THROW(check_memory(spec, 1e12));
  try {
    check_memory(spec, 1e6);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& error) {
    ASSERT_EQ(error.issues().size(), 1u);
    EXPECT_NE(error.issues()[0].message().find("particles"), std::string::npos)
        << error.issues()[0].message();
    EXPECT_NE(error.issues()[0].message().find("GB"), std::string::npos);
  }
}

TEST(InputMemory, ContactCountsTheGridOncePerVelocityField) {
  const std::string bodies = R"({"grid": {"dim": 2, "min": [0, 0], "max": [1, 1], "cell_size": 0.01},
    "materials": [{"name": "m", "model": "linear_elastic", "density": 1, "E": 1, "nu": 0.3}],
    "bodies": [{"material": "m", "shape": {"type": "box", "min": [0, 0], "max": [0.3, 0.3]}},
               {"material": "m", "shape": {"type": "box", "min": [0.5, 0.5], "max": [0.9, 0.9]}},
               {"material": "m", "shape": {"type": "disk", "center": [0.2, 0.7], "radius": 0.1}}],
    "solver": {"end_time": 1})";
  const MemoryEstimate plain = estimate_memory(parse_spec(bodies + "}"));
  const MemoryEstimate contact =
      estimate_memory(parse_spec(bodies + R"(, "contact": {"law": "frictionless"}})"));
  EXPECT_EQ(plain.fields, 1);
  EXPECT_EQ(contact.fields, 3);
  EXPECT_EQ(contact.particles, plain.particles);
  // Two more fields of at least mass + 8 vectors (16 bytes each in 2-D) per node.
  EXPECT_GE(contact.bytes - plain.bytes, 2 * plain.nodes * (8.0 + 8 * 16.0));
}

}  // namespace
}  // namespace matpoint
