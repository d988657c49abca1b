// The materials an implicit run can use, as its residuals see them: the Kirchhoff stress tau(F) on any
// scalar type (double, or the dual numbers of the AD Jacobian, ad_jacobian.hpp) from the state of
// the last converged step, and the stress update that advances that state once a step converged.
//   - neo_hookean (log_j): tau written on the scalar type itself (Aulisa & Capodaglio eq. (12),
//     Iaconeta 2017 §7.1), so AD differentiates it directly;
//   - mohr_coulomb, drucker_prager, von_mises (the Hencky plastic frame, Iaconeta 2017 §7.2): tau(F)
//     and its exact derivative d tau / d F, the consistent tangent of the return map
//     (material/plastic_tangent.hpp), carried into the dual numbers by the chain rule. The return
//     map is not differentiated by AD (its region choice and eigen-decomposition are not smooth
//     code); its derivative is the closed form, checked against differences.
// The state stays that of the step start during Newton's iterations (the return is from
// b^trial = F C_p,n^-1 F^T, a function of F alone), so a failed or cut step leaves no trace.
#pragma once

#include <stdexcept>
#include <type_traits>
#include <variant>

#include "matpoint/material/material.hpp"
#include "matpoint/material/plastic_tangent.hpp"

namespace matpoint::implicit {

class ImplicitMaterial {
 public:
  /// Throws std::invalid_argument for a model the implicit solvers do not take (the input reader
  /// refuses them first, naming the material).
  explicit ImplicitMaterial(const Material& material) {
    std::visit(
        [&](const auto& m) {
          using M = std::decay_t<decltype(m)>;
          if constexpr (std::is_same_v<M, NeoHookean>) {
            model_ = m, lambda = m.lambda, mu = m.mu;
          } else if constexpr (std::is_same_v<M, MohrCoulomb> || std::is_same_v<M, DruckerPrager> ||
                               std::is_same_v<M, VonMises>) {
            model_ = m, lambda = m.elastic.lambda, mu = m.elastic.mu;
          } else {
            throw std::invalid_argument("a material model the implicit solvers do not take");
          }
        },
        material);
  }

  double lambda = 0.0, mu = 0.0;  // elastic constants: soft stiffness (eq. (26)), small-strain checks

  /// tau(F) (D x D; plane strain in 2-D) from the stored state, which it does not change; dt: the
  /// step (rate-dependent yield stresses).
  template <class S, int D>
  [[nodiscard]] Eigen::Matrix<S, D, D> kirchhoff_stress(const Eigen::Matrix<S, D, D>& F, const double* state,
                                                        double dt) const {
    return std::visit(
        [&](const auto& m) -> Eigen::Matrix<S, D, D> {
          using M = std::decay_t<decltype(m)>;
          if constexpr (std::is_same_v<M, NeoHookean>) {
            return m.template kirchhoff_stress<S, D>(F);
          } else {
            Mat<D> value;
            for (int i = 0; i < D; ++i)
              for (int j = 0; j < D; ++j) value(i, j) = value_of(F(i, j));
            constexpr bool derivative = !std::is_same_v<S, double>;
            return kirchhoff_of<S, D>(
                hencky_plastic_response(m.elastic, m.yield, embed3<D>(value), state, derivative, dt), F);
          }
        },
        model_);
  }

  /// The Cauchy stress at the converged F (and sigma_zz in plane strain); advances the plastic state.
  template <int D>
  [[nodiscard]] Mat<D> update_stress(const Mat<D>& F, double* state, double& sigma_zz, double dt) const {
    return std::visit(
        [&](const auto& m) -> Mat<D> {
          using M = std::decay_t<decltype(m)>;
          if constexpr (std::is_same_v<M, NeoHookean>)
            return m.template stress<D>(F, sigma_zz);
          else
            return m.template stress<D>(F, 0.0, state, sigma_zz, dt);
        },
        model_);
  }

 private:
  std::variant<NeoHookean, MohrCoulomb, DruckerPrager, VonMises> model_;
};

/// tau(F) of a model with or without a state argument (the unit tests pass NeoHookean itself).
template <class S, int D, class Model>
[[nodiscard]] Eigen::Matrix<S, D, D> kirchhoff_stress_of(const Model& m, const Eigen::Matrix<S, D, D>& F,
                                                         const double* state, double dt) {
  if constexpr (std::is_same_v<Model, ImplicitMaterial>)
    return m.template kirchhoff_stress<S, D>(F, state, dt);
  else
    return m.template kirchhoff_stress<S, D>(F);
}

/// The converged stress update of a model with or without a state.
template <int D, class Model>
[[nodiscard]] Mat<D> updated_stress_of(const Model& m, const Mat<D>& F, double* state, double& sigma_zz,
                                       double dt) {
  if constexpr (std::is_same_v<Model, ImplicitMaterial>)
    return m.template update_stress<D>(F, state, sigma_zz, dt);
  else
    return m.template stress<D>(F, sigma_zz);
}

}  // namespace matpoint::implicit
