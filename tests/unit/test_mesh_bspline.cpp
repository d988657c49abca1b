// The C1 quadratic B-spline patch (mesh/element_types.hpp BSpline2, structured_bspline2): each
// element's nine functions against the Cox-de Boor recursion on the open uniform knot vector (Piegl
// & Tiller, The NURBS Book, eq. (2.5)), evaluated independently here over the whole patch; partition
// of unity and values >= 0; the affine map reproduced by the control points at the Greville
// abscissae; value and gradient continuous across every element edge (C1); on a side only the
// side's control points are not zero; gradients against central differences; the patch's area and
// the point locator; the .vtu cells through the mapped corners.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <sstream>
#include <string>

#include "matpoint/implicit/element_geometry.hpp"
#include "matpoint/mesh/mesh_vtu.hpp"
#include "matpoint/mesh/point_locator.hpp"
#include "matpoint/mesh/structured_mesh.hpp"

namespace mesh_bspline_tests {

using namespace matpoint;
using namespace matpoint::mesh;

/// Open uniform knots of degree 2 on [a, b] with n cells: a, a, a, a + h, ..., b, b, b.
std::vector<double> open_knots(double a, double b, int n) {
  std::vector<double> t{a, a};
  for (int k = 0; k <= n; ++k) t.push_back(a + (b - a) * k / n);
  t.push_back(b), t.push_back(b);
  return t;
}

/// B-spline i of degree p on knots t at x (Cox-de Boor; the last span closed at its right end).
double cox_de_boor(const std::vector<double>& t, int i, int p, double x) {
  if (p == 0) {
    const auto i1 = static_cast<std::size_t>(i + 1);
    const bool last = t[i1] == t.back() && x == t.back();
    return (t[static_cast<std::size_t>(i)] <= x && (x < t[i1] || last) &&
            t[static_cast<std::size_t>(i)] < t[i1])
               ? 1.0
               : 0.0;
  }
  const auto ti = t[static_cast<std::size_t>(i)], tip = t[static_cast<std::size_t>(i + p)];
  const auto ti1 = t[static_cast<std::size_t>(i + 1)], tip1 = t[static_cast<std::size_t>(i + p + 1)];
  double v = 0.0;
  if (tip > ti) v += (x - ti) / (tip - ti) * cox_de_boor(t, i, p - 1, x);
  if (tip1 > ti1) v += (tip1 - x) / (tip1 - ti1) * cox_de_boor(t, i + 1, p - 1, x);
  return v;
}

struct Patch {
  double x0, x1, y0, y1;
  int nx, ny;
  Mesh<2> mesh;
  Patch(double ax, double bx, int cx, double ay, double by, int cy)
      : x0(ax),
        x1(bx),
        y0(ay),
        y1(by),
        nx(cx),
        ny(cy),
        mesh(structured_bspline2(AxisSpacing::uniform(ax, bx, cx), AxisSpacing::uniform(ay, by, cy))) {}
  [[nodiscard]] Index element_at(int i, int j) const { return static_cast<Index>(j) * nx + i; }
  /// The cell holding x (its lower-left cell on a shared edge) and xi in it.
  [[nodiscard]] std::pair<Index, Vec<2>> cell_of(const Vec<2>& x) const {
    const double hx = (x1 - x0) / nx, hy = (y1 - y0) / ny;
    const int i = std::min(nx - 1, static_cast<int>((x[0] - x0) / hx));
    const int j = std::min(ny - 1, static_cast<int>((x[1] - y0) / hy));
    const Vec<2> xi(2.0 * (x[0] - x0 - i * hx) / hx - 1.0, 2.0 * (x[1] - y0 - j * hy) / hy - 1.0);
    return {element_at(i, j), xi};
  }
};

/// The patches of the tests: several cells, two cells, one cell along an axis.
std::vector<Patch> patches() { return {Patch(0.0, 2.0, 5, -1.0, 1.0, 4), Patch(1.0, 1.5, 2, 0.0, 3.0, 1)}; }

TEST(BSplinePatch, NodesAreTheGrevilleAbscissaeAndElementsTheCells) {
  const Patch p(0.0, 2.0, 5, -1.0, 1.0, 4);
  ASSERT_EQ(p.mesh.node_count(), 7 * 6);
  ASSERT_EQ(p.mesh.element_count(), 5 * 4);
  const std::vector<double> gx{0.0, 0.2, 0.6, 1.0, 1.4, 1.8, 2.0};
  for (int i = 0; i < 7; ++i)
    EXPECT_NEAR(p.mesh.nodes[static_cast<std::size_t>(i)][0], gx[static_cast<std::size_t>(i)], 1e-15);
  EXPECT_EQ(p.mesh.node_sets.at("left").size(), 6U);
  for (Index n : p.mesh.node_sets.at("bottom")) EXPECT_EQ(p.mesh.nodes[static_cast<std::size_t>(n)][1], -1.0);
  EXPECT_NEAR(mesh_measure<2>(p.mesh, p.mesh.nodes), 4.0, 1e-13);
}

TEST(BSplinePatch, ElementFunctionsAreTheCoxDeBoorSplinesOfTheOpenKnots) {
  std::mt19937 rng(3);
  for (const Patch& p : patches()) {
    const auto tx = open_knots(p.x0, p.x1, p.nx), ty = open_knots(p.y0, p.y1, p.ny);
    std::uniform_real_distribution<double> ux(p.x0, p.x1), uy(p.y0, p.y1);
    const int columns = p.nx + 2;
    for (int k = 0; k < 400; ++k) {
      Vec<2> x(ux(rng), uy(rng));
      if (k == 0) x = Vec<2>(p.x0, p.y0);  // the corners: the open knots interpolate
      if (k == 1) x = Vec<2>(p.x1, p.y1);
      const auto [e, xi] = p.cell_of(x);
      const auto N = BSpline2::values(xi, p.mesh.element_variant(e));
      const auto ids = p.mesh.element_nodes(e);
      double sum = 0.0;
      for (int I = 0; I < 9; ++I) {
        const auto node = ids[static_cast<std::size_t>(I)];
        const int i = static_cast<int>(node % columns), j = static_cast<int>(node / columns);
        EXPECT_NEAR(N[I], cox_de_boor(tx, i, 2, x[0]) * cox_de_boor(ty, j, 2, x[1]), 1e-13)
            << "x = " << x.transpose();
        EXPECT_GE(N[I], 0.0);
        sum += N[I];
      }
      EXPECT_NEAR(sum, 1.0, 1e-14);
    }
  }
}

TEST(BSplinePatch, ControlPointsReproduceTheAffineMapOfEachCell) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const Patch& p : patches())
    for (Index e = 0; e < p.mesh.element_count(); ++e) {
      const auto X = implicit::gather_nodes<BSpline2>(p.mesh.nodes, p.mesh.element_nodes(e));
      const int i = static_cast<int>(e % p.nx), j = static_cast<int>(e / p.nx);
      const double hx = (p.x1 - p.x0) / p.nx, hy = (p.y1 - p.y0) / p.ny;
      for (int k = 0; k < 20; ++k) {
        const Vec<2> xi(u(rng), u(rng));
        const Vec<2> x = X.transpose() * BSpline2::values(xi, p.mesh.element_variant(e));
        EXPECT_NEAR(x[0], p.x0 + (i + 0.5 * (xi[0] + 1.0)) * hx, 1e-14);
        EXPECT_NEAR(x[1], p.y0 + (j + 0.5 * (xi[1] + 1.0)) * hy, 1e-14);
        double det = 0.0;
        implicit::physical_gradients<BSpline2>(X, xi, p.mesh.element_variant(e), &det);
        EXPECT_NEAR(det, 0.25 * hx * hy, 1e-14);
      }
    }
}

