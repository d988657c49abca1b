// The serial run's storage order of particles (docs/scale-out.md §6): by the brick-major cell at
// the last sort_by_cell (the sort key), then by id. Every particle-to-grid sum and every gather of
// other ranks' particles visits them in this order, on any number of ranks and threads.
#pragma once

#include "matpoint/core/types.hpp"

namespace matpoint {

/// True when the particle of sort key `key_a` and id `id_a` comes before the particle (key_b, id_b).
[[nodiscard]] inline bool serially_before(Index key_a, long id_a, Index key_b, long id_b) {
  return key_a != key_b ? key_a < key_b : id_a < id_b;
}

}  // namespace matpoint
