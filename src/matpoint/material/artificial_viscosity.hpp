// Artificial bulk viscosity (von Neumann & Richtmyer 1950, Nairn 2026 ref. [28]): a pressure q added
// to every material's stress while the particle is being compressed, with the linear and
// quadratic coefficients of NairnMPM (Nairn 2026 extraction §3: defaults A1 = 0.2, A2 = 2.0):
//   q = rho h |D_kk| (A1 c + A2 h |D_kk|)  if D_kk = tr L < 0,  else 0
// rho: current density, h: smallest cell size, c: the material's wave speed. The work -q dV is
// heat: materials with an energy history (Mie-Grueneisen) add it to their internal energy; for the
// elastic models it is dissipated.
#pragma once

namespace matpoint {

struct ArtificialViscosity {
  double linear = 0.0;     // A1
  double quadratic = 0.0;  // A2
  double cell_size = 0.0;  // h

  [[nodiscard]] bool active() const { return linear != 0.0 || quadratic != 0.0; }
  [[nodiscard]] double pressure(double density, double volume_rate, double wave_speed) const {
    if (!(volume_rate < 0.0)) return 0.0;
    const double rate = -volume_rate;
    return density * cell_size * rate * (linear * wave_speed + quadratic * cell_size * rate);
  }
};

}  // namespace matpoint
