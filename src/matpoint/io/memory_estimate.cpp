#include "matpoint/io/memory_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "matpoint/core/errors.hpp"
#include "matpoint/particles/graded_generators.hpp"

namespace matpoint {

namespace {

/// Nodes per particle stencil, generous (a CPDI domain may span two cells per axis).
int stencil_width(ShapeKind shape) {
  switch (shape) {
    case ShapeKind::Linear:
      return 2;
    case ShapeKind::BSpline2:
    case ShapeKind::UGIMP:
    case ShapeKind::CpGIMP:
      return 3;
    case ShapeKind::BSpline3:
    case ShapeKind::B2GIMP:
    case ShapeKind::CPDI1:
    case ShapeKind::CPDI2:
      return 4;
    case ShapeKind::B2CPDI:
      return 5;
  }
  return 4;
}

/// Aulisa & Capodaglio's graded disk or beam (particles/graded_generators.hpp): generated to count
/// them (milliseconds for their 10^5 particles); 0 when the generator refuses the parameters (the
/// set-up reports that).
std::size_t graded_particle_count(const BodySpec& body) {
  try {
    if (body.shape == BodyShape::GradedDisk)
      return graded_disk(Vec<2>(body.center[0], body.center[1]), body.radius, body.core_radius,
                         body.core_divisions, body.layer_growth, 1.0)
          .position.size();
    return graded_beam(body.min[0], 0.5 * (body.min[1] + body.max[1]), body.max[1] - body.min[1],
                       body.max[0] - body.min[0], body.core_height, body.core_divisions, body.layer_growth,
                       1.0)
        .position.size();
  } catch (const std::invalid_argument&) {
    return 0;
  }
}

std::string gigabytes(double bytes) {
  std::ostringstream out;
  out.precision(3);
  out << bytes / 1e9 << " GB";
  return out.str();
}

}  // namespace

MemoryEstimate estimate_memory(const Spec& spec) {
  const int d = spec.grid.dim;
  MemoryEstimate e;
  e.nodes = 1;
  for (int a = 0; a < d; ++a) e.nodes *= spec.grid.cells[a] + 1.0;
  for (const auto& body : spec.bodies) {
    if (body.shape == BodyShape::GradedDisk || body.shape == BodyShape::GradedBeam) {
      e.particles += static_cast<double>(graded_particle_count(body));  // exact: the generator's own count
      continue;
    }
    double count = 1;
    for (int a = 0; a < d; ++a) {
      double lo = body.min[a], hi = body.max[a];
      if (body.shape == BodyShape::Disk) lo = body.center[a] - body.radius, hi = body.center[a] + body.radius;
      if (body.shape == BodyShape::Polygon && a < 2) {  // (a 3-D polygon is a prism: z from min/max)
        lo = hi = body.polygon.front()[a];
        for (const auto& v : body.polygon) lo = std::min(lo, v[a]), hi = std::max(hi, v[a]);
      }
      const double cells = std::ceil((hi - lo) / spec.grid.cell_size[a]) + 1.0;
      count *= cells * body.particles_per_cell;
    }
    e.particles += count;
  }
  // Contact keeps every grid array once per velocity field (body or material, field_stencils.hpp).
  if (spec.contact.enabled)
    e.fields = static_cast<int>(spec.contact.by_material ? spec.materials.size() : spec.bodies.size());
  // Per particle: x, v, size0, F, stress, L, mass, volume0, ids, the step's stencil (weights and
  // gradients), scratch of the transfers; per node and field: mass, 6 vectors, the threads'
  // scatter bands, and with contact the gradient and position sums of the normals.
  const double vec = 8.0 * d, mat = 8.0 * d * d;
  const double width = std::pow(stencil_width(spec.solver.shape), d);
  const double per_particle = 3 * vec + 3 * mat + 40 + 2 * vec + width * (8.0 + vec) + (1 << d) * vec;
  const double per_field_node = 8.0 + 8 * vec + 2 * (8.0 + 2 * vec) + (spec.contact.enabled ? 2 * vec : 0.0);
  e.bytes = e.particles * per_particle + e.nodes * e.fields * per_field_node;
  return e;
}

std::optional<double> available_memory() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  double kb = 0;
  std::string unit;
  while (meminfo >> key >> kb >> unit)
    if (key == "MemAvailable:") return kb * 1024.0;
  return std::nullopt;
}

void check_memory(const Spec& spec, std::optional<double> available) {
  if (!available) return;
  const MemoryEstimate e = estimate_memory(spec);
  if (e.bytes <= *available) return;
  std::ostringstream value, expected;
  value.precision(3);
  value << "about " << e.particles << " particles and " << e.nodes << " nodes, needing about "
        << gigabytes(e.bytes);
  expected << "a problem that fits in the " << gigabytes(*available)
           << " of memory available (coarser grid.cell_size or fewer particles_per_cell)";
  throw InputError({{"bodies", value.str(), expected.str()}});
}

}  // namespace matpoint
