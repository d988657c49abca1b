// Coupled heat conduction in the explicit solver (Nairn 2026 §3.5; explicit/heat_transport.hpp)
// against the analytic solutions of the 1-D heat equation dT/dt = a d2T/dx2, a = kappa / (rho C_V),
// on a rod at rest:
//  - a sine mode T = T0 + A sin(pi x / L) between ends held at T0 decays as A exp(-a (pi/L)^2 t);
//  - a rod suddenly held at T1 on one end (semi-infinite while the heat has not reached the
//    other): T = T0 + (T1 - T0) erfc(x / (2 sqrt(a t))), and the heat that entered through the end
//    is Q = 2 (T1 - T0) rho C_V sqrt(a t / pi) per unit area;
//  - transport FMPM(k) (T_p = S T+(k)) on the sine mode converges to the exact decay with k;
//  - a fixed flux q into the x- face of a 2-D block (semi-infinite in x, insulated in y):
//    T = T0 + (2 q / kappa) sqrt(a t / pi) exp(-x^2 / (4 a t)) - (q x / kappa) erfc(x / (2 sqrt(a t))),
//    the same at every y, and the heat q A t in, for every basis;
//  - a homogeneous adiabatic compression of a thermoelastic rod: dT = -3 alpha K T0 tr(eps) / (rho C_V)
//    at small strain (alpha the linear expansion coefficient, K the bulk modulus).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <sstream>
#include <string>

#include "matpoint/analysis/verification.hpp"
#include "matpoint/explicit/explicit_step.hpp"
#include "matpoint/io/input.hpp"
#include "matpoint/shape/cpdi_stencils.hpp"
#include "matpoint/shape/tensor_bases.hpp"
#include "matpoint/shape/tensor_stencils.hpp"

namespace heat_conduction_tests {

using namespace matpoint;
constexpr double kPi = std::numbers::pi;

/// A 1-D rod on [0, 1] at rest filling the grid, rho = C_V = kappa = 1 (a = 1), with `heat` as the
/// input's heat section.
Spec rod_spec(int cells, const std::string& heat) {
  std::ostringstream text;
  text << R"({"grid": {"dim": 1, "min": [0], "max": [1], "cell_size": )" << 1.0 / cells << R"(},
    "materials": [{"name": "rod", "model": "linear_elastic", "density": 1, "E": 1, "nu": 0.3,
                   "heat_capacity": 1, "conductivity": 1}],
    "bodies": [{"name": "rod", "material": "rod", "shape": {"type": "box", "min": [0], "max": [1]}}],
    "solver": {"scheme": "usl", "end_time": 1, "courant": 0.5},
    "heat": )"
       << heat << "}";
  return parse_spec(text.str());
}

/// Runs to t_end with the stable step (the last one shortened to land on t_end).
template <int D>
void run_to(Simulation<D>& sim, double t_end) {
  ExplicitStepper<D, TensorStencils<D, LinearBasis>> stepper(sim);
  while (sim.time < t_end * (1 - 1e-12)) stepper.step(std::min(stable_time_step(sim), t_end - sim.time));
}

/// The least-squares amplitude of T_p - T0 on sin(pi x_p).
double sine_amplitude(const Simulation<1>& sim, double T0) {
  double num = 0.0, den = 0.0;
  for (std::size_t p = 0; p < sim.particles.size(); ++p) {
    const double s = std::sin(kPi * sim.particles.x[p][0]);
    num += (sim.particles.temperature[p] - T0) * s;
    den += s * s;
  }
  return num / den;
}

constexpr const char* kSineHeat = R"({"initial_temperature": 300,
    "temperature_sine": {"amplitude": 10, "wave_vector": [3.141592653589793]},
    "conditions": [{"face": "x-", "temperature": 300}, {"face": "x+", "temperature": 300}]})";

/// Relative error of the mode's amplitude after it decayed to 1/e (t = 1 / pi^2).
double sine_decay_error(int cells, const std::string& heat) {
  Simulation<1> sim = build_simulation<1>(rod_spec(cells, heat));
  const double t_end = 1.0 / (kPi * kPi);
  run_to(sim, t_end);
  const double exact = 10.0 * std::exp(-kPi * kPi * t_end);
  return sine_amplitude(sim, 300.0) / exact - 1.0;
}

