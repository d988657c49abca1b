#include "matpoint/analysis/measures_eval.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "matpoint/analysis/bounce.hpp"

namespace matpoint {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// B = K + U + D - W_ext: kinetic, strain, friction work, external work (an exact run keeps B(0)).
double energy_balance(const HistorySample& s) {
  return s.kinetic_energy + s.strain_energy + s.friction_work + s.plastic_work - s.external_work;
}

/// The energy scale of relative energy measures: the largest of the initial energy K(0) + U(0)
/// and |W_ext| over the run, the energy the problem was given or has received. A problem that
/// starts at rest under gravity has E(0) = 0 and is measured against the work gravity did.
double energy_scale(const History& h) {
  const auto& s0 = h.samples.front();
  double scale = s0.kinetic_energy + s0.strain_energy;
  for (const auto& s : h.samples) scale = std::max(scale, std::abs(s.external_work));
  return scale;
}

/// A drift relative to the scale; a problem that never had or received energy drifts by 0.
double relative_drift(double drift, double scale) {
  if (scale > 0) return drift / scale;
  return drift == 0.0 ? 0.0 : std::copysign(std::numeric_limits<double>::infinity(), drift);
}

double max_relative_energy_error(const History& h) {
  if (h.samples.empty()) return kNaN;
  const double b0 = energy_balance(h.samples.front()), scale = energy_scale(h);
  double worst = 0.0;
  for (const auto& s : h.samples)
    worst = std::max(worst, std::abs(relative_drift(energy_balance(s) - b0, scale)));
  return worst;
}

double max_relative_momentum_error(const History& h, double scale) {
  if (h.samples.empty() || !(scale > 0)) return kNaN;
  const auto& s0 = h.samples.front();
  double worst = 0.0;
  for (const auto& s : h.samples) {
    double d2 = 0.0;
    for (int a = 0; a < h.dim; ++a) {
      const double d = s.momentum[a] - s0.momentum[a] - (s.external_impulse[a] - s0.external_impulse[a]);
      d2 += d * d;
    }
    worst = std::max(worst, std::sqrt(d2) / scale);
  }
  return worst;
}

struct BarData {
  double v0, c, length;
};

BarData vibrating_bar(const Spec& spec) {
  const auto& body = spec.bodies.front();
  const auto& m = spec.materials[body.material];
  return {body.sine_amplitude[0], std::sqrt(m.youngs_modulus / m.density), body.max[0] - body.min[0]};
}

double bar_velocity_error(const Spec& spec, const History& h) {
  const auto bar = vibrating_bar(spec);
  const double amplitude = 2.0 * bar.v0 / std::numbers::pi;
  double worst = 0.0;
  for (const auto& s : h.samples) {
    const double exact = vibrating_bar_com_velocity(bar.v0, bar.c, bar.length, s.time);
    worst = std::max(worst, std::abs(s.body_com_velocity[0][0] - exact) / amplitude);
  }
  return worst;
}

double bar_period_error(const Spec& spec, const History& h) {
  std::vector<double> crossings;
  for (std::size_t k = 1; k < h.samples.size(); ++k) {
    const double a = h.samples[k - 1].body_com_velocity[0][0], b = h.samples[k].body_com_velocity[0][0];
    if ((a > 0) != (b > 0) && a != b) {
      const double ta = h.samples[k - 1].time, tb = h.samples[k].time;
      crossings.push_back(ta + (tb - ta) * a / (a - b));
    }
  }
  if (crossings.size() < 2) return kNaN;
  const double period =
      2.0 * (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  const auto bar = vibrating_bar(spec);
  const double exact = 4.0 * bar.length / bar.c;
  return std::abs(period - exact) / exact;
}

/// Least-squares slope of v_x(t) = momentum_x / mass through every output.
double fitted_com_acceleration_x(const History& h) {
  if (h.samples.size() < 3) return kNaN;
  double st = 0, sv = 0, stt = 0, stv = 0;
  for (const auto& s : h.samples) {
    double mass = 0.0;
    for (double m : s.body_mass) mass += m;
    const double v = s.momentum[0] / mass;
    st += s.time, sv += v, stt += s.time * s.time, stv += s.time * v;
  }
  const auto n = static_cast<double>(h.samples.size());
  return (n * stv - st * sv) / (n * stt - st * st);
}

/// The x of the centre of mass of all bodies.
double com_x(const HistorySample& s) {
  double mass = 0.0, moment = 0.0;
  for (std::size_t b = 0; b < s.body_mass.size(); ++b) {
    mass += s.body_mass[b];
    moment += s.body_mass[b] * s.body_com_position[b][0];
  }
  return moment / mass;
}

/// Least-squares a of x(t) - x(0) = a t^2 / 2 through every output, x the centre of mass of all
/// bodies (a body starting from rest; the position integrates out the velocity's oscillations).
double fitted_com_displacement_acceleration_x(const History& h) {
  if (h.samples.size() < 3) return kNaN;
  const double x0 = com_x(h.samples.front()), t0 = h.samples.front().time;
  double sqq = 0, sqx = 0;
  for (const auto& s : h.samples) {
    const double q = 0.5 * (s.time - t0) * (s.time - t0);
    sqq += q * q, sqx += q * (com_x(s) - x0);
  }
  return sqx / sqq;
}

/// Aulisa & Capodaglio eq. (52) against eq. (49), x = g_x t^2 / 3: the first probe's x displacement
/// (history column probe_NAME_ux, after the probe's D position columns). NaN without a probe.
double rolling_disk_mean_relative_error(const Spec& spec, const History& h) {
  if (spec.output.probes.empty() || h.samples.size() < 2) return kNaN;
  const auto ux = static_cast<std::size_t>(h.dim);  // position (D values), then displacement
  const double gx = spec.loads.gravity[0], t0 = h.samples.front().time;
  const double d0 = h.samples.front().probes.at(ux);
  double sum = 0.0;
  std::size_t count = 0;
  for (const auto& s : h.samples) {
    const double t = s.time - t0;
    if (!(t > 0)) continue;
    const double exact = gx * t * t / 3.0;
    sum += std::abs(exact - (s.probes.at(ux) - d0)) / std::abs(exact);
    ++count;
  }
  return count > 0 ? sum / static_cast<double>(count) : kNaN;
}

/// A rigid solid disk rolling without slip from rest down a plane along x (gravity (g_x, g_y) =
/// g (sin theta, -cos theta) in the plane's axes): d(t) = g_x t^2 / 3 (Iaconeta 2017 eqs. (64)-(66)).
double rolling_displacement(const Spec& spec, double t) { return spec.loads.gravity[0] * t * t / 3.0; }

/// The fitted centre-of-mass acceleration over the rolling one, 2/3 g_x.
double rolling_acceleration_ratio(const Spec& spec, const History& h) {
  return fitted_com_displacement_acceleration_x(h) / (2.0 / 3.0 * spec.loads.gravity[0]);
}

/// (d(t_end) - d_exact(t_end)) / d_exact(t_end), d the centre of mass's x displacement.
double rolling_final_displacement_error(const Spec& spec, const History& h) {
  if (h.samples.size() < 2) return kNaN;
  const double t = h.samples.back().time - h.samples.front().time;
  const double exact = rolling_displacement(spec, t);
  return (com_x(h.samples.back()) - com_x(h.samples.front()) - exact) / exact;
}

/// Iaconeta 2017 eq. (67) over the output times: sqrt(sum (u - u_num)^2), u and u_num the
/// horizontal components (eq. (66): the plane's x times cos theta, cos theta = -g_y / |g|).
double rolling_displacement_error_norm(const Spec& spec, const History& h) {
  if (h.samples.size() < 2 || h.dim < 2) return kNaN;
  const double gx = spec.loads.gravity[0], gy = spec.loads.gravity[1];
  const double cos_theta = -gy / std::hypot(gx, gy);
  const double x0 = com_x(h.samples.front()), t0 = h.samples.front().time;
  double sum = 0.0;
  for (const auto& s : h.samples) {
    const double e = (rolling_displacement(spec, s.time - t0) - (com_x(s) - x0)) * cos_theta;
    sum += e * e;
  }
  return std::sqrt(sum);
}

/// The free vibration of the first probe after gravity is switched off (Aulisa & Capodaglio Test B,
/// extraction AT-9): its displacement along the gravity's largest component, over the output times
/// after loads.gravity_scale's last table time. Cycles run between successive upward crossings of
/// the signal's mean over whole cycles (linear interpolation between output times).
struct FreeVibration {
  double period = kNaN;  // mean over the whole cycles
  double decay = kNaN;   // 1 - (peak-to-peak of the last cycle) / (of the first)
  double offset = kNaN;  // mean over the whole cycles / peak-to-peak of the first
};

FreeVibration free_vibration(const Spec& spec, const History& h) {
  FreeVibration out;
  if (spec.output.probes.empty() || h.samples.size() < 4) return out;
  int axis = 0;
  for (int a = 1; a < h.dim; ++a)
    if (std::abs(spec.loads.gravity[a]) > std::abs(spec.loads.gravity[axis])) axis = a;
  const auto column = static_cast<std::size_t>(h.dim + axis);  // position (D values), then displacement
  const TimeFunction& scale = spec.loads.gravity_scale;
  const double t_free = scale.times.empty() ? h.samples.front().time : scale.times.back();
  std::vector<double> t, u;
  for (const auto& s : h.samples)
    if (s.time >= t_free) t.push_back(s.time), u.push_back(s.probes.at(column));
  if (t.size() < 4) return out;
  const auto mean_between = [&](double a, double b) {  // trapezoid rule, whole intervals in [a, b]
    double sum = 0.0, length = 0.0;
    for (std::size_t k = 1; k < t.size(); ++k)
      if (t[k - 1] >= a && t[k] <= b)
        sum += 0.5 * (u[k] + u[k - 1]) * (t[k] - t[k - 1]), length += t[k] - t[k - 1];
    return length > 0 ? sum / length : kNaN;
  };
  const auto upward_crossings = [&](double level) {
    std::vector<double> times;
    for (std::size_t k = 1; k < t.size(); ++k)
      if (u[k - 1] < level && u[k] >= level)
        times.push_back(t[k - 1] + (level - u[k - 1]) / (u[k] - u[k - 1]) * (t[k] - t[k - 1]));
    return times;
  };
  std::vector<double> crossings = upward_crossings(mean_between(t.front(), t.back()));
  if (crossings.size() < 2) return out;
  const double centre = mean_between(crossings.front(), crossings.back());  // over whole cycles
  crossings = upward_crossings(centre);
  if (crossings.size() < 2) return out;
  const auto peak_to_peak = [&](double a, double b) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::size_t k = 0; k < t.size(); ++k)
      if (t[k] >= a && t[k] <= b) lo = std::min(lo, u[k]), hi = std::max(hi, u[k]);
    return hi - lo;
  };
  const std::size_t n = crossings.size();
  const double first = peak_to_peak(crossings[0], crossings[1]);
  out.period = (crossings[n - 1] - crossings[0]) / static_cast<double>(n - 1);
  out.decay = 1.0 - peak_to_peak(crossings[n - 2], crossings[n - 1]) / first;
  out.offset = centre / first;
  return out;
}

