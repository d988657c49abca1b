#include "matpoint/material/material.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "matpoint/core/errors.hpp"
#include "matpoint/core/lanes.hpp"
#include "matpoint/material/neo_hookean_lanes.hpp"

namespace matpoint {

namespace {

constexpr double kRadiansPerDegree = 3.14159265358979323846 / 180.0;

MohrCoulombYield mohr_coulomb_yield(const MaterialSpec& spec) {
  return {spec.cohesion,
          spec.friction_angle * kRadiansPerDegree,
          spec.dilation_angle * kRadiansPerDegree,
          spec.residual_cohesion,
          spec.residual_friction_angle * kRadiansPerDegree,
          spec.softening_strain,
          spec.tension_cutoff};
}

/// Whether c_p(F) <= `fastest` is certain without b_max, the largest eigenvalue of B = F F^T (in
/// 3-D Eigen's direct solver, the costliest part of the time step's wave speed). NeoHookean's
/// c_p^2 = (mu (b_max + 1) + V) / rho with V = lambda (1 - ln J) <= lambda / J (ln J >= 1 - 1/J) or
/// V = lambda (J^2 + 1) / 2, so c_p <= fastest when b_max <= T = (rho fastest^2 - V_upper) / mu - 1,
/// which holds when T I - B is positive definite: its LDL^T factorisation (backward stable, as
/// Cholesky) has positive pivots. T is lowered by 1e-9 of the sizes involved, far above the
/// rounding of c_p, of the eigenvalue and of the factorisation (~1e-15 of them), so a particle this
/// skips could not have raised the maximum: the recorded maximum is bitwise the one of computing
/// every c_p, and most particles (all but those that raise the running maximum) skip.
bool wave_speed_certainly_below(const NeoHookean& m, const Mat<3>& F, double J, double fastest) {
  if (!(fastest > 0.0) || !(m.mu > 0.0) || !(m.lambda >= 0.0) || !(J > 0.0)) return false;
  const double V = m.volumetric == NeoHookeanVolumetric::LogJ ? m.lambda / J : 0.5 * m.lambda * (J * J + 1.0);
  const Mat<3> B = F * F.transpose();
  const double target = m.density * fastest * fastest;  // mu (b_max + 1) + V may reach this
  const double T = (target - V) / m.mu - 1.0 - 1e-9 * (B.trace() + 1.0 + (target + V) / m.mu);
  const double d0 = T - B(0, 0);  // A = T I - B = L diag(d) L^T
  if (!(d0 > 0.0)) return false;
  const double l10 = -B(1, 0) / d0, l20 = -B(2, 0) / d0;
  const double d1 = (T - B(1, 1)) + l10 * B(1, 0);
  if (!(d1 > 0.0)) return false;
  const double e21 = -B(2, 1) + l20 * B(1, 0);  // A21 - l20 d0 l10
  const double d2 = (T - B(2, 2)) + l20 * B(2, 0) - e21 * e21 / d1;
  return d2 > 0.0;
}

/// The stress (sigma_zz in 2-D) and the running maximum wave speed of the kLanes neo-Hookean
/// particles from `first` through the lanes, as update_stress's per-particle code forms them, when
/// all are of material `index` with det F > 0 and a finite stress results; false (nothing written)
/// otherwise, and the caller updates them one by one (which reports the failures). In 3-D the
/// wave speeds follow particle by particle (wave_speed_certainly_below skips most).
template <int D>
bool update_stress_lanes(const NeoHookean& model, int index, ParticleSet<D>& particles, std::ptrdiff_t first,
                         double& fastest) {
  for (std::ptrdiff_t p = first; p < first + kLanes; ++p)
    if (particles.material[p] != index) return false;
  const LaneMatrix<D> F = LaneMatrix<D>::load(&particles.F[first]);
  const Lanes J = F.determinant();
  if (!stdx::all_of(J > 0.0)) return false;
  Lanes sigma_zz, speed;
  LaneMatrix<D> sigma;
  if constexpr (D == 2) {
    sigma = neo_hookean_stress_and_wave_speed_lanes(model, F, J, sigma_zz, speed);
  } else {
    const Lanes lnJ = model.volumetric == NeoHookeanVolumetric::LogJ ? log_per_lane(J) : Lanes(0.0);
    sigma = neo_hookean_stress_lanes<D>(model, J, lnJ, F * F.transposed(), sigma_zz);
  }
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j)
      if (!stdx::all_of(stdx::isfinite(sigma(i, j)))) return false;
  sigma.store(&particles.stress[first]);
  if constexpr (D == 2) {
    sigma_zz.copy_to(&particles.stress_zz[first], stdx::element_aligned);
    for (int lane = 0; lane < kLanes; ++lane) fastest = std::max(fastest, static_cast<double>(speed[lane]));
  } else {
    for (int lane = 0; lane < kLanes; ++lane) {
      const Mat<D>& F_p = particles.F[first + lane];
      double c = 0.0;
      if (!wave_speed_certainly_below(model, F_p, static_cast<double>(J[lane]), fastest))
        c = model.wave_speed_at<D>(F_p);
      fastest = std::max(fastest, c);
    }
  }
  return true;
}

}  // namespace

