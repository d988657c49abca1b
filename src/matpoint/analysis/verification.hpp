// Built-in verification problems: the manufactured solutions of Gong 2015 §4.5-4.7 (extraction
// §7.3, §7.4) with the dissertation's error norms (extraction A8), run over a list of resolutions,
// with observed orders and the claims of Gong 2015 (extraction §7.3, §8, §10) tested with one margin.
// docs/verification.md describes the problems, the norms and the measured orders.
#pragma once

#include <array>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "matpoint/core/types.hpp"
#include "matpoint/io/spec.hpp"

namespace matpoint {

/// The exact solution of the 1-D bar (eqs. (4.35)-(4.39)) and of the 2-D axis-aligned problem
/// (eqs. (4.41)-(4.46)) on [0, 1]^D: U_a = G sin(pi X_a) sin(c pi t), c = sqrt(E / rho0), a
/// neo-Hookean solid in Gong's (4.5) form (our `volumetric: log_j`), plane strain in 2-D. The Lame
/// constants follow the corrected relation (extraction A3): lambda = E nu / ((1 + nu)(1 - 2 nu)).
struct ManufacturedSolution {
  double G = 1e-4;
  double E = 1e7, nu = 0.3, rho0 = 1e3;
  [[nodiscard]] double lambda() const { return E * nu / ((1 + nu) * (1 - 2 * nu)); }
  [[nodiscard]] double mu() const { return E / (2 * (1 + nu)); }
  [[nodiscard]] double c() const;  // sqrt(E / rho0): the solution's parameter, not the wave speed (A4)

  // Per axis (the problem separates): X is the Lagrangian coordinate along that axis.
  [[nodiscard]] double U(double X, double t) const;  // displacement (4.35)
  [[nodiscard]] double V(double X, double t) const;  // velocity (4.37)
  [[nodiscard]] double F(double X, double t) const;  // stretch F_aa (4.36), (4.44)

