// An upper estimate of the memory a run needs, from the validated Spec alone (before any particle
// is made), so that an input asking for more than the machine has is refused with exit 2 and a
// number instead of an out-of-memory kill (issue 8, "input safety").
#pragma once

#include <cstdint>
#include <optional>

#include "matpoint/io/spec.hpp"

namespace matpoint {

struct MemoryEstimate {
  double particles = 0;  // upper estimate: every sub-cell centre of each body's bounding box
  double nodes = 0;
  int fields = 1;  // grid velocity fields: one, or with contact one per body (or material)
  double bytes = 0;
};

/// Particles from the bodies' bounding boxes (cells covered x particles_per_cell^D), bytes from the
/// per-particle and per-node storage of the explicit solver with the chosen basis.
MemoryEstimate estimate_memory(const Spec& spec);

/// MemAvailable of /proc/meminfo in bytes, or nothing where it cannot be read.
std::optional<double> available_memory();

/// Throws InputError naming the estimate when it exceeds `available` (default: MemAvailable).
void check_memory(const Spec& spec, std::optional<double> available = available_memory());

}  // namespace matpoint
