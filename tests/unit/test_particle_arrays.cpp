// for_each_array (particles/particle_set.hpp) and sort_by_cell (particles/generators.hpp): the
// visitor lists every per-particle array with its values per particle (the bytes per particle
// of docs/scale-out.md §5), and the cell sort carries every array of a particle together. The
// expected storage order and values come from how the particles were built, not from the code.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "matpoint/particles/generators.hpp"

namespace {

using namespace matpoint;

template <int D>
std::vector<std::string> visited_names(const ParticleSet<D>& ps) {
  std::vector<std::string> names;
  for_each_array(ps, [&names](const char* name, const auto&, std::size_t) { names.emplace_back(name); });
  return names;
}

/// Bytes per particle of the arrays with one element per particle (state excluded).
template <int D>
std::size_t bytes_per_particle(ParticleSet<D>& ps) {
  std::size_t bytes = 0;
  for_each_array(ps, [&bytes](const char* name, auto& array, std::size_t count) {
    if (std::string(name) != "state") bytes += count * sizeof(array[0]);
  });
  return bytes;
}

TEST(ParticleArrays, ForEachArrayListsEveryArrayInUse) {
  const std::vector<std::string> always{"x", "v",        "mass", "volume0", "size0", "F",  "stress",
                                        "L", "material", "body", "id",      "x0",    "v0", "state"};
  ParticleSet<1> one;
  std::set<std::string> expected(always.begin(), always.end());
  auto names = visited_names(one);
  EXPECT_EQ(std::set<std::string>(names.begin(), names.end()), expected) << "1-D";
  EXPECT_EQ(names.size(), expected.size()) << "an array visited twice";

  ParticleSet<2> two;
  two.track_corners = true;
  two.has_temperature = true;
  expected.insert({"stress_zz", "corners", "temperature"});
  names = visited_names(two);
  EXPECT_EQ(std::set<std::string>(names.begin(), names.end()), expected) << "2-D with corners and heat";
  EXPECT_EQ(names.size(), expected.size());

  ParticleSet<3> three;
  three.track_corners = true;
  expected.erase("stress_zz");
  expected.erase("temperature");
  names = visited_names(three);
  EXPECT_EQ(std::set<std::string>(names.begin(), names.end()), expected) << "3-D with corners";
}

TEST(ParticleArrays, BytesPerParticleOfTheDesign) {
  // docs/scale-out.md §5: 216 B per particle in 2-D and 368 B in 3-D before state, corners
  // (64 / 192 B) and temperature (8 B).
  ParticleSet<2> two;
  EXPECT_EQ(bytes_per_particle(two), 216u);
  two.track_corners = true;
  two.has_temperature = true;
  EXPECT_EQ(bytes_per_particle(two), 216u + 64u + 8u);
  ParticleSet<3> three;
  EXPECT_EQ(bytes_per_particle(three), 368u);
  three.track_corners = true;
  EXPECT_EQ(bytes_per_particle(three), 368u + 192u);
}

// --- sort_by_cell: 24 particles in a 4 x 3 grid of unit cells, two per cell ---
// The expected order is the cells' row-major order (x fastest); a brick-major cell order with
// bricks of at least 4 x 3 cells (one brick here) is the same order.

constexpr int kCellsX = 4, kCells = 12, kParticles = 24;

/// The position of particle k in cell c (x fastest): k < 12 left, k >= 12 right of the centre.
Vec<2> position_in(int c, int k) { return {c % kCellsX + (k < kCells ? 0.25 : 0.75), c / kCellsX + 0.5}; }

Mat<2> mat(double a, double b, double c, double d) {
  Mat<2> m;
  m << a, b, c, d;
  return m;
}

/// Particle k (generation order, so id k) is added in cell 5k mod 12: the storage order is not
/// the cell order. Every array gets values that name k.
ParticleSet<2> shuffled_particles() {
  ParticleSet<2> ps;
  ps.track_corners = true;
  ps.has_temperature = true;
  ps.state_stride = 2;
  for (int k = 0; k < kParticles; ++k) {
    const double d = k;
    ps.add(position_in(5 * k % kCells, k), Vec<2>(d, -2 * d), 1 + d, 0.5 + d,
           Vec<2>(0.1 * (d + 1), 0.2 * (d + 1)), k % 3, k % 2);
    ps.F[k] = mat(1 + d, 2, 3, 4 + d);
    ps.stress[k] = mat(d, -d, -d, 2 * d);
    ps.stress_zz[k] = 10 + d;
    ps.L[k] = mat(0.5 * d, 0, 0, -0.5 * d);
    ps.x0[k] = Vec<2>(100 + d, 200 + d);
    ps.v0[k] = Vec<2>(300 + d, 400 + d);
    ps.state[2 * k] = d + 0.25, ps.state[2 * k + 1] = d + 0.75;
    ps.temperature[k] = 1000 + d;
  }
  return ps;
}

/// Every array of storage index p holds the values particle `id` was given; `x` its position now.
void expect_particle(const ParticleSet<2>& ps, std::size_t p, long id, const Vec<2>& x) {
  const double d = static_cast<double>(id);
  ASSERT_EQ(ps.id[p], id) << "storage index " << p;
  EXPECT_EQ(ps.x[p], x) << "id " << id;
  EXPECT_EQ(ps.v[p], Vec<2>(d, -2 * d)) << "id " << id;
  EXPECT_EQ(ps.mass[p], 1 + d);
  EXPECT_EQ(ps.volume0[p], 0.5 + d);
  EXPECT_EQ(ps.size0[p], Vec<2>(0.1 * (d + 1), 0.2 * (d + 1)));
  EXPECT_EQ(ps.F[p], mat(1 + d, 2, 3, 4 + d));
  EXPECT_EQ(ps.stress[p], mat(d, -d, -d, 2 * d));
  EXPECT_EQ(ps.stress_zz[p], 10 + d);
  EXPECT_EQ(ps.L[p], mat(0.5 * d, 0, 0, -0.5 * d));
  EXPECT_EQ(ps.material[p], id % 3);
  EXPECT_EQ(ps.body[p], id % 2);
  EXPECT_EQ(ps.x0[p], Vec<2>(100 + d, 200 + d)) << "id " << id;
  EXPECT_EQ(ps.v0[p], Vec<2>(300 + d, 400 + d)) << "id " << id;
  EXPECT_EQ(ps.state[2 * p], d + 0.25) << "id " << id;
  EXPECT_EQ(ps.state[2 * p + 1], d + 0.75) << "id " << id;
  EXPECT_EQ(ps.temperature[p], 1000 + d);
  // add() put the corners at the generated position +- half the domain edges
  const Vec<2> x_generated = position_in(static_cast<int>(5 * id % kCells), static_cast<int>(id));
  const Vec<2> half(0.5 * (0.1 * (d + 1)), 0.5 * (0.2 * (d + 1)));
  EXPECT_EQ(ps.corners[p][0], Vec<2>(x_generated - half)) << "id " << id;
  EXPECT_EQ(ps.corners[p][3], Vec<2>(x_generated + half)) << "id " << id;
}

void expect_whole_arrays(const ParticleSet<2>& ps) {
  for_each_array(ps, [&ps](const char* name, const auto& array, std::size_t count) {
    EXPECT_EQ(array.size(), ps.size() * count) << name;
  });
}

TEST(ParticleArrays, SortByCellKeepsEveryArrayOfAParticleTogether) {
  const Grid<2> grid(Vec<2>::Zero(), Vec<2>::Ones(), {kCellsX, 3}, 0);
  ParticleSet<2> ps = shuffled_particles();
  sort_by_cell(grid, ps);
  expect_whole_arrays(ps);
  // Cell c holds ids k with 5k = c (mod 12): k = 5c mod 12 (5 * 5 = 1 mod 12) and k + 12, in
  // id order.
  for (int p = 0; p < kParticles; ++p) {
    const int c = p / 2, id = 5 * c % kCells + kCells * (p % 2);
    expect_particle(ps, static_cast<std::size_t>(p), id, position_in(5 * id % kCells, id));
  }

  // Move particle k to cell 7k + 3 (mod 12) and sort again: cell c now holds k = 7 (c - 3) mod 12
  // (7 * 7 = 1 mod 12) and k + 12, still in id order (their old cell was shared too).
  auto moved = [](long k) {
    return position_in(static_cast<int>((7 * k + 3) % kCells), static_cast<int>(k));
  };
  for (std::size_t p = 0; p < ps.size(); ++p) ps.x[p] = moved(ps.id[p]);
  sort_by_cell(grid, ps);
  expect_whole_arrays(ps);
  for (int p = 0; p < kParticles; ++p) {
    const int c = p / 2, id = 7 * (c - 3 + kCells) % kCells + kCells * (p % 2);
    expect_particle(ps, static_cast<std::size_t>(p), id, moved(id));
  }
}

}  // namespace

