// Finite element types of the implicit family's meshes (Aulisa & Capodaglio, implicit MPM-FEM,
// §4 and §11.1: Q9 Lagrange quadrilaterals; the others for Gmsh meshes and tests). One struct per
// type, all members static: a loop picks the type once (visit_element_type) and then calls the
// shape functions without virtual calls.
//
// Local node numbering (Gmsh's, which is also FEMuS's for Q9; Gmsh reference manual, "Node
// ordering"):
//   Q4/Q9  corners (-1,-1) (1,-1) (1,1) (-1,1) counter-clockwise, then the Q9 mid-sides of the
//          bottom, right, top and left edges, then the centre.
//   T3/T6  corners (0,0) (1,0) (0,1), then the T6 mid-sides of the edges 0-1, 1-2, 2-0.
//   Hex8   bottom face zeta = -1 corners (-1,-1) (1,-1) (1,1) (-1,1), then the same on zeta = +1.
// Faces (local node ids, corners first, ordered counter-clockwise seen from outside in 3-D):
//   Q4/Q9  0: eta = -1, 1: xi = +1, 2: eta = +1, 3: xi = -1 (Q9 adds the face's mid-side node).
//   T3/T6  0: edge 0-1, 1: edge 1-2, 2: edge 2-0.
//   Hex8   0: zeta = -1, 1: eta = -1, 2: xi = +1, 3: eta = +1, 4: xi = -1, 5: zeta = +1.
#pragma once

#include <array>
#include <cstdint>
#include <stdexcept>
#include <utility>
#include <vector>

#include "matpoint/core/types.hpp"

