// Particles as a structure of arrays, kept sorted by cell (DESIGN.md: arrays, not objects).
#pragma once

#include "matpoint/core/types.hpp"

#include <vector>

namespace matpoint {

template <int D> struct ParticleSet {
  std::vector<Vec<D>> x;        // position
  std::vector<Vec<D>> v;        // velocity
  std::vector<double> mass;
  std::vector<double> volume0;  // initial volume
  std::vector<Vec<D>> size0;    // initial domain edge lengths (for domain-based bases)
  std::vector<Mat<D>> F;        // deformation gradient
  std::vector<Mat<D>> stress;   // Cauchy stress
  std::vector<Mat<D>> L;        // velocity gradient of the last stress update
  std::vector<int> material;    // index into the simulation's materials
  std::vector<int> body;        // index into the input's bodies
  std::vector<long> id;         // stable id: the generation order, unchanged by sorting
  // Per-material history: state_stride values per particle (0 for the elastic materials).
  int state_stride = 0;
  std::vector<double> state;

  [[nodiscard]] std::size_t size() const { return x.size(); }
  [[nodiscard]] double volume(std::size_t p) const { return volume0[p] * F[p].determinant(); }

  void add(const Vec<D>& position, const Vec<D>& velocity, double m, double vol, const Vec<D>& size,
           int material_id, int body_id) {
    id.push_back(static_cast<long>(x.size()));
    x.push_back(position);
    v.push_back(velocity);
    mass.push_back(m);
    volume0.push_back(vol);
    size0.push_back(size);
    F.push_back(Mat<D>::Identity());
    stress.push_back(Mat<D>::Zero());
    L.push_back(Mat<D>::Zero());
    material.push_back(material_id);
    body.push_back(body_id);
    state.resize(state.size() + state_stride, 0.0);
  }
};

}  // namespace matpoint
