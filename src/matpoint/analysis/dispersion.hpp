// Linearised 1-D stability and dispersion analysis of explicit MPM (Gong 2015, ch. 7; implementer's
// extraction gong-2015-improving-mpm.md, section 6). Theory and limits: docs/theory/stability.md.
//
// Model (Gong 7.1-7.10): a bar with sigma = E (F - 1), C^2 = E / rho0, linearised about a uniform state
// (v0, F0). Scheme (7.13)-(7.16): linear hat functions on cells of size h, N = N_p^e equally spaced
// particles per cell at x = x_{I-1} + (2p - 1) h / (2N) (7.11), staggered leapfrog, advection dropped.
// Everything here is non-dimensional: theta = k h and CFL = C F0 dt / h (7.30); the paper's background
// velocity v0 enters only the exact relation (exact_frequency), because (7.13)-(7.14) drop advection.
#pragma once

#include <Eigen/Dense>
#include <numbers>
#include <vector>

namespace matpoint {

/// Which discrete dispersion relation is evaluated.
enum class DispersionRelation {
  /// The paper's relation (7.29)-(7.30) with the square on sin(theta/2) kept (extraction section 6.4):
  /// sin(omega dt / 2) = M = CFL sin^2(theta/2) / (N sin(theta / (2N))). It comes from the Fourier
  /// ansatz (7.17) on every particle, with the F update projected on that mode by summing over p^e
  /// (7.24); the sub-cell particle modes are left out (extraction A31).
  Corrected,
  /// Exact Bloch analysis of the scheme (7.15)-(7.16) itself: the velocity update sees only the cell
  /// sums of F and every particle of a cell gets the same increment, so M = CFL sin(theta/2) for any N,
  /// plus N - 1 neutral sub-cell modes (eigenvalue 1). Not in the paper; see docs/theory/stability.md.
  Scheme,
};

/// CFL = C F0 dt / h with C = sqrt(E / rho0): Gong 2015 eq. (7.30).
[[nodiscard]] double courant_number(double wave_speed, double f0, double dt, double h);

/// Exact right-going frequency of the linearised equations (7.9)-(7.10) for the ansatz
/// exp(i (k x - omega t)): omega = v0 k + C F0 k (the paper states C F0 k for v0 = 0).
[[nodiscard]] double exact_frequency(double k, double wave_speed, double f0, double v0 = 0.0);

/// M(theta) / CFL: sin^2(theta/2) / (N sin(theta/(2N))) for Corrected, sin(theta/2) for Scheme.
/// Continuous at theta = 0 (value 0).
[[nodiscard]] double dispersion_shape(double theta, int particles_per_cell, DispersionRelation relation);

/// M(theta) of (7.30): sin(omega dt / 2) = +-M; |M| <= 1 for all theta is the stability condition.
[[nodiscard]] double amplification_m(double theta, double courant, int particles_per_cell,
                                     DispersionRelation relation = DispersionRelation::Corrected);

/// The one-step amplification matrix of the non-dimensional state (v / C at t^{s-1/2}, F at t^s).
/// Corrected: the 2x2 matrix of (7.21) and (7.24), with the particle sums evaluated term by term (not
/// through identity 7.23), so its eigenvalues check the closed form of M. Scheme: the (N+1)x(N+1) Bloch
/// matrix of (7.15)-(7.16) for (v_I, F of the N particles of cell I).
[[nodiscard]] Eigen::MatrixXcd amplification_matrix(double theta, double courant, int particles_per_cell,
                                                    DispersionRelation relation);

/// Largest eigenvalue modulus (closed form for 2x2, Eigen's complex eigensolver otherwise).
[[nodiscard]] double spectral_radius(const Eigen::MatrixXcd& matrix);

/// One wave number of a dispersion curve (acoustic branch).
struct DispersionPoint {
  double theta = 0.0;              ///< k h
  double m = 0.0;                  ///< M(theta): sin(omega dt / 2) = M (7.30)
  double spectral_radius = 1.0;    ///< max |eigenvalue| of amplification_matrix
  double omega_dt = 0.0;           ///< Re(omega dt) = 2 Re asin(M)
  double phase_speed_ratio = 1.0;  ///< Re(omega) / (C F0 k) = omega_dt / (CFL theta); 1 at theta = 0
  double growth_per_step = 0.0;    ///< |Im(omega dt)| = 2 acosh|M| when |M| > 1, else 0
};

[[nodiscard]] DispersionPoint dispersion_point(double theta, double courant, int particles_per_cell,
                                               DispersionRelation relation = DispersionRelation::Corrected);

/// `samples` points evenly spaced on [0, theta_max] (both ends included; samples >= 2).
[[nodiscard]] std::vector<DispersionPoint> dispersion_curve(double courant, int particles_per_cell,
                                                            DispersionRelation relation, int samples,
                                                            double theta_max = std::numbers::pi);

/// The wave numbers scanned for a bound: theta in [0, max(2, N) pi], i.e. the range of (7.31),
/// [0, 2 pi], joined with every particle wave number |k h'| <= pi, h' = h / N.
[[nodiscard]] double bound_theta_max(int particles_per_cell);

struct CourantBound {
  double courant = 0.0;  ///< largest CFL with max |eigenvalue| <= 1 for every scanned theta
  double theta = 0.0;    ///< the wave number that becomes unstable first
};

/// The tight linear-stability bound: bisection on CFL of "the spectral radius of amplification_matrix
/// is <= 1 at every theta" over a 1025-point theta scan of [0, theta_max], refined four times around
/// the theta that fails first (each time 32 times finer), so a narrow maximum of |M| is not missed.
/// theta_max <= 0 means bound_theta_max(N). Corrected gives 1/max_theta sin^2(theta/2)/(N sin(theta/2N))
/// (extraction section 6.4, T16: 1, 1.29904, 1.34479, 1.36035 for N = 1..4); Scheme gives 1.
[[nodiscard]] CourantBound tight_courant_bound(int particles_per_cell,
                                               DispersionRelation relation = DispersionRelation::Corrected,
                                               double theta_max = 0.0);

/// The paper's sufficient bound, eq. (7.31) as printed (the square dropped): the same search applied
/// to M = CFL sin(theta/2) / (N sin(theta/(2N))) on 0 <= theta <= 2 pi. It returns 1 for every N,
/// Gong's (7.32) "CFL <= 1".
[[nodiscard]] double sufficient_courant_bound(int particles_per_cell);

/// c2 in  omega / (C F0 k) = 1 - c2 theta^2 + O(theta^4)  (Gong 7.33-7.34 give only O(theta^2)).
/// Corrected: 1/12 - 1/(24 N^2) - CFL^2/24 (extraction section 6.4); Scheme: (1 - CFL^2)/24, the
/// classical staggered-leapfrog value (equal to Corrected at N = 1).
[[nodiscard]] double phase_error_coefficient(double courant, int particles_per_cell,
                                             DispersionRelation relation = DispersionRelation::Corrected);

/// 1 - c2 theta^2: the small-theta phase-speed ratio, error O(theta^4).
[[nodiscard]] double phase_speed_ratio_expansion(double theta, double courant, int particles_per_cell,
                                                 DispersionRelation relation = DispersionRelation::Corrected);

/// CFL theta/2 (1 - m2 theta^2), m2 = 1/12 - 1/(24 N^2) (Corrected) or 1/24 (Scheme): the small-theta
/// expansion of M(theta), relative error O(theta^4).
[[nodiscard]] double amplification_m_expansion(double theta, double courant, int particles_per_cell,
                                               DispersionRelation relation = DispersionRelation::Corrected);

/// "corrected" / "scheme".
[[nodiscard]] const char* to_string(DispersionRelation relation);

}  // namespace matpoint
