// Particle generators: fill a body's shape with particles at the centres of the sub-cells of each
// grid cell (particles_per_cell per direction), and the cell sort that keeps transfers local.
#pragma once

#include <functional>
#include <vector>

#include "matpoint/grid/grid.hpp"
#include "matpoint/io/spec.hpp"
#include "matpoint/particles/particle_set.hpp"

namespace matpoint {

/// Which generated particles a set stores, by position (a rank of a decomposed run: those in its
/// box); empty: every one.
template <int D>
using KeepParticle = std::function<bool(const Vec<D>&)>;

/// Generates the particles of one body in their generation order (the ids), stores those that
/// `keep` accepts (all when it is empty) and skips the others' ids; returns how many it generated.
template <int D>
std::size_t generate_body(const BodySpec& body, int body_index, const MaterialSpec& material,
                          const Grid<D>& grid, ParticleSet<D>& particles, const KeepParticle<D>& keep = {});

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
