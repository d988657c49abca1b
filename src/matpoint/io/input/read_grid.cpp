// The input reader, section units and grid (docs/input.md).
#include <algorithm>
#include <cassert>
#include <cctype>
#include <climits>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <iomanip>
#include <limits>
#include <set>
#include <sstream>
#include <string_view>
#include <utility>

#include "matpoint/analysis/measures.hpp"
#include "matpoint/core/errors.hpp"
#include "matpoint/io/input/keywords.hpp"
#include "matpoint/io/input/spec_reader.hpp"
#include "matpoint/io/memory_estimate.hpp"
#include "matpoint/io/particle_fields.hpp"
#include "matpoint/shape/stencil_width.hpp"

namespace matpoint::input_detail {

void SpecReader::read_units(const Object& units) {
  for (const char* key : {"length", "time", "mass", "stress", "energy"}) (void)units.optional(key).string();
}

void SpecReader::read_grid(const Object& grid) {
  const std::size_t issues_before = issues_.size();
  const auto dim = grid.required("dim").integer(1, 3);
  dim_ = static_cast<int>(dim.value_or(0));  // 0: unknown, vectors below then take 1 to 3 numbers
  const auto lo = grid.required("min").vector(dim_);
  const auto hi = grid.required("max").vector(dim_);
  const auto cell_size = read_cell_size(grid.required("cell_size"));
  if (!dim || !lo || !hi || !cell_size) return;
  GridSpec& g = spec_.grid;
  g.dim = dim_;
  g.min = *lo;
  g.max = *hi;
  g.cell_size = *cell_size;
  for (int a = 0; a < dim_; ++a)
    if (!(g.max[a] > g.min[a])) {
      grid.required("max").fail(numbers_text(dim_, kAnyNumber) + ", each greater than grid.min's");
      return;
    }
  read_cell_counts(grid.required("cell_size"));
  grid_ok_ = issues_.size() == issues_before;
}

/// A number (the same in every direction) or a vector, all > 0.
std::optional<Triple> SpecReader::read_cell_size(const Value& v) const {
  const std::string expected = "a number > 0 or " + numbers_text(dim_, kPositive);
  if (!v.usable(expected)) return std::nullopt;
  if (v.get().is_number()) {
    const auto h = v.number(kPositive);
    if (!h) return std::nullopt;
    Triple out{};
    for (int a = 0; a < std::max(dim_, 1); ++a) out[a] = *h;
    return out;
  }
  if (!v.get().is_array()) {
    v.fail(expected);
    return std::nullopt;
  }
  return v.vector(dim_, kPositive);
}

/// cells = (max - min) / cell_size: a whole number >= 1 per direction, at most kMaxCells in all.
void SpecReader::read_cell_counts(const Value& cell_size) {
  GridSpec& g = spec_.grid;
  Triple counts{};
  double total = 1;
  for (int a = 0; a < dim_; ++a) {
    const double n = (g.max[a] - g.min[a]) / g.cell_size[a];
    counts[a] = std::round(n);
    if (counts[a] < 1 || std::abs(n - counts[a]) > kCellCountTolerance * counts[a]) {
      cell_size.fail("cell_size dividing (max - min) into a whole number of cells");
      return;
    }
    total *= counts[a];
  }
  if (total > kMaxCells) {
    cell_size.fail("at most 1e8 cells");
    return;
  }
  for (int a = 0; a < dim_; ++a) g.cells[a] = static_cast<int>(counts[a]);
}

}  // namespace matpoint::input_detail