/// The index of a solver column of history.csv (implicit runs' Newton and node-probe columns).
std::optional<std::size_t> solver_column(const History& h, const std::string& name) {
  const auto it = std::find(h.solver_columns.begin(), h.solver_columns.end(), name);
  if (it == h.solver_columns.end()) return std::nullopt;
  return static_cast<std::size_t>(it - h.solver_columns.begin());
}

/// The block on a rigid incline (examples/incline-friction): gravity (g sin theta, -g cos theta).
double sliding_block_error(const Spec& spec, const History& h) {
  if (h.samples.size() < 2) return kNaN;
  const double gx = spec.loads.gravity[0], gy = spec.loads.gravity[1];
  const double mu = spec.contact.law.law == ContactLaw::Coulomb ? spec.contact.law.friction : 0.0;
  const double slide = std::max(0.0, gx - mu * std::abs(gy));  // g (sin theta - mu cos theta)
  const double x0 = h.samples.front().body_com_position[0][0];
  const double t_end = h.samples.back().time;
  double worst = 0.0;
  for (const auto& s : h.samples) {
    if (s.time < 0.5 * t_end) continue;
    const double exact = 0.5 * slide * s.time * s.time;
    const double scale = slide > 0.0 ? exact : 0.5 * gx * s.time * s.time;
    worst = std::max(worst, std::abs(s.body_com_position[0][0] - x0 - exact) / scale);
  }
  return worst;
}

}  // namespace

