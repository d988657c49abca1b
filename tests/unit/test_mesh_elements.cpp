// Element types of the implicit family's meshes (mesh/element_types.hpp): partition of unity,
// Kronecker delta at the nodes, polynomial reproduction to the element's degree, gradients against
// central differences, faces on the reference boundary, and Gauss rules against the analytic
// integrals of monomials (square/cube: prod 2/(k+1) for even k, 0 for odd; reference triangle:
// int x^i y^j = i! j! / (i + j + 2)!).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "matpoint/mesh/element_types.hpp"

namespace {

using namespace matpoint;
using namespace matpoint::mesh;

template <class E>
class ElementTypeTest : public ::testing::Test {};
using ElementTypes = ::testing::Types<Q4, Q9, T3, T6, Hex8>;
TYPED_TEST_SUITE(ElementTypeTest, ElementTypes);

/// Random points inside the reference element.
template <class E>
std::vector<Vec<E::kDim>> sample_points(int count) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec<E::kDim>> out;
  while (static_cast<int>(out.size()) < count) {
    Vec<E::kDim> xi;
    for (int a = 0; a < E::kDim; ++a) xi[a] = u(rng);
    if constexpr (E::kSimplex) xi = (xi.array() + 1.0) * 0.5;  // [0,1]^2, then keep the triangle
    if (E::contains(xi, 0.0)) out.push_back(xi);
  }
  return out;
}

/// Monomial prod xi_a^k_a.
template <int D>
double monomial(const Vec<D>& xi, const std::array<int, D>& k) {
  double v = 1.0;
  for (int a = 0; a < D; ++a) v *= std::pow(xi[a], k[a]);
  return v;
}

/// All exponent tuples of the element's polynomial space: each k_a <= degree for quads/hexes
/// (tensor Lagrange space), total degree <= degree for triangles.
template <class E>
std::vector<std::array<int, E::kDim>> element_space() {
  std::vector<std::array<int, E::kDim>> out;
  const int n = E::kDegree + 1;
  int total = 1;
  for (int a = 0; a < E::kDim; ++a) total *= n;
  for (int c = 0; c < total; ++c) {
    std::array<int, E::kDim> k{};
    int sum = 0;
    for (int a = 0, rest = c; a < E::kDim; ++a, rest /= n) sum += (k[a] = rest % n);
    if (!E::kSimplex || sum <= E::kDegree) out.push_back(k);
  }
  return out;
}

TYPED_TEST(ElementTypeTest, PartitionOfUnityAndZeroGradientSum) {
  using E = TypeParam;
  for (const auto& xi : sample_points<E>(50)) {
    EXPECT_NEAR(E::values(xi).sum(), 1.0, 1e-14);
    EXPECT_LT(E::gradients(xi).colwise().sum().cwiseAbs().maxCoeff(), 1e-13);
  }
}

TYPED_TEST(ElementTypeTest, KroneckerDeltaAtNodes) {
  using E = TypeParam;
  const auto nodes = E::reference_nodes();
  for (int j = 0; j < E::kNodes; ++j) {
    const Vec<E::kDim> xi = nodes.row(j).transpose();
    const auto n = E::values(xi);
    for (int i = 0; i < E::kNodes; ++i) EXPECT_NEAR(n[i], i == j ? 1.0 : 0.0, 1e-15) << i << " at " << j;
    EXPECT_TRUE(E::contains(xi, 1e-12));
  }
}

TYPED_TEST(ElementTypeTest, ReproducesItsPolynomialSpaceAndGradients) {
  using E = TypeParam;
  constexpr int D = E::kDim;
  const auto nodes = E::reference_nodes();
  for (const auto& k : element_space<E>()) {
    Eigen::Matrix<double, E::kNodes, 1> nodal;
    for (int i = 0; i < E::kNodes; ++i) nodal[i] = monomial<D>(nodes.row(i).transpose(), k);
    for (const auto& xi : sample_points<E>(20)) {
      EXPECT_NEAR(E::values(xi).dot(nodal), monomial<D>(xi, k), 1e-13);
      const Vec<D> grad = E::gradients(xi).transpose() * nodal;
      for (int a = 0; a < D; ++a) {
        if (k[a] == 0) {
          EXPECT_NEAR(grad[a], 0.0, 1e-13);
          continue;
        }
        auto km = k;
        --km[a];
        EXPECT_NEAR(grad[a], k[a] * monomial<D>(xi, km), 1e-13);
      }
    }
  }
}

TYPED_TEST(ElementTypeTest, GradientsMatchCentralDifferences) {
  using E = TypeParam;
  const double h = 1e-6;
  for (const auto& xi : sample_points<E>(20)) {
    const auto g = E::gradients(xi);
    for (int a = 0; a < E::kDim; ++a) {
      Vec<E::kDim> p = xi, m = xi;
      p[a] += h, m[a] -= h;
      const Eigen::Matrix<double, E::kNodes, 1> fd = (E::values(p) - E::values(m)) / (2.0 * h);
      EXPECT_LT((fd - g.col(a)).cwiseAbs().maxCoeff(), 1e-8);
    }
  }
}

