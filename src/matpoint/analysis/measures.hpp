// Named quantities a run can measure and compare with a reference (input "checks", summary.json).
#pragma once

#include <array>
#include <string_view>

namespace matpoint {

struct MeasureInfo {
  std::string_view name;
  std::string_view meaning;
};

inline constexpr std::array<MeasureInfo, 38> kMeasures{{
    {"max_relative_energy_error",
     "max over output times of |B(t) - B(0)| / E_s, B = K + U + D - W_ext (kinetic, strain energy, friction "
     "work of contact, external work), E_s = max(K(0) + U(0), max |W_ext| over the run): the energy given or "
     "received, so a problem starting at rest under gravity is measured against the work of gravity"},
    {"max_relative_momentum_error",
     "max over output times of |P(t) - P(0) - I_ext(t)| / sum_p m_p |V_p(0)|, I_ext the impulse of gravity "
     "and of the grid velocity conditions (contact with a rigid body is not counted in it)"},
    {"min_jacobian", "smallest det F of any particle at any output time"},
    {"mean_rms_velocity_change",
     "mean over the output times after t = 0 of sqrt(mean_p |V_p(t) - V_p(0)|^2): the velocity error of a "
     "problem whose exact particle velocities stay at their initial values (Nairn 2026 §3.1)"},
    {"final_time", "simulated time reached at the end of the run"},
    {"kinetic_energy_change", "K(end) / K(0) - 1: the signed relative change of kinetic energy over the run"},
    {"final_kinetic_energy_fraction",
     "K(end) / max over output times of K: how far a collapse or flow has come to rest"},
    {"late_kinetic_energy_peak_change",
     "max K over the outputs in the last tenth of the run / K(0) - 1: for a periodic motion whose kinetic "
     "energy peaks in that window, the energy lost without the phase error of sampling at one time"},
    {"total_energy_change",
     "(B(end) - B(0)) / E_s: the signed relative change of the energy balance B = K + U + D - W_ext, with "
     "the scale E_s of max_relative_energy_error"},
    {"final_com_velocity_x", "x velocity of the centre of mass of all bodies at the last output"},
    {"final_com_velocity_y", "y velocity of the centre of mass of all bodies at the last output"},
    {"final_com_velocity_z", "z velocity of the centre of mass of all bodies at the last output"},
    {"vibrating_bar_period_error",
     "|T_measured - T_exact| / T_exact for a 1-D bar fixed at x = min and free at the other end, "
     "T_exact = 4 L / sqrt(E / rho), T_measured from the zero crossings of the centre-of-mass velocity"},
    {"vibrating_bar_com_velocity_error",
     "max over output times of |v_cm(t) - v_exact(t)| / v_amp, v_exact = v_amp cos(pi c t / (2 L)), "
     "v_amp = 2 v0 / pi, for the first-mode bar of examples/vibrating-bar-1d"},
    {"fitted_com_acceleration_x",
     "least-squares slope of the centre-of-mass x velocity against time over all output times (a body "
     "under constant acceleration)"},
    {"fitted_com_displacement_acceleration_x",
     "a of the least-squares fit x(t) - x(0) = a t^2 / 2 over all output times, x the centre of mass of all "
     "bodies: the acceleration of a body starting from rest, insensitive to velocity oscillations "
     "(examples/rolling-disk)"},
    {"rolling_disk_mean_relative_error",
     "Aulisa & Capodaglio eq. (52): the mean over the output times t > 0 of |x(t) - d(t)| / x(t), d the x "
     "displacement of the first probe (the disk's centre particle), x = g_x t^2 / 3 the rigid disk rolling "
     "without slip (eq. (49)) with g_x the input's gravity along x (the plane's axes) "
     "(examples/implicit-rolling-disk)"},
    {"rolling_acceleration_ratio",
     "fitted_com_displacement_acceleration_x / (2/3 g_x): the acceleration of the bodies' centre of mass "
     "against a rigid solid disk rolling without slip from rest down a plane along x, a = 2/3 g sin(theta) "
     "(Iaconeta 2017 eqs. (64)-(66)), g_x = g sin(theta) the input's gravity along x (the plane's axes); 1 "
     "when rolling, 1.5 when sliding without friction (examples/implicit-rolling-disk-incline)"},
    {"rolling_final_displacement_error",
     "(d(t_end) - g_x t_end^2 / 3) / (g_x t_end^2 / 3): the signed relative error of the x displacement d of "
     "the bodies' centre of mass at the last output against the disk rolling without slip (Iaconeta 2017 eq. "
     "(66) in the plane's axes; g_x as rolling_acceleration_ratio)"},
    {"rolling_displacement_error_norm",
     "Iaconeta 2017 eq. (67): sqrt(sum over the output times of (u(t) - u_num(t))^2) in m, u = (1/3) g sin "
     "theta cos theta t^2 the horizontal displacement of the disk rolling without slip (eq. (66)), u_num = d "
     "cos theta, d the x displacement of the bodies' centre of mass, theta from the input's gravity (tan "
     "theta = g_x / -g_y); it grows with the number of output times (the paper does not state its sampling)"},
    {"node_probe_final_uy",
     "implicit runs: the y displacement in the last step of the mesh node of the first output.node_probes "
     "entry, "
     "at the last output (the whole displacement in a single-step static analysis: "
     "examples/cantilever-static)"},
    {"implicit_step_cuts",
     "implicit runs: the number of step cuts over the run (a step whose Newton iteration failed is halved "
     "and "
     "retried), the sum of history.csv's step_cuts column; 0 when Newton converged at every step"},
    {"free_vibration_period",
     "the first probe's free vibration after gravity is switched off (loads.gravity_scale; over the output "
     "times after its last table time): the mean period of its displacement along the gravity's largest "
     "component, between upward crossings of its mean over whole cycles (Aulisa & Capodaglio Test B, "
     "examples/implicit-cantilever)"},
    {"free_vibration_amplitude_decay",
     "for the free vibration of free_vibration_period: 1 - (peak-to-peak of the last whole cycle) / "
     "(peak-to-peak "
     "of the first): the amplitude lost (Aulisa & Capodaglio Test B)"},
    {"free_vibration_mean_offset",
     "for the free vibration of free_vibration_period: the mean displacement over the whole cycles divided "
     "by the "
     "peak-to-peak of the first: the oscillation's centre against the undeformed position (Test B)"},
    {"shock_plateau_stress",
     "at the end of the run, the median of -sigma_xx over the particles where -sigma_xx is at least half its "
     "largest value: the plateau behind a compressive shock moving along x (examples/shock-interface)"},
    {"sliding_block_displacement_error",
     "max over the outputs in the second half of the run of |d(t) - d_exact(t)| / s(t): body 0 slides on a "
     "rigid floor normal to y with gravity (g sin theta, -g cos theta) and Coulomb friction mu; d = x shift "
     "of its centre of mass, d_exact = 1/2 g (sin theta - mu cos theta) t^2 when positive (sliding), else 0 "
     "(sticking); s = d_exact when sliding, 1/2 g sin theta t^2 (the frictionless slide) when sticking"},
    {"temperature_max",
     "coupled heat (input section heat): the largest particle temperature over the output times (history.csv "
     "temperature_max), K: the hottest spot of a run heated by friction or compression (Nairn 2026 Fig. 7)"},
    {"internal_kinetic_energy_change",
     "coupled heat: (U + K)(end) / (U + K)(0) - 1, U = history.csv internal_energy (strain energy, "
     "thermoelastic coupling and heat: docs/theory/heat.md) and K the kinetic energy: conserved by a "
     "globally adiabatic run, where friction's work becomes heat (Nairn 2026 Fig. 9A)"},
    {"bounce_first_impact_time",
     "body 0 dropped under gravity: the time of its centre of mass's largest downward speed before it first "
     "stops falling, when the contact force starts to exceed gravity (free fall from a clearance c: "
     "sqrt(2 c / |g|)) (analysis/bounce.hpp)"},
    {"bounce_apex_fraction",
     "body 0 dropped under gravity: the first apex of its centre of mass after the first impact, (h_apex - "
     "h_min) / (h(0) - h_min), h the height against gravity, h_min the lowest of the impact: the share of "
     "the drop the first bounce regains (Aulisa & Capodaglio Fig. 12) (analysis/bounce.hpp)"},
    {"bounce_lowest_apex_fraction",
     "as bounce_apex_fraction, the lowest apex of all the bounces in the run: no decay of the bounces keeps "
     "it near bounce_apex_fraction"},
    {"total_mass_change",
     "M(end) / M(0) - 1: the relative change of the bodies' total mass (history.csv mass columns) over the "
     "run"},
    {"final_max_x",
     "at the end of the run, the largest x of any particle centre (about half a particle spacing inside the "
     "body's surface): a run-out front (examples/soil-column-collapse)"},
    {"final_runout_x",
     "at the end of the run, the x behind which 99 % of the bodies' mass lies (particle centres): the front "
     "of a granular deposit without the thin tail of single particles that its front sheds, whose length "
     "scales with the particle size (examples/soil-column-collapse/granular.json)"},
    {"final_max_y", "as final_max_x, along y"},
    {"final_max_z",
     "as final_max_x, along z: the length of a rod standing on a wall at z = 0 (examples/taylor-bar)"},
    {"final_max_radius_xy",
     "3-D: at the end of the run, the largest distance of any particle centre from the z axis: the radius "
     "of a rod along the z axis where it is widest, less about half a particle spacing (the foot of "
     "examples/taylor-bar)"},
}};

[[nodiscard]] constexpr bool is_known_measure(std::string_view name) {
  for (const auto& m : kMeasures)
    if (m.name == name) return true;
  return false;
}

}  // namespace matpoint
