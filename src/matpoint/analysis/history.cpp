#include "matpoint/analysis/history.hpp"

#include <iomanip>
#include <limits>
#include <sstream>

namespace matpoint {

std::string History::csv() const {
  static constexpr const char* axis = "xyz";
  std::ostringstream out;
  out << "time,step,kinetic_energy,strain_energy,total_energy,external_work,energy_balance";
  for (int a = 0; a < dim; ++a) out << ",momentum_" << axis[a];
  out << ",min_jacobian,rms_velocity_change,friction_work,plastic_work";
  for (int b = 0; b < body_count; ++b) {
    out << ",body" << b << "_kinetic_energy,body" << b << "_strain_energy";
    for (int a = 0; a < dim; ++a) out << ",body" << b << "_momentum_" << axis[a];
    for (int a = 0; a < dim; ++a) out << ",body" << b << "_com_velocity_" << axis[a];
    for (int a = 0; a < dim; ++a) out << ",body" << b << "_com_" << axis[a];
  }
  for (int a = 0; a < dim; ++a) out << ",grid_momentum_difference_" << axis[a];
  out << ",checkerboard_velocity,grid_rms_velocity,hourglass_energy,dt";
  for (const auto& column : solver_columns) out << ',' << column;
  for (const auto& column : probe_columns) out << ',' << column;
  out << '\n' << std::setprecision(12);
  for (const auto& s : samples) {
    const double total = s.kinetic_energy + s.strain_energy;
    out << s.time << ',' << s.step << ',' << s.kinetic_energy << ',' << s.strain_energy << ',' << total << ','
        << s.external_work << ',' << total + s.friction_work + s.plastic_work - s.external_work;
    for (int a = 0; a < dim; ++a) out << ',' << s.momentum[a];
    out << ',' << s.min_jacobian << ',' << s.rms_velocity_change << ',' << s.friction_work << ','
        << s.plastic_work;
    for (int b = 0; b < body_count; ++b) {
      out << ',' << s.body_kinetic[b] << ',' << s.body_strain[b];
      for (int a = 0; a < dim; ++a) out << ',' << s.body_momentum[b][a];
      for (int a = 0; a < dim; ++a) out << ',' << s.body_com_velocity[b][a];
      for (int a = 0; a < dim; ++a) out << ',' << s.body_com_position[b][a];
    }
    for (int a = 0; a < dim; ++a) out << ',' << s.grid_momentum_difference[a];
    out << ',' << s.checkerboard_velocity << ',' << s.grid_rms_velocity << ',' << s.hourglass_energy << ','
        << s.dt;
    for (std::size_t c = 0; c < solver_columns.size(); ++c)
      out << ',' << (c < s.solver.size() ? s.solver[c] : std::numeric_limits<double>::quiet_NaN());
    for (std::size_t c = 0; c < probe_columns.size(); ++c)  // nan: a row from before the probe existed
      out << ',' << (c < s.probes.size() ? s.probes[c] : std::numeric_limits<double>::quiet_NaN());
    out << '\n';
  }
  return out.str();
}

}  // namespace matpoint
