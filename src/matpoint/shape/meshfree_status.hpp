// How the meshfree shape functions at one point were obtained (Iaconeta et al. 2017 §4.2; the
// failures that §6.5's repairs address, extraction §6.5).
#pragma once

#include <cstdint>

namespace matpoint {

enum class MeshfreeStatus : std::uint8_t {
  Ok,              // the asked basis
  Shepard,         // MLS: singular moment matrix, constant basis used (extraction §6.2)
  IllConditioned,  // LME: the Hessian's inverse condition number is below the tolerance (§6.5)
  NotConverged,    // LME: Newton on the dual problem did not converge (x outside the cloud's hull)
  Empty,           // no node carries weight
};

inline const char* to_string(MeshfreeStatus s) {
  switch (s) {
    case MeshfreeStatus::Ok:
      return "ok";
    case MeshfreeStatus::Shepard:
      return "shepard";
    case MeshfreeStatus::IllConditioned:
      return "ill_conditioned";
    case MeshfreeStatus::NotConverged:
      return "not_converged";
    case MeshfreeStatus::Empty:
      return "empty";
  }
  return "unknown";
}

}  // namespace matpoint
