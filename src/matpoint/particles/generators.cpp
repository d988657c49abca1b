#include "matpoint/particles/generators.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <random>

#include "matpoint/grid/brick_schedule.hpp"
#include "matpoint/mesh/triangle_pattern.hpp"
#include "matpoint/particles/graded_generators.hpp"
#include "matpoint/particles/serial_order.hpp"

namespace matpoint {

namespace {

bool polygon_contains(const std::vector<std::array<double, 2>>& poly, double x, double y) {
  bool inside = false;  // even-odd rule
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const auto& a = poly[i];
    const auto& b = poly[j];
    if ((a[1] > y) != (b[1] > y) && x < (b[0] - a[0]) * (y - a[1]) / (b[1] - a[1]) + a[0]) inside = !inside;
  }
  return inside;
}

template <int D>
Vec<D> initial_velocity(const BodySpec& body, const Vec<D>& x) {
  Vec<D> v;
  double phase = body.sine_phase;
  for (int a = 0; a < D; ++a) phase += body.sine_wave_vector[a] * x[a];
  for (int a = 0; a < D; ++a)
    v[a] = body.velocity[a] + (body.has_sine_velocity ? body.sine_amplitude[a] * std::sin(phase) : 0.0);
  if (body.has_velocity_gradient)
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) v[a] += body.velocity_gradient[a][b] * x[b];
  return v;
}

/// Where a generator puts each particle it generates, in generation order: the body's initial
/// velocity and velocity noise (drawn for every generated particle, so the same seed gives every
/// particle the same noise on any rank count), then the set stores it or, when `keep` refuses it,
/// only counts its id.
template <int D>
class ParticleEmitter {
 public:
  ParticleEmitter(const BodySpec& body, int body_index, const MaterialSpec& material,
                  ParticleSet<D>& particles, const KeepParticle<D>& keep)
      : body_(body),
        body_index_(body_index),
        material_(material),
        particles_(particles),
        keep_(keep),
        rng_(body.noise_seed) {}

  /// A particle at x of initial volume `volume` (mass = density x volume) and domain edges `size`.
  void operator()(const Vec<D>& x, double volume, const Vec<D>& size) {
    emit(x, material_.density * volume, volume, size);
  }
  /// The same with its mass given (the graded generators integrate it).
  void emit(const Vec<D>& x, double mass, double volume, const Vec<D>& size) {
    Vec<D> v = initial_velocity<D>(body_, x);
    if (body_.noise_amplitude > 0.0)
      for (int a = 0; a < D; ++a) v[a] += body_.noise_amplitude * normal_(rng_);
    ++generated_;
    if (keep_ && !keep_(x)) {
      particles_.skip();
      return;
    }
    particles_.add(x, v, mass, volume, size, body_.material, body_index_);
  }

  [[nodiscard]] std::size_t generated() const { return generated_; }

 private:
  const BodySpec& body_;
  int body_index_;
  const MaterialSpec& material_;
  ParticleSet<D>& particles_;
  const KeepParticle<D>& keep_;
  std::mt19937 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
  std::size_t generated_ = 0;
};

template <int D>
void bounding_box(const BodySpec& body, Vec<D>& lo, Vec<D>& hi) {
  for (int a = 0; a < D; ++a) {
    switch (body.shape) {
      case BodyShape::Box:
      case BodyShape::GradedBeam:
        lo[a] = body.min[a];
        hi[a] = body.max[a];
        break;
      case BodyShape::Disk:
      case BodyShape::GradedDisk:
        lo[a] = body.center[a] - body.radius;
        hi[a] = body.center[a] + body.radius;
        break;
      case BodyShape::Polygon:
        if (a == 2) {  // a prism along z
          lo[a] = body.min[a];
          hi[a] = body.max[a];
          break;
        }
        lo[a] = hi[a] = body.polygon.front()[a];
        for (const auto& v : body.polygon) {
          lo[a] = std::min(lo[a], v[a]);
          hi[a] = std::max(hi[a], v[a]);
        }
        break;
    }
  }
}

