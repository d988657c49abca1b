// The time history of a run (one sample per output time), kept in memory for the checks and
// written as history.csv.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace matpoint {

struct HistorySample {
  double time = 0.0;
  long step = 0;
  double dt = 0.0;  // the size of the step that reached this row (0 at the start)
  double kinetic_energy = 0.0, strain_energy = 0.0, external_work = 0.0;
  double friction_work = 0.0;  // energy dissipated by contact friction (docs/theory/contact.md)
  double plastic_work = 0.0;   // energy dissipated by plastic flow (material/hencky_plasticity.hpp)
  std::array<double, 3> momentum{}, external_impulse{};
  double min_jacobian = 1.0;
  double rms_velocity_change = 0.0;
  // Grid diagnostics (Gong 2015 extraction A18, A19; analysis/grid_modes.hpp, Simulation)
  std::array<double, 3> grid_momentum_difference{};
  double checkerboard_velocity = 0.0, grid_rms_velocity = 0.0, hourglass_energy = 0.0;
  std::vector<double> body_kinetic, body_strain, body_mass;
  std::vector<std::array<double, 3>> body_momentum, body_com_velocity, body_com_position;
  std::vector<double> solver;  // the solver's own columns, History::solver_columns (implicit: Newton)
  std::vector<double> probes;  // output.probes, History::probe_columns values (analysis/probes.hpp)
};

struct History {
  int dim = 2;
  int body_count = 1;
  std::vector<std::string> solver_columns;  // before the probes: e.g. newton_iterations (implicit)
  std::vector<std::string> probe_columns;   // the last columns: probe_NAME_x, ... (empty: no probes)
  std::vector<HistorySample> samples;

  /// The CSV text: header, then one row per sample (columns documented in docs/output.md).
  [[nodiscard]] std::string csv() const;
};

}  // namespace matpoint
