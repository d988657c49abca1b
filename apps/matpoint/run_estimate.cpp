#include "run_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "matpoint/io/memory_estimate.hpp"

namespace matpoint {

namespace {

/// Million particle-steps per second on one thread, by basis, in 2-D and 3-D: bench/README.md
/// ("Cost per particle-step of each shape function", bench-2d / bench-3d, USL, FLIP). 1-D runs
/// are taken at twice the 2-D rate. FMPM(k), XPIC(k), contact and MLS mappings cost more.
double rate_per_thread(ShapeKind basis, int dim) {
  struct Rate {
    ShapeKind basis;
    double two_d, three_d;
  };
  static constexpr Rate kRates[] = {
      {ShapeKind::Linear, 11.5, 4.64}, {ShapeKind::BSpline2, 8.8, 2.84}, {ShapeKind::BSpline3, 6.4, 1.70},
      {ShapeKind::UGIMP, 6.9, 2.65},   {ShapeKind::CpGIMP, 6.8, 2.62},   {ShapeKind::B2GIMP, 5.2, 1.56},
      {ShapeKind::CPDI1, 4.8, 1.55},   {ShapeKind::CPDI2, 3.3, 0.83},    {ShapeKind::B2CPDI, 3.2, 0.79}};
  for (const auto& r : kRates)
    if (r.basis == basis) return 1e6 * (dim == 3 ? r.three_d : dim == 2 ? r.two_d : 2 * r.two_d);
  return 1e6;
}

std::string duration_text(double seconds) {
  char text[64];
  if (seconds < 60)
    std::snprintf(text, sizeof text, "%.2g s", seconds);
  else if (seconds < 3600)
    std::snprintf(text, sizeof text, "%.2g min", seconds / 60);
  else if (seconds < 86400 * 2)
    std::snprintf(text, sizeof text, "%.2g h", seconds / 3600);
  else
    std::snprintf(text, sizeof text, "%.2g days", seconds / 86400);
  return text;
}

/// Implicit particle-Newmark MPM (bench/README.md, examples/implicit-rolling-disk and
/// implicit-cantilever): the residual + AD Jacobian assembly runs at about 1.4 M particle points
/// per second on one thread, and Tests A and B take about 4 Newton iterations per step. The
/// sparse factorisation is left out: it depends on the mesh (a third of the step at 2e4 nodes).
constexpr double kImplicitPointsPerSecond = 1.4e6, kNewtonIterationsPerStep = 4.0;

}  // namespace

RunEstimate estimate_run(const Spec& spec) {
  RunEstimate e;
  e.particles = estimate_memory(spec).particles;
  const SolverSpec& solver = spec.solver;
  e.dt = solver.dt.value_or(0.0);
  e.implicit = solver.is_implicit();
  if (e.implicit && solver.implicit.dt_schedule) e.dt = (*solver.implicit.dt_schedule)(0.0);
  if (!solver.dt && !e.implicit) {  // as the run's first step: the fastest elastic (or bulk sound) wave
    double speed = 0.0, h = INFINITY;
    for (const auto& m : spec.materials)
      speed = std::max({speed, std::sqrt((m.lambda + 2.0 * m.mu) / m.density), m.bulk_sound_speed});
    for (int a = 0; a < spec.grid.dim; ++a) h = std::min(h, spec.grid.cell_size[a]);
    if (speed > 0.0) e.dt = solver.courant * h / speed;
  }
  if (!(e.dt > 0.0)) return e;
  e.steps = std::ceil(solver.end_time / e.dt * (1 - 1e-12));
  if (solver.max_steps > 0) e.steps = std::min(e.steps, static_cast<double>(solver.max_steps));
  e.seconds = e.implicit ? e.steps * kNewtonIterationsPerStep * e.particles / kImplicitPointsPerSecond
                         : e.steps * e.particles / rate_per_thread(solver.shape, spec.grid.dim);
  return e;
}

std::string describe(const RunEstimate& e) {
  char text[256];
  if (e.steps <= 0) {
    std::snprintf(text, sizeof text, "at most %.3g particles; no step estimate (no elastic wave speed)",
                  e.particles);
    return text;
  }
  std::snprintf(text, sizeof text,
                "about %.3g steps of dt = %.3g x at most %.3g particles: roughly %s on one thread%s", e.steps,
                e.dt, e.particles, duration_text(e.seconds).c_str(),
                e.implicit ? " (Newton's assembly; the sparse solves add more on fine meshes)" : "");
  return text;
}

}  // namespace matpoint