namespace {

/// The order after sort_by_cell is (cell, id) whatever the storage order before (the order a
/// run on several ranks must reproduce after migration, docs/scale-out.md §6): the same particles
/// stored in reverse sort to the same sequence of ids, the one read off their cells.
TEST(ParticleArrays, SortByCellOrderDoesNotDependOnTheStorageOrderBefore) {
  const Grid<2> grid(Vec<2>::Zero(), Vec<2>::Ones(), {kCellsX, 3}, 0);
  ParticleSet<2> forward = shuffled_particles();
  ParticleSet<2> reversed;
  for (std::size_t q = forward.size(); q-- > 0;)
    reversed.add(forward.x[q], forward.v[q], forward.mass[q], forward.volume0[q], forward.size0[q],
                 forward.material[q], forward.body[q]);
  for (std::size_t p = 0; p < reversed.size(); ++p) reversed.id[p] = forward.id[forward.size() - 1 - p];
  sort_by_cell(grid, forward);
  sort_by_cell(grid, reversed);
  for (int p = 0; p < kParticles; ++p) {
    const int c = p / 2, id = 5 * c % kCells + kCells * (p % 2);  // cell c: ids 5c mod 12, then + 12
    EXPECT_EQ(forward.id[p], id) << "storage index " << p;
    EXPECT_EQ(reversed.id[p], id) << "storage index " << p;
  }
}

}  // namespace