TEST(BSplinePatch, ValueAndGradientAreContinuousAcrossEveryEdge) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const Patch& p : patches()) {
    std::vector<double> f(static_cast<std::size_t>(p.mesh.node_count()));
    for (double& v : f) v = u(rng);
    const auto field = [&](Index e, const Vec<2>& xi, Vec<2>& gradient) {
      const auto X = implicit::gather_nodes<BSpline2>(p.mesh.nodes, p.mesh.element_nodes(e));
      const auto N = BSpline2::values(xi, p.mesh.element_variant(e));
      const auto G = implicit::physical_gradients<BSpline2>(X, xi, p.mesh.element_variant(e));
      double value = 0.0;
      gradient.setZero();
      const auto ids = p.mesh.element_nodes(e);
      for (int I = 0; I < 9; ++I) {
        const double fi = f[static_cast<std::size_t>(ids[static_cast<std::size_t>(I)])];
        value += N[I] * fi;
        gradient += fi * G.row(I).transpose();
      }
      return value;
    };
    int edges = 0;
    for (int j = 0; j < p.ny; ++j)
      for (int i = 0; i < p.nx; ++i)
        for (int axis = 0; axis < 2; ++axis) {
          if ((axis == 0 && i + 1 == p.nx) || (axis == 1 && j + 1 == p.ny)) continue;
          const Index e = p.element_at(i, j), n = axis == 0 ? p.element_at(i + 1, j) : p.element_at(i, j + 1);
          for (int k = 0; k < 5; ++k) {
            const double s = u(rng);
            const Vec<2> here = axis == 0 ? Vec<2>(1.0, s) : Vec<2>(s, 1.0);
            const Vec<2> there = axis == 0 ? Vec<2>(-1.0, s) : Vec<2>(s, -1.0);
            Vec<2> g1, g2;
            const double v1 = field(e, here, g1), v2 = field(n, there, g2);
            EXPECT_NEAR(v1, v2, 1e-13);
            EXPECT_NEAR((g1 - g2).norm(), 0.0, 1e-11 * (1.0 + g1.norm()));  // C1: no jump in the gradient
          }
          ++edges;
        }
    EXPECT_EQ(edges, (p.nx - 1) * p.ny + p.nx * (p.ny - 1));
  }
}

