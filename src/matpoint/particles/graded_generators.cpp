// Graded disk and beam of Aulisa & Capodaglio, Appendix A, as their released code builds them
// (extraction aulisa-capodaglio-implicit-mpm-fem.md §10 "[CODE]"). Each formula below names the
// extraction item it follows and how it differs from the printed pseudocode.
#include "matpoint/particles/graded_generators.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace matpoint {

namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("graded generator: " + what);
}

void add(GradedParticles& out, const Vec<2>& x, double mass, double rho) {
  out.position.push_back(x);
  out.mass.push_back(mass);
  out.volume.push_back(mass / rho);
}

// Ring count of the disk core, N_r = floor(N_theta0 / 2 pi) (extraction §10.1 [CODE]; the authors
// convert the double to unsigned). The pseudocode's ceil gives 48 rings instead of 47 for N_theta0
// = 300 and does not reproduce the paper's counts.
int disk_core_rings(int N_theta0) {
  return static_cast<int>(std::floor(N_theta0 / (2.0 * std::numbers::pi)));
}

// Core of the disk: the centre particle, then rings r_i = R0 - i dR, i = 0..N_r-1, of
// N_theta_i = ceil(N_theta0 r_i / R0) equally spaced particles (Appendix A). Every core particle,
// centre included, has the same mass rho pi R0^2 / N_core (Appendix A, m_p = rho pi R0^2 / p).
// N_theta0 r_i / R0 is evaluated in the authors' order (N_theta0 * r_i) / R0: ceil is sensitive to
// rounding where the quotient is an integer (i = 0).
void add_disk_core(GradedParticles& out, const Vec<2>& centre, double R0, int N_theta0, double dR, int N_r,
                   double rho) {
  out.position.push_back(centre);
  for (int i = 0; i < N_r; ++i) {
    const double r = R0 - i * dR;
    const int n = static_cast<int>(std::ceil(N_theta0 * r / R0));
    const double dtheta = 2.0 * std::numbers::pi / n;
    for (int j = 0; j < n; ++j)
      out.position.push_back(centre + r * Vec<2>(std::cos(j * dtheta), std::sin(j * dtheta)));
  }
  out.core_count = out.position.size();
  const double m = rho * std::numbers::pi * R0 * R0 / static_cast<double>(out.core_count);
  out.mass.assign(out.core_count, m);
  out.volume.assign(out.core_count, m / rho);
}

// Boundary layers of the disk (extraction §10.1 [CODE]): dR_i = dR_{i-1} / f, r_i = r_{i-1} + dR_i,
// N_theta_i = ceil(f N_theta_{i-1}) from N_theta0, m_p = rho r_i (2 pi / N_theta_i) dR_i, for
// i = 1..N_b with N_b the smallest n with sum_{k<=n} f^-k >= (R - R0) / dR, so the last ring lies
// slightly outside R (1.60085 for R = 1.6, as in the authors' code). The pseudocode instead fits a
// to a given N_b so that sum_{k<=N_b} dR a^k = R - R0 exactly and takes N_theta_i =
// ceil(N_theta0 / a^i) without iterating the ceil; with its ceil ring count it gives 46 982
// particles instead of the paper's 48 739 (extraction §10.1).
void add_disk_layers(GradedParticles& out, const Vec<2>& centre, double R, double R0, int N_theta0, double dR,
                     double f, double rho) {
  out.layers = R - R0 > 1e-10 * R ? graded_layer_count((R - R0) / dR, f) : 0;
  double r = R0;
  double n = N_theta0;
  for (int i = 1; i <= out.layers; ++i) {
    dR /= f;
    r += dR;
    n = std::ceil(n * f);
    const double dtheta = 2.0 * std::numbers::pi / n;
    const double m = rho * r * dtheta * dR;
    for (int j = 0; j < static_cast<int>(n); ++j)
      add(out, centre + r * Vec<2>(std::cos(j * dtheta), std::sin(j * dtheta)), m, rho);
  }
}

// Core of the beam (extraction §10.2 [CODE]): dH = H0 / (N_H - 1), L0 = L - (H - H0)/2,
// N_L = ceil(L0 / dH) + 1 columns (the pseudocode omits the +1), dL = L0 / (N_L - 1); particles at
// (x0 + i dL, y0 - H0/2 + j dH), column by column, with equal masses rho L0 H0 / (N_H N_L) (the
// pseudocode's rho dL dH would overcount the core's area by the end rows and columns).
void add_beam_core(GradedParticles& out, double x0, double y0, double H0, double L0, int N_H, double dH,
                   int N_L, double rho) {
  const double dL = L0 / (N_L - 1);
  const double m = rho * L0 * H0 / (static_cast<double>(N_H) * N_L);
  for (int i = 0; i < N_L; ++i)
    for (int j = 0; j < N_H; ++j) add(out, Vec<2>(x0 + i * dL, y0 - H0 / 2 + j * dH), m, rho);
  out.core_count = out.position.size();
}