TYPED_TEST(ElementTypeTest, FacesLieOnTheReferenceBoundaryAndCoverCorners) {
  using E = TypeParam;
  const auto nodes = E::reference_nodes();
  std::vector<int> corner_uses(E::kCorners, 0);
  for (const auto& face : E::faces()) {
    // All of a face's nodes share one boundary equation: a coordinate at +-1 (or 0 / 1 - sum).
    int shared = 0;
    for (int a = 0; a < E::kDim; ++a) {
      bool all = true;
      for (int i : face) all = all && nodes(i, a) == nodes(face[0], a);
      shared += all ? 1 : 0;
    }
    bool hypotenuse = true;
    for (int i : face) hypotenuse = hypotenuse && std::abs(nodes.row(i).sum() - 1.0) < 1e-15;
    EXPECT_TRUE(shared == 1 || (E::kSimplex && hypotenuse));
    for (int i : face)
      if (i < E::kCorners) ++corner_uses[i];
  }
  // Each corner lies on D faces.
  for (int c = 0; c < E::kCorners; ++c) EXPECT_EQ(corner_uses[c], E::kDim);
}

TYPED_TEST(ElementTypeTest, ContainsRejectsOutsidePoints) {
  using E = TypeParam;
  Vec<E::kDim> far = E::centre();
  far[0] = 1.1;
  EXPECT_FALSE(E::contains(far, 1e-12));
  EXPECT_TRUE(E::contains(far, 0.5));
  Vec<E::kDim> low = E::centre();
  low[E::kDim - 1] = -1.05;
  EXPECT_FALSE(E::contains(low, 1e-12));
  EXPECT_TRUE(E::contains(E::centre(), 0.0));
}

/// Exact integral of a monomial over the reference element.
template <class E>
double exact_integral(const std::array<int, E::kDim>& k) {
  if constexpr (E::kSimplex) {
    return std::tgamma(k[0] + 1.0) * std::tgamma(k[1] + 1.0) / std::tgamma(k[0] + k[1] + 3.0);
  } else {
    double v = 1.0;
    for (int ka : k) v *= ka % 2 == 0 ? 2.0 / (ka + 1) : 0.0;
    return v;
  }
}

TYPED_TEST(ElementTypeTest, GaussRulesIntegrateMonomialsExactlyToTheirDegree) {
  using E = TypeParam;
  constexpr int D = E::kDim;
  for (int n = 1; n <= max_gauss_rule<E>(); ++n) {
    const auto& rule = gauss_rule<E>(n);
    ASSERT_EQ(rule.points.size(), rule.weights.size());
    // Exact degree: 2n - 1 per coordinate (Gauss-Legendre) or total degree n (triangle rules).
    const int per = E::kSimplex ? n : 2 * n - 1;
    const int top = E::kSimplex ? n : 2 * n - 1;
    for (int c = 0; c < static_cast<int>(std::pow(top + 1, D)); ++c) {
      std::array<int, D> k{};
      int sum = 0;
      for (int a = 0, rest = c; a < D; ++a, rest /= top + 1) sum += (k[a] = rest % (top + 1));
      if (E::kSimplex && sum > per) continue;
      double q = 0.0;
      for (std::size_t p = 0; p < rule.points.size(); ++p)
        q += rule.weights[p] * monomial<D>(rule.points[p], k);
      EXPECT_NEAR(q, exact_integral<E>(k), 1e-15 * rule.points.size())
          << "rule " << n << " exponent " << k[0] << "," << k[1];
    }
    for (std::size_t p = 0; p < rule.points.size(); ++p) {
      EXPECT_GT(rule.weights[p], 0.0);
      EXPECT_TRUE(E::contains(rule.points[p], 0.0));
    }
  }
  EXPECT_THROW(gauss_rule<E>(0), std::invalid_argument);
  EXPECT_THROW(gauss_rule<E>(max_gauss_rule<E>() + 1), std::invalid_argument);
}

TEST(ElementTypes, GaussRuleIsNotExactBeyondItsDegree) {
  // The 2-point rule misses x^4 (2/5 exact, 2 * (1/3)^2 = 2/9 per direction), so the test above
  // would notice a rule of the wrong order.
  const auto& rule = gauss_rule<Q4>(2);
  double q = 0.0;
  for (std::size_t p = 0; p < rule.points.size(); ++p) q += rule.weights[p] * std::pow(rule.points[p][0], 4);
  EXPECT_NEAR(q, 2.0 * 2.0 / 9.0, 1e-15);
}

TEST(ElementTypes, VisitPicksTheCompileTimeType) {
  EXPECT_EQ(visit_element_type(ElementShape::Q9, [](auto e) { return decltype(e)::kNodes; }), 9);
  EXPECT_EQ(visit_element_type(ElementShape::T6, [](auto e) { return decltype(e)::kNodes; }), 6);
  EXPECT_EQ(visit_element_type(ElementShape::Hex8, [](auto e) { return decltype(e)::kDim; }), 3);
  EXPECT_STREQ(shape_name(ElementShape::T3), "t3");
  EXPECT_EQ(visit_element_type_of_dim<2>(ElementShape::Q4, [](auto e) { return decltype(e)::kNodes; }), 4);
  EXPECT_THROW(visit_element_type_of_dim<2>(ElementShape::Hex8, [](auto e) { return decltype(e)::kNodes; }),
               std::invalid_argument);
}

}  // namespace
