// A 1-D reduced model of Aulisa & Capodaglio's particle-Newmark implicit MPM, to find where the free
// vibration of Test B loses its energy (README.md, "Why the free vibration is damped on fine
// meshes"). A bar clamped at x = 0 (length L = 0.625 m, rho = 10 000 kg/m^3, E = 1.74 MPa as the
// beam; tau = mu (F^2 - 1) + lambda ln F with mu = lambda = E / 3, so that E is the small-strain
// modulus) vibrates in its first longitudinal mode, v(x, 0) = V sin(pi x / 2L), on a background of
// `ne` elements over [0, 2L]: quadratic Lagrange (deg 2, Q9's 1-D counterpart, C0), linear Lagrange
// (deg 1, C0) or uniform quadratic B-splines (deg 3 here, C1). Particles start `ppc` per element,
// equally spaced. Each step is the paper's: particles as quadrature points (eq. (20)), a_p from
// eq. (21) with the particle's own v_p^n, a_p^n, F_p = (1 + du/dx) F_p^n (eq. (24)), Newton with the
// exact Jacobian, then eqs. (19), (17) and x_p += u_p (eq. (35)); the grid is reset to the mesh.
// Soft stiffness (eq. (26)) mu C on every active element keeps lone particles attached.
//
// Energy audit. Newmark (gamma = 1/2) on a fixed grid conserves K + U up to O(dt^3) and a bounded
// (beta - 1/4) dt^2 term, provided the step starts in equilibrium, M a^n + f_int(u^n) = f_ext. The
// particle formulation carries a_p^n from the previous step's grid; on this step's grid the
// equilibrium has a defect e = M A^n + f_int^n - f_ext^n (A^n: the mass-weighted projection of a_p^n),
// and K + U changes by (1/2) u~ . e per step, computable without the projection as
// (1/2) sum_p [m_p (a_p^n - b) u~_p + V0_p tau_p^n du~/dx(x_p)]. The program prints the sum of the
// steps' changes of K + U beside the sum of these defect works, and the kinetic energy the grid
// cannot see (K minus that of the projection of v_p on the grid).
//
// Build and run (no matpoint code needed):
//   g++ -O2 -Wall -Wextra -I/usr/include/eigen3 -o reduced_bar reduced_bar.cpp
//   ./reduced_bar ne 32 ppc 16 deg 2 V 1 T 0.4
// Options (name value pairs): ne, ppc, deg (1, 2, 3 = B-spline), V [m/s], dt [s] (0.002), T [s],
// beta (0.3), soft (C, 1e-3). README.md has the table these produce.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace {

