// Quadrature rules of the element types (element_types.hpp).
#include "matpoint/mesh/element_types.hpp"

#include <cmath>
#include <string>

namespace matpoint::mesh {

namespace {

/// n-point Gauss-Legendre rule on [-1, 1], n = 1..4 (Abramowitz & Stegun, Table 25.4, closed forms).
QuadratureRule<1> gauss_legendre(int n) {
  QuadratureRule<1> r;
  auto add = [&r](double x, double w) {
    r.points.push_back(Vec<1>::Constant(x));
    r.weights.push_back(w);
  };
  if (n == 1) {
    add(0.0, 2.0);
  } else if (n == 2) {
    const double a = 1.0 / std::sqrt(3.0);
    add(-a, 1.0), add(a, 1.0);
  } else if (n == 3) {
    const double a = std::sqrt(0.6);
    add(-a, 5.0 / 9.0), add(0.0, 8.0 / 9.0), add(a, 5.0 / 9.0);
  } else {
    // x = sqrt(3/7 -+ 2/7 sqrt(6/5)), w = (18 +- sqrt 30) / 36.
    const double a = std::sqrt(3.0 / 7.0 - 2.0 / 7.0 * std::sqrt(1.2));
    const double b = std::sqrt(3.0 / 7.0 + 2.0 / 7.0 * std::sqrt(1.2));
    const double wa = (18.0 + std::sqrt(30.0)) / 36.0, wb = (18.0 - std::sqrt(30.0)) / 36.0;
    add(-b, wb), add(-a, wa), add(a, wa), add(b, wb);
  }
  return r;
}

/// Tensor product of the n-point Gauss-Legendre rule in Dim directions, first coordinate fastest.
template <int Dim>
QuadratureRule<Dim> tensor_rule(int n) {
  const QuadratureRule<1> g = gauss_legendre(n);
  QuadratureRule<Dim> r;
  int total = 1;
  for (int a = 0; a < Dim; ++a) total *= n;
  for (int k = 0; k < total; ++k) {
    Vec<Dim> x;
    double w = 1.0;
    for (int a = 0, rest = k; a < Dim; ++a, rest /= n) {
      x[a] = g.points[rest % n][0];
      w *= g.weights[rest % n];
    }
    r.points.push_back(x);
    r.weights.push_back(w);
  }
  return r;
}

/// Appends the centroid with weight w of the unit-area-normalised rule (reference area 1/2).
void add_centroid(QuadratureRule<2>& r, double w) {
  r.points.push_back(Vec<2>::Constant(1.0 / 3.0));
  r.weights.push_back(0.5 * w);
}

/// Appends the symmetric orbit of the barycentric point (a, a, 1 - 2a) (3 points) or
/// (a, b, 1 - a - b) (6 points) with weight w of the unit-area-normalised rule.
void add_orbit(QuadratureRule<2>& r, double a, double b, double w) {
  const double c = 1.0 - a - b;
  std::vector<std::array<double, 3>> orbit;
  if (a == b) {
    orbit = {{a, a, c}, {a, c, a}, {c, a, a}};
  } else {
    orbit = {{a, b, c}, {b, c, a}, {c, a, b}, {b, a, c}, {a, c, b}, {c, b, a}};
  }
  for (const auto& l : orbit) {
    r.points.push_back(Vec<2>(l[1], l[2]));
    r.weights.push_back(0.5 * w);  // reference triangle area 1/2
  }
}

/// Symmetric triangle rules with positive weights (Dunavant 1985, Int. J. Numer. Meth. Eng. 21,
/// 1129-1148, Table: degrees 1, 2, 4, 5, 6; degree 3 uses the degree-4 rule because Dunavant's
/// 4-point degree-3 rule has a negative weight). Degree 5 in closed form (Strang & Fix's 7-point
/// rule: a = (6 -+ sqrt 15)/21, w = (155 -+ sqrt 15)/1200, centroid 9/40). Dunavant's 15-digit
/// values of degrees 4 and 6 were refined to 30 digits by solving the moment equations (mpmath).
QuadratureRule<2> triangle_rule(int degree) {
  QuadratureRule<2> r;
  if (degree == 1) {
    add_centroid(r, 1.0);
  } else if (degree == 2) {
    add_orbit(r, 1.0 / 6.0, 1.0 / 6.0, 1.0 / 3.0);
  } else if (degree <= 4) {
    add_orbit(r, 0.445948490915964886318329253883, 0.445948490915964886318329253883,
              0.223381589678011465695007008433);
    add_orbit(r, 0.091576213509770743459571463402, 0.091576213509770743459571463402,
              0.109951743655321867638326324900);
  } else if (degree == 5) {
    const double s = std::sqrt(15.0);
    add_centroid(r, 9.0 / 40.0);
    add_orbit(r, (6.0 + s) / 21.0, (6.0 + s) / 21.0, (155.0 + s) / 1200.0);
    add_orbit(r, (6.0 - s) / 21.0, (6.0 - s) / 21.0, (155.0 - s) / 1200.0);
  } else {
    add_orbit(r, 0.063089014491502228340331602870, 0.063089014491502228340331602870,
              0.050844906370206816920936809106);
    add_orbit(r, 0.249286745170910421291638553107, 0.249286745170910421291638553107,
              0.116786275726379366025289611386);
    add_orbit(r, 0.053145049844816947353249671631, 0.310352451033784405416607733956,
              0.082851075618373575193553456421);
  }
  return r;
}

[[noreturn]] void bad_rule(const char* element, int n, int max) {
  throw std::invalid_argument(std::string("gauss_rule<") + element + ">: " + std::to_string(n) +
                              " is outside 1.." + std::to_string(max));
}

/// The rules 1..Max of one element type, built once on first use (thread-safe static).
template <class Element, int Max, class Build>
const QuadratureRule<Element::kDim>& cached(int n, Build build) {
  static const std::array<QuadratureRule<Element::kDim>, Max> rules = [&] {
    std::array<QuadratureRule<Element::kDim>, Max> all;
    for (int k = 1; k <= Max; ++k) all[k - 1] = build(k);
    return all;
  }();
  if (n < 1 || n > Max) bad_rule(Element::kName, n, Max);
  return rules[n - 1];
}

}  // namespace

template <>
const QuadratureRule<2>& gauss_rule<Q4>(int n) {
  return cached<Q4, 4>(n, tensor_rule<2>);
}
template <>
const QuadratureRule<2>& gauss_rule<Q9>(int n) {
  return cached<Q9, 4>(n, tensor_rule<2>);
}
template <>
const QuadratureRule<3>& gauss_rule<Hex8>(int n) {
  return cached<Hex8, 4>(n, tensor_rule<3>);
}
template <>
const QuadratureRule<2>& gauss_rule<BSpline2>(int n) {
  return cached<BSpline2, 4>(n, tensor_rule<2>);
}
template <>
const QuadratureRule<2>& gauss_rule<T3>(int n) {
  return cached<T3, 6>(n, triangle_rule);
}
template <>
const QuadratureRule<2>& gauss_rule<T6>(int n) {
  return cached<T6, 6>(n, triangle_rule);
}

const char* shape_name(ElementShape shape) {
  return visit_element_type(shape, [](auto e) { return decltype(e)::kName; });
}

}  // namespace matpoint::mesh