TEST(HeatConduction, SineModeDecaysAtTheAnalyticRateSecondOrderInH) {
  std::vector<double> h, error;
  for (int cells : {16, 32, 64}) {
    const double e = sine_decay_error(cells, kSineHeat);
    h.push_back(1.0 / cells);
    error.push_back(std::abs(e));
    std::printf("sine mode, %d cells: amplitude error %.3e\n", cells, e);
  }
  EXPECT_LT(error[1], 0.005);  // issue target: within 0.5 % (32 cells)
  EXPECT_LT(error[2], 0.005);
  EXPECT_NEAR(least_squares_order({h[0], h[1]}, {error[0], error[1]}), 2.0, kOrderMargin);
  EXPECT_NEAR(least_squares_order({h[1], h[2]}, {error[1], error[2]}), 2.0, kOrderMargin);
}

TEST(HeatConduction, SuddenlyHeatedEndMatchesErfc) {
  // T1 - T0 = 100 K held on x = 0 from t = 0; at t = 0.0025 the heat has reached 2 sqrt(a t) = 0.1,
  // a tenth of the rod, and the far end is still at T0 (erfc(5) = 1.5e-12). h = 0.005 = sqrt(a t) / 10.
  const double t_end = 0.0025, T0 = 300.0, T1 = 400.0, h = 0.005;
  Simulation<1> sim = build_simulation<1>(
      rod_spec(200, R"({"initial_temperature": 300, "conditions": [{"face": "x-", "temperature": 400}]})"));
  run_to(sim, t_end);
  double worst = 0.0, worst_end_cell = 0.0, content = 0.0;
  for (std::size_t p = 0; p < sim.particles.size(); ++p) {
    const double x = sim.particles.x[p][0], T = sim.particles.temperature[p];
    const double exact = T0 + (T1 - T0) * std::erfc(x / (2.0 * std::sqrt(t_end)));
    // The particles of the heated end's cell took the step T1 - T0 of its node at once (FLIP keeps
    // it), which the erfc spreads over the cell: reported, not checked against the 1 % below.
    double& w = x < h ? worst_end_cell : worst;
    w = std::max(w, std::abs(T - exact) / (T1 - T0));
    content += sim.particles.mass[p] * (T - T0);  // C_V = 1
  }
  const double heat = 2.0 * (T1 - T0) * std::sqrt(t_end / kPi);  // rho = C_V = a = 1, unit area
  std::printf(
      "erfc: largest |T - T_exact| / (T1 - T0) = %.3e (heated end's cell: %.3e); heat content %.6g, "
      "heat in %.6g, exact %.6g\n",
      worst, worst_end_cell, content, sim.boundary_heat, heat);
  EXPECT_LT(worst, 0.01);                               // within 1 % of T1 - T0 beyond the first cell
  EXPECT_NEAR(content / heat, 1.0, 0.01);               // the heat that entered, within 1 %
  EXPECT_NEAR(sim.boundary_heat / content, 1.0, 1e-9);  // counted at the fixed node = what the rod holds
}

TEST(HeatConduction, TransportFmpmConvergesToTheExactDecayWithK) {
  // T_p = S T+(k): FMPM(1) (lumped capacity, PIC-like) smooths the mode at every step; the series
  // of eqs. (5)-(6) with the capacity in place of the mass removes that smoothing as k grows.
  std::vector<double> error;
  for (int k : {1, 2, 4, 8}) {
    std::string heat = kSineHeat;
    heat.insert(heat.size() - 1, ", \"transfer\": \"fmpm\", \"fmpm_order\": " + std::to_string(k));
    error.push_back(std::abs(sine_decay_error(32, heat)));
    std::printf("transport FMPM(%d), 32 cells: amplitude error %.3e\n", k, error.back());
  }
  // FMPM(1) loses most of the mode; each doubling of k up to 4 cuts the error, and k = 8 adds only
  // round-off to k = 4 (the series has converged: A^k dT is negligible for this smooth mode).
  EXPECT_LT(error[1], error[0]);
  EXPECT_LT(error[2], error[1]);
  EXPECT_NEAR(error[3], error[2], 1e-3 * error[2]);
  EXPECT_LT(error.back(), 0.005);  // within 0.5 % of the exact decay, as FLIP
}

