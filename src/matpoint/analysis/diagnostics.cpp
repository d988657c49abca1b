#include "matpoint/analysis/diagnostics.hpp"

#include <algorithm>
#include <cmath>

namespace matpoint {

template <int D> Diagnostics<D> measure_diagnostics(const Simulation<D>& sim, int body_count) {
  Diagnostics<D> d;
  const auto& ps = sim.particles;
  const auto bodies = static_cast<std::size_t>(body_count);
  // This rank's raw sums, in one vector for one reduction (docs/scale-out.md §7). Per body b at
  // b * kPerBody: 1/2 sum M|V|^2, sum M, sum M V (D), sum M X (D), strain energy; then the
  // sum of |V - V(0)|^2, the particle count and the plastic work.
  constexpr std::size_t kPerBody = 3 + 2 * D;
  std::vector<double> sums(kPerBody * bodies + 3, 0.0);
  const auto body_sum = [&](int b, std::size_t k) -> double& {
    return sums[kPerBody * static_cast<std::size_t>(b) + k];
  };
  double rms_sum = 0.0;
  // Extreme Jacobians: from the first particle on (as the serial code always did), +-infinity on
  // a rank without particles.
  double min_jacobian = ps.size() ? ps.F[0].determinant() : std::numeric_limits<double>::infinity();
  double max_jacobian = ps.size() ? min_jacobian : -std::numeric_limits<double>::infinity();
  for (std::size_t p = 0; p < ps.size(); ++p) {  // serial: output times only, and deterministic
    const int b = ps.body[p];
    body_sum(b, 0) += 0.5 * ps.mass[p] * ps.v[p].squaredNorm();
    body_sum(b, 1) += ps.mass[p];
    const Vec<D> momentum = ps.mass[p] * ps.v[p];
    const Vec<D> moment = ps.mass[p] * ps.x[p];
    for (int a = 0; a < D; ++a) {
      body_sum(b, 2 + a) += momentum[a];
      body_sum(b, 2 + D + a) += moment[a];
    }
    const double J = ps.F[p].determinant();
    min_jacobian = std::min(min_jacobian, J);
    max_jacobian = std::max(max_jacobian, J);
    rms_sum += (ps.v[p] - ps.v0[p]).squaredNorm();
  }
  for (int b = 0; b < body_count; ++b) body_sum(b, 2 + 2 * D) = strain_energy<D>(sim.materials, ps, b);
  const std::size_t tail = kPerBody * bodies;
  sums[tail] = rms_sum;
  sums[tail + 1] = static_cast<double>(ps.size());
  sums[tail + 2] = plastic_work<D>(ps);
  sim.comm.sum(sums);  // rank order: the same bits on every rank; one rank: unchanged
  std::vector<double> extremes{-min_jacobian, max_jacobian};
  sim.comm.max(extremes);

  const double count = sums[tail + 1];
  d.min_jacobian = count > 0 ? -extremes[0] : 1.0;
  d.max_jacobian = count > 0 ? extremes[1] : 1.0;
  d.rms_velocity_change = count > 0 ? std::sqrt(sums[tail] / count) : 0.0;
  d.plastic_work = sums[tail + 2];
  d.body_kinetic.assign(bodies, 0.0);
  d.body_strain.assign(bodies, 0.0);
  d.body_mass.assign(bodies, 0.0);
  d.body_momentum.assign(bodies, Vec<D>::Zero());
  d.body_com_position.assign(bodies, Vec<D>::Zero());
  for (int b = 0; b < body_count; ++b) {
    d.body_kinetic[b] = body_sum(b, 0);
    d.body_mass[b] = body_sum(b, 1);
    for (int a = 0; a < D; ++a) {
      d.body_momentum[b][a] = body_sum(b, 2 + a);
      d.body_com_position[b][a] = body_sum(b, 2 + D + a);
    }
    d.body_strain[b] = body_sum(b, 2 + 2 * D);
    d.kinetic_energy += d.body_kinetic[b];
    d.strain_energy += d.body_strain[b];
    d.momentum += d.body_momentum[b];
    if (d.body_mass[b] > 0.0) d.body_com_position[b] /= d.body_mass[b];
  }
  return d;
}

template Diagnostics<1> measure_diagnostics<1>(const Simulation<1>&, int);
template Diagnostics<2> measure_diagnostics<2>(const Simulation<2>&, int);
template Diagnostics<3> measure_diagnostics<3>(const Simulation<3>&, int);

}  // namespace matpoint