  /// Body force per unit mass (4.39) / (4.46) at the Lagrangian position X.
  template <int D>
  [[nodiscard]] Vec<D> body_force(const Vec<D>& X, double t) const;
  /// Exact Cauchy stress (in-plane block), sigma = [lambda ln J I + mu (F F^T - I)] / J.
  template <int D>
  [[nodiscard]] Mat<D> stress(const Vec<D>& X, double t) const;
  /// Exact density rho0 / J.
  template <int D>
  [[nodiscard]] double density(const Vec<D>& X, double t) const;
};

struct MmsOptions {
  int dim = 1;  // 1: the bar (§4.5); 2: the axis-aligned square (§4.7)
  ShapeKind shape = ShapeKind::Linear;
  Mapping mapping = Mapping::MPM;  // impm: Gong ch. 5; mls_velocity with cpdi1: improved CPDI (§6.6)
  double amplitude = 1e-4;         // G
  int particles_per_cell = 2;      // per direction, cell-centred (extraction A1, A2)
  double end_time = 0.02;          // T: one period (A9)
  int threads = 1;
  // Zero the constrained components of the old node velocity too (extraction A24, Gong's loop);
  // false: matpoint's default (Nairn 2026), where the FLIP increment carries the wall reaction.
  // Both are input choices (solver.constrain_old_velocity).
  bool constrain_old_velocity = true;
};

/// "Gong walls (solver.constrain_old_velocity = true)" or the default's text: every check names it.
std::string wall_treatment(const MmsOptions& options);

/// Errors at T by particle quadrature with the current volumes V_p = M_p / rho_p (extraction A8):
/// E_q = sqrt(sum_p V_p |q_p - q(X_p, T)|^2), the particle velocity against V(X_p, T - dt / 2)
/// (leapfrog: the particle velocity after the last step is v^{n-1/2}). Grid velocity (A8, the
/// dissertation's MLS device): the numerical v_p^{n-1/2} and the exact V(X_p, t^{n-1/2}) are both
/// mapped to the nodes from x_p^n by linear MLS with the cubic weight and compared with weight h^D
/// per node; constrained components on the walls are left out (zero in both).
struct MmsResult {
  int cells = 0;  // per direction
  double h = 0, dt = 0;
  long steps = 0;
  bool finished = false;  // false: a numerical guard stopped the run (det F <= 0, NaN, ...)
  std::string message;    // the guard's message when not finished
  bool inverted = false;  // the guard that stopped it was det F <= 0 (a particle turned inside out)
  double displacement = 0, stress = 0, density = 0, velocity = 0, grid_velocity = 0;
  double min_jacobian = 1, max_jacobian = 1;
};

/// The problem as an input Spec (grid [0,1]^D with `cells` per direction, one body filling it,
/// neo-Hookean log_j, USL, FLIP, F = (I + dt L) F, dt = 0.4 h / c with T / dt = 5 cells, fixed
/// ends in 1-D, roller walls in 2-D). The initial velocity and the body force are set on the
/// Simulation by run_mms.
Spec mms_spec(const MmsOptions& options, int cells);

/// One run at `cells` cells per direction; never throws on a numerical failure (it is reported in
/// the result), throws InputError on bad options.
MmsResult run_mms(const MmsOptions& options, int cells);

/// Least-squares slope of log(error) against log(h).
double least_squares_order(const std::vector<double>& h, const std::vector<double>& error);

/// The quantities whose orders are measured.
inline const std::array<const char*, 5> kMmsQuantities{"displacement", "stress", "density", "velocity",
                                                       "grid_velocity"};
double mms_quantity(const MmsResult& r, const std::string& quantity);

/// What a source claims about an observed order, and how the claim is tested.
///  AtLeast: "order p" for a method whose order p is its highest: pass when measured >= p - margin.
///  Near: "order p" for p < 2 (e.g. first order): pass when |measured - p| <= margin, so that a
///    first-order claim cannot be met by a second-order result.
///  NoConvergence: "does not converge": pass only on the specific failure the source describes,
///    never on NaN: either every run of the range finished with finite errors, the order is below
///    kNoConvergenceOrder and the finest error is above half the coarsest (extraction T6), or a run of
///    the range was stopped by the det F <= 0 guard (extraction §8, A29).
enum class OrderClaim { AtLeast, Near, NoConvergence };

/// The one margin on every order claim: "expected 2, pass >= 1.8"; "expected 1, pass 0.8 .. 1.2".
/// It allows for the pre-asymptotic first mesh of the fit range, not for a different order.
inline constexpr double kOrderMargin = 0.2;
inline constexpr double kNoConvergenceOrder = 0.5;  // extraction T6, T10

/// An acceptance threshold on an observed order.
struct OrderExpectation {
  std::string quantity;  // one of kMmsQuantities
  OrderClaim claim = OrderClaim::AtLeast;
  double expected = 2.0;  // the order the source claims (0 for no convergence)
  std::string source;
  int from_cells = 8, to_cells = 64;  // the fit range (cells per direction); skipped if < 2 runs in it
};

/// An acceptance threshold on an error value at one resolution (e.g. extraction T7's E_stress(1/64)).
struct ErrorLimit {
  std::string quantity;
  int cells = 64;
  double below = 0;
  std::string source;
};

struct VerificationCase {
  std::string name;     // e.g. "mms-1d/linear/G=0.0001"
  std::string problem;  // "mms-1d" or "mms-2d"
  MmsOptions options;
  std::vector<int> cells;  // resolutions (cells per direction)
  std::vector<OrderExpectation> expectations;
  std::vector<ErrorLimit> error_limits;
};

/// One check of the report: {name, method, measured, expected, tolerance, relation, pass, source,
/// kind}: `relation` ">=" passes at measured >= expected - tolerance, "~" at |measured - expected| <=
/// tolerance, "<" at measured < expected (tolerance 0), "no convergence" as OrderClaim::NoConvergence
/// (expected = the order bound). `kind` is "verification" (an independent reference) for every
/// built-in check.
struct VerificationCheck {
  std::string name, method, relation, source;
  double measured = 0, expected = 0, tolerance = 0;
  bool pass = false;
  std::string kind = "verification";
};

struct VerificationOutcome {
  VerificationCase spec;
  std::vector<MmsResult> runs;
  std::vector<double> orders;  // per kMmsQuantities, over the finished runs (NaN if fewer than 2)
  std::vector<VerificationCheck> checks;
  [[nodiscard]] bool pass() const;
};

/// The order claims (Gong 2015, extraction §8, §10) that apply to a problem, basis and amplitude.
std::vector<OrderExpectation> expected_orders(int dim, ShapeKind shape, double amplitude);

/// The built-in suite: short resolutions for CI, or the papers' (`full`).
std::vector<VerificationCase> verification_suite(bool full);

/// A case for a problem name ("mms-1d", "mms-2d") with a chosen basis, mapping and amplitude, the
/// wall treatment (true: Gong's) and the time of the error measurement (T = one period, or T / 4).
VerificationCase make_case(const std::string& problem, ShapeKind shape, double amplitude, bool full,
                           Mapping mapping = Mapping::MPM, bool gong_walls = true, double end_time = 0.02);

/// The expectations at T / 4 (extraction §8, "two traps" 1, and A9): the exact strain is not zero
/// there, so the cellwise-constant strain error of linear elements makes the particle stress
/// first order while displacement and velocity stay second order.
std::vector<OrderExpectation> quarter_period_orders(int dim, ShapeKind shape, Mapping mapping,
                                                    double amplitude);

/// The expectations of extraction §10 for IMPM (T7, T8, T11) and improved CPDI (T12-like, T14).
std::vector<OrderExpectation> expected_orders(int dim, ShapeKind shape, Mapping mapping, double amplitude);

/// Cross-method checks (extraction T14, T15): at the resolutions h = 1/512, 1/1024, 1/2048 present
/// in both, the stress error of improved CPDI and of IMPM is below CPDI's (1-D, same amplitude).
std::vector<VerificationCheck> comparison_checks(const std::vector<VerificationOutcome>& outcomes);

/// The label of a method: the shape name, "impm" or "improved-cpdi" (cpdi1/cpdi2 + MLS velocity).
std::string method_name(ShapeKind shape, Mapping mapping);

/// The check of one order claim on the runs of a case (those inside the claim's mesh range); none
/// when fewer than two runs fall in the range.
std::optional<VerificationCheck> order_check(const VerificationCase& c, const OrderExpectation& x,
                                             const std::vector<MmsResult>& runs);

/// Runs every resolution of a case; `on_run` (optional) is called after each.
VerificationOutcome run_case(const VerificationCase& c,
                             const std::function<void(const MmsResult&)>& on_run = {});

/// {name, method, measured, expected, tolerance, pass, source} for every check (and `extra`).
nlohmann::json checks_json(const std::vector<VerificationOutcome>& outcomes,
                           const std::vector<VerificationCheck>& extra = {});

const char* shape_name(ShapeKind shape);

}  // namespace matpoint