double shock_plateau_stress(std::vector<double> stress_xx) {
  if (stress_xx.empty()) return kNaN;
  double largest = 0.0;
  for (double& s : stress_xx) largest = std::max(largest, s = -s);
  if (!(largest > 0)) return kNaN;
  std::erase_if(stress_xx, [&](double s) { return s < 0.5 * largest; });
  const auto middle = stress_xx.begin() + static_cast<std::ptrdiff_t>(stress_xx.size() / 2);
  std::nth_element(stress_xx.begin(), middle, stress_xx.end());
  return *middle;
}

double vibrating_bar_com_velocity(double v0, double wave_speed, double length, double t) {
  return 2.0 * v0 / std::numbers::pi * std::cos(std::numbers::pi * wave_speed * t / (2.0 * length));
}

double evaluate_measure(std::string_view name, const Spec& spec, const History& history,
                        double momentum_scale, const FinalState* final_state) {
  if (name == "fitted_com_acceleration_x") return fitted_com_acceleration_x(history);
  if (name == "fitted_com_displacement_acceleration_x")
    return fitted_com_displacement_acceleration_x(history);
  if (name == "rolling_disk_mean_relative_error") return rolling_disk_mean_relative_error(spec, history);
  if (name == "rolling_acceleration_ratio") return rolling_acceleration_ratio(spec, history);
  if (name == "rolling_final_displacement_error") return rolling_final_displacement_error(spec, history);
  if (name == "rolling_displacement_error_norm") return rolling_displacement_error_norm(spec, history);
  if (name == "node_probe_final_uy") {  // the first output.node_probes node, last row (implicit runs)
    if (spec.output.node_probes.empty() || history.samples.empty()) return kNaN;
    const auto column = solver_column(history, "node_" + spec.output.node_probes[0].name + "_uy");
    return column ? history.samples.back().solver.at(*column) : kNaN;
  }
  if (name == "implicit_step_cuts") {  // the sum of history.csv's step_cuts column (implicit runs)
    const auto column = solver_column(history, "step_cuts");
    if (!column) return kNaN;
    double cuts = 0.0;
    for (const auto& s : history.samples) cuts += s.solver.at(*column);
    return cuts;
  }
  if (name == "free_vibration_period") return free_vibration(spec, history).period;
  if (name == "free_vibration_amplitude_decay") return free_vibration(spec, history).decay;
  if (name == "free_vibration_mean_offset") return free_vibration(spec, history).offset;
  if (name.starts_with("final_max_") && name.size() == 11) {  // final_max_x, _y, _z
    const auto axis = static_cast<std::size_t>(name.back() - 'x');
    return final_state && axis < 3 ? final_state->reach[axis] : kNaN;
  }
  if (name == "final_max_radius_xy") return final_state ? final_state->radius_xy : kNaN;
  if (name == "final_runout_x") return final_state ? final_state->runout_x : kNaN;
  if (name == "temperature_max") {  // coupled heat: the largest temperature_max of history.csv
    const auto column = solver_column(history, "temperature_max");
    if (!column || history.samples.empty()) return kNaN;
    double largest = -std::numeric_limits<double>::infinity();
    for (const auto& s : history.samples) largest = std::max(largest, s.solver.at(*column));
    return largest;
  }
  if (name == "internal_kinetic_energy_change") {  // coupled heat: (U + K)(end) / (U + K)(0) - 1
    const auto column = solver_column(history, "internal_energy");
    if (!column || history.samples.empty()) return kNaN;
    const auto energy = [&](const HistorySample& s) { return s.solver.at(*column) + s.kinetic_energy; };
    return energy(history.samples.back()) / energy(history.samples.front()) - 1.0;
  }
  if (name == "bounce_first_impact_time") return bounces_of_first_body(spec, history).first_impact_time;
  if (name == "bounce_apex_fraction" || name == "bounce_lowest_apex_fraction") {
    const auto apexes = bounces_of_first_body(spec, history).apex_fractions;
    if (apexes.empty()) return kNaN;
    return name == "bounce_apex_fraction" ? apexes.front() : *std::min_element(apexes.begin(), apexes.end());
  }
  if (name == "total_mass_change") {
    if (history.samples.empty()) return kNaN;
    const auto mass = [](const HistorySample& s) {
      double m = 0.0;
      for (double b : s.body_mass) m += b;
      return m;
    };
    return mass(history.samples.back()) / mass(history.samples.front()) - 1.0;
  }
  if (name == "shock_plateau_stress")
    return final_state ? shock_plateau_stress(final_state->stress_xx) : kNaN;
  if (name == "max_relative_energy_error") return max_relative_energy_error(history);
  if (name == "max_relative_momentum_error") return max_relative_momentum_error(history, momentum_scale);
  if (name == "min_jacobian") {
    double j = std::numeric_limits<double>::infinity();
    for (const auto& s : history.samples) j = std::min(j, s.min_jacobian);
    return history.samples.empty() ? kNaN : j;
  }
  if (name == "late_kinetic_energy_peak_change") {
    if (history.samples.empty()) return kNaN;
    const double t_end = history.samples.back().time, window = 0.1 * (t_end - history.samples.front().time);
    double peak = 0.0;
    for (const auto& s : history.samples)
      if (s.time >= t_end - window) peak = std::max(peak, s.kinetic_energy);
    return peak / history.samples.front().kinetic_energy - 1.0;
  }
  if (name == "final_kinetic_energy_fraction") {
    double peak = 0.0;
    for (const auto& s : history.samples) peak = std::max(peak, s.kinetic_energy);
    return history.samples.empty() || !(peak > 0.0) ? kNaN : history.samples.back().kinetic_energy / peak;
  }
  if (name == "kinetic_energy_change" || name == "total_energy_change") {
    if (history.samples.empty()) return kNaN;
    const auto& first = history.samples.front();
    const auto& last = history.samples.back();
    if (name == "kinetic_energy_change") return last.kinetic_energy / first.kinetic_energy - 1.0;
    return relative_drift(energy_balance(last) - energy_balance(first), energy_scale(history));
  }
  if (name == "mean_rms_velocity_change") {
    if (history.samples.size() < 2) return kNaN;
    double sum = 0.0;
    for (std::size_t k = 1; k < history.samples.size(); ++k) sum += history.samples[k].rms_velocity_change;
    return sum / static_cast<double>(history.samples.size() - 1);
  }
  if (name == "final_time") return history.samples.empty() ? kNaN : history.samples.back().time;
  if (name.starts_with("final_com_velocity_")) {
    const int axis = name.back() - 'x';
    if (history.samples.empty() || axis >= history.dim) return kNaN;
    const auto& last = history.samples.back();
    double mass = 0.0;
    for (double m : last.body_mass) mass += m;
    return last.momentum[axis] / mass;
  }
  if (name == "vibrating_bar_com_velocity_error") return bar_velocity_error(spec, history);
  if (name == "vibrating_bar_period_error") return bar_period_error(spec, history);
  if (name == "sliding_block_displacement_error") return sliding_block_error(spec, history);
  return kNaN;
}

}  // namespace matpoint