namespace matpoint::mesh {

enum class ElementShape { T3, T6, Q4, Q9, Hex8, BSpline2 };

/// Where an element lies in a patch, for element types whose shape functions depend on it (the
/// B-spline cells at a patch's ends, BSpline2); always 0 for the Lagrange elements, whose
/// `values` and `gradients` accept it and ignore it. A mesh keeps one per element
/// (Mesh::element_variant).
using ElementVariant = std::uint8_t;

namespace detail {

/// 1-D Lagrange polynomials on the nodes -1, 0, 1 (index 0, 1, 2) and their derivatives.
inline std::array<double, 3> lagrange2(double s) {
  return {0.5 * s * (s - 1.0), 1.0 - s * s, 0.5 * s * (s + 1.0)};
}
inline std::array<double, 3> lagrange2_derivative(double s) { return {s - 0.5, -2.0 * s, s + 0.5}; }

/// 1-D linear Lagrange polynomials on the nodes -1, 1 and their derivatives.
inline std::array<double, 2> lagrange1(double s) { return {0.5 * (1.0 - s), 0.5 * (1.0 + s)}; }
inline constexpr std::array<double, 2> kLagrange1Derivative = {-0.5, 0.5};

/// Reference-square membership with a tolerance: |xi_a| <= 1 + tolerance.
template <int D>
bool in_cube(const Vec<D>& xi, double tolerance) {
  return (xi.array().abs() <= 1.0 + tolerance).all();
}

/// Reference-triangle membership: xi >= -tol, eta >= -tol, xi + eta <= 1 + tol.
inline bool in_triangle(const Vec<2>& xi, double tolerance) {
  return xi[0] >= -tolerance && xi[1] >= -tolerance && xi[0] + xi[1] <= 1.0 + tolerance;
}

}  // namespace detail

/// Bilinear quadrilateral on [-1, 1]^2.
struct Q4 {
  static constexpr ElementShape kShape = ElementShape::Q4;
  /// The element of the corners alone; its values are the corner weights of a point (refinement).
  using Linear = Q4;
  static constexpr int kDim = 2, kNodes = 4, kDegree = 1, kCorners = 4;
  static constexpr bool kSimplex = false;
  static constexpr bool kNonNegative = true;  // shape values >= 0 inside the element
  static constexpr const char* kName = "q4";
  static constexpr int kFaces = 4, kNodesPerFace = 2;
  /// Tensor indices (0 = -1, 1 = +1) of each local node.
  static constexpr std::array<std::array<int, 2>, kNodes> kTensor = {{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};

  static Eigen::Matrix<double, kNodes, 1> values(const Vec<kDim>& xi, ElementVariant /*variant*/ = 0) {
    const auto a = detail::lagrange1(xi[0]), b = detail::lagrange1(xi[1]);
    Eigen::Matrix<double, kNodes, 1> n;
    for (int i = 0; i < kNodes; ++i) n[i] = a[kTensor[i][0]] * b[kTensor[i][1]];
    return n;
  }
  static Eigen::Matrix<double, kNodes, kDim> gradients(const Vec<kDim>& xi, ElementVariant /*variant*/ = 0) {
    const auto a = detail::lagrange1(xi[0]), b = detail::lagrange1(xi[1]);
    const auto& d = detail::kLagrange1Derivative;
    Eigen::Matrix<double, kNodes, kDim> g;
    for (int i = 0; i < kNodes; ++i) {
      g(i, 0) = d[kTensor[i][0]] * b[kTensor[i][1]];
      g(i, 1) = a[kTensor[i][0]] * d[kTensor[i][1]];
    }
    return g;
  }
  static Eigen::Matrix<double, kNodes, kDim> reference_nodes() {
    Eigen::Matrix<double, kNodes, kDim> r;
    for (int i = 0; i < kNodes; ++i)
      for (int a = 0; a < kDim; ++a) r(i, a) = 2.0 * kTensor[i][a] - 1.0;
    return r;
  }
  static Vec<kDim> centre() { return Vec<kDim>::Zero(); }
  static bool contains(const Vec<kDim>& xi, double tolerance) { return detail::in_cube<kDim>(xi, tolerance); }
  static std::array<std::array<int, kNodesPerFace>, kFaces> faces() {
    return {{{0, 1}, {1, 2}, {2, 3}, {3, 0}}};
  }
};

/// Biquadratic (9-node Lagrange) quadrilateral on [-1, 1]^2, the element of the paper's §11.
struct Q9 {
  static constexpr ElementShape kShape = ElementShape::Q9;
  /// The element of the corners alone; its values are the corner weights of a point (refinement).
  using Linear = Q4;
  static constexpr int kDim = 2, kNodes = 9, kDegree = 2, kCorners = 4;
  static constexpr bool kSimplex = false;
  static constexpr bool kNonNegative = false;  // the corner and mid-side functions dip below 0
  static constexpr const char* kName = "q9";
  static constexpr int kFaces = 4, kNodesPerFace = 3;
  /// Tensor indices (0, 1, 2 for -1, 0, 1) of each local node.
  static constexpr std::array<std::array<int, 2>, kNodes> kTensor = {
      {{0, 0}, {2, 0}, {2, 2}, {0, 2}, {1, 0}, {2, 1}, {1, 2}, {0, 1}, {1, 1}}};

  static Eigen::Matrix<double, kNodes, 1> values(const Vec<kDim>& xi, ElementVariant /*variant*/ = 0) {
    const auto a = detail::lagrange2(xi[0]), b = detail::lagrange2(xi[1]);
    Eigen::Matrix<double, kNodes, 1> n;
    for (int i = 0; i < kNodes; ++i) n[i] = a[kTensor[i][0]] * b[kTensor[i][1]];
    return n;
  }
  static Eigen::Matrix<double, kNodes, kDim> gradients(const Vec<kDim>& xi, ElementVariant /*variant*/ = 0) {
    const auto a = detail::lagrange2(xi[0]), b = detail::lagrange2(xi[1]);
    const auto da = detail::lagrange2_derivative(xi[0]), db = detail::lagrange2_derivative(xi[1]);
    Eigen::Matrix<double, kNodes, kDim> g;
    for (int i = 0; i < kNodes; ++i) {
      g(i, 0) = da[kTensor[i][0]] * b[kTensor[i][1]];
      g(i, 1) = a[kTensor[i][0]] * db[kTensor[i][1]];
    }
    return g;
  }
  static Eigen::Matrix<double, kNodes, kDim> reference_nodes() {
    Eigen::Matrix<double, kNodes, kDim> r;
    for (int i = 0; i < kNodes; ++i)
      for (int a = 0; a < kDim; ++a) r(i, a) = kTensor[i][a] - 1.0;
    return r;
  }
  static Vec<kDim> centre() { return Vec<kDim>::Zero(); }
  static bool contains(const Vec<kDim>& xi, double tolerance) { return detail::in_cube<kDim>(xi, tolerance); }
  static std::array<std::array<int, kNodesPerFace>, kFaces> faces() {
    return {{{0, 1, 4}, {1, 2, 5}, {2, 3, 6}, {3, 0, 7}}};
  }
};

/// Linear triangle on the reference triangle (0,0) (1,0) (0,1); N = barycentric coordinates.
struct T3 {
  static constexpr ElementShape kShape = ElementShape::T3;
  /// The element of the corners alone; its values are the corner weights of a point (refinement).
  using Linear = T3;
  static constexpr int kDim = 2, kNodes = 3, kDegree = 1, kCorners = 3;
  static constexpr bool kSimplex = true;
  static constexpr bool kNonNegative = true;  // shape values >= 0 inside the element
  static constexpr const char* kName = "t3";
  static constexpr int kFaces = 3, kNodesPerFace = 2;