/// array's blocks of `count` elements in the storage order `order` (block k <- block order[k]).
template <class T>
void permute(const std::vector<Index>& order, std::vector<T>& array, std::size_t count) {
  if (count == 0) return;
  const std::vector<T> copy = array;
  if (count == 1) {
    for (std::size_t k = 0; k < order.size(); ++k) array[k] = copy[order[k]];
    return;
  }
  for (std::size_t k = 0; k < order.size(); ++k)
    std::copy_n(copy.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(order[k]) * count), count,
                array.begin() + static_cast<std::ptrdiff_t>(k * count));
}

/// Aulisa & Capodaglio's graded disk or beam (particles/graded_generators.hpp; the beam's left end
/// at box min x, its mid-height the box's); each particle's domain is the square of its volume
/// (only the domain-based bases of explicit runs use it).
void add_graded(const BodySpec& body, const MaterialSpec& material, ParticleEmitter<2>& emit) {
  const GradedParticles g =
      body.shape == BodyShape::GradedDisk
          ? graded_disk(Vec<2>(body.center[0], body.center[1]), body.radius, body.core_radius,
                        body.core_divisions, body.layer_growth, material.density)
          : graded_beam(body.min[0], 0.5 * (body.min[1] + body.max[1]), body.max[1] - body.min[1],
                        body.max[0] - body.min[0], body.core_height, body.core_divisions, body.layer_growth,
                        material.density);
  for (std::size_t k = 0; k < g.position.size(); ++k) {
    const double side = std::sqrt(g.volume[k]);
    emit.emit(g.position[k], g.mass[k], g.volume[k], Vec<2>(side, side));
  }
}

/// bodies[].placement "gauss" on a structured T3 mesh (Iaconeta 2017 §5.2: three material points
/// per triangle): each triangle of each grid cell, split as the mesh splits it (mesh/triangle_pattern.hpp),
/// gets the points of the symmetric 3-point rule, barycentric (2/3, 1/6, 1/6) and its permutations
/// (exact for quadratics; Zienkiewicz & Taylor vol. 1, Table 9.3), each with a third of the
/// triangle's area; the points outside the body's shape are left out.
void add_triangle_points(const BodySpec& body, const Grid<2>& grid, const std::array<int, 2>& first,
                         const std::array<int, 2>& last, ParticleEmitter<2>& emit) {
  const mesh::TrianglePattern pattern = *body.triangle_points;
  // a third of a triangle's area: half a cell (rising, falling, alternating) or a quarter (crossed)
  const double volume = grid.h[0] * grid.h[1] / (pattern == mesh::TrianglePattern::Crossed ? 12.0 : 6.0);
  const double side = std::sqrt(volume);
  for (int j = first[1]; j <= last[1]; ++j)
    for (int i = first[0]; i <= last[0]; ++i)
      for (const auto& t : mesh::cell_triangles(pattern, i, j))
        for (int k = 0; k < 3; ++k) {
          Vec<2> x = grid.origin;
          for (int c = 0; c < 3; ++c) {
            const auto& corner = mesh::kCellCorner[static_cast<std::size_t>(t[static_cast<std::size_t>(c)])];
            const double weight = c == k ? 2.0 / 3.0 : 1.0 / 6.0;
            x[0] += weight * (i + corner[0]) * grid.h[0];
            x[1] += weight * (j + corner[1]) * grid.h[1];
          }
          if (shape_contains<2>(body, x)) emit(x, volume, Vec<2>(side, side));
        }
}

}  // namespace

template <int D>
bool shape_contains(const BodySpec& body, const Vec<D>& x) {
  switch (body.shape) {
    case BodyShape::Box:
    case BodyShape::GradedBeam:
      for (int a = 0; a < D; ++a)
        if (x[a] < body.min[a] || x[a] > body.max[a]) return false;
      return true;
    case BodyShape::Disk:
    case BodyShape::GradedDisk: {
      double r2 = 0;
      for (int a = 0; a < D; ++a) r2 += (x[a] - body.center[a]) * (x[a] - body.center[a]);
      return r2 <= body.radius * body.radius;
    }
    case BodyShape::Polygon:
      if constexpr (D == 2) return polygon_contains(body.polygon, x[0], x[1]);
      if constexpr (D == 3)  // a prism along z
        return x[2] >= body.min[2] && x[2] <= body.max[2] && polygon_contains(body.polygon, x[0], x[1]);
      return false;
  }
  return false;
}