struct FluxResult {
  double heat;     // heat content / (q A t)
  double counted;  // heat_in / (q A t)
  double across;   // largest |T_p - mean T at its x| / (T(0) - T0): non-uniformity along the face
  double profile;  // largest |T_p - T_exact| / (T(0) - T0) beyond the first cell
};

/// q = 100 W/m^2 into the x- face of the block [0, 1] x [0, 0.25] (rho = C_V = kappa = 1, 32 x 8
/// cells), `basis` (input name) with the stencils `Stencils`, transport FMPM(4) (the FLIP-like update
/// keeps particle-scale ripples of 3 % next to the heated face), until t = 0.04 (2 sqrt(a t) = 0.4: the far
/// end is still at T0, erfc(2.5) = 4e-4).
template <class Stencils>
FluxResult fixed_flux(const std::string& basis) {
  const double q = 100.0, t_end = 0.04, T0 = 300.0, width = 0.25;
  const std::string text = R"({"grid": {"dim": 2, "min": [0, 0], "max": [1, 0.25], "cell_size": 0.03125},
    "materials": [{"name": "m", "model": "linear_elastic", "density": 1, "E": 1, "nu": 0.3,
                   "heat_capacity": 1, "conductivity": 1}],
    "bodies": [{"name": "b", "material": "m", "shape": {"type": "box", "min": [0, 0], "max": [1, 0.25]}}],
    "solver": {"scheme": "usl", "end_time": 1, "courant": 0.5, "basis": ")" +
                           basis + R"("},
    "heat": {"initial_temperature": 300, "transfer": "fmpm", "fmpm_order": 4,
             "conditions": [{"face": "x-", "flux": 100}]}})";
  Simulation<2> sim = build_simulation<2>(parse_spec(text));
  ExplicitStepper<2, Stencils> stepper(sim);
  while (sim.time < t_end * (1 - 1e-12)) stepper.step(std::min(stable_time_step(sim), t_end - sim.time));
  const double surface = 2.0 * q * std::sqrt(t_end / kPi);  // T(0) - T0
  std::map<long, std::pair<double, int>> by_x;              // mean T of the particles at one x
  const auto key = [](double x) { return std::lround(x * 1e6); };
  double content = 0.0;
  FluxResult r{0, 0, 0, 0};
  for (std::size_t p = 0; p < sim.particles.size(); ++p) {
    const double x = sim.particles.x[p][0], T = sim.particles.temperature[p];
    content += sim.particles.mass[p] * (T - T0);
    auto& [sum, count] = by_x[key(x)];
    sum += T;
    ++count;
    const double s = x / (2.0 * std::sqrt(t_end));
    const double exact = T0 + surface * std::exp(-s * s) - q * x * std::erfc(s);
    if (x > 0.03125) r.profile = std::max(r.profile, std::abs(T - exact) / surface);
  }
  for (std::size_t p = 0; p < sim.particles.size(); ++p) {
    const auto& [sum, count] = by_x[key(sim.particles.x[p][0])];
    r.across = std::max(r.across, std::abs(sim.particles.temperature[p] - sum / count) / surface);
  }
  const double in = q * width * t_end;
  r.heat = content / in;
  r.counted = sim.boundary_heat / in;
  return r;
}

