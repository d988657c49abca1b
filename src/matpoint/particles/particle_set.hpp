// Particles as a structure of arrays, kept sorted by cell (DESIGN.md: arrays, not objects).
// for_each_array (below) lists every per-particle array: a new one must be added there too, so
// that sorting (and, later, migration between ranks: docs/scale-out.md §5) carries it.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "matpoint/core/types.hpp"

namespace matpoint {

template <int D>
struct ParticleSet {
  static constexpr int kCorners = 1 << D;  // corners of a particle domain (segment, quad, hexahedron)
  using Corners = std::array<Vec<D>, kCorners>;
  std::vector<Vec<D>> x;  // position
  std::vector<Vec<D>> v;  // velocity
  std::vector<double> mass;
  std::vector<double> volume0;  // initial volume
  std::vector<Vec<D>> size0;    // initial domain edge lengths (for domain-based bases)
  std::vector<Mat<D>> F;        // deformation gradient
  std::vector<Mat<D>> stress;   // Cauchy stress
  // Out-of-plane Cauchy stress sigma_zz of plane strain (2-D only; empty in 1-D and 3-D): every
  // material computes it with F_zz = 1, and the writers give 2-D stress as 3 x 3 with it.
  std::vector<double> stress_zz;
  std::vector<Mat<D>> L;      // velocity gradient of the last stress update
  std::vector<int> material;  // index into the simulation's materials
  std::vector<int> body;      // index into the input's bodies
  std::vector<long> id;       // stable id: the generation order, unchanged by sorting
  // Lagrangian position X_p and initial velocity V_p(0), as generated (add() sets them to the
  // position and velocity given; build_simulation sets them again after the velocity noise).
  // Displacement u = x - X, probes, body forces B(X, t), the rms velocity change.
  std::vector<Vec<D>> x0;
  std::vector<Vec<D>> v0;
  // Per-material history: state_stride values per particle (0 for the elastic materials).
  int state_stride = 0;
  std::vector<double> state;
  // Per material index: 1 where its state has the plastic layout of material/hencky_plasticity.hpp
  // (equivalent plastic strain, yield state), for the writers. Set with state_stride.
  std::vector<char> plastic_material;
  // CPDI2 particle domains: corner positions, moved with the grid velocity (Gong 2015 eq. (6.28)).
  // Filled only when track_corners is set before the particles are added; corner c has the sign
  // +1 along axis a where bit a of c is set (tensor order: (-,-), (+,-), (-,+), (+,+) in 2-D).
  bool track_corners = false;
  std::vector<Corners> corners;
  // Coupled heat conduction (io/spec.hpp HeatSpec): temperature per particle, kept when
  // has_temperature is set (add() then starts a particle at 0); empty when off.
  bool has_temperature = false;
  std::vector<double> temperature;
  // The largest present wave speed max_p c_p (material/wave_speed.hpp) as the last update_stress
  // computed it beside the stresses, for the time step (stable_time_step with the recorded speed);
  // negative: unknown. It holds while F, state, material and the set of particles are as that
  // update left them (the order does not matter): update_deformation and add() reset it, and so
  // must any other code that writes F or state or adds or removes particles (a checkpoint read,
  // ExplicitSolver::restore; a migration between ranks).
  double recorded_wave_speed = -1.0;
  // The id the next add() gives: the number of particles generated so far, including those a
  // rank of a decomposed run generated and left to another rank (skip()).
  long next_id = 0;

  [[nodiscard]] std::size_t size() const { return x.size(); }
  [[nodiscard]] bool plastic(std::size_t p) const {
    const auto m = static_cast<std::size_t>(material[p]);
    return m < plastic_material.size() && plastic_material[m] != 0;
  }
  [[nodiscard]] double volume(std::size_t p) const { return volume0[p] * F[p].determinant(); }
  /// Half-extent of particle p's deformed domain along the unit vector n: the sum over its edges
  /// r_k = F e_k l_k / 2 of |r_k . n| (CPDI's |r1 . n| + |r2 . n|; Nairn 2026 extraction §2.5).
  [[nodiscard]] double half_extent(std::size_t p, const Vec<D>& n) const {
    return 0.5 * (F[p].transpose() * n).cwiseAbs().dot(size0[p]);
  }

  /// A particle generated for another rank: it takes the next id, and this set does not store it.
  void skip() { ++next_id; }

  void add(const Vec<D>& position, const Vec<D>& velocity, double m, double vol, const Vec<D>& size,
           int material_id, int body_id) {
    recorded_wave_speed = -1.0;
    id.push_back(next_id++);
    x.push_back(position);
    v.push_back(velocity);
    x0.push_back(position);
    v0.push_back(velocity);
    mass.push_back(m);
    volume0.push_back(vol);
    size0.push_back(size);
    F.push_back(Mat<D>::Identity());
    stress.push_back(Mat<D>::Zero());
    if constexpr (D == 2) stress_zz.push_back(0.0);
    L.push_back(Mat<D>::Zero());
    material.push_back(material_id);
    body.push_back(body_id);
    state.resize(state.size() + state_stride, 0.0);
    if (track_corners) {
      Corners c;
      for (int k = 0; k < kCorners; ++k)
        for (int a = 0; a < D; ++a) c[k][a] = position[a] + ((k >> a & 1) != 0 ? 0.5 : -0.5) * size[a];
      corners.push_back(c);
    }
    if (has_temperature) temperature.push_back(0.0);
  }
};

namespace particle_set_detail {

template <int D, class Set, class Fn>
void for_each_array(Set& ps, Fn&& fn) {
  fn("x", ps.x, std::size_t{1});
  fn("v", ps.v, std::size_t{1});
  fn("mass", ps.mass, std::size_t{1});
  fn("volume0", ps.volume0, std::size_t{1});
  fn("size0", ps.size0, std::size_t{1});
  fn("F", ps.F, std::size_t{1});
  fn("stress", ps.stress, std::size_t{1});
  if constexpr (D == 2) fn("stress_zz", ps.stress_zz, std::size_t{1});
  fn("L", ps.L, std::size_t{1});
  fn("material", ps.material, std::size_t{1});
  fn("body", ps.body, std::size_t{1});
  fn("id", ps.id, std::size_t{1});
  fn("x0", ps.x0, std::size_t{1});
  fn("v0", ps.v0, std::size_t{1});
  fn("state", ps.state, static_cast<std::size_t>(ps.state_stride));
  if (ps.track_corners) fn("corners", ps.corners, std::size_t{1});
  if (ps.has_temperature) fn("temperature", ps.temperature, std::size_t{1});
}

}  // namespace particle_set_detail

/// Calls fn(name, array, count) on every per-particle array of `ps` in use: `array` (a
/// std::vector) holds `count` elements per particle, particle p's at [p * count, (p + 1) * count):
/// state_stride doubles for `state` (count 0: no history), 1 for every other array. stress_zz is
/// visited in 2-D only, corners with track_corners, temperature with has_temperature; the
/// per-material plastic_material is not a particle array. Sorting and (later) migration use it, so
/// an array listed here cannot be left behind (docs/scale-out.md §5).
template <int D, class Fn>
void for_each_array(ParticleSet<D>& ps, Fn&& fn) {
  particle_set_detail::for_each_array<D>(ps, fn);
}
template <int D, class Fn>
void for_each_array(const ParticleSet<D>& ps, Fn&& fn) {
  particle_set_detail::for_each_array<D>(ps, fn);
}

}  // namespace matpoint