Material make_material(const MaterialSpec& spec) {
  switch (spec.model) {
    case MaterialModel::NeoHookean:
      return NeoHookean{spec.density, spec.lambda, spec.mu, spec.volumetric};
    case MaterialModel::MieGruneisen:
      return MieGruneisen{spec.density, spec.bulk_sound_speed, spec.hugoniot_slope, spec.gruneisen, spec.mu};
    case MaterialModel::Rigid:
      return Rigid{spec.density};
    case MaterialModel::MohrCoulomb:
      return MohrCoulomb{spec.density, {spec.lambda, spec.mu}, mohr_coulomb_yield(spec)};
    case MaterialModel::DruckerPrager:
      return DruckerPrager{spec.density, {spec.lambda, spec.mu}, {mohr_coulomb_yield(spec), spec.match}};
    case MaterialModel::VonMises:
      return VonMises{spec.density,
                      {spec.lambda, spec.mu},
                      {spec.yield_stress, spec.hardening_modulus, spec.jc_b, spec.jc_n, spec.jc_c,
                       spec.jc_reference_rate}};
    case MaterialModel::LinearElastic:
      break;
  }
  return LinearElastic{spec.density, spec.youngs_modulus, spec.lambda, spec.mu};
}

int state_size(const Material& m) {
  return std::visit(
      [](const auto& model) {
        if constexpr (requires { std::decay_t<decltype(model)>::state_size; })
          return std::decay_t<decltype(model)>::state_size;
        return 0;
      },
      m);
}

std::vector<std::string> state_names(const Material& m) {
  return std::visit(
      [](const auto& model) {
        using Model = std::decay_t<decltype(model)>;
        std::vector<std::string> names;
        if constexpr (requires { Model::state_names; })
          for (const auto& name : Model::state_names) names.emplace_back(name);
        int size = 0;
        if constexpr (requires { Model::state_size; }) size = Model::state_size;
        for (int i = static_cast<int>(names.size()); i < size; ++i)
          names.push_back("state" + std::to_string(i));
        return names;
      },
      m);
}

template <int D>
void set_state_layout(const std::vector<Material>& materials, ParticleSet<D>& particles) {
  particles.state_stride = 0;
  particles.plastic_material.assign(materials.size(), 0);
  for (std::size_t m = 0; m < materials.size(); ++m) {
    particles.state_stride = std::max(particles.state_stride, state_size(materials[m]));
    particles.plastic_material[m] = std::visit(
        [](const auto& model) -> char {
          using Model = std::decay_t<decltype(model)>;
          return std::is_same_v<Model, MohrCoulomb> || std::is_same_v<Model, DruckerPrager> ||
                 std::is_same_v<Model, VonMises>;
        },
        materials[m]);
  }
}

/// The geostatic (infinite-slope) Kirchhoff stress at F = I at `depth` below the free surface:
/// sigma_vv = rho g_v depth, sigma_av = rho g_a depth (the shear of the slope-parallel planes, from
/// d sigma_av / d x_v + rho g_a = 0 with no traction on the surface), sigma_aa = K0 sigma_vv for the
/// other axes a (the vertical axis v the last one; g_v < 0).
template <int D>
Mat3 geostatic_stress(double density, const Triple& gravity, double k0, double depth) {
  constexpr int vertical = D - 1;
  const double vertical_stress = density * gravity[vertical] * depth;
  Mat3 tau = Mat3(Vec3::Constant(k0 * vertical_stress).asDiagonal());
  tau(vertical, vertical) = vertical_stress;
  for (int a = 0; a < vertical; ++a) tau(a, vertical) = tau(vertical, a) = density * gravity[a] * depth;
  return tau;
}

