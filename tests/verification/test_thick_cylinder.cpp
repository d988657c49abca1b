// A thick-walled cylinder (inner radius a = 1, outer b = 2, plane strain) under internal pressure,
// loaded into the plastic range and unloaded: the residual stresses of an elastic-perfectly plastic
// Tresca material (Mohr-Coulomb with phi = psi = 0, shear strength k = c). The analytic solution is
// Hill's (R. Hill, The Mathematical Theory of Plasticity, 1950, ch. V, the expansion of a
// cylindrical tube in plane strain, with Tresca's criterion): with the plastic zone a <= r <= c,
//   p = k (1 - c^2 / b^2 + 2 ln(c / a))
//   a <= r <= c:  sigma_r = -p + 2 k ln(r / a),               sigma_t = sigma_r + 2 k
//   c <= r <= b:  sigma_r = -k c^2/b^2 (b^2/r^2 - 1),          sigma_t =  k c^2/b^2 (b^2/r^2 + 1)
// exact for any Poisson ratio while sigma_z = nu (sigma_r + sigma_t) stays the intermediate
// principal stress (|sigma_r| <= 2 k (1 - nu) / (1 - 2 nu); 3.5 k here). Unloading is elastic (Lamé)
// when p <= 2 k (1 - a^2/b^2) (no reverse yielding), so the residual stress is the loaded one minus
//   sigma_r^L = p a^2/(b^2 - a^2) (1 - b^2/r^2),  sigma_t^L = p a^2/(b^2 - a^2) (1 + b^2/r^2).
// Here c = 1.5: p = 1.2484 k, between first yield 0.75 k and 1.5 k.
//
// The solver: the implicit particle MPM in static analysis (particles at the elements' 3 x 3 Gauss
// points, so the MPM is the updated-Lagrangian FEM with that quadrature), a quarter of the tube with
// symmetry conditions, the pressure as a follower load on the inner faces (loads.tractions'
// implicit/surface_load.hpp), 8 load steps up and 8 down.
// E / k = 1e6, because the theory is a small-strain one: the finite-strain solution differs from it
// by about 10 k^2 / E (measured floor of the error below: 1e-3 k at E / k = 1e4, 1e-4 k at 1e5,
// 1e-5 k at 1e6, whatever the mesh and the load steps).
// Measured (element means, below): loaded 2.3e-4 k and residual 2.1e-4 k on 4 x 6 Q9 elements,
// 5.8e-6 k and 7.1e-6 k on 8 x 12, 9.8e-6 k and 7.3e-6 k on 16 x 24 (the finite-strain floor);
// 32 load steps instead of 8 change none of them by more than 5 %. Bounds: 1e-4 k on 8 x 12 (ten
// times that floor) and a fall by at least 4 (second order) from 4 x 6.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "matpoint/implicit/particle_newmark/particle_newmark_stepper.hpp"
#include "matpoint/material/material.hpp"

