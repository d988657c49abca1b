// Linearised 1-D stability / dispersion analysis of Gong 2015 ch. 7 (extraction section 6, test T16):
// tight Courant bounds of (7.29) with the square kept, the paper's sufficient bound (7.31)-(7.32), the
// amplification matrix against the closed form of M, the O(theta^4) small-theta expansions, and the
// exact Bloch relation of the scheme (7.15)-(7.16) against direct time stepping of those equations.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>
#include <vector>

#include "matpoint/analysis/dispersion.hpp"

namespace {

using namespace matpoint;
constexpr double kPi = std::numbers::pi;

TEST(Dispersion, TightCourantBoundsMatchT16) {
  // Source: Gong 2015 ch. 7, eq. (7.29) with the square on sin(theta/2) restored; extraction
  // gong-2015-improving-mpm.md section 6.4 table and acceptance test T16: 1.0000, 1.29904, 1.34479,
  // 1.36035 (+-1e-4), reached at theta = pi, 2.4619, 2.3862, 2.3616.
  const double expected[] = {1.0000, 1.29904, 1.34479, 1.36035};
  const double theta_at_max[] = {kPi, 2.4619, 2.3862, 2.3616};
  for (int n = 1; n <= 4; ++n) {
    const CourantBound bound = tight_courant_bound(n);
    EXPECT_NEAR(bound.courant, expected[n - 1], 1e-4) << "N_p^e = " << n;
    EXPECT_NEAR(bound.theta, theta_at_max[n - 1], 1e-3) << "N_p^e = " << n;
  }
}

TEST(Dispersion, TightBoundsAgreeWithClosedForms) {
  // N = 1: M = CFL sin(theta/2), bound 1. N = 2: with x = theta/4, sin^2(theta/2) / (2 sin x) =
  // 2 sin x cos^2 x, largest at tan^2 x = 1/2, value 4 / (3 sqrt 3), so the bound is 3 sqrt(3) / 4.
  EXPECT_NEAR(tight_courant_bound(1).courant, 1.0, 1e-11);
  EXPECT_NEAR(tight_courant_bound(2).courant, 3.0 * std::sqrt(3.0) / 4.0, 1e-11);
  EXPECT_NEAR(tight_courant_bound(2).theta, 4.0 * std::atan(std::sqrt(0.5)), 1e-5);
  // Extraction section 6.4 table: N = 5, 8, 16 give 1.367482, 1.375157, 1.378829, and as N -> infinity
  // M / CFL -> 2 sin^2(theta/2) / theta, largest where tan(theta/2) = theta, bound about 1.3800; the
  // bound increases with N towards it.
  EXPECT_NEAR(tight_courant_bound(5).courant, 1.367482, 2e-6);
  EXPECT_NEAR(tight_courant_bound(8).courant, 1.375157, 2e-6);
  EXPECT_NEAR(tight_courant_bound(16).courant, 1.378829, 2e-6);
  double previous = 0.0;
  for (int n : {1, 2, 3, 4, 5, 8, 16, 32}) {
    const double bound = tight_courant_bound(n).courant;
    EXPECT_GT(bound, previous) << "N_p^e = " << n;
    EXPECT_LT(bound, 1.3801) << "N_p^e = " << n;
    previous = bound;
  }
}

TEST(Dispersion, TightBoundIsTheSameOverTheGridAndTheParticleWaveNumbers) {
  // Extraction section 6.4: theta in [0, N pi] (every particle wave number) gives the maxima of [0, 2 pi].
  for (int n = 2; n <= 8; ++n)
    EXPECT_NEAR(tight_courant_bound(n, DispersionRelation::Corrected, n * kPi).courant,
                tight_courant_bound(n, DispersionRelation::Corrected, 2.0 * kPi).courant, 1e-11)
        << "N_p^e = " << n;
}

TEST(Dispersion, PaperSufficientBoundIsOne) {
  // Gong (7.31)-(7.32) as printed: the square dropped, min over 0 <= theta <= 2 pi is 1, "CFL <= 1".
  for (int n = 1; n <= 8; ++n) EXPECT_NEAR(sufficient_courant_bound(n), 1.0, 1e-9) << "N_p^e = " << n;
}

TEST(Dispersion, AmplificationMatrixEigenvaluesSatisfyTheClosedForm) {
  // The matrix is built from the particle sums of (7.21) and (7.24) term by term; its eigenvalues obey
  // sin^2(omega dt / 2) = M^2, i.e. lambda + 1/lambda = 2 - 4 M^2, with M from (7.29) + identity (7.23).
  // Without the square (the printed form) this fails by a factor sin(theta/2) in M.
  for (int n = 1; n <= 5; ++n)
    for (double theta : {0.3, 1.1, 2.4, 3.0, 5.5})
      for (double courant : {0.4, 0.9, 1.3}) {
        const Eigen::MatrixXcd g = amplification_matrix(theta, courant, n, DispersionRelation::Corrected);
        EXPECT_NEAR(std::abs(g.determinant() - 1.0), 0.0, 1e-13);  // leapfrog is symplectic
        const double m = amplification_m(theta, courant, n);
        const Eigen::ComplexEigenSolver<Eigen::MatrixXcd> solver(g, false);
        for (const auto& lambda : solver.eigenvalues())
          EXPECT_NEAR(std::abs(lambda + 1.0 / lambda - (2.0 - 4.0 * m * m)), 0.0, 1e-9)
              << "N_p^e = " << n << ", theta = " << theta << ", CFL = " << courant;
      }
}

TEST(Dispersion, GrowthRateIsTheLogOfTheSpectralRadius) {
  for (int n = 1; n <= 4; ++n) {
    const CourantBound bound = tight_courant_bound(n);
    // Above the bound, at the critical theta: |M| > 1, growth 2 acosh|M| from (7.30) equals ln max|lambda|.
    const DispersionPoint unstable = dispersion_point(bound.theta, 1.2 * bound.courant, n);
    EXPECT_GT(std::abs(unstable.m), 1.0);
    EXPECT_GT(unstable.growth_per_step, 0.1);
    EXPECT_NEAR(unstable.growth_per_step, std::log(unstable.spectral_radius),
                1e-9 * unstable.growth_per_step);
    EXPECT_NEAR(unstable.omega_dt, kPi, 1e-15);
    // Just below it, every wave number is neutral (|lambda| = 1 up to round-off at the double root).
    for (const auto& p :
         dispersion_curve(0.999 * bound.courant, n, DispersionRelation::Corrected, 201, bound_theta_max(n))) {
      EXPECT_EQ(p.growth_per_step, 0.0) << "theta = " << p.theta;
      EXPECT_NEAR(p.spectral_radius, 1.0, 1e-6) << "theta = " << p.theta;
    }
  }
}

TEST(Dispersion, PhaseSpeedLimits) {
  // theta -> 0: the numerical wave speed is C F0 (7.34). N = 1, CFL = 1: omega dt = 2 asin(sin(theta/2))
  // = theta for theta <= pi, so leapfrog is exact (the "magic" time step).
  for (int n = 1; n <= 4; ++n) EXPECT_DOUBLE_EQ(dispersion_point(0.0, 0.7, n).phase_speed_ratio, 1.0);
  for (const auto& p : dispersion_curve(1.0, 1, DispersionRelation::Corrected, 33))
    EXPECT_NEAR(p.phase_speed_ratio, 1.0, 1e-7) << "theta = " << p.theta;
  EXPECT_DOUBLE_EQ(courant_number(100.0, 1.1, 1e-4, 0.02), 0.55);  // C F0 dt / h (7.30)
  EXPECT_DOUBLE_EQ(exact_frequency(3.0, 100.0, 1.1, 2.0), 3.0 * (2.0 + 110.0));
}

// Ratio of the errors of an expansion at theta and theta / 2.
template <class Exact, class Expansion>
double halving_ratio(double theta, Exact exact, Expansion expansion) {
  return (exact(theta) - expansion(theta)) / (exact(theta / 2) - expansion(theta / 2));
}

TEST(Dispersion, SmallThetaExpansionsAreFourthOrder) {
  // M(theta) = CFL theta/2 (1 - m2 theta^2) + O(theta^5) and c/C F0 = 1 - c2 theta^2 + O(theta^4)
  // (extraction section 6.4). If the theta^2 coefficient is right the error is c4 theta^4 (1 + O(theta^2)),
  // so halving theta divides it by 16 (1 + O(theta^2)); a wrong coefficient gives 4, a vanishing c4 gives
  // 64. The theta^4 coefficient of the phase speed (derived with sympy) is
  // (27 N^4 CFL^4 - 60 N^4 CFL^2 + 16 N^4 + 30 N^2 CFL^2 - 20 N^2 + 7) / (5760 N^4): it vanishes for
  // instance at N = 2, CFL = 1/2, so the Courant numbers below avoid its roots (N = 1: 1/3, 1; N = 2..4:
  // about 0.50-0.54 and 1.30-1.36). At theta = 0.1 the O(theta^2) correction is below 0.2 % (mpmath:
  // ratios within 16 +- 0.02 on these points), and the round-off in an error of ~1e-10 moves a ratio by
  // ~1e-5, hence the tolerance 0.05: far from 4 and 64.
  for (const auto relation : {DispersionRelation::Corrected, DispersionRelation::Scheme})
    for (int n = 1; n <= 4; ++n)
      for (double courant : {0.25, 0.7, 0.95}) {
        const auto phase = [&](double t) {
          return dispersion_point(t, courant, n, relation).phase_speed_ratio;
        };
        const auto phase_expansion = [&](double t) {
          return phase_speed_ratio_expansion(t, courant, n, relation);
        };
        const auto m = [&](double t) { return amplification_m(t, courant, n, relation); };
        const auto m_expansion = [&](double t) { return amplification_m_expansion(t, courant, n, relation); };
        for (double theta : {0.1, 0.05}) {
          EXPECT_NEAR(halving_ratio(theta, phase, phase_expansion), 16.0, 0.05)
              << to_string(relation) << ", N_p^e = " << n << ", CFL = " << courant << ", theta = " << theta;
          // M's relative error is O(theta^4), its absolute error O(theta^5): ratio 32.
          EXPECT_NEAR(halving_ratio(theta, m, m_expansion), 32.0, 0.1)
              << to_string(relation) << ", N_p^e = " << n << ", CFL = " << courant << ", theta = " << theta;
        }
      }
}

// Direct time stepping of Gong (7.15)-(7.16) on a periodic row of cells, in the non-dimensional variables
// of amplification_matrix (v / C, F); node I is the right end of cell I. Returns the state norm per step.
std::vector<double> step_scheme(int n, double courant, int cells, int steps) {
  std::vector<double> v(cells, 0.0), f(cells * n);
  for (std::size_t j = 0; j < f.size(); ++j) f[j] = std::sin(1.7 * j + 0.3) + 0.5 * std::cos(5.1 * j);
  const auto F = [&](int cell, int p) -> double& { return f[((cell + cells) % cells) * n + (p - 1)]; };
  std::vector<double> norms;
  for (int s = 0; s < steps; ++s) {
    for (int node = 0; node < cells; ++node) {  // (7.15)
      double sum = 0.0;
      for (int p = 1; p <= n; ++p) sum += F(node + 1, p) - F(node, n - p + 1);
      v[node] += courant / n * sum;
    }
    for (int cell = 0; cell < cells; ++cell)  // (7.16): every particle of the cell, same increment
      for (int p = 1; p <= n; ++p) F(cell, p) += courant * (v[cell] - v[(cell - 1 + cells) % cells]);
    double norm = 0.0;
    for (double x : v) norm += x * x;
    for (double x : f) norm += x * x;
    norms.push_back(std::sqrt(norm));
  }
  return norms;
}

TEST(Dispersion, SchemeRelationMatchesDirectTimeStepping) {
  // The scheme (7.15)-(7.16) itself is stable up to CFL = 1 for every N (its velocity update sees only
  // cell sums of F), not up to the (7.29) bound: at N = 2, CFL = 1.1 the paper's relation predicts
  // stability, yet the 2h mode (theta = pi) grows by exp(2 acosh 1.1) per step.
  for (int n = 1; n <= 4; ++n)
    EXPECT_NEAR(tight_courant_bound(n, DispersionRelation::Scheme).courant, 1.0, 1e-11) << "N_p^e = " << n;
  const int n = 2;
  const double courant = 1.1;
  for (const auto& p : dispersion_curve(courant, n, DispersionRelation::Corrected, 401, bound_theta_max(n)))
    EXPECT_LE(p.spectral_radius, 1.0 + 1e-6) << "(7.29) is stable here, theta = " << p.theta;
  const std::vector<double> norms = step_scheme(n, courant, 16, 200);
  const double measured = std::log(norms[199] / norms[99]) / 100.0;
  const DispersionPoint predicted = dispersion_point(kPi, courant, n, DispersionRelation::Scheme);
  EXPECT_NEAR(predicted.growth_per_step, 2.0 * std::acosh(1.1), 1e-12);
  EXPECT_NEAR(std::log(predicted.spectral_radius), predicted.growth_per_step, 1e-9);
  EXPECT_NEAR(measured, predicted.growth_per_step, 1e-3 * predicted.growth_per_step);
  // Below CFL = 1 the same stepping stays bounded (leapfrog modes neutral, sub-cell modes frozen).
  const std::vector<double> stable = step_scheme(n, 0.98, 16, 4000);
  EXPECT_LT(stable.back(), 10.0 * stable.front());
}

TEST(Dispersion, RejectsBadArguments) {
  EXPECT_THROW((void)tight_courant_bound(0), std::invalid_argument);
  EXPECT_THROW((void)amplification_m(1.0, 0.5, -1), std::invalid_argument);
  EXPECT_THROW((void)dispersion_curve(0.5, 1, DispersionRelation::Corrected, 1), std::invalid_argument);
}

}  // namespace
