// Graded disk and beam of Aulisa & Capodaglio (Appendix A; extraction
// aulisa-capodaglio-implicit-mpm-fem.md §10, [CODE] variant). Expected counts, radii, extents and
// masses are the extraction's table (§10.1, §10.2), which quotes the authors' released code; the
// paper's own counts are one higher (48 739, 57 084, 23 041; extraction item A11). The layer
// geometry is also checked against closed forms of the geometric sums.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "matpoint/particles/graded_generators.hpp"

namespace graded_generators_tests {

using namespace matpoint;
constexpr double kPi = std::numbers::pi;

double total(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0); }

double max_radius(const GradedParticles& p, const Vec<2>& centre) {
  double r = 0.0;
  for (const auto& x : p.position) r = std::max(r, (x - centre).norm());
  return r;
}

// Closed form of the disk's layers: dR_i = dR f^-i, r_i = R0 + dR (1 - f^-i)/(f - 1), so the total
// mass is rho pi R0^2 + 2 pi rho sum_i r_i dR_i with sum_i f^-i = g(1), sum_i f^-2i = g(2),
// g(q) = (1 - f^-qN) / (f^q - 1).
struct DiskClosedForm {
  double outer_radius, mass;
};
DiskClosedForm disk_closed_form(double R0, double dR, double f, int N, double rho) {
  const auto g = [&](int q) { return (1.0 - std::pow(f, -q * N)) / (std::pow(f, q) - 1.0); };
  const double c = dR / (f - 1.0);
  const double sum_r_dR = (R0 + c) * dR * g(1) - c * dR * g(2);
  return {R0 + c * (1.0 - std::pow(f, -N)), rho * kPi * R0 * R0 + 2.0 * kPi * rho * sum_r_dR};
}

struct DiskCase {
  double R, R0;
  int N_theta0;
  double f;
  int layers;
  std::size_t core, count;
  double mass_excess_percent, outer_radius;  // extraction §10.1 table (see DiskRollingCoupled)
  double percent_digit, radius_digit;        // one unit of the last quoted digit
};

void check_disk(const DiskCase& c) {
  const double rho = 1000.0;
  const Vec<2> centre(0.3, -0.2);
  const GradedParticles p = graded_disk(centre, c.R, c.R0, c.N_theta0, c.f, rho);
  EXPECT_EQ(p.layers, c.layers);
  EXPECT_EQ(p.core_count, c.core);
  ASSERT_EQ(p.position.size(), c.count);
  ASSERT_EQ(p.mass.size(), c.count);
  ASSERT_EQ(p.volume.size(), c.count);
  // Particle 0 is the centre particle the paper tracks (extraction §11).
  EXPECT_EQ(p.position[0], centre);
  // Core: equal masses summing to rho pi R0^2 (Appendix A).
  const double core_mass = std::accumulate(p.mass.begin(), p.mass.begin() + p.core_count, 0.0);
  EXPECT_NEAR(core_mass, rho * kPi * c.R0 * c.R0, 1e-12 * core_mass);
  EXPECT_EQ(p.mass[0], p.mass[p.core_count - 1]);
  for (std::size_t i = 0; i < p.mass.size(); ++i) ASSERT_DOUBLE_EQ(p.volume[i], p.mass[i] / rho);
  // Outermost ring and total mass against the extraction's table (half a unit of the quoted digit)
  // and against the closed form of the geometric sums.
  const double r_out = max_radius(p, centre);
  EXPECT_NEAR(r_out, c.outer_radius, 0.5 * c.radius_digit);
  const double excess = 100.0 * (total(p.mass) / (rho * kPi * c.R * c.R) - 1.0);
  EXPECT_NEAR(excess, c.mass_excess_percent, 0.5 * c.percent_digit);
  const int N_r = static_cast<int>(std::floor(c.N_theta0 / (2.0 * kPi)));
  const DiskClosedForm exact = disk_closed_form(c.R0, c.R0 / N_r, c.f, c.layers, rho);
  EXPECT_NEAR(r_out, exact.outer_radius, 1e-12 * c.R);
  EXPECT_NEAR(total(p.mass), exact.mass, 1e-11 * exact.mass);
}

TEST(GradedGenerators, DiskRollingUncoupled) {
  // §6.2 Test A: R 1.6, R0 1.4, N_theta0 300, f 1.14 -> 22 layers, 7 224 core, 48 738 in all.
  check_disk({1.6, 1.4, 300, 1.14, 22, 7224, 48738, 0.22, 1.60085, 0.01, 1e-5});
}

TEST(GradedGenerators, DiskScaledForBouncing) {
  // §6.3 Test D uses the same disk scaled by 0.1: same counts, radius and mass excess scale.
  check_disk({0.16, 0.14, 300, 1.14, 22, 7224, 48738, 0.22, 0.160085, 0.01, 1e-6});
}

