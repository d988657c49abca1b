// Forward-mode automatic differentiation: a dual number with a fixed number N of derivative slots
// (N = the element's dof count: 18 for a 2-D Q9 element, 24 for Hex8). The implicit solver's element
// residuals are templates on the scalar type; instantiated with Dual<N> seeded on the element's
// dofs they give the residual and the exact element Jacobian in one pass (Aulisa & Capodaglio,
// implicit MPM-FEM §3.3: the Jacobian by automatic differentiation of the element residual).
//
// Why our own type and not Eigen's AutoDiffScalar<Matrix<double, N, 1>>: bench/bench_ad.cpp measures
// one Q9 element residual + 18 x 18 Jacobian with 9 particles both ways (numbers in
// implicit/ad_jacobian.hpp). Plain loops over std::array let GCC vectorise each operation, while
// AutoDiffScalar builds expression templates of Eigen vectors (with EIGEN_DONT_VECTORIZE, see the
// top CMakeLists.txt) and copies them on every mixed double/AD operation.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>

namespace matpoint {

template <int N>
struct Dual {
  /// The derivative array is padded to whole 64-byte lines and aligned: every operation is then a
  /// loop of full-width vector instructions, and copies never split a vector (a store of one
  /// width followed by a load of another stalls store forwarding; measured 3x slower unpadded).
  static constexpr int kPadded = (N + 7) / 8 * 8;
  alignas(64) std::array<double, kPadded> d{};  // derivatives with respect to the N seeded variables
  double v = 0.0;                               // value

  Dual() = default;
  Dual(double value) : v(value) {}  // NOLINT(google-explicit-constructor): constants mix freely
  /// Variable number `slot`: derivative 1 in that slot, 0 elsewhere.
  static Dual variable(double value, int slot) {
    Dual x(value);
    x.d[static_cast<std::size_t>(slot)] = 1.0;
    return x;
  }