namespace matpoint {
namespace thick_cylinder_tests {

using implicit::FaceLoad;
using implicit::ImplicitMaterial;
using implicit::ImplicitParticleState;
using implicit::ParticleNewmarkOptions;
using implicit::ParticleNewmarkStepper;

constexpr double kA = 1.0, kB = 2.0, kShear = 1.0, kPlasticRadius = 1.5;
constexpr double kYoung = 1e6, kPoisson = 0.3;
constexpr double kHalfPi = 1.57079632679489661923;

/// The pressure that drives the plastic front to kPlasticRadius.
double loading_pressure() {
  const double c = kPlasticRadius;
  return kShear * (1 - c * c / (kB * kB) + 2 * std::log(c / kA));
}

/// Hill's (sigma_r, sigma_t) at radius r under the loading pressure.
std::pair<double, double> loaded_stress(double r) {
  const double c = kPlasticRadius, k = kShear;
  if (r <= c) {
    const double radial = -loading_pressure() + 2 * k * std::log(r / kA);
    return {radial, radial + 2 * k};
  }
  const double f = k * c * c / (kB * kB);
  return {-f * (kB * kB / (r * r) - 1), f * (kB * kB / (r * r) + 1)};
}

/// The residual stress after unloading: loaded minus Lamé's elastic solution for the same pressure.
std::pair<double, double> residual_stress(double r) {
  const auto [radial, hoop] = loaded_stress(r);
  const double f = loading_pressure() * kA * kA / (kB * kB - kA * kA);
  return {radial - f * (1 - kB * kB / (r * r)), hoop - f * (1 + kB * kB / (r * r))};
}

/// A quarter annulus a <= r <= b, 0 <= theta <= pi/2 of radial x circumferential elements of type E,
/// nodes placed on the polar grid; boundaries "inner" (faces 3, xi = -1), "x0" (theta = pi/2, the
/// nodes on x = 0) and "y0" (theta = 0).
template <class E>
mesh::Mesh<2> quarter_annulus(int radial, int circumferential) {
  constexpr int p = E::kDegree;
  mesh::Mesh<2> m;
  m.shape = E::kShape;
  m.nodes_per_element = E::kNodes;
  const int nr = p * radial + 1, nt = p * circumferential + 1;
  const auto node = [&](int i, int j) { return static_cast<Index>(j * nr + i); };
  for (int j = 0; j < nt; ++j)
    for (int i = 0; i < nr; ++i) {
      const double r = kA + (kB - kA) * i / (nr - 1), theta = kHalfPi * j / (nt - 1);
      m.nodes.push_back(Vec<2>(r * std::cos(theta), r * std::sin(theta)));
    }
  for (int j = 0; j < circumferential; ++j)
    for (int i = 0; i < radial; ++i) {
      for (const auto& t : E::kTensor) m.connectivity.push_back(node(p * i + t[0], p * j + t[1]));
      if (i == 0) m.boundary_faces["inner"].push_back({m.element_count() - 1, 3});
    }
  for (int i = 0; i < nr; ++i) {
    m.node_sets["y0"].push_back(node(i, 0));
    m.node_sets["x0"].push_back(node(i, nt - 1));
  }
  return m;
}

struct CylinderErrors {
  double loaded = 0, residual = 0;  // rms over the particles of (sigma_r, sigma_t) errors, / k
  long particles = 0;
};

/// (sigma_r, sigma_t) of a 2-D Cauchy stress at position x.
std::pair<double, double> polar(const Mat<2>& sigma, const Vec<2>& x) {
  const Vec<2> n = x.normalized(), t(-n[1], n[0]);
  return {n.dot(sigma * n), t.dot(sigma * t)};
}

template <class E>
CylinderErrors run_cylinder(int radial, int circumferential, int steps = 8) {
  const auto m = quarter_annulus<E>(radial, circumferential);
  const double lambda = kYoung * kPoisson / ((1 + kPoisson) * (1 - 2 * kPoisson));
  const double mu = kYoung / (2 * (1 + kPoisson));
  const std::vector<Material> materials{MohrCoulomb{1.0, {lambda, mu}, MohrCoulombYield{kShear, 0.0, 0.0}}};

  ParticleSet<2> particles;
  set_state_layout<2>(materials, particles);
  const auto& rule = mesh::gauss_rule<E>(E::kDegree + 1);
  for (Index e = 0; e < m.element_count(); ++e) {
    const auto x = mesh::element_coordinates<E>(m, m.nodes, e);
    for (std::size_t q = 0; q < rule.points.size(); ++q) {
      const Vec<2> position = x.transpose() * E::values(rule.points[q]);
      const double volume = rule.weights[q] * (x.transpose() * E::gradients(rule.points[q])).determinant();
      particles.add(position, Vec<2>::Zero(), volume, volume, Vec<2>::Constant(std::sqrt(volume)), 0, 0);
    }
  }

  ParticleNewmarkOptions<2> options;
  options.static_analysis = true;
  options.newton.increment_tolerance = 1e-9;
  options.newton.residual_relative = 1e-9;
  std::vector<char> dirichlet(static_cast<std::size_t>(m.node_count() * 2), 0);
  for (const Index n : m.node_sets.at("x0")) dirichlet[static_cast<std::size_t>(n * 2)] = 1;
  for (const Index n : m.node_sets.at("y0")) dirichlet[static_cast<std::size_t>(n * 2 + 1)] = 1;
  ParticleNewmarkStepper<E, ImplicitMaterial> stepper(m, {ImplicitMaterial(materials[0])}, options,
                                                      dirichlet);
  ImplicitParticleState<2> state;
  stepper.initialize(particles, state);

  const auto loads = [&](double pressure) {
    std::vector<FaceLoad<2>> out;
    for (const auto& [element, face] : m.boundary_faces.at("inner"))
      out.push_back({element, face, true, pressure, Vec<2>::Zero()});
    return out;
  };
  // The error of each element's mean stress (volume-weighted over its particles, which stay in the
  // element they were generated in), rms over the elements: the particles' own stresses carry the
  // checkerboard of fully integrated elements under isochoric plastic flow (Nagtegaal, Parks & Rice
  // 1974): within an element the three Gauss rows alternate by +-1.4 % of k in the mean stress, an
  // amplitude that does not fall with h; the element means converge.
  const auto rms = [&](auto&& exact) {
    const std::size_t per_element = rule.points.size();
    double sum = 0;
    for (std::size_t first = 0; first < particles.size(); first += per_element) {
      double volume = 0, radial = 0, hoop = 0;
      for (std::size_t p = first; p < first + per_element; ++p) {
        const auto [r_h, t_h] = polar(particles.stress[p], particles.x[p]);
        const auto [r_e, t_e] = exact(particles.x[p].norm());
        volume += particles.volume0[p];
        radial += particles.volume0[p] * (r_h - r_e);
        hoop += particles.volume0[p] * (t_h - t_e);
      }
      sum += (radial * radial + hoop * hoop) / (volume * volume);
    }
    return std::sqrt(sum / (2.0 * static_cast<double>(particles.size() / per_element))) / kShear;
  };

  CylinderErrors errors{INFINITY, INFINITY, 0};  // a failed run fails every bound
  errors.particles = static_cast<long>(particles.size());
  const int kSteps = steps;
  const double peak = loading_pressure();
  double previous = 0;
  for (int n = 1; n <= 2 * kSteps; ++n) {
    const double pressure = peak * (n <= kSteps ? n : 2 * kSteps - n) / kSteps;
    stepper.set_face_loads(loads(pressure), loads(previous));
    const auto report = stepper.step(particles, state, 1.0);
    EXPECT_TRUE(report.ok()) << "load step " << n << ": " << report.newton.message;
    if (!report.ok()) return errors;
    previous = pressure;
    if (n == kSteps) {
      errors.loaded = rms(loaded_stress);
    }
  }
  errors.residual = rms(residual_stress);
  return errors;
}

TEST(ThickCylinder, ResidualStressAfterUnloadingIsHills) {
  ASSERT_GT(loading_pressure(), kShear * (1 - kA * kA / (kB * kB)));      // beyond first yield
  ASSERT_LT(loading_pressure(), 2 * kShear * (1 - kA * kA / (kB * kB)));  // no reverse yielding
  const CylinderErrors coarse = run_cylinder<mesh::Q9>(4, 6);
  const CylinderErrors fine = run_cylinder<mesh::Q9>(8, 12);
  std::printf("Q9  4 x  6: %ld particles, rms error of the element means: loaded %.3e k, residual %.3e k\n",
              coarse.particles, coarse.loaded, coarse.residual);
  std::printf("Q9  8 x 12: %ld particles, rms error of the element means: loaded %.3e k, residual %.3e k\n",
              fine.particles, fine.loaded, fine.residual);
  EXPECT_LT(fine.loaded, 1e-4);
  EXPECT_LT(fine.residual, 1e-4);
  EXPECT_LT(fine.loaded, 0.25 * coarse.loaded);  // at least second order in h
  EXPECT_LT(fine.residual, 0.25 * coarse.residual);
}

}  // namespace thick_cylinder_tests
}  // namespace matpoint
