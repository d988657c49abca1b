#include "matpoint/analysis/diagnostics.hpp"

#include <algorithm>
#include <cmath>

namespace matpoint {

template <int D> Diagnostics<D> measure_diagnostics(const Simulation<D>& sim, int body_count) {
  Diagnostics<D> d;
  const auto& ps = sim.particles;
  d.body_kinetic.assign(body_count, 0.0);
  d.body_strain.assign(body_count, 0.0);
  d.body_mass.assign(body_count, 0.0);
  d.body_momentum.assign(body_count, Vec<D>::Zero());
  d.body_com_position.assign(body_count, Vec<D>::Zero());
  d.min_jacobian = ps.size() ? ps.F[0].determinant() : 1.0;
  d.max_jacobian = d.min_jacobian;
  for (std::size_t p = 0; p < ps.size(); ++p) {  // serial: output times only, and deterministic
    const int b = ps.body[p];
    d.body_kinetic[b] += 0.5 * ps.mass[p] * ps.v[p].squaredNorm();
    d.body_momentum[b] += ps.mass[p] * ps.v[p];
    d.body_mass[b] += ps.mass[p];
    d.body_com_position[b] += ps.mass[p] * ps.x[p];
    const double J = ps.F[p].determinant();
    d.min_jacobian = std::min(d.min_jacobian, J);
    d.max_jacobian = std::max(d.max_jacobian, J);
    d.rms_velocity_change += (ps.v[p] - ps.v0[p]).squaredNorm();
  }
  d.rms_velocity_change = ps.size() ? std::sqrt(d.rms_velocity_change / static_cast<double>(ps.size())) : 0.0;
  for (int b = 0; b < body_count; ++b) {
    d.body_strain[b] = strain_energy<D>(sim.materials, ps, b);
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
