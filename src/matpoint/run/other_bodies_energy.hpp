// Energies of bodies that are not particles (an implicit run's FE bodies), which a solver reports
// so that history.csv's totals and the energy guard's balance include them (run/run_loop.hpp).
#pragma once

namespace matpoint {

struct OtherBodiesEnergy {
  double kinetic = 0.0, strain = 0.0, external_work = 0.0;
};

}  // namespace matpoint
