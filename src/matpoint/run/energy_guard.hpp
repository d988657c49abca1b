// The energy-growth guard: an explicit run that goes unstable gains energy from nowhere, often
// long before a particle leaves the grid or det F turns negative (Nairn's bar with cpGIMP and
// FMPM(16) at C = 0.2 grew its kinetic energy 25-fold and exited 0). The guard watches the energy
// balance B(t) = K + U + D - W_ext (kinetic, strain, friction and plastic work, external work), which an
// accurate run keeps at B(0), and stops the run (exit 3) when it rises by more than
// `solver.max_energy_growth` times the energy scale
//   E_scale(t) = max(K(0) + U(0), max |W_ext| over the output times so far and now),
// the energy the problem was given or has received (docs/input.md). A loss never trips it.
#pragma once

#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "matpoint/analysis/history.hpp"
#include "matpoint/core/errors.hpp"
#include "matpoint/explicit/simulation.hpp"
#include "matpoint/material/material.hpp"

namespace matpoint {

/// The scale every relative energy measure divides by (energy plots and checks use the same one).
struct EnergyScale {
  double initial = 0.0;        // K(0) + U(0)
  double external_work = 0.0;  // max |W_ext| seen so far
  [[nodiscard]] double value() const { return std::max(initial, external_work); }
};

class EnergyGuard {
 public:
  /// Steps between checks: the guard needs a pass over the particles (their strain energy), so
  /// it runs every few steps and at every output, not every step.
  static constexpr long kInterval = 10;

  /// `max_growth` empty: off. `history`: the run's rows so far (a restart's included): B(0) and
  /// the scale come from them, so a restarted run decides exactly as the uninterrupted one.
  /// `every_step`: check after every step (implicit solvers: a step's Newton solve costs far more
  /// than the pass, and a run that diverges between checks can reach a state where Newton's
  /// relative criteria are met on garbage); their advice is then about the time step, not Courant.
  EnergyGuard(std::optional<double> max_growth, const History& history, bool every_step = false)
      : max_growth_(max_growth), interval_(every_step ? 1 : kInterval), implicit_(every_step) {
    if (history.samples.empty()) return;
    const auto& first = history.samples.front();
    scale_.initial = first.kinetic_energy + first.strain_energy;
    balance0_ = balance(first.kinetic_energy, first.strain_energy, first.friction_work + first.plastic_work,
                        first.external_work);
    for (const auto& s : history.samples)
      scale_.external_work = std::max(scale_.external_work, std::abs(s.external_work));
  }

  /// Called after every step; `recorded`: the step was written to the history (its row counts
  /// in the scale). Throws NumericalFailure naming the step, the growth and the fastest particle.
  /// `other`: the energies of bodies that are not particles (FE bodies), called only when checked.
  template <int D, class OtherEnergy>
  void after_step(const Simulation<D>& sim, bool recorded, const OtherEnergy& other) {
    if (!max_growth_ || (!recorded && sim.step % interval_ != 0)) return;
    const auto [other_kinetic, other_strain, other_work] = other();
    // This rank's particle sums and its part of the accumulated works (one rank: the whole),
    // added over the ranks in rank order: every rank decides on the same bits (a collective).
    std::vector<double> sums{kinetic_energy(sim.particles), strain_energy<D>(sim.materials, sim.particles),
                             plastic_work<D>(sim.particles), sim.friction_work, sim.external_work};
    sim.comm.sum(sums);
    const double external = sums[4] + other_work;
    if (recorded) scale_.external_work = std::max(scale_.external_work, std::abs(external));
    const double scale = std::max(scale_.value(), std::abs(external));
    const double b = balance(sums[0] + other_kinetic, sums[1] + other_strain, sums[3] + sums[2], external);
    if (!(scale > 0.0)) return;  // nothing given, nothing received: nothing to compare with
    const double growth = (b - balance0_) / scale;
    if (growth <= *max_growth_ && std::isfinite(b)) return;
    std::ostringstream what;
    what << "energy balance K + U + D - W_ext = " << b << " rose from " << balance0_ << " by " << growth
         << " times the energy scale " << scale << " (solver.max_energy_growth = " << *max_growth_
         << (implicit_ ? "): the run is unstable; lower solver.dt or look for the particles that go first"
                       : "): the run is unstable; lower solver.courant (docs/theory/stability.md)");
    throw NumericalFailure(sim.step, sim.time, fastest_particle(sim), what.str());
  }

 private:
  /// dissipated: friction and plastic work.
  static double balance(double kinetic, double strain, double dissipated, double external) {
    return kinetic + strain + dissipated - external;
  }
  template <int D>
  static double kinetic_energy(const ParticleSet<D>& ps) {
    const auto n = static_cast<std::ptrdiff_t>(ps.size());
    double k = 0.0;
#pragma omp parallel for schedule(static) if (n > kParallelMinimum) reduction(+ : k)
    for (std::ptrdiff_t p = 0; p < n; ++p) k += 0.5 * ps.mass[p] * ps.v[p].squaredNorm();
    return k;
  }
  /// The fastest particle of all ranks (a collective in a decomposed run: the rank holding it
  /// sends the words); "" when there is none.
  template <int D>
  static std::string fastest_particle(const Simulation<D>& sim) {
    const auto& ps = sim.particles;
    std::ostringstream entity;
    double speed = -1.0;  // none here
    if (ps.size() > 0) {
      std::size_t fastest = 0;
      for (std::size_t p = 1; p < ps.size(); ++p)
        if (!(ps.v[p].squaredNorm() <= ps.v[fastest].squaredNorm())) fastest = p;
      speed = ps.v[fastest].squaredNorm();
      entity << "particle " << ps.id[fastest] << " (body " << ps.body[fastest]
             << ", the fastest: |v| = " << ps.v[fastest].norm() << ") at x = (" << ps.x[fastest].transpose()
             << ")";
    }
    if (!sim.comm.distributed()) return entity.str();
    const std::vector<double> speeds = sim.comm.all_gather(std::vector<double>{speed});
    int holder = 0;  // the lowest rank with the fastest (NaN counts as the fastest, as above)
    for (int r = 1; r < static_cast<int>(speeds.size()); ++r)
      if (!(speeds[static_cast<std::size_t>(r)] <= speeds[static_cast<std::size_t>(holder)])) holder = r;
    return sim.comm.broadcast(entity.str(), holder);
  }

  std::optional<double> max_growth_;
  long interval_ = kInterval;
  bool implicit_ = false;
  EnergyScale scale_;
  double balance0_ = 0.0;
};

}  // namespace matpoint
