// Particle domains as the domain-based bases see them, for output (ParaView) and tests: the
// corners of each particle's segment / quadrilateral / hexahedron in tensor order (see
// ParticleSet::corners).
#pragma once

#include <vector>

#include "matpoint/io/spec.hpp"
#include "matpoint/shape/cpdi_stencils.hpp"
#include "matpoint/shape/tensor_stencils.hpp"

namespace matpoint {

/// True for the bases that integrate over a particle domain (GIMP and CPDI families).
[[nodiscard]] constexpr bool has_particle_domains(ShapeKind shape) {
  return shape != ShapeKind::Linear && shape != ShapeKind::BSpline2 && shape != ShapeKind::BSpline3;
}

namespace detail {
template <class Basis, int D>
typename ParticleSet<D>::Corners gimp_box(const Grid<D>& grid, const ParticleSet<D>& ps, std::size_t p) {
  typename ParticleSet<D>::Corners c;
  Vec<D> l;
  for (int a = 0; a < D; ++a) l[a] = gimp_half_width<Basis, D>(grid, ps, p, a) * grid.h[a];
  for (int k = 0; k < ParticleSet<D>::kCorners; ++k)
    for (int a = 0; a < D; ++a) c[k][a] = ps.x[p][a] + ((k >> a & 1) != 0 ? l[a] : -l[a]);
  return c;
}
}  // namespace detail

/// Corners of every particle's domain under `shape`; empty for the point bases.
template <int D>
std::vector<typename ParticleSet<D>::Corners> particle_domains(ShapeKind shape, const Grid<D>& grid,
                                                               const ParticleSet<D>& ps) {
  std::vector<typename ParticleSet<D>::Corners> out;
  if (!has_particle_domains(shape)) return out;
  out.resize(ps.size());
  for (std::size_t p = 0; p < ps.size(); ++p) {
    switch (shape) {
      case ShapeKind::UGIMP:
      case ShapeKind::B2GIMP:
        out[p] = detail::gimp_box<UGimpBasis, D>(grid, ps, p);
        break;
      case ShapeKind::CpGIMP:
        out[p] = detail::gimp_box<CpGimpBasis, D>(grid, ps, p);
        break;
      case ShapeKind::CPDI2:
        out[p] = ps.corners[p];
        break;
      default:  // CPDI1, B2CPDI
        out[p] = parallelogram_corners<D>(ps, p);
        break;
    }
  }
  return out;
}

}  // namespace matpoint