struct Options {
  int ne = 32, ppc = 16, deg = 2;
  double V = 1.0, dt = 0.002, T = 0.4, beta = 0.3, soft = 1e-3;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i + 1 < argc; i += 2) {
    const char* k = argv[i];
    const double v = std::atof(argv[i + 1]);
    if (!std::strcmp(k, "ne"))
      o.ne = static_cast<int>(v);
    else if (!std::strcmp(k, "ppc"))
      o.ppc = static_cast<int>(v);
    else if (!std::strcmp(k, "deg"))
      o.deg = static_cast<int>(v);
    else if (!std::strcmp(k, "V"))
      o.V = v;
    else if (!std::strcmp(k, "dt"))
      o.dt = v;
    else if (!std::strcmp(k, "T"))
      o.T = v;
    else if (!std::strcmp(k, "beta"))
      o.beta = v;
    else if (!std::strcmp(k, "soft"))
      o.soft = v;
    else {
      std::fprintf(stderr, "unknown option %s\n", k);
      std::exit(2);
    }
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  const double E = 1.74e6, rho = 1e4, mu = E / 3, lam = E / 3, L = 0.625, h = 2 * L / o.ne, gamma = 0.5;
  const double beta = o.beta, dt = o.dt;
  const bool spline = o.deg == 3;
  const int nn = spline ? o.ne + 2 : o.deg * o.ne + 1;  // nodes (B-spline: control points)
  const int nd = spline ? 3 : o.deg + 1;                // shape functions per element
  const int stride = spline ? 1 : o.deg;                // first node of element e: stride * e
  const int np = static_cast<int>(std::lround(L / h)) * o.ppc;
  std::vector<double> x(np), V0(np, L / np), m(np), F(np, 1.0), v(np), a(np, 0.0);
  for (int p = 0; p < np; ++p) {
    x[p] = (p + 0.5) * L / np;
    m[p] = rho * V0[p];
    v[p] = o.V * std::sin(M_PI * x[p] / (2 * L));
  }
  const auto shape = [&](double xi, double* N, double* dN) {  // xi in [-1, 1]
    if (spline) {
      const double t = (xi + 1) / 2;
      N[0] = (1 - t) * (1 - t) / 2, N[1] = (-2 * t * t + 2 * t + 1) / 2, N[2] = t * t / 2;
      dN[0] = -(1 - t) / h, dN[1] = (1 - 2 * t) / h, dN[2] = t / h;
    } else if (o.deg == 2) {
      N[0] = xi * (xi - 1) / 2, N[1] = 1 - xi * xi, N[2] = xi * (xi + 1) / 2;
      dN[0] = (xi - 0.5) * 2 / h, dN[1] = -4 * xi / h, dN[2] = (xi + 0.5) * 2 / h;
    } else {
      N[0] = (1 - xi) / 2, N[1] = (1 + xi) / 2, dN[0] = -1 / h, dN[1] = 1 / h;
    }
  };
  const auto tau = [&](double f) { return mu * (f * f - 1) + lam * std::log(f); };
  const auto dtau = [&](double f) { return 2 * mu * f + lam / f; };
  const auto W = [&](double f) {
    return mu / 2 * (f * f - 1) - mu * std::log(f) + lam / 2 * std::log(f) * std::log(f);
  };
  const auto locate = [&](double xp, int& e, double& xi) {
    e = std::min(static_cast<int>(std::floor(xp / h)), o.ne - 1);
    xi = 2 * (xp - (e + 0.5) * h) / h;
  };
  const auto energies = [&](double& K, double& U) {
    K = U = 0;
    for (int p = 0; p < np; ++p) K += 0.5 * m[p] * v[p] * v[p], U += V0[p] * W(F[p]);
  };
  const auto projected_kinetic = [&]() {  // 1/2 V^T M V, V the mass-weighted projection of v_p
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(nn, nn);
    Eigen::VectorXd b = Eigen::VectorXd::Zero(nn);
    std::vector<char> used(nn, 0);
    for (int p = 0; p < np; ++p) {
      int e;
      double xi, N[3], dN[3];
      locate(x[p], e, xi), shape(xi, N, dN);
      for (int i = 0; i < nd; ++i) {
        used[stride * e + i] = 1, b[stride * e + i] += m[p] * N[i] * v[p];
        for (int j = 0; j < nd; ++j) M(stride * e + i, stride * e + j) += m[p] * N[i] * N[j];
      }
    }
    for (int i = 0; i < nn; ++i)
      if (!used[i]) M(i, i) = 1, b[i] = 0;
    const Eigen::VectorXd Vg = M.ldlt().solve(b);
    return 0.5 * Vg.dot(M * Vg);
  };
  const double gx[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)}, gw[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  double K0, U0;
  energies(K0, U0);
  const double E0 = K0 + U0;
  const int steps = static_cast<int>(std::lround(o.T / dt));
  double changes = 0, defect = 0;
  for (int n = 1; n <= steps; ++n) {
    std::vector<int> el(np);
    std::vector<double> xi(np);
    std::vector<char> active(o.ne, 0), used(nn, 0);
    for (int p = 0; p < np; ++p) {
      locate(x[p], el[p], xi[p]);
      active[el[p]] = 1;
      for (int i = 0; i < nd; ++i) used[stride * el[p] + i] = 1;
    }
    double Kb, Ub;
    energies(Kb, Ub);
    Eigen::VectorXd u = Eigen::VectorXd::Zero(nn);
    for (int it = 0; it < 30; ++it) {  // Newton on u~ from 0
      Eigen::MatrixXd K = Eigen::MatrixXd::Zero(nn, nn);
      Eigen::VectorXd r = Eigen::VectorXd::Zero(nn);
      for (int e = 0; e < o.ne; ++e)  // soft stiffness, 3 Gauss points
        if (active[e])
          for (int g = 0; g < 3; ++g) {
            double N[3], dN[3], du = 0;
            shape(gx[g], N, dN);
            for (int j = 0; j < nd; ++j) du += dN[j] * u[stride * e + j];
            for (int i = 0; i < nd; ++i) {
              r[stride * e + i] += o.soft * mu * du * dN[i] * gw[g] * h / 2;
              for (int j = 0; j < nd; ++j)
                K(stride * e + i, stride * e + j) += o.soft * mu * dN[i] * dN[j] * gw[g] * h / 2;
            }
          }
      for (int p = 0; p < np; ++p) {  // particles: inertia (21) and stress (20)
        double N[3], dN[3], up = 0, H = 1;
        shape(xi[p], N, dN);
        const int f0 = stride * el[p];
        for (int j = 0; j < nd; ++j) up += N[j] * u[f0 + j], H += dN[j] * u[f0 + j];
        const double f = H * F[p], an = (up - dt * v[p] - dt * dt * (0.5 - beta) * a[p]) / (beta * dt * dt);
        const double ks = V0[p] * (dtau(f) * F[p] / H - tau(f) / (H * H)), km = m[p] / (beta * dt * dt);
        for (int i = 0; i < nd; ++i) {
          r[f0 + i] += m[p] * an * N[i] + V0[p] * tau(f) / H * dN[i];
          for (int j = 0; j < nd; ++j) K(f0 + i, f0 + j) += km * N[i] * N[j] + ks * dN[i] * dN[j];
        }
      }
      for (int i = 0; i < nn; ++i)  // empty nodes and the Lagrange clamp: u~ = 0
        if (!used[i] || (i == 0 && !spline)) K.row(i).setZero(), K.col(i).setZero(), K(i, i) = 1, r[i] = 0;
      if (spline) {  // the B-spline clamp u(0) = (u_0 + u_1) / 2 = 0 by a penalty
        const double P = 1e14, g = 0.5 * (u[0] + u[1]);
        r[0] += P * 0.5 * g, r[1] += P * 0.5 * g;
        K(0, 0) += P / 4, K(0, 1) += P / 4, K(1, 0) += P / 4, K(1, 1) += P / 4;
      }
      const Eigen::VectorXd d = K.partialPivLu().solve(-r);
      u += d;
      if (d.norm() <= 1e-11 * std::max(u.norm(), 1e-30)) break;
    }
    for (int p = 0; p < np; ++p) {  // defect work, then (19), (17), (24), (35)
      double N[3], dN[3], up = 0, H = 1;
      shape(xi[p], N, dN);
      const int f0 = stride * el[p];
      for (int j = 0; j < nd; ++j) up += N[j] * u[f0 + j], H += dN[j] * u[f0 + j];
      defect += 0.5 * (m[p] * a[p] * up + V0[p] * tau(F[p]) * (H - 1));
      const double an = (up - dt * v[p] - dt * dt * (0.5 - beta) * a[p]) / (beta * dt * dt);
      v[p] += dt * ((1 - gamma) * a[p] + gamma * an);
      a[p] = an, F[p] *= H, x[p] += up;
    }
    double Ka, Ua;
    energies(Ka, Ua);
    changes += Ka + Ua - Kb - Ub;
    if (n % std::max(1, steps / 4) == 0)
      std::printf("t = %.3f s: (K + U) / E0 = %.5f, kinetic energy the grid cannot see / E0 = %.5f\n", n * dt,
                  (Ka + Ua) / E0, (Ka - projected_kinetic()) / E0);
  }
  std::printf("ne %d ppc %d deg %d V %g dt %g: K + U lost %.5f of E0; sum of (1/2) u~ . e = %.5f of E0\n",
              o.ne, o.ppc, o.deg, o.V, dt, -changes / E0, -defect / E0);
}