TEST(HeatConduction, FixedFluxPutsInQATForEveryBasisUniformlyAlongTheFace) {
  // The flux goes to the face's nodes with A_i = int_face N_i dA of the basis's grid functions
  // (grid/thermal_conditions.hpp): the heat in is q A t to round-off for every basis. Along the
  // face the block must heat uniformly (the 1-D solution): exactly so for the hat-based bases, whose
  // lumped capacities next to the face's edges (2 particles per cell) are the same h/2, h as the
  // areas. The quadratic B-spline's lumped capacities there are 0.531 h, 0.969 h (particle quadrature)
  // against the exact integrals 0.542 h, 0.958 h that the areas now use, and the hat areas h/2, h
  // the flux used before: the non-uniformity must be smaller than with the hat areas.
  const auto check = [](const char* name, const FluxResult& r) {
    std::printf(
        "fixed flux, %s: heat content / qAt - 1 = %.2e, heat_in / qAt - 1 = %.2e, along the face %.2e, "
        "profile %.2e\n",
        name, r.heat - 1, r.counted - 1, r.across, r.profile);
    EXPECT_NEAR(r.heat, 1.0, 1e-9) << name;
    EXPECT_NEAR(r.counted, 1.0, 1e-9) << name;
  };
  for (const auto& [name, r] :
       {std::pair{"linear", fixed_flux<TensorStencils<2, LinearBasis>>("linear")},
        std::pair{"ugimp", fixed_flux<TensorStencils<2, UGimpBasis>>("ugimp")},
        std::pair{"cpdi1", fixed_flux<CpdiStencils<2, HatKernel, CpdiDomain::Parallelogram>>("cpdi1")}}) {
    check(name, r);
    EXPECT_LT(r.across, 1e-9) << name;   // uniform along the face to round-off
    EXPECT_LT(r.profile, 0.01) << name;  // the analytic profile within 1 % beyond the first cell
  }
  const FluxResult b2 = fixed_flux<TensorStencils<2, QuadraticBSplineBasis>>("bspline2");
  const FluxResult b3 = fixed_flux<TensorStencils<2, CubicBSplineBasis>>("bspline3");
  const FluxResult b2gimp = fixed_flux<TensorStencils<2, B2GimpBasis>>("b2gimp");
  check("bspline2", b2);
  check("bspline3", b3);
  check("b2gimp", b2gimp);
  // The quadratic B-splines with the hat areas (the input's basis only sets the areas here):
  const FluxResult hat_areas = fixed_flux<TensorStencils<2, QuadraticBSplineBasis>>("linear");
  check("bspline2 with the hat areas", hat_areas);
  EXPECT_LT(b2.across, hat_areas.across);
}

TEST(HeatConduction, AdiabaticCompressionHeatsByTheThermoelasticValue) {
  // 0.5 % homogeneous compression of a neo-Hookean rod (E = 1 GPa, nu = 0.33, rho = 1500 kg/m^3,
  // C_V = 1500 J/(kg K), alpha = 60 ppm/K, T0 = 300 K: Nairn 2026 §3.2.2's disks), no conduction:
  // v = -x / s on [0, 1] m with the x- end fixed and the x+ end moving at -1 m/s.
  const std::string text = R"({"grid": {"dim": 1, "min": [0], "max": [1], "cell_size": 0.03125},
    "materials": [{"name": "disk", "model": "neo_hookean", "density": 1500, "E": 1e9, "nu": 0.33,
                   "heat_capacity": 1500, "conductivity": 0.1, "thermal_expansion": 6e-5}],
    "bodies": [{"name": "rod", "material": "disk", "shape": {"type": "box", "min": [0], "max": [1]},
                "velocity_gradient": [[-1]]}],
    "boundary_conditions": [{"face": "x-", "type": "fixed"},
                            {"face": "x+", "type": "velocity", "velocity": [-1]}],
    "solver": {"scheme": "usl", "end_time": 1, "courant": 0.5},
    "heat": {"initial_temperature": 300, "conduction": false}})";
  Simulation<1> sim = build_simulation<1>(parse_spec(text));
  run_to(sim, 0.005);
  const double E = 1e9, nu = 0.33, K = E / (3 * (1 - 2 * nu)), alpha = 6e-5, rho = 1500, C = 1500, T0 = 300;
  double worst_small = 0.0, worst_finite = 0.0, strain = 0.0;
  for (std::size_t p = 0; p < sim.particles.size(); ++p) {
    const double J = sim.particles.F[p].determinant(), dT = sim.particles.temperature[p] - T0;
    const double small = -3 * alpha * K * T0 * (J - 1) / (rho * C);  // tr(eps) = J - 1
    const double finite =
        T0 * (std::exp(-3 * alpha * K * std::log(J) / (rho * C)) - 1);  // heat_transport.hpp
    worst_small = std::max(worst_small, std::abs(dT / small - 1));
    worst_finite = std::max(worst_finite, std::abs(dT / finite - 1));
    strain = std::min(strain, J - 1);
  }
  std::printf("adiabatic compression: tr(eps) down to %.4f; dT vs small-strain %.3e, vs finite form %.3e\n",
              strain, worst_small, worst_finite);
  EXPECT_LT(strain, -0.0045);     // the rod was compressed by about 0.5 %
  EXPECT_LT(worst_small, 0.01);   // the issue's small-strain value within 1 %
  EXPECT_LT(worst_finite, 1e-9);  // the finite form T0 exp(-3 K alpha ln J / (rho0 C_V)), to round-off
}

}  // namespace heat_conduction_tests
