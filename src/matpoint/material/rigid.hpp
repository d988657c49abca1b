// A rigid material: its particles move with a prescribed velocity (MaterialSpec::rigid_velocity,
// imposed by the contact fields, explicit/contact.hpp) and feel no stress. It has mass, for the
// contact normals, but no elastic energy and no wave speed (it does not limit the time step).
#pragma once

#include "matpoint/core/types.hpp"

namespace matpoint {

struct Rigid {
  double density;

  template <int D>
  [[nodiscard]] Mat<D> stress(const Mat<D>& /*F*/, double& sigma_zz) const {
    sigma_zz = 0.0;
    return Mat<D>::Zero();
  }
  template <int D>
  [[nodiscard]] double energy_density(const Mat<D>& /*F*/) const {
    return 0.0;
  }
  template <int D>
  [[nodiscard]] double wave_speed() const {
    return 0.0;
  }
};

}  // namespace matpoint