namespace {

/// Particles at the centres of ppc^D equal sub-cells of every grid cell in [first, last] (or at the
/// cell's ppc^D Gauss-Legendre points, ppc = 2 or 3, each with its weight's share of the cell's
/// volume: bodies[].placement "gauss"), those inside the body's shape.
template <int D>
void add_lattice_points(const BodySpec& body, const Grid<D>& grid, const std::array<int, D>& first,
                        const std::array<int, D>& last, ParticleEmitter<D>& emit) {
  const int ppc = body.particles_per_cell;
  const Vec<D> sub = grid.h / ppc;
  // Gauss-Legendre on [0, 1]: 2 points (1 -+ 1/sqrt(3)) / 2 with weights 1/2; 3 points
  // (1 - sqrt(3/5)) / 2, 1/2, (1 + sqrt(3/5)) / 2 with weights 5/18, 8/18, 5/18.
  const double g2 = 0.5 / std::sqrt(3.0), g3 = 0.5 * std::sqrt(0.6);
  const std::array<double, 3> gauss_abscissa = ppc == 3 ? std::array<double, 3>{0.5 - g3, 0.5, 0.5 + g3}
                                                        : std::array<double, 3>{0.5 - g2, 0.5 + g2, 0.0};
  const std::array<double, 3> gauss_weight =
      ppc == 3 ? std::array<double, 3>{5.0 / 18, 8.0 / 18, 5.0 / 18} : std::array<double, 3>{0.5, 0.5, 0.0};
  // The offset of sub-cell s in its cell: the sub-cell centre (s + 1/2) h / ppc, or the Gauss point.
  const auto offset = [&](int s, int a) {
    if (body.gauss_points) return gauss_abscissa[static_cast<std::size_t>(s)] * grid.h[a];
    return (s + 0.5) * sub[a];
  };
  const auto particle_volume = [&](const std::array<int, D>& s) {
    if (!body.gauss_points) return sub.prod();
    double v = grid.h.prod();
    for (int a = 0; a < D; ++a) v *= gauss_weight[static_cast<std::size_t>(s[a])];
    return v;
  };

  // Walk cells, then sub-cells, in row-major order (x fastest), so particles come out cell-sorted.
  std::array<int, D> cell = first;
  while (true) {
    std::array<int, D> s{};
    while (true) {
      Vec<D> x;
      for (int a = 0; a < D; ++a) x[a] = grid.origin[a] + cell[a] * grid.h[a] + offset(s[a], a);
      if (shape_contains<D>(body, x)) emit(x, particle_volume(s), sub);
      int a = 0;
      while (a < D && ++s[a] == ppc) s[a++] = 0;
      if (a == D) break;
    }
    int a = 0;
    while (a < D && ++cell[a] > last[a]) cell[a] = first[a], ++a;
    if (a == D) break;
  }
}

}  // namespace

template <int D>
std::size_t generate_body(const BodySpec& body, int body_index, const MaterialSpec& material,
                          const Grid<D>& grid, ParticleSet<D>& particles, const KeepParticle<D>& keep) {
  Vec<D> lo = Vec<D>::Zero(), hi = Vec<D>::Zero();
  bounding_box<D>(body, lo, hi);
  std::array<int, D> first{}, last{};
  for (int a = 0; a < D; ++a) {
    first[a] = std::max(0, static_cast<int>(std::floor((lo[a] - grid.origin[a]) / grid.h[a])));
    last[a] = std::min(grid.cells[a] - 1, static_cast<int>(std::floor((hi[a] - grid.origin[a]) / grid.h[a])));
  }
  ParticleEmitter<D> emit(body, body_index, material, particles, keep);
  if constexpr (D == 2) {
    if (body.shape == BodyShape::GradedDisk || body.shape == BodyShape::GradedBeam)
      add_graded(body, material, emit);
    else if (body.triangle_points)
      add_triangle_points(body, grid, first, last, emit);
    else
      add_lattice_points<D>(body, grid, first, last, emit);
  } else {
    add_lattice_points<D>(body, grid, first, last, emit);
  }
  return emit.generated();
}