template <int D>
void set_geostatic_stress(const std::vector<Material>& materials, const std::vector<BodySpec>& bodies,
                          const Triple& gravity, ParticleSet<D>& particles) {
  constexpr int vertical = D - 1;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (!bodies[b].geostatic) continue;
    if (!(gravity[vertical] < 0.0))
      throw InputError({{"bodies[" + std::to_string(b) + "].geostatic",
                         "gravity with no downward (-" + std::string(1, "xyz"[vertical]) + ") component",
                         "loads.gravity with a negative " + std::string(1, "xyz"[vertical]) +
                             " component for a geostatic stress"}});
    for (std::size_t p = 0; p < particles.size(); ++p) {
      if (particles.body[p] != static_cast<int>(b)) continue;
      std::visit(
          [&](const auto& model) {
            if constexpr (requires {
                            model.elastic.mu;
                            model.yield;
                          }) {  // the plastic models
              const double depth = std::max(bodies[b].geostatic_surface - particles.x[p][vertical], 0.0);
              const Mat3 tau = geostatic_stress<D>(model.density, gravity, bodies[b].k0, depth);
              // At F = I, b_e = C_p^-1 = exp(2 D^-1 tau) on tau's principal axes.
              const Eigen::SelfAdjointEigenSolver<Mat3> eigen(tau);
              const Vec3 b_e = (2.0 * model.elastic.strain(eigen.eigenvalues())).array().exp().matrix();
              store_plastic_metric(from_principal(b_e, eigen.eigenvectors()),
                                   &particles.state[p * particles.state_stride]);
            }
          },
          materials[static_cast<std::size_t>(particles.material[p])]);
    }
  }
}

template <int D>
long update_stress(const std::vector<Material>& materials, ParticleSet<D>& particles,
                   const ArtificialViscosity& av, double dt) {
  const auto n = static_cast<std::ptrdiff_t>(particles.size());
  const auto stride = static_cast<std::ptrdiff_t>(particles.state_stride);
  long first_bad = -1;
  double fastest = 0.0;  // max_p c_p, as max_current_wave_speed (wave_speed.hpp) finds it
  for (std::size_t m = 0; m < materials.size(); ++m) {
    std::visit(
        [&](const auto& model) {
          using Model = std::decay_t<decltype(model)>;
          const double c = model.template wave_speed<D>();
          constexpr bool kSpeedWithState = requires { model.template wave_speed_at<D>(Mat<D>{}, nullptr); };
          constexpr bool kSpeedAtF = requires { model.template wave_speed_at<D>(Mat<D>{}); };
          // 3-D neo-Hookean: c_p only where it could raise the maximum; 1-D, 2-D: with the stress
          constexpr bool kSkipSlower = D == 3 && std::is_same_v<Model, NeoHookean>;
          constexpr bool kWithStress = !kSkipSlower && requires(double& x) {
            model.template stress_and_wave_speed<D>(Mat<D>{}, x, x);
          };
          if constexpr (!kSpeedWithState && !kSpeedAtF) fastest = std::max(fastest, c);
          // One particle's update; first_bad and fastest are the calling thread's reduction copies.
          auto update_particle = [&](std::ptrdiff_t p, long& first_bad, double& fastest) {
            if (particles.material[p] != static_cast<int>(m)) return;
            const Mat<D>& F = particles.F[p];
            const double J = F.determinant();
            if (!(J > 0.0)) {
              first_bad = std::max(first_bad, static_cast<long>(n - p));  // max of (n - p) = min p
              return;
            }
            const double q = av.active() ? av.pressure(particles.mass[p] / (particles.volume0[p] * J),
                                                       particles.L[p].trace(), c)
                                         : 0.0;
            double zz;
            double speed = 0.0;  // c_p of the updated F and state (the wave_speed_at models)
            if constexpr (requires { model.yield; }) {  // the plastic models: rate terms need dt
              particles.stress[p] = model.template stress<D>(F, q, &particles.state[p * stride], zz, dt);
            } else if constexpr (requires { Model::state_size; }) {
              particles.stress[p] = model.template stress<D>(F, q, &particles.state[p * stride], zz);
            } else if constexpr (kSkipSlower) {
              particles.stress[p] = model.template stress<D>(F, zz) - q * Mat<D>::Identity();
              zz -= q;
              if (!wave_speed_certainly_below(model, F, J, fastest))
                speed = model.template wave_speed_at<D>(F);
            } else if constexpr (kWithStress) {
              particles.stress[p] =
                  model.template stress_and_wave_speed<D>(F, zz, speed) - q * Mat<D>::Identity();
              zz -= q;
            } else {
              particles.stress[p] = model.template stress<D>(F, zz) - q * Mat<D>::Identity();
              zz -= q;
            }
            if constexpr (kSpeedWithState)
              speed = model.template wave_speed_at<D>(F, &particles.state[p * stride]);
            else if constexpr (kSpeedAtF && !kSkipSlower && !kWithStress)
              speed = model.template wave_speed_at<D>(F);
            if constexpr (kSpeedWithState || kSpeedAtF) fastest = std::max(fastest, speed);
            if constexpr (D == 2) particles.stress_zz[p] = zz;
            if (!particles.stress[p].allFinite()) first_bad = std::max(first_bad, static_cast<long>(n - p));
          };
          // Neo-Hookean without artificial viscosity: kLanes particles at once where a batch is all
          // of this material (neo_hookean_lanes.hpp; bitwise the per-particle results).
          constexpr bool kLanesPath = D >= 2 && std::is_same_v<Model, NeoHookean>;
          const std::ptrdiff_t batches = kLanesPath && !av.active() ? n / kLanes : 0;
          if constexpr (kLanesPath) {
#pragma omp parallel for schedule(static) if (n > kParallelMinimum) reduction(max : first_bad, fastest)
            for (std::ptrdiff_t b = 0; b < batches; ++b) {
              const std::ptrdiff_t first = b * kLanes;
              if (!update_stress_lanes(model, static_cast<int>(m), particles, first, fastest))
                for (std::ptrdiff_t p = first; p < first + kLanes; ++p)
                  update_particle(p, first_bad, fastest);
            }
          }
          const std::ptrdiff_t rest = batches * kLanes;
#pragma omp parallel for schedule(static) if (n - rest > kParallelMinimum) reduction(max : first_bad, fastest)
          for (std::ptrdiff_t p = rest; p < n; ++p) update_particle(p, first_bad, fastest);
        },
        materials[m]);
  }
  // A failed update ends the step: no time step follows it from this state.
  particles.recorded_wave_speed = first_bad < 0 ? fastest : -1.0;
  return first_bad < 0 ? -1 : n - first_bad;
}

