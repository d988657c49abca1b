// Particle generators: fill a body's shape with particles at the centres of the sub-cells of each
// grid cell (particles_per_cell per direction), and the cell sort that keeps transfers local.
#pragma once

#include <vector>

#include "matpoint/grid/grid.hpp"
#include "matpoint/io/spec.hpp"
#include "matpoint/particles/particle_set.hpp"

namespace matpoint {

/// Adds the particles of one body; returns how many were added.
template <int D>
std::size_t generate_body(const BodySpec& body, int body_index, const MaterialSpec& material,
                          const Grid<D>& grid, ParticleSet<D>& particles);

/// True when x lies inside the body's shape (boundary included).
template <int D>
bool shape_contains(const BodySpec& body, const Vec<D>& x);

/// Sorts all particle arrays by the cell that holds them, cells in brick-major order
/// (BrickSchedule::brick_major_cell: the particles of one brick of the scatter lie together), and
/// by id within a cell: the resulting order does not depend on the order before. `sorted_cells`,
/// when given, receives each particle's brick-major cell in the new order.
template <int D>
void sort_by_cell(const Grid<D>& grid, ParticleSet<D>& particles, std::vector<Index>* sorted_cells = nullptr);

}  // namespace matpoint
