// Evaluation of the named measures of analysis/measures.hpp over a run's history.
#pragma once

#include <array>
#include <limits>
#include <string_view>
#include <vector>

#include "matpoint/analysis/history.hpp"
#include "matpoint/io/spec.hpp"

namespace matpoint {

/// What the measures of the final state need from the particles at the end of a run.
struct FinalState {
  std::vector<double> stress_xx;  // sigma_xx of every particle
  // Per axis the largest coordinate of a particle centre (NaN beyond D), and in 3-D the largest
  // distance of a particle centre from the z axis (NaN otherwise).
  std::array<double, 3> reach{std::numeric_limits<double>::quiet_NaN(),
                              std::numeric_limits<double>::quiet_NaN(),
                              std::numeric_limits<double>::quiet_NaN()};
  double radius_xy = std::numeric_limits<double>::quiet_NaN();
  double runout_x = std::numeric_limits<double>::quiet_NaN();  // x behind which 99 % of the mass lies
};

/// The measured value, or NaN when the run does not allow it (e.g. too few zero crossings, or a
/// final-state measure without `final_state`). `momentum_scale` is sum_p M_p |V_p(0)|.
double evaluate_measure(std::string_view name, const Spec& spec, const History& history,
                        double momentum_scale, const FinalState* final_state = nullptr);

/// Median of -sigma_xx over the values with -sigma_xx >= half the largest (measure shock_plateau_stress).
double shock_plateau_stress(std::vector<double> stress_xx);

/// Centre-of-mass velocity of a 1-D bar of length L fixed at x = 0 and free at x = L, started in
/// its first mode V(x, 0) = v0 sin(pi x / (2 L)): v_cm(t) = 2 v0 / pi cos(pi c t / (2 L)).
double vibrating_bar_com_velocity(double v0, double wave_speed, double length, double t);

}  // namespace matpoint
