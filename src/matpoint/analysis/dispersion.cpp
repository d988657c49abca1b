#include "matpoint/analysis/dispersion.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <stdexcept>
#include <string>

namespace matpoint {

namespace {

using Complex = std::complex<double>;
constexpr Complex kI{0.0, 1.0};
constexpr double kPi = std::numbers::pi;

// Below this |theta| the closed forms are replaced by their limits (their relative error there is
// O(theta^2) < 1e-24).
constexpr double kTinyTheta = 1e-12;

// "Stable" means spectral radius <= 1 + kRadiusTolerance. At |M| = 1 the two leapfrog eigenvalues
// meet at -1 (a double root), where round-off moves them by about sqrt(machine epsilon) ~ 1e-8; the
// tolerance sits well above that. For |M| = 1 + d the radius is (|M| + sqrt(M^2 - 1))^2 ~ 1 + 2 sqrt(2 d),
// so the tolerance shifts a bound by d ~ (1e-6 / 2)^2 / 2 ~ 1e-13 relative.
constexpr double kRadiusTolerance = 1e-6;
constexpr int kScanIntervals = 1024;  // coarse theta scan
constexpr int kZoomIntervals = 64;    // each refinement: 64 intervals over two coarse ones
constexpr int kZoomLevels = 4;        // 32^4 ~ 1e6 times finer than the coarse scan
constexpr double kBisectionTolerance = 1e-14;

void require_particles(int particles_per_cell) {
  if (particles_per_cell < 1)
    throw std::invalid_argument("particles per cell must be >= 1, got " + std::to_string(particles_per_cell));
}

// The leapfrog pair: v' = v + a_v F, then F' = F + a_F v' (staggered, update-stress-last order).
Eigen::MatrixXcd leapfrog_matrix(Complex a_v, Complex a_f) {
  Eigen::MatrixXcd g(2, 2);
  g << 1.0, a_v, a_f, 1.0 + a_f * a_v;
  return g;
}

// The printed relation before Gong (7.31), square dropped: M / CFL = sin(theta/2) / (N sin(theta/(2N))).
// It tends to 1 (not 0) as theta -> 0, so it is not a dispersion relation; it serves only to reproduce
// the paper's sufficient bound (7.31)-(7.32).
double printed_shape(double theta, int n) {
  if (std::abs(theta) < kTinyTheta) return 1.0;
  const double denominator = n * std::sin(theta / (2.0 * n));
  return denominator == 0.0 ? 0.0 : std::sin(theta / 2.0) / denominator;
}

using RadiusFunction = std::function<double(double theta, double courant)>;

bool stable_everywhere(const RadiusFunction& radius, double courant, const std::vector<double>& thetas) {
  return std::all_of(thetas.begin(), thetas.end(),
                     [&](double theta) { return radius(theta, courant) <= 1.0 + kRadiusTolerance; });
}

double least_stable_theta(const RadiusFunction& radius, double courant, const std::vector<double>& thetas) {
  double worst = thetas.front(), largest = -1.0;
  for (double theta : thetas) {
    const double r = radius(theta, courant);
    if (r > largest) largest = r, worst = theta;
  }
  return worst;
}

void append_linspace(std::vector<double>& thetas, double from, double to, int intervals) {
  for (int j = 0; j <= intervals; ++j) thetas.push_back(from + (to - from) * j / intervals);
}

// Bisection on the Courant number; on entry `lo` is stable and `hi` unstable on `thetas`.
void bisect(const RadiusFunction& radius, const std::vector<double>& thetas, double& lo, double& hi) {
  while (hi - lo > kBisectionTolerance * hi) {
    const double mid = 0.5 * (lo + hi);
    (stable_everywhere(radius, mid, thetas) ? lo : hi) = mid;
  }
}

// The largest Courant number with radius(theta, courant) <= 1 + tolerance for all theta in [0, theta_max]:
// a coarse scan, then kZoomLevels refinements around the theta that fails first. Stability is assumed
// monotone in the Courant number at each theta (|M| = CFL |M / CFL|): points are only ever added, each
// level can only lower the bound, and when it does, the earlier points are stable below the old bound,
// so the bisection needs only the new ones. CFL = 0 (the identity map) is always stable.
CourantBound search_bound(const RadiusFunction& radius, double theta_max) {
  if (!(theta_max > 0.0)) throw std::invalid_argument("theta_max must be > 0");
  std::vector<double> thetas;
  append_linspace(thetas, 0.0, theta_max, kScanIntervals);
  double lo = 0.0, hi = 2.0;
  while (stable_everywhere(radius, hi, thetas)) {
    lo = hi;
    hi *= 2.0;
    if (hi > 1e12) throw std::runtime_error("no unstable Courant number found below 1e12");
  }
  bisect(radius, thetas, lo, hi);
  double spacing = theta_max / kScanIntervals;
  double worst = least_stable_theta(radius, hi, thetas);
  for (int level = 0; level < kZoomLevels; ++level) {
    std::vector<double> zoom;
    append_linspace(zoom, std::max(0.0, worst - spacing), std::min(theta_max, worst + spacing),
                    kZoomIntervals);
    if (!stable_everywhere(radius, lo, zoom)) {
      hi = lo;
      lo = 0.0;
      bisect(radius, zoom, lo, hi);
    }
    thetas.insert(thetas.end(), zoom.begin(), zoom.end());
    worst = least_stable_theta(radius, hi, thetas);
    spacing *= 2.0 / kZoomIntervals;
  }
  return {lo, worst};
}

}  // namespace

double courant_number(double wave_speed, double f0, double dt, double h) { return wave_speed * f0 * dt / h; }

double exact_frequency(double k, double wave_speed, double f0, double v0) {
  return v0 * k + wave_speed * f0 * k;
}

double dispersion_shape(double theta, int particles_per_cell, DispersionRelation relation) {
  require_particles(particles_per_cell);
  if (std::abs(theta) < kTinyTheta) return 0.5 * theta;
  if (relation == DispersionRelation::Scheme) return std::sin(theta / 2.0);
  // Gong (7.29)-(7.30) with the square kept (extraction section 6.4); (7.23) summed the particle sines.
  const int n = particles_per_cell;
  const double s = std::sin(theta / 2.0);
  const double denominator = n * std::sin(theta / (2.0 * n));
  return denominator == 0.0 ? 0.0 : s * s / denominator;  // theta = 2 pi N j: 0/0 with limit 0
}

double amplification_m(double theta, double courant, int particles_per_cell, DispersionRelation relation) {
  return courant * dispersion_shape(theta, particles_per_cell, relation);  // Gong (7.30)
}

Eigen::MatrixXcd amplification_matrix(double theta, double courant, int particles_per_cell,
                                      DispersionRelation relation) {
  require_particles(particles_per_cell);
  const int n = particles_per_cell;
  if (relation == DispersionRelation::Corrected) {
    // Gong (7.19)-(7.21): the velocity update sums exp(+-i k h' (2p-1)/2) over the particles of the two
    // cells beside node I; (7.24) sums the F update of every particle of cell I over p^e, after dividing
    // by the particle's own phase. Both sums are taken term by term here, not through (7.23)/(7.25).
    Complex sum_v = 0.0, sum_f = 0.0;
    for (int p = 1; p <= n; ++p) {
      const double offset = theta * (2.0 * p - 1.0) / (2.0 * n);  // k (x_p - x_{I-1}), cell I
      sum_v += std::exp(kI * offset) - std::exp(-kI * offset);
      sum_f += std::exp(kI * (theta - offset)) - std::exp(-kI * offset);
    }
    return leapfrog_matrix(courant * sum_v / double(n), courant * sum_f / double(n));
  }
  // Bloch analysis of (7.15)-(7.16): v_I = u e^{i theta I}, F of particle p of cell I = f_p e^{i theta I}.
  // Velocity half step (7.15): u += CFL/N (e^{i theta} - 1) sum_p f_p; then every particle of cell I
  // (7.16): f_p += CFL (1 - e^{-i theta}) u.
  Eigen::MatrixXcd velocity = Eigen::MatrixXcd::Identity(n + 1, n + 1);
  Eigen::MatrixXcd deformation = Eigen::MatrixXcd::Identity(n + 1, n + 1);
  const Complex to_node = courant / n * (std::exp(kI * theta) - 1.0);
  const Complex to_particle = courant * (1.0 - std::exp(-kI * theta));
  for (int p = 1; p <= n; ++p) {
    velocity(0, p) = to_node;
    deformation(p, 0) = to_particle;
  }
  return deformation * velocity;
}

double spectral_radius(const Eigen::MatrixXcd& matrix) {
  if (matrix.rows() == 2 && matrix.cols() == 2) {
    // Roots of lambda^2 - t lambda + d: the larger from the formula, the smaller as d / larger.
    const Complex t = matrix.trace(), d = matrix.determinant();
    const Complex root = std::sqrt(0.25 * t * t - d);
    const Complex a = 0.5 * t + root, b = 0.5 * t - root;
    const Complex big = std::abs(a) >= std::abs(b) ? a : b;
    if (std::abs(big) == 0.0) return 0.0;
    return std::max(std::abs(big), std::abs(d / big));
  }
  const Eigen::ComplexEigenSolver<Eigen::MatrixXcd> solver(matrix, /*computeEigenvectors=*/false);
  if (solver.info() != Eigen::Success) throw std::runtime_error("eigenvalue computation failed");
  return solver.eigenvalues().cwiseAbs().maxCoeff();
}

DispersionPoint dispersion_point(double theta, double courant, int particles_per_cell,
                                 DispersionRelation relation) {
  DispersionPoint point;
  point.theta = theta;
  point.m = amplification_m(theta, courant, particles_per_cell, relation);
  point.spectral_radius = spectral_radius(amplification_matrix(theta, courant, particles_per_cell, relation));
  // Gong (7.30): omega dt = 2 asin(M); for |M| > 1, asin(M) = +-pi/2 -+ i acosh|M| (growing branch).
  if (std::abs(point.m) <= 1.0) {
    point.omega_dt = 2.0 * std::asin(point.m);
  } else {
    point.omega_dt = std::copysign(kPi, point.m);
    point.growth_per_step = 2.0 * std::acosh(std::abs(point.m));
  }
  if (std::abs(theta) < kTinyTheta)
    point.phase_speed_ratio = 1.0;
  else if (courant > 0.0)
    point.phase_speed_ratio = point.omega_dt / (courant * theta);
  else  // CFL -> 0: the semi-discrete limit 2 M / (CFL theta)
    point.phase_speed_ratio = 2.0 * dispersion_shape(theta, particles_per_cell, relation) / theta;
  return point;
}

std::vector<DispersionPoint> dispersion_curve(double courant, int particles_per_cell,
                                              DispersionRelation relation, int samples, double theta_max) {
  if (samples < 2) throw std::invalid_argument("a dispersion curve needs at least 2 samples");
  std::vector<DispersionPoint> curve;
  curve.reserve(samples);
  for (int j = 0; j < samples; ++j)
    curve.push_back(dispersion_point(theta_max * j / (samples - 1), courant, particles_per_cell, relation));
  return curve;
}

double bound_theta_max(int particles_per_cell) {
  require_particles(particles_per_cell);
  return std::max(2, particles_per_cell) * kPi;
}

CourantBound tight_courant_bound(int particles_per_cell, DispersionRelation relation, double theta_max) {
  if (theta_max <= 0.0) theta_max = bound_theta_max(particles_per_cell);
  return search_bound(
      [&](double theta, double courant) {
        return spectral_radius(amplification_matrix(theta, courant, particles_per_cell, relation));
      },
      theta_max);
}

double sufficient_courant_bound(int particles_per_cell) {
  require_particles(particles_per_cell);
  // Gong (7.31) as printed, over its range 0 <= theta <= 2 pi; the leapfrog pair with a_v = a_F = 2 i M
  // has sin(omega dt / 2) = M, as (7.27)-(7.28).
  const auto radius = [&](double theta, double courant) {
    const Complex a = 2.0 * kI * courant * printed_shape(theta, particles_per_cell);
    return spectral_radius(leapfrog_matrix(a, a));
  };
  return search_bound(radius, 2.0 * kPi).courant;
}

double phase_error_coefficient(double courant, int particles_per_cell, DispersionRelation relation) {
  require_particles(particles_per_cell);
  // omega dt = 2 asin(M) = 2 M (1 + M^2/6 + ...) with M = CFL theta/2 (1 - m2 theta^2 + ...), so
  // omega / (C F0 k) = 1 - (m2 - CFL^2/24) theta^2 + O(theta^4).
  const double n = particles_per_cell;
  const double m2 = relation == DispersionRelation::Scheme ? 1.0 / 24.0 : 1.0 / 12.0 - 1.0 / (24.0 * n * n);
  return m2 - courant * courant / 24.0;
}

double phase_speed_ratio_expansion(double theta, double courant, int particles_per_cell,
                                   DispersionRelation relation) {
  return 1.0 - phase_error_coefficient(courant, particles_per_cell, relation) * theta * theta;
}

double amplification_m_expansion(double theta, double courant, int particles_per_cell,
                                 DispersionRelation relation) {
  require_particles(particles_per_cell);
  // sin^2(theta/2) = theta^2/4 (1 - theta^2/12 + ...), N sin(theta/(2N)) = theta/2 (1 - theta^2/(24 N^2) +
  // ...).
  const double n = particles_per_cell;
  const double m2 = relation == DispersionRelation::Scheme ? 1.0 / 24.0 : 1.0 / 12.0 - 1.0 / (24.0 * n * n);
  return courant * 0.5 * theta * (1.0 - m2 * theta * theta);
}

const char* to_string(DispersionRelation relation) {
  return relation == DispersionRelation::Scheme ? "scheme" : "corrected";
}

}  // namespace matpoint