template <int D>
double strain_energy(const std::vector<Material>& materials, const ParticleSet<D>& particles, int body) {
  const auto stride = static_cast<std::ptrdiff_t>(particles.state_stride);
  double energy = 0.0;
  const auto n = static_cast<std::ptrdiff_t>(particles.size());
  for (std::size_t m = 0; m < materials.size(); ++m) {
    std::visit(
        [&](const auto& model) {
#pragma omp parallel for schedule(static) if (n > kParallelMinimum) reduction(+ : energy)
          for (std::ptrdiff_t p = 0; p < n; ++p) {
            if (particles.material[p] != static_cast<int>(m) || (body >= 0 && particles.body[p] != body))
              continue;
            if constexpr (requires { std::decay_t<decltype(model)>::state_size; })
              energy += particles.volume0[p] *
                        model.template energy_density<D>(particles.F[p], &particles.state[p * stride]);
            else
              energy += particles.volume0[p] * model.template energy_density<D>(particles.F[p]);
          }
        },
        materials[m]);
  }
  return energy;
}

template <int D>
double plastic_work(const ParticleSet<D>& particles) {
  if (particles.state_stride < kPlasticStateSize) return 0.0;
  const auto stride = static_cast<std::ptrdiff_t>(particles.state_stride);
  const auto n = static_cast<std::ptrdiff_t>(particles.size());
  double work = 0.0;
#pragma omp parallel for schedule(static) if (n > kParallelMinimum) reduction(+ : work)
  for (std::ptrdiff_t p = 0; p < n; ++p)
    if (particles.plastic(static_cast<std::size_t>(p)))
      work += particles.volume0[p] * particles.state[p * stride + kPlasticWork];
  return work;
}

template void set_state_layout<1>(const std::vector<Material>&, ParticleSet<1>&);
template void set_state_layout<2>(const std::vector<Material>&, ParticleSet<2>&);
template void set_state_layout<3>(const std::vector<Material>&, ParticleSet<3>&);
template void set_geostatic_stress<1>(const std::vector<Material>&, const std::vector<BodySpec>&,
                                      const Triple&, ParticleSet<1>&);
template void set_geostatic_stress<2>(const std::vector<Material>&, const std::vector<BodySpec>&,
                                      const Triple&, ParticleSet<2>&);
template void set_geostatic_stress<3>(const std::vector<Material>&, const std::vector<BodySpec>&,
                                      const Triple&, ParticleSet<3>&);
template long update_stress<1>(const std::vector<Material>&, ParticleSet<1>&, const ArtificialViscosity&,
                               double);
template long update_stress<2>(const std::vector<Material>&, ParticleSet<2>&, const ArtificialViscosity&,
                               double);
template long update_stress<3>(const std::vector<Material>&, ParticleSet<3>&, const ArtificialViscosity&,
                               double);
template double strain_energy<1>(const std::vector<Material>&, const ParticleSet<1>&, int);
template double strain_energy<2>(const std::vector<Material>&, const ParticleSet<2>&, int);
template double strain_energy<3>(const std::vector<Material>&, const ParticleSet<3>&, int);
template double plastic_work<1>(const ParticleSet<1>&);
template double plastic_work<2>(const ParticleSet<2>&);
template double plastic_work<3>(const ParticleSet<3>&);

}  // namespace matpoint