TEST(GradedGenerators, DiskRollingCoupled) {
  // §6.3 Test C: R 1.6, R0 1.4, N_theta0 600, f 1.05 -> 24 layers, 28 847 core, 57 083 in all,
  // outermost ring 1.60335. The extraction quotes the mass excess as +0.50 %, but the closed form
  // of the layer sums (disk_closed_form, independent of the generator's loop) gives +0.4938 %: the
  // extraction's figure is a rounding slip of 0.006 points, so the closed form's +0.49 % is expected.
  check_disk({1.6, 1.4, 600, 1.05, 24, 28847, 57083, 0.49, 1.60335, 0.01, 1e-5});
}

TEST(GradedGenerators, BeamCantilever) {
  // §6.2 Test B (extraction §10.2, §11.2): L 0.625, H 0.25, left-end centre (0, 0), H0 0.15,
  // N_H 20, f 1.148, rho 10 000 -> 74 x 20 core, 20 layers, 23 040 particles, extent
  // L ~ 0.62485, H ~ 0.24994, mass 1569.6 against rho L H = 1562.5.
  const double x0 = 0.0, y0 = 0.0, H = 0.25, L = 0.625, H0 = 0.15, f = 1.148, rho = 10000.0;
  const int N_H = 20;
  const GradedParticles p = graded_beam(x0, y0, H, L, H0, N_H, f, rho);
  EXPECT_EQ(p.core_count, 74u * 20u);
  EXPECT_EQ(p.layers, 20);
  ASSERT_EQ(p.position.size(), 23040u);
  double xmin = 1e9, xmax = -1e9, ymin = 1e9, ymax = -1e9;
  for (const auto& x : p.position) {
    xmin = std::min(xmin, x.x()), xmax = std::max(xmax, x.x());
    ymin = std::min(ymin, x.y()), ymax = std::max(ymax, x.y());
  }
  EXPECT_EQ(xmin, x0);  // the clamped end
  EXPECT_NEAR(xmax - x0, 0.62485, 0.5e-5);
  EXPECT_NEAR(ymax - ymin, 0.24994, 0.5e-5);
  EXPECT_NEAR(ymax + ymin, 2 * y0, 1e-14);
  EXPECT_NEAR(total(p.mass), 1569.6, 0.05);
  EXPECT_DOUBLE_EQ(rho * L * H, 1562.5);
  // Core masses: rho L0 H0 in all (extraction §10.2). Closed forms of the layer extents:
  // L_N = L0 + dL (1 - f^-N)/(f - 1), H_N = H0 + 2 dH (1 - f^-N)/(f - 1).
  const double core_mass = std::accumulate(p.mass.begin(), p.mass.begin() + p.core_count, 0.0);
  const double L0 = L - (H - H0) / 2, dH = H0 / (N_H - 1), dL = L0 / 73;
  EXPECT_NEAR(core_mass, rho * L0 * H0, 1e-12 * core_mass);
  const double s = (1.0 - std::pow(f, -20)) / (f - 1.0);
  EXPECT_NEAR(xmax, L0 + dL * s, 1e-13);
  EXPECT_NEAR(ymax - ymin, H0 + 2 * dH * s, 1e-13);
  for (std::size_t i = 0; i < p.mass.size(); ++i) ASSERT_DOUBLE_EQ(p.volume[i], p.mass[i] / rho);
}

TEST(GradedGenerators, LayerCountIsTheSmallestSufficient) {
  // sum_{k=1..n} 2^-k = 1 - 2^-n: the smallest n reaching 0.9 is 4 (0.9375), reaching 0.5 is 1.
  EXPECT_EQ(graded_layer_count(0.9, 2.0), 4);
  EXPECT_EQ(graded_layer_count(0.5, 2.0), 1);
  EXPECT_EQ(graded_layer_count(0.0, 2.0), 0);
  // The sum never reaches 1/(f - 1): no layer count exists.
  EXPECT_THROW(graded_layer_count(1.0, 2.0), std::invalid_argument);
  EXPECT_THROW(graded_layer_count(0.5, 1.0), std::invalid_argument);
}

TEST(GradedGenerators, RejectsBadParameters) {
  const Vec<2> o = Vec<2>::Zero();
  EXPECT_THROW(graded_disk(o, 1.0, 1.2, 300, 1.14, 1000.0), std::invalid_argument);  // R < R0
  EXPECT_THROW(graded_disk(o, 1.6, 1.4, 6, 1.14, 1000.0), std::invalid_argument);    // no core ring
  EXPECT_THROW(graded_disk(o, 1.6, 1.4, 300, 1.0, 1000.0), std::invalid_argument);   // f = 1
  EXPECT_THROW(graded_disk(o, 3.0, 1.4, 300, 1.14, 1000.0), std::invalid_argument);  // layers cannot reach R
  EXPECT_THROW(graded_beam(0, 0, 0.1, 0.625, 0.15, 20, 1.148, 1e4), std::invalid_argument);  // H < H0
  EXPECT_THROW(graded_beam(0, 0, 0.25, 0.625, 0.15, 1, 1.148, 1e4), std::invalid_argument);  // N_H = 1
  // R = R0 and H = H0: the core alone.
  EXPECT_EQ(graded_disk(o, 1.4, 1.4, 300, 1.14, 1000.0).layers, 0);
  EXPECT_EQ(graded_beam(0, 0, 0.15, 0.625, 0.15, 20, 1.148, 1e4).layers, 0);
}

}  // namespace graded_generators_tests
