// Evaluation of the named measures of analysis/measures.hpp over a run's history.
#pragma once

#include "matpoint/analysis/history.hpp"
#include "matpoint/io/spec.hpp"

#include <string_view>

namespace matpoint {

/// The measured value, or NaN when the run does not allow it (e.g. too few zero crossings).
/// `momentum_scale` is sum_p M_p |V_p(0)|.
double evaluate_measure(std::string_view name, const Spec& spec, const History& history, double momentum_scale);

/// Centre-of-mass velocity of a 1-D bar of length L fixed at x = 0 and free at x = L, started in
/// its first mode V(x, 0) = v0 sin(pi x / (2 L)): v_cm(t) = 2 v0 / pi cos(pi c t / (2 L)).
double vibrating_bar_com_velocity(double v0, double wave_speed, double length, double t);

}  // namespace matpoint