  Dual& operator+=(const Dual& b) {
    v += b.v;
    for (int k = 0; k < Dual<N>::kPadded; ++k) d[k] += b.d[k];
    return *this;
  }
  Dual& operator-=(const Dual& b) {
    v -= b.v;
    for (int k = 0; k < Dual<N>::kPadded; ++k) d[k] -= b.d[k];
    return *this;
  }
  Dual& operator*=(const Dual& b) {
    for (int k = 0; k < Dual<N>::kPadded; ++k) d[k] = d[k] * b.v + v * b.d[k];
    v *= b.v;
    return *this;
  }
  Dual& operator/=(const Dual& b) {
    const double inv = 1.0 / b.v;
    const double q = v * inv;
    for (int k = 0; k < Dual<N>::kPadded; ++k) d[k] = (d[k] - q * b.d[k]) * inv;
    v = q;
    return *this;
  }
  Dual& operator+=(double b) {
    v += b;
    return *this;
  }
  Dual& operator-=(double b) {
    v -= b;
    return *this;
  }
  Dual& operator*=(double b) {
    v *= b;
    for (int k = 0; k < Dual<N>::kPadded; ++k) d[k] *= b;
    return *this;
  }
  Dual& operator/=(double b) { return *this *= 1.0 / b; }
};

template <int N>
Dual<N> operator-(const Dual<N>& a) {
  Dual<N> r;
  r.v = -a.v;
  for (int k = 0; k < Dual<N>::kPadded; ++k) r.d[k] = -a.d[k];
  return r;
}
template <int N>
Dual<N> operator+(Dual<N> a, const Dual<N>& b) {
  return a += b;
}
template <int N>
Dual<N> operator-(Dual<N> a, const Dual<N>& b) {
  return a -= b;
}
template <int N>
Dual<N> operator*(Dual<N> a, const Dual<N>& b) {
  return a *= b;
}
template <int N>
Dual<N> operator/(Dual<N> a, const Dual<N>& b) {
  return a /= b;
}
template <int N>
Dual<N> operator+(Dual<N> a, double b) {
  return a += b;
}
template <int N>
Dual<N> operator-(Dual<N> a, double b) {
  return a -= b;
}
template <int N>
Dual<N> operator*(Dual<N> a, double b) {
  return a *= b;
}
template <int N>
Dual<N> operator/(Dual<N> a, double b) {
  return a /= b;
}
template <int N>
Dual<N> operator+(double a, Dual<N> b) {
  return b += a;
}
template <int N>
Dual<N> operator*(double a, Dual<N> b) {
  return b *= a;
}
template <int N>
Dual<N> operator-(double a, const Dual<N>& b) {
  Dual<N> r = -b;
  r.v += a;
  return r;
}
template <int N>
Dual<N> operator/(double a, const Dual<N>& b) {
  Dual<N> r;
  r.v = a / b.v;
  const double s = -r.v / b.v;
  for (int k = 0; k < Dual<N>::kPadded; ++k) r.d[k] = s * b.d[k];
  return r;
}

// Comparisons look at the value only (branches in a residual are frozen per evaluation).
template <int N>
bool operator<(const Dual<N>& a, const Dual<N>& b) {
  return a.v < b.v;
}
template <int N>
bool operator>(const Dual<N>& a, const Dual<N>& b) {
  return a.v > b.v;
}
template <int N>
bool operator<=(const Dual<N>& a, const Dual<N>& b) {
  return a.v <= b.v;
}
template <int N>
bool operator>=(const Dual<N>& a, const Dual<N>& b) {
  return a.v >= b.v;
}
template <int N>
bool operator==(const Dual<N>& a, const Dual<N>& b) {
  return a.v == b.v;
}
template <int N>
bool operator!=(const Dual<N>& a, const Dual<N>& b) {
  return a.v != b.v;
}

/// f(a) with f(a.v) and f'(a.v) given: the chain rule.
template <int N>
Dual<N> chain(const Dual<N>& a, double f, double df) {
  Dual<N> r;
  r.v = f;
  for (int k = 0; k < Dual<N>::kPadded; ++k) r.d[k] = df * a.d[k];
  return r;
}
template <int N>
Dual<N> log(const Dual<N>& a) {
  return chain(a, std::log(a.v), 1.0 / a.v);
}
template <int N>
Dual<N> exp(const Dual<N>& a) {
  const double e = std::exp(a.v);
  return chain(a, e, e);
}
template <int N>
Dual<N> sqrt(const Dual<N>& a) {
  const double s = std::sqrt(a.v);
  return chain(a, s, 0.5 / s);
}
template <int N>
Dual<N> abs(const Dual<N>& a) {
  return a.v < 0.0 ? -a : a;
}
template <int N>
Dual<N> pow(const Dual<N>& a, double p) {
  const double f = std::pow(a.v, p);
  return chain(a, f, p * std::pow(a.v, p - 1.0));
}
template <int N>
bool isfinite(const Dual<N>& a) {
  return std::isfinite(a.v);
}

/// acc += a * b in one pass (the inner loops of the element residuals: a dual times a shape-function
/// gradient). The generic form serves double and other scalar types.
template <class S>
void add_product(S& acc, const S& a, double b) {
  acc += a * b;
}
template <int N>
void add_product(Dual<N>& acc, const Dual<N>& a, double b) {
  acc.v += a.v * b;
  for (int k = 0; k < Dual<N>::kPadded; ++k) acc.d[k] += a.d[k] * b;
}

/// The value of a double or a dual number (for code templated on the scalar).
inline double value_of(double x) { return x; }
template <int N>
double value_of(const Dual<N>& x) {
  return x.v;
}

}  // namespace matpoint

namespace Eigen {

template <int N>
struct NumTraits<matpoint::Dual<N>> : NumTraits<double> {
  using Real = matpoint::Dual<N>;
  using NonInteger = matpoint::Dual<N>;
  using Nested = matpoint::Dual<N>;
  using Literal = double;
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    RequireInitialization = 1,
    ReadCost = 1,
    AddCost = N,
    MulCost = 2 * N
  };
};
// Products and sums of dual and double matrices (dual times a shape-function gradient).
template <int N, typename BinaryOp>
struct ScalarBinaryOpTraits<matpoint::Dual<N>, double, BinaryOp> {
  using ReturnType = matpoint::Dual<N>;
};
template <int N, typename BinaryOp>
struct ScalarBinaryOpTraits<double, matpoint::Dual<N>, BinaryOp> {
  using ReturnType = matpoint::Dual<N>;
};

}  // namespace Eigen
