// Surface loads on the faces of a mesh boundary (loads.tractions): the external force
//   f_I = int_face N_I t dA
// enters the residual as r_I -= f_I, with either
//   - a dead traction t (fixed vector, per unit length/area of the face as meshed, x~), or
//   - a pressure p (t = -p n, n the outward unit normal of the face's current position x~ + u~: a
//     follower load, so p n dA = p (dx/ds rotated) ds in 2-D and p (dx/ds x dx/dt) ds dt in 3-D,
//     and its derivative in u~, the load stiffness, comes with the AD Jacobian).
// Faces are the mesh's (mesh/element_types.hpp: corners counter-clockwise around a 2-D element, and
// counter-clockwise seen from outside a 3-D one), so the face's rotated tangent points outwards.
// Face shape functions: linear (2 nodes), quadratic (3 nodes: corners, then the mid-side node) and
// bilinear (4 corners of a hexahedron's face); Gauss rules with 3 points per direction, exact for
// straight faces.
#pragma once

#include <array>
#include <cmath>

#include "matpoint/core/dual.hpp"
#include "matpoint/core/types.hpp"
#include "matpoint/mesh/element_types.hpp"

namespace matpoint::implicit {

/// The load on one face at one time: a pressure (positive pushing into the body) or a traction.
template <int D>
struct FaceLoad {
  Index element = 0;
  int face = 0;
  bool follower = false;  // true: `pressure` acts; false: `traction` acts
  double pressure = 0.0;
  Vec<D> traction = Vec<D>::Zero();
};

/// Shape functions of a face with n nodes at face coordinates s (1 or 2 of them): values and
/// derivatives (one column per face coordinate).
template <int D, int NodesPerFace>
struct FaceShape;

template <>
struct FaceShape<2, 2> {
  static void at(const double* s, std::array<double, 2>& N, std::array<std::array<double, 1>, 2>& dN) {
    const auto n = mesh::detail::lagrange1(s[0]);
    N = n;
    dN = {{{mesh::detail::kLagrange1Derivative[0]}, {mesh::detail::kLagrange1Derivative[1]}}};
  }
};

template <>
struct FaceShape<2, 3> {  // corners at s = -1, +1, mid-side node at s = 0
  static void at(const double* s, std::array<double, 3>& N, std::array<std::array<double, 1>, 3>& dN) {
    const auto n = mesh::detail::lagrange2(s[0]), d = mesh::detail::lagrange2_derivative(s[0]);
    N = {n[0], n[2], n[1]};
    dN = {{{d[0]}, {d[2]}, {d[1]}}};
  }
};

template <>
struct FaceShape<3, 4> {  // corners (-1,-1) (1,-1) (1,1) (-1,1)
  static void at(const double* s, std::array<double, 4>& N, std::array<std::array<double, 2>, 4>& dN) {
    const auto a = mesh::detail::lagrange1(s[0]), b = mesh::detail::lagrange1(s[1]);
    const auto& d = mesh::detail::kLagrange1Derivative;
    constexpr int tensor[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int i = 0; i < 4; ++i) {
      N[static_cast<std::size_t>(i)] = a[tensor[i][0]] * b[tensor[i][1]];
      dN[static_cast<std::size_t>(i)] = {d[tensor[i][0]] * b[tensor[i][1]],
                                         a[tensor[i][0]] * d[tensor[i][1]]};
    }
  }
};

/// The face's nodes (rows) in the step's reference configuration x~.
template <class E>
using FaceNodes = Eigen::Matrix<double, E::kNodesPerFace, E::kDim>;

/// r -= int_face N_I t dA over one face: u and r hold the face nodes' D components each
/// (node-major, the face's node order of E::faces()), x the face nodes in x~.
template <class E, class S>
void add_surface_load_residual(const FaceNodes<E>& x, const FaceLoad<E::kDim>& load, const S* u, S* r) {
  constexpr int D = E::kDim, n = E::kNodesPerFace, face_dim = D - 1;
  constexpr double g = 0.7745966692414834;  // 3-point Gauss-Legendre: +-sqrt(3/5), weights 5/9, 8/9
  constexpr double points[3] = {-g, 0.0, g}, weights[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  const int count = face_dim == 1 ? 3 : 9;
  for (int q = 0; q < count; ++q) {
    const double s[2] = {points[q % 3], points[q / 3]};
    const double w = face_dim == 1 ? weights[q] : weights[q % 3] * weights[q / 3];
    std::array<double, n> N;
    std::array<std::array<double, face_dim>, n> dN;
    FaceShape<D, n>::at(s, N, dN);
    std::array<S, D> force;  // the force per unit face coordinate measure at this point
    if (load.follower) {
      // Tangents of the current face x~ + u~ along each face coordinate.
      std::array<std::array<S, D>, face_dim> t;
      for (int k = 0; k < face_dim; ++k)
        for (int i = 0; i < D; ++i) {
          S sum(0.0);
          for (int a = 0; a < n; ++a) {
            sum += x(a, i) * dN[static_cast<std::size_t>(a)][static_cast<std::size_t>(k)];
            add_product(sum, u[a * D + i], dN[static_cast<std::size_t>(a)][static_cast<std::size_t>(k)]);
          }
          t[static_cast<std::size_t>(k)][static_cast<std::size_t>(i)] = sum;
        }
      // Outward n dA: (t_y, -t_x) in 2-D, t_s x t_t in 3-D; the force is -p n dA.
      std::array<S, D> normal;
      if constexpr (D == 2) {
        normal = {t[0][1], -t[0][0]};
      } else {
        normal = {t[0][1] * t[1][2] - t[0][2] * t[1][1], t[0][2] * t[1][0] - t[0][0] * t[1][2],
                  t[0][0] * t[1][1] - t[0][1] * t[1][0]};
      }
      for (int i = 0; i < D; ++i)
        force[static_cast<std::size_t>(i)] = -load.pressure * normal[static_cast<std::size_t>(i)];
    } else {
      // |dX/ds| (2-D) or |dX/ds x dX/dt| (3-D) of the face as meshed.
      Eigen::Matrix<double, D, face_dim> T = Eigen::Matrix<double, D, face_dim>::Zero();
      for (int a = 0; a < n; ++a)
        for (int k = 0; k < face_dim; ++k)
          T.col(k) += x.row(a).transpose() * dN[static_cast<std::size_t>(a)][static_cast<std::size_t>(k)];
      double measure = 0.0;
      if constexpr (D == 2)
        measure = T.col(0).norm();
      else
        measure = Vec<3>(T.col(0)).cross(Vec<3>(T.col(1))).norm();
      for (int i = 0; i < D; ++i) force[static_cast<std::size_t>(i)] = S(load.traction[i] * measure);
    }
    for (int a = 0; a < n; ++a)
      for (int i = 0; i < D; ++i)
        r[a * D + i] -= force[static_cast<std::size_t>(i)] * (w * N[static_cast<std::size_t>(a)]);
  }
}

}  // namespace matpoint::implicit