  static Eigen::Matrix<double, kNodes, 1> values(const Vec<kDim>& xi, ElementVariant /*variant*/ = 0) {
    return {1.0 - xi[0] - xi[1], xi[0], xi[1]};
  }
  static Eigen::Matrix<double, kNodes, kDim> gradients(const Vec<kDim>& /*xi*/,
                                                       ElementVariant /*variant*/ = 0) {
    Eigen::Matrix<double, kNodes, kDim> g;
    g << -1.0, -1.0, 1.0, 0.0, 0.0, 1.0;
    return g;
  }
  static Eigen::Matrix<double, kNodes, kDim> reference_nodes() {
    Eigen::Matrix<double, kNodes, kDim> r;
    r << 0.0, 0.0, 1.0, 0.0, 0.0, 1.0;
    return r;
  }
  static Vec<kDim> centre() { return Vec<kDim>::Constant(1.0 / 3.0); }
  static bool contains(const Vec<kDim>& xi, double tolerance) { return detail::in_triangle(xi, tolerance); }
  static std::array<std::array<int, kNodesPerFace>, kFaces> faces() { return {{{0, 1}, {1, 2}, {2, 0}}}; }
};

/// Quadratic triangle: corners N = L(2L - 1), mid-sides N = 4 L_a L_b in the barycentric L
/// (Zienkiewicz & Taylor, The Finite Element Method, vol. 1, §8.8).
struct T6 {
  static constexpr ElementShape kShape = ElementShape::T6;
  /// The element of the corners alone; its values are the corner weights of a point (refinement).
  using Linear = T3;
  static constexpr int kDim = 2, kNodes = 6, kDegree = 2, kCorners = 3;
  static constexpr bool kSimplex = true;
  static constexpr bool kNonNegative = false;  // the corner functions dip below 0
  static constexpr const char* kName = "t6";
  static constexpr int kFaces = 3, kNodesPerFace = 3;