// One "⊐"-shaped layer of the beam at half-height h/2 and length l, spacings dl x dh (extraction §10.2
// [CODE]): the top row (cols points from x0 to x0 + l), the right end going down (rows - 1 points),
// the bottom row going back (cols - 1 points), cols = ceil(l / dl) + 1, rows = ceil(h / dh) + 1, each
// of mass rho dl dh. The pseudocode puts the top and bottom rows at y0 +- H0/2 (the core's rows)
// where y0 +- H_i/2 is meant.
void add_beam_layer(GradedParticles& out, double x0, double y0, double h, double l, double dl, double dh,
                    double rho) {
  const int cols = static_cast<int>(std::ceil(l / dl)) + 1;
  const int rows = static_cast<int>(std::ceil(h / dh)) + 1;
  const double sx = l / (cols - 1);
  const double sy = h / (rows - 1);
  const double m = rho * dl * dh;
  for (int j = 0; j < cols; ++j) add(out, Vec<2>(x0 + j * sx, y0 + h / 2), m, rho);
  for (int j = 1; j < rows; ++j) add(out, Vec<2>(x0 + l, y0 + h / 2 - j * sy), m, rho);
  // x0 + l - j sx of the paper, written from the left end so that the last point is exactly x0.
  for (int j = 1; j < cols; ++j) add(out, Vec<2>(x0 + (cols - 1 - j) * sx, y0 - h / 2), m, rho);
}

}  // namespace

int graded_layer_count(double target, double f) {
  require(f > 1.0, "boundary-layer ratio f = " + std::to_string(f) + ", expected > 1");
  require(target < 1.0 / (f - 1.0), "boundary layers of ratio f = " + std::to_string(f) +
                                        " reach at most 1/(f-1) = " + std::to_string(1.0 / (f - 1.0)) +
                                        " core spacings, asked for " + std::to_string(target));
  int n = 0;
  double sum = 0.0;
  while (sum < target) sum += std::pow(f, -(++n));
  return n;
}

GradedParticles graded_disk(const Vec<2>& centre, double R, double R0, int N_theta0, double f, double rho) {
  require(R0 > 0.0 && R >= R0,
          "disk radii R = " + std::to_string(R) + ", R0 = " + std::to_string(R0) + ", expected R >= R0 > 0");
  require(disk_core_rings(N_theta0) >= 1, "N_theta0 = " + std::to_string(N_theta0) + ", expected >= 7");
  require(f > 1.0, "boundary-layer ratio f = " + std::to_string(f) + ", expected > 1");
  require(rho > 0.0, "density " + std::to_string(rho) + ", expected > 0");
  const int N_r = disk_core_rings(N_theta0);
  const double dR = R0 / N_r;
  GradedParticles out;
  add_disk_core(out, centre, R0, N_theta0, dR, N_r, rho);
  add_disk_layers(out, centre, R, R0, N_theta0, dR, f, rho);
  return out;
}

// Layers of the beam (extraction §10.2 [CODE]): dL_i = dL_{i-1} / f, dH_i = dH_{i-1} / f,
// L_i = L_{i-1} + dL_i, H_i = H_{i-1} + 2 dH_i from (L0, H0, dL, dH), for i = 1..N_b' - 1 with
// N_b' = the layer count of (H - H0)/2 / dH. The authors' loop stops one layer short of N_b' (21 for
// the paper's beam, 20 generated), so the beam ends at about H - 6e-5 and L - 1.5e-4.
GradedParticles graded_beam(double x0, double y0, double H, double L, double H0, int N_H, double f,
                            double rho) {
  require(H0 > 0.0 && H >= H0, "beam heights H = " + std::to_string(H) + ", H0 = " + std::to_string(H0) +
                                   ", expected H >= H0 > 0");
  require(L > (H - H0) / 2, "beam length L = " + std::to_string(L) + ", expected > (H - H0)/2");
  require(N_H >= 2, "N_H = " + std::to_string(N_H) + ", expected >= 2");
  require(f > 1.0, "boundary-layer ratio f = " + std::to_string(f) + ", expected > 1");
  require(rho > 0.0, "density " + std::to_string(rho) + ", expected > 0");
  const double dH = H0 / (N_H - 1);
  const double L0 = L - (H - H0) / 2;
  const int N_L = static_cast<int>(std::ceil(L0 / dH)) + 1;
  GradedParticles out;
  add_beam_core(out, x0, y0, H0, L0, N_H, dH, N_L, rho);
  const int N_b = H - H0 > 1e-10 * H ? graded_layer_count(0.5 * (H - H0) / dH, f) : 1;
  double dl = L0 / (N_L - 1), dh = dH, l = L0, h = H0;
  for (int i = 1; i < N_b; ++i) {
    dl /= f;
    dh /= f;
    l += dl;
    h += 2 * dh;
    add_beam_layer(out, x0, y0, h, l, dl, dh, rho);
  }
  out.layers = N_b - 1;
  return out;
}

}  // namespace matpoint