namespace {

/// The permutation that orders particles by (cell, id), cell[p] in [lowest, highest]: the serial
/// storage order (docs/scale-out.md §6), by id within a cell so that it depends on where the
/// particles are and not on how they were stored before (on any number of ranks, once particles
/// migrate). A counting sort over the cells [lowest, highest] when they are not many more than the
/// particles (a serial run, a rank's slab of brick layers); a comparison sort when they are (a
/// rank's box cut along x or y spans whole rows of the brick-major numbering, mostly other ranks'
/// cells, e.g. 80 times its own at 1024 ranks in 3-D). Both give the same order.
std::vector<Index> order_by_cell_and_id(const std::vector<Index>& cell, Index lowest, Index highest,
                                        const std::vector<long>& id) {
  const std::size_t n = cell.size();
  std::vector<Index> order(n);
  const Index cell_count = highest - lowest + 1;
  if (cell_count > 8 * static_cast<Index>(n) + 65536) {
    std::iota(order.begin(), order.end(), Index{0});
    std::sort(order.begin(), order.end(),
              [&](Index a, Index b) { return serially_before(cell[a], id[a], cell[b], id[b]); });
    return order;
  }
  std::vector<Index> start(cell_count + 1, 0);
  for (const Index c : cell) ++start[c - lowest + 1];
  for (Index c = 0; c < cell_count; ++c) start[c + 1] += start[c];
  for (std::size_t p = 0; p < n; ++p) order[start[cell[p] - lowest]++] = static_cast<Index>(p);
  // After the placement loop start[c] is the end of cell c.
  const auto by_id = [&id](Index a, Index b) { return id[a] < id[b]; };
  for (Index c = 0, begin = 0; c < cell_count; begin = start[c], ++c)
    if (start[c] - begin > 1) std::sort(order.begin() + begin, order.begin() + start[c], by_id);
  return order;
}

}  // namespace

template <int D>
void sort_by_cell(const Grid<D>& grid, ParticleSet<D>& particles, std::vector<Index>* sorted_cells) {
  const std::size_t n = particles.size();
  // Cells in brick-major order: the particles of a brick of the scatter's schedule lie together.
  std::vector<Index> cell(n);
  bool sorted = true;
  Index lowest = std::numeric_limits<Index>::max(), highest = 0;
  for (std::size_t p = 0; p < n; ++p) {
    cell[p] = BrickSchedule<D>::brick_major_cell(grid, grid.cell_coords(particles.x[p]));
    lowest = std::min(lowest, cell[p]), highest = std::max(highest, cell[p]);
    if (p > 0 && serially_before(cell[p], particles.id[p], cell[p - 1], particles.id[p - 1])) sorted = false;
  }
  if (sorted) {
    if (sorted_cells != nullptr) *sorted_cells = std::move(cell);
    return;
  }
  const std::vector<Index> order = order_by_cell_and_id(cell, lowest, highest, particles.id);
  for_each_array(particles,
                 [&order](const char*, auto& array, std::size_t count) { permute(order, array, count); });
  if (sorted_cells != nullptr) {
    sorted_cells->resize(n);
    for (std::size_t q = 0; q < n; ++q) (*sorted_cells)[q] = cell[order[q]];
  }
}

#define MATPOINT_INSTANTIATE(D)                                                                    \
  template std::size_t generate_body<D>(const BodySpec&, int, const MaterialSpec&, const Grid<D>&, \
                                        ParticleSet<D>&, const KeepParticle<D>&);                  \
  template bool shape_contains<D>(const BodySpec&, const Vec<D>&);                                 \
  template void sort_by_cell<D>(const Grid<D>&, ParticleSet<D>&, std::vector<Index>*);
MATPOINT_INSTANTIATE(1)
MATPOINT_INSTANTIATE(2)
MATPOINT_INSTANTIATE(3)
#undef MATPOINT_INSTANTIATE

}  // namespace matpoint