  static Eigen::Matrix<double, kNodes, 1> values(const Vec<kDim>& xi, ElementVariant /*variant*/ = 0) {
    const double l0 = 1.0 - xi[0] - xi[1], l1 = xi[0], l2 = xi[1];
    Eigen::Matrix<double, kNodes, 1> n;
    n << l0 * (2.0 * l0 - 1.0), l1 * (2.0 * l1 - 1.0), l2 * (2.0 * l2 - 1.0), 4.0 * l0 * l1, 4.0 * l1 * l2,
        4.0 * l2 * l0;
    return n;
  }
  static Eigen::Matrix<double, kNodes, kDim> gradients(const Vec<kDim>& xi, ElementVariant /*variant*/ = 0) {
    // dL0/dxi = (-1, -1), dL1/dxi = (1, 0), dL2/dxi = (0, 1).
    const double l0 = 1.0 - xi[0] - xi[1], l1 = xi[0], l2 = xi[1];
    Eigen::Matrix<double, kNodes, kDim> g;
    g << -(4.0 * l0 - 1.0), -(4.0 * l0 - 1.0),  //
        4.0 * l1 - 1.0, 0.0,                    //
        0.0, 4.0 * l2 - 1.0,                    //
        4.0 * (l0 - l1), -4.0 * l1,             //
        4.0 * l2, 4.0 * l1,                     //
        -4.0 * l2, 4.0 * (l0 - l2);
    return g;
  }
  static Eigen::Matrix<double, kNodes, kDim> reference_nodes() {
    Eigen::Matrix<double, kNodes, kDim> r;
    r << 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.5, 0.0, 0.5, 0.5, 0.0, 0.5;
    return r;
  }
  static Vec<kDim> centre() { return Vec<kDim>::Constant(1.0 / 3.0); }
  static bool contains(const Vec<kDim>& xi, double tolerance) { return detail::in_triangle(xi, tolerance); }
  static std::array<std::array<int, kNodesPerFace>, kFaces> faces() {
    return {{{0, 1, 3}, {1, 2, 4}, {2, 0, 5}}};
  }
};

/// Trilinear hexahedron on [-1, 1]^3.
struct Hex8 {
  static constexpr ElementShape kShape = ElementShape::Hex8;
  /// The element of the corners alone; its values are the corner weights of a point (refinement).
  using Linear = Hex8;
  static constexpr int kDim = 3, kNodes = 8, kDegree = 1, kCorners = 8;
  static constexpr bool kSimplex = false;
  static constexpr bool kNonNegative = true;  // shape values >= 0 inside the element
  static constexpr const char* kName = "hex8";
  static constexpr int kFaces = 6, kNodesPerFace = 4;
  /// Tensor indices (0 = -1, 1 = +1) of each local node.
  static constexpr std::array<std::array<int, 3>, kNodes> kTensor = {
      {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}};

