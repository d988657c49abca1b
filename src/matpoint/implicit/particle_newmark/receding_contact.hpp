// Receding-contact correction (Aulisa & Capodaglio §5, eq. (47) as corrected in the extraction, A3):
// for a particle moving away from a Dirichlet (or FEM-interface) face of its host element, the nodal
// displacements used to build F_p and the current gradients are replaced, node by node on the face, by
//   u*_a = (1 - C_c) u_a + C_c (4/3 u_mid(a) - 1/3 u_far(a)),
// the second-order one-sided extrapolation with zero normal derivative at the face (f'(-1) = 0 for a
// quadratic f through the three nodes of a line normal to the face). The switch (A4): the particle's
// old velocity along the face's inward normal is > 0, evaluated once per step (frozen during Newton).
#pragma once

#include <array>
#include <cstdint>

#include "matpoint/core/types.hpp"
#include "matpoint/mesh/element_types.hpp"

namespace matpoint::implicit {

/// Face triples (face node a, far node, mid node) per face; only the Q9 element has them (the
/// correction needs three nodes along each line normal to the face).
template <class E>
struct RecedingStencil {
  static constexpr bool kSupported = false;
};

/// Q9, local numbering of mesh/element_types.hpp (= FEMuS's): the extraction's §8 table.
template <>
struct RecedingStencil<mesh::Q9> {
  static constexpr bool kSupported = true;
  static constexpr std::array<std::array<std::array<int, 3>, 3>, 4> kTriples = {{
      {{{0, 3, 7}, {1, 2, 5}, {4, 6, 8}}},  // face 0, eta = -1
      {{{1, 0, 4}, {2, 3, 6}, {5, 7, 8}}},  // face 1, xi = +1
      {{{2, 1, 5}, {3, 0, 7}, {6, 4, 8}}},  // face 2, eta = +1
      {{{3, 2, 6}, {0, 1, 4}, {7, 5, 8}}},  // face 3, xi = -1
  }};
};

/// C_c per local face of one element (0: no correction on that face).
template <class E>
using FaceCoefficients = std::array<double, E::kFaces>;

/// Applies the correction in place to the element's nodal displacements u (node-major, D per node)
/// for every face whose bit is set in `faces`, face by face in increasing order (a corner shared
/// by two switched faces takes the second face's formula on the already corrected values).
template <class E, class S>
void apply_receding_correction(std::uint32_t faces, const FaceCoefficients<E>& coefficient, S* u) {
  static_assert(RecedingStencil<E>::kSupported, "the receding correction is written for Q9 elements");
  constexpr int D = E::kDim;
  for (int f = 0; f < E::kFaces; ++f) {
    if ((faces >> f & 1u) == 0) continue;
    const double c = coefficient[static_cast<std::size_t>(f)];
    for (const auto& [a, far, mid] : RecedingStencil<E>::kTriples[static_cast<std::size_t>(f)])
      for (int i = 0; i < D; ++i)
        u[a * D + i] =
            (1.0 - c) * u[a * D + i] + c * ((4.0 / 3.0) * u[mid * D + i] - (1.0 / 3.0) * u[far * D + i]);
  }
}

/// Inward unit normal of local face f of a 2-D element with nodes x (faces run counter-clockwise,
/// so the inward normal is the face's first-to-second-corner direction turned by +90 degrees).
template <class E>
Vec<2> inward_face_normal(const Eigen::Matrix<double, E::kNodes, 2>& x, int f) {
  const auto face = E::faces()[static_cast<std::size_t>(f)];
  const Vec<2> t = x.row(face[1]).transpose() - x.row(face[0]).transpose();
  return Vec<2>(-t[1], t[0]).normalized();
}

/// The velocity at t^n of the wall behind each face: 0 for a Dirichlet wall at rest, the FE body's
/// node velocity for the interface with an FE body (A4: the authors' code takes the face's mid-side node).
template <class E>
using FaceVelocities = std::array<Vec<2>, E::kFaces>;

/// Walls at rest behind every face (Eigen's vectors are not zeroed by default construction).
template <class E>
const FaceVelocities<E>& walls_at_rest() {
  static const FaceVelocities<E> zero = [] {
    FaceVelocities<E> v;
    v.fill(Vec<2>::Zero());
    return v;
  }();
  return zero;
}

/// The per-particle switch of A4: bit f set where face f has C_c > 0 and the particle's old velocity
/// relative to the wall has a positive component along the face's inward normal.
template <class E>
std::uint32_t receding_switches(const Eigen::Matrix<double, E::kNodes, 2>& x,
                                const FaceCoefficients<E>& coefficient, const Vec<2>& velocity_old,
                                const FaceVelocities<E>& wall_velocity = walls_at_rest<E>()) {
  std::uint32_t bits = 0;
  for (int f = 0; f < E::kFaces; ++f) {
    const Vec<2>& wall = wall_velocity[static_cast<std::size_t>(f)];
    if (coefficient[static_cast<std::size_t>(f)] > 0.0 &&
        (velocity_old - wall).dot(inward_face_normal<E>(x, f)) > 0.0)
      bits |= 1u << f;
  }
  return bits;
}

}  // namespace matpoint::implicit