TEST(BSplinePatch, OnASideOnlyTheSidesControlPointsAreNotZero) {
  const Patch p(0.0, 2.0, 5, -1.0, 1.0, 4);
  for (const auto& [side, nodes] : p.mesh.node_sets) {
    const int axis = side == "left" || side == "right" ? 0 : 1;
    const double at = side == "left" ? p.x0 : side == "right" ? p.x1 : side == "bottom" ? p.y0 : p.y1;
    for (double s : {0.05, 0.3, 0.5, 0.77, 0.99}) {
      Vec<2> x = axis == 0 ? Vec<2>(at, p.y0 + s * (p.y1 - p.y0)) : Vec<2>(p.x0 + s * (p.x1 - p.x0), at);
      const auto [e, xi] = p.cell_of(x);
      const auto N = BSpline2::values(xi, p.mesh.element_variant(e));
      const auto ids = p.mesh.element_nodes(e);
      double on_side = 0.0;
      for (int I = 0; I < 9; ++I) {
        const bool member = std::binary_search(nodes.begin(), nodes.end(), ids[static_cast<std::size_t>(I)]);
        if (member)
          on_side += N[I];
        else
          EXPECT_NEAR(N[I], 0.0, 1e-15) << side;
      }
      EXPECT_NEAR(on_side, 1.0, 1e-14) << side;
    }
  }
}

TEST(BSplinePatch, GradientsMatchCentralDifferencesInEveryVariant) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-0.95, 0.95);
  const double h = 1e-6;
  for (int ex = 0; ex < 4; ++ex)
    for (int ey = 0; ey < 4; ++ey) {
      const ElementVariant v = BSpline2::variant_of(ex, ey);
      for (int k = 0; k < 10; ++k) {
        const Vec<2> xi(u(rng), u(rng));
        const auto G = BSpline2::gradients(xi, v);
        for (int a = 0; a < 2; ++a) {
          Vec<2> plus = xi, minus = xi;
          plus[a] += h, minus[a] -= h;
          const Eigen::Matrix<double, 9, 1> fd =
              (BSpline2::values(plus, v) - BSpline2::values(minus, v)) / (2.0 * h);
          EXPECT_LT((fd - G.col(a)).cwiseAbs().maxCoeff(), 1e-9) << "variant " << ex << ", " << ey;
        }
      }
    }
}

TEST(BSplinePatch, PointLocatorFindsTheCell) {
  const Patch p(0.0, 2.0, 5, -1.0, 1.0, 4);
  const PointLocator<2> locator(p.mesh, p.mesh.nodes);
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> ux(0.0, 2.0), uy(-1.0, 1.0);
  for (int k = 0; k < 200; ++k) {
    const Vec<2> x(ux(rng), uy(rng));
    const auto loc = locator.locate(x);
    ASSERT_TRUE(loc.has_value());
    const auto [e, xi] = p.cell_of(x);
    EXPECT_EQ(loc->element, e);
    EXPECT_NEAR((loc->xi - xi).norm(), 0.0, 1e-12);
  }
  EXPECT_FALSE(locator.locate(Vec<2>(2.1, 0.0)).has_value());
}

TEST(BSplinePatch, VtuCellsPassThroughTheMappedCorners) {
  const Patch p(0.0, 2.0, 5, -1.0, 1.0, 4);
  std::vector<Vec<2>> d(static_cast<std::size_t>(p.mesh.node_count()), Vec<2>(0.5, -0.25));  // a translation
  const std::string text = mesh_vtu<2>(p.mesh, &d);
  EXPECT_NE(text.find("NumberOfPoints=\"80\" NumberOfCells=\"20\""), std::string::npos);
  /// The numbers of the data array that follows `name`.
  const auto numbers_after = [&](const std::string& name) {
    std::istringstream in(text.substr(text.find('>', text.find(name)) + 1));
    std::vector<double> out;
    double v = 0.0;
    while (in >> v) out.push_back(v);
    return out;
  };
  const auto points = numbers_after("Name=\"Points\"");
  const auto moved = numbers_after("Name=\"displacement\"");
  ASSERT_GE(points.size(), 3U * 80U);
  ASSERT_GE(moved.size(), 3U * 80U);
  // Element 7 (i = 2, j = 1): corners (0.8, -0.5) (1.2, -0.5) (1.2, 0) (0.8, 0), counter-clockwise.
  const double corners[4][2] = {{0.8, -0.5}, {1.2, -0.5}, {1.2, 0.0}, {0.8, 0.0}};
  for (int c = 0; c < 4; ++c) {
    const auto k = static_cast<std::size_t>(3 * (4 * 7 + c));
    EXPECT_NEAR(points[k], corners[c][0], 1e-14);
    EXPECT_NEAR(points[k + 1], corners[c][1], 1e-14);
    EXPECT_NEAR(moved[k], 0.5, 1e-14);
    EXPECT_NEAR(moved[k + 1], -0.25, 1e-14);
  }
}

TEST(BSplinePatch, UnequalCellsAreRefused) {
  EXPECT_THROW(
      structured_bspline2(AxisSpacing::geometric(0.0, 1.0, 4, 1.5), AxisSpacing::uniform(0.0, 1.0, 2)),
      std::invalid_argument);
}

}  // namespace mesh_bspline_tests