  static Eigen::Matrix<double, kNodes, 1> values(const Vec<kDim>& xi, ElementVariant /*variant*/ = 0) {
    const auto a = detail::lagrange1(xi[0]), b = detail::lagrange1(xi[1]), c = detail::lagrange1(xi[2]);
    Eigen::Matrix<double, kNodes, 1> n;
    for (int i = 0; i < kNodes; ++i) n[i] = a[kTensor[i][0]] * b[kTensor[i][1]] * c[kTensor[i][2]];
    return n;
  }
  static Eigen::Matrix<double, kNodes, kDim> gradients(const Vec<kDim>& xi, ElementVariant /*variant*/ = 0) {
    const auto a = detail::lagrange1(xi[0]), b = detail::lagrange1(xi[1]), c = detail::lagrange1(xi[2]);
    const auto& d = detail::kLagrange1Derivative;
    Eigen::Matrix<double, kNodes, kDim> g;
    for (int i = 0; i < kNodes; ++i) {
      const auto& t = kTensor[i];
      g(i, 0) = d[t[0]] * b[t[1]] * c[t[2]];
      g(i, 1) = a[t[0]] * d[t[1]] * c[t[2]];
      g(i, 2) = a[t[0]] * b[t[1]] * d[t[2]];
    }
    return g;
  }
  static Eigen::Matrix<double, kNodes, kDim> reference_nodes() {
    Eigen::Matrix<double, kNodes, kDim> r;
    for (int i = 0; i < kNodes; ++i)
      for (int a = 0; a < kDim; ++a) r(i, a) = 2.0 * kTensor[i][a] - 1.0;
    return r;
  }
  static Vec<kDim> centre() { return Vec<kDim>::Zero(); }
  static bool contains(const Vec<kDim>& xi, double tolerance) { return detail::in_cube<kDim>(xi, tolerance); }
  static std::array<std::array<int, kNodesPerFace>, kFaces> faces() {
    return {{{0, 3, 2, 1}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}, {4, 5, 6, 7}}};
  }
};

namespace detail {

/// The three quadratic B-splines of one cell of a uniform open knot vector (Piegl & Tiller, The
/// NURBS Book, §2.2, eq. (2.5)) at the cell's local s = (xi + 1) / 2 in [0, 1], and their
/// derivatives with respect to xi. `end` says where the cell lies in its patch: 0 inside (knots
/// ..., k - 1, k, k + 1, k + 2, ...: the uniform splines), 1 first cell (knots 0, 0, 0, 1, 2),
/// 2 last cell (the mirror image), 3 the only cell (knots 0, 0, 0, 1, 1, 1: Bernstein). With open
/// knots the patch's end functions interpolate: at s = 0 of a first cell only the first is 1.
inline std::array<double, 3> bspline2(double xi, int end) {
  const double s = 0.5 * (xi + 1.0), r = 1.0 - s;
  switch (end) {
    case 1:
      return {r * r, s * (2.0 - 1.5 * s), 0.5 * s * s};
    case 2:
      return {0.5 * r * r, r * (2.0 - 1.5 * r), s * s};
    case 3:
      return {r * r, 2.0 * s * r, s * s};
    default:
      return {0.5 * r * r, 0.5 + s * r, 0.5 * s * s};
  }
}
inline std::array<double, 3> bspline2_derivative(double xi, int end) {
  const double s = 0.5 * (xi + 1.0), r = 1.0 - s;  // d/dxi = (1/2) d/ds
  switch (end) {
    case 1:
      return {-r, 1.0 - 1.5 * s, 0.5 * s};
    case 2:
      return {-0.5 * r, -(1.0 - 1.5 * r), s};
    case 3:
      return {-r, r - s, s};
    default:
      return {-0.5 * r, 0.5 * (r - s), 0.5 * s};
  }
}

}  // namespace detail

/// One cell of a 2-D patch of C1 quadratic B-splines on uniform open knot vectors (the smooth
/// background grid of B-spline MPM: Steffen, Kirby & Berzins 2008; for the implicit MPMs a
/// background whose gradients do not jump between elements, see docs/theory/implicit.md). The
/// cell is [-1, 1]^2 in xi; its nine "nodes" are the control points of the 3 x 3 splines that are
/// not zero on it, local node ix + 3 iy (ix, iy = 0, 1, 2 from low to high). The control points
/// sit at the Greville abscissae (the mean of each spline's inner knots: the patch's ends, then
/// h/2, 3h/2, ... from them), where they reproduce the affine map of the cell exactly. Each
/// element's ElementVariant says where it lies along each axis (2 bits per axis, x first: 0 inside,
/// 1 first, 2 last, 3 only cell; detail::bspline2). Values are >= 0 and sum to 1; at the patch's
/// sides only the side's row of control points is not zero, so a Dirichlet condition on a side's
/// control points is a Dirichlet condition on the side.
struct BSpline2 {
  static constexpr ElementShape kShape = ElementShape::BSpline2;
  static constexpr int kDim = 2, kNodes = 9, kDegree = 2, kCorners = 4;
  static constexpr bool kSimplex = false;
  static constexpr bool kNonNegative = true;  // B-splines are >= 0
  static constexpr const char* kName = "bspline2";
  /// A side's three control points (for FE bodies' faces and surface loads, which a B-spline mesh
  /// does not take: the input refuses them).
  static constexpr int kFaces = 4, kNodesPerFace = 3;

  /// Where the cell lies along axis a (0 inside, 1 first, 2 last, 3 only).
  static constexpr int end_along(ElementVariant variant, int axis) { return (variant >> (2 * axis)) & 3; }
  static constexpr ElementVariant variant_of(int end_x, int end_y) {
    return static_cast<ElementVariant>(end_x | (end_y << 2));
  }

  static Eigen::Matrix<double, kNodes, 1> values(const Vec<kDim>& xi, ElementVariant variant) {
    const auto a = detail::bspline2(xi[0], end_along(variant, 0));
    const auto b = detail::bspline2(xi[1], end_along(variant, 1));
    Eigen::Matrix<double, kNodes, 1> n;
    for (int iy = 0; iy < 3; ++iy)
      for (int ix = 0; ix < 3; ++ix) n[ix + 3 * iy] = a[ix] * b[iy];
    return n;
  }
  static Eigen::Matrix<double, kNodes, kDim> gradients(const Vec<kDim>& xi, ElementVariant variant) {
    const int ex = end_along(variant, 0), ey = end_along(variant, 1);
    const auto a = detail::bspline2(xi[0], ex), b = detail::bspline2(xi[1], ey);
    const auto da = detail::bspline2_derivative(xi[0], ex), db = detail::bspline2_derivative(xi[1], ey);
    Eigen::Matrix<double, kNodes, kDim> g;
    for (int iy = 0; iy < 3; ++iy)
      for (int ix = 0; ix < 3; ++ix) {
        g(ix + 3 * iy, 0) = da[ix] * b[iy];
        g(ix + 3 * iy, 1) = a[ix] * db[iy];
      }
    return g;
  }
  static Vec<kDim> centre() { return Vec<kDim>::Zero(); }
  static bool contains(const Vec<kDim>& xi, double tolerance) { return detail::in_cube<kDim>(xi, tolerance); }
  static std::array<std::array<int, kNodesPerFace>, kFaces> faces() {
    return {{{0, 1, 2}, {2, 5, 8}, {8, 7, 6}, {6, 3, 0}}};
  }
};

/// Quadrature points (reference coordinates) and weights; the weights sum to the reference
/// element's measure (4 for the square, 1/2 for the triangle, 8 for the cube).
template <int Dim>
struct QuadratureRule {
  std::vector<Vec<Dim>> points;
  std::vector<double> weights;
};

/// Quads and hexes: tensor Gauss-Legendre rule with points_per_direction = 1..4 (exact for
/// polynomials of degree 2n - 1 in each coordinate). Triangles: a symmetric rule with positive
/// weights exact for total degree points_per_direction = 1..6. Built once, shared (thread-safe).
/// Throws std::invalid_argument outside these ranges.
template <class Element>
const QuadratureRule<Element::kDim>& gauss_rule(int points_per_direction);

template <>
const QuadratureRule<2>& gauss_rule<Q4>(int points_per_direction);
template <>
const QuadratureRule<2>& gauss_rule<Q9>(int points_per_direction);
template <>
const QuadratureRule<2>& gauss_rule<T3>(int degree);
template <>
const QuadratureRule<2>& gauss_rule<T6>(int degree);
template <>
const QuadratureRule<3>& gauss_rule<Hex8>(int points_per_direction);
template <>
const QuadratureRule<2>& gauss_rule<BSpline2>(int points_per_direction);

/// Highest argument gauss_rule accepts for the element type.
template <class Element>
constexpr int max_gauss_rule() {
  return Element::kSimplex ? 6 : 4;
}

/// Runtime shape -> compile-time type: calls f(Q9{}) etc. Choose once per loop, not per point.
template <class F>
decltype(auto) visit_element_type(ElementShape shape, F&& f) {
  switch (shape) {
    case ElementShape::T3:
      return std::forward<F>(f)(T3{});
    case ElementShape::T6:
      return std::forward<F>(f)(T6{});
    case ElementShape::Q4:
      return std::forward<F>(f)(Q4{});
    case ElementShape::Q9:
      return std::forward<F>(f)(Q9{});
    case ElementShape::Hex8:
      return std::forward<F>(f)(Hex8{});
    case ElementShape::BSpline2:
      return std::forward<F>(f)(BSpline2{});
  }
  throw std::invalid_argument("visit_element_type: unknown element shape");
}

/// Like visit_element_type, for code that only makes sense in dimension D (a Mesh<D>): shapes of
/// another dimension throw std::invalid_argument instead of instantiating f for them.
template <int D, class F>
decltype(auto) visit_element_type_of_dim(ElementShape shape, F&& f) {
  if constexpr (D == 2) {
    switch (shape) {
      case ElementShape::T3:
        return std::forward<F>(f)(T3{});
      case ElementShape::T6:
        return std::forward<F>(f)(T6{});
      case ElementShape::Q4:
        return std::forward<F>(f)(Q4{});
      case ElementShape::Q9:
        return std::forward<F>(f)(Q9{});
      case ElementShape::BSpline2:
        return std::forward<F>(f)(BSpline2{});
      default:
        break;
    }
  } else if constexpr (D == 3) {
    if (shape == ElementShape::Hex8) return std::forward<F>(f)(Hex8{});
  }
  throw std::invalid_argument("element shape does not match the mesh dimension");
}

/// Spatial dimension of a shape (2 for T3, T6, Q4, Q9, BSpline2; 3 for Hex8).
constexpr int shape_dimension(ElementShape shape) { return shape == ElementShape::Hex8 ? 3 : 2; }

/// Lower-case name ("q9", ...) of a shape.
const char* shape_name(ElementShape shape);

}  // namespace matpoint::mesh
