#include "matpoint/explicit/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "matpoint/core/errors.hpp"
#include "matpoint/grid/brick_schedule.hpp"
#include "matpoint/material/wave_speed.hpp"
#include "matpoint/parallel/box_partition.hpp"
#include "matpoint/particles/generators.hpp"
#include "matpoint/shape/tensor_bases.hpp"

namespace matpoint {

namespace {

/// Bodies must not share material: a particle centre of body b inside the shape of an earlier body a
/// would put the overlap's mass in the grid twice. One issue per overlapping pair (path of body b).
/// A collective in a decomposed run: the bodies' boxes and the counts are over every rank's
/// particles, so every rank finds the same issues.
template <int D>
std::vector<InputIssue> overlapping_bodies(const Spec& spec, const ParticleSet<D>& particles,
                                           const Vec<D>& cell, const Communicator& comm) {
  const std::size_t n = spec.bodies.size();
  // box[(b * 2 + 0) * D + a] = -lo_b[a], box[(b * 2 + 1) * D + a] = hi_b[a]: one max over the ranks
  std::vector<double> box(2 * n * D, -std::numeric_limits<double>::infinity());
  for (std::size_t p = 0; p < particles.size(); ++p) {  // particle boxes grown by a cell bound the shapes
    const auto b = static_cast<std::size_t>(particles.body[p]);
    for (int a = 0; a < D; ++a) {
      box[2 * b * D + a] = std::max(box[2 * b * D + a], cell[a] - particles.x[p][a]);
      box[(2 * b + 1) * D + a] = std::max(box[(2 * b + 1) * D + a], particles.x[p][a] + cell[a]);
    }
  }
  comm.max(box);
  const auto inside_box = [&](std::size_t b, const Vec<D>& x) {
    for (int a = 0; a < D; ++a)
      if (x[a] < -box[2 * b * D + a] || x[a] > box[(2 * b + 1) * D + a]) return false;
    return true;
  };
  std::vector<double> count(n * n, 0.0);  // count[b * n + a]: centres of b inside a, a < b
  for (std::size_t p = 0; p < particles.size(); ++p) {
    const auto b = static_cast<std::size_t>(particles.body[p]);
    const Vec<D>& x = particles.x[p];
    for (std::size_t a = 0; a < b; ++a)
      if (inside_box(a, x) && shape_contains<D>(spec.bodies[a], x)) count[b * n + a] += 1.0;
  }
  comm.sum(count);  // exact: integers in doubles
  std::vector<InputIssue> issues;
  for (std::size_t b = 0; b < n; ++b)
    for (std::size_t a = 0; a < b; ++a)
      if (count[b * n + a] > 0)
        issues.push_back({"bodies[" + std::to_string(b) + "].shape",
                          std::to_string(static_cast<long>(count[b * n + a])) +
                              " particle centre(s) inside bodies[" + std::to_string(a) + "] (\"" +
                              spec.bodies[a].name + "\")",
                          "bodies that do not overlap (the overlap's mass would count twice)"});
  return issues;
}

/// Generates every body's particles: all of them in a serial run. A rank of a decomposed run
/// (docs/scale-out.md §5) stores only the particles of its box, so that no rank ever holds the
/// whole set: the bodies are generated twice, once to count the particles per brick, from which
/// every rank computes the same balanced boxes (sim.partition, where the stepper starts),
/// and once to keep its own; the ids are the generation order on any rank count. Returns the
/// bodies that generated no particle at all.
template <int D>
std::vector<InputIssue> generate_particles(const Spec& spec, Simulation<D>& sim) {
  KeepParticle<D> keep;
  if (sim.comm.distributed()) {
    const auto bricks = BoxPartition<D>::whole(sim.grid);  // the brick numbering of the counts
    std::vector<std::size_t> count(bricks.brick_count(), 0);
    const KeepParticle<D> count_only = [&](const Vec<D>& x) {
      ++count[static_cast<std::size_t>(bricks.brick_of_cell(sim.grid.cell_coords(x)))];
      return false;
    };
    ParticleSet<D> none;
    for (std::size_t b = 0; b < spec.bodies.size(); ++b) {
      const auto& body = spec.bodies[b];
      generate_body<D>(body, static_cast<int>(b), spec.materials[body.material], sim.grid, none, count_only);
    }
    const auto partition = BoxPartition<D>::balanced(sim.grid, count, sim.comm.size());
    sim.partition = partition.ints();
    keep = [partition, grid = sim.grid, rank = sim.comm.rank()](const Vec<D>& x) {
      return partition.owner_of_cell(grid.cell_coords(x)) == rank;
    };
  }
  std::vector<InputIssue> empty_bodies;
  for (std::size_t b = 0; b < spec.bodies.size(); ++b) {
    const auto& body = spec.bodies[b];
    if (generate_body<D>(body, static_cast<int>(b), spec.materials[body.material], sim.grid, sim.particles,
                         keep) == 0)
      empty_bodies.push_back(
          {"bodies[" + std::to_string(b) + "].shape", "a shape that holds no particle centre",
           "a shape that contains at least one sub-cell centre (enlarge it or refine the grid)"});
  }
  return empty_bodies;
}

}  // namespace

int ghost_layers(ShapeKind shape) {
  switch (shape) {
    case ShapeKind::BSpline2:
      return QuadraticBSplineBasis::ghost_layers;
    default:  // every other basis folds the missing nodes onto the grid edge (shape/kernels.hpp)
      break;
  }
  return LinearBasis::ghost_layers;
}

namespace {

/// One grid velocity field per body (or material), rigid fields with their prescribed velocity.
template <int D>
void set_up_contact(const Spec& spec, Simulation<D>& sim) {
  const ContactSpec& c = spec.contact;
  const auto fields = static_cast<int>(c.by_material ? spec.materials.size() : spec.bodies.size());
  sim.has_contact = true;
  sim.fields_by_material = c.by_material;
  sim.field_of.resize(static_cast<std::size_t>(fields));
  for (int f = 0; f < fields; ++f) sim.field_of[f] = f;
  std::vector<std::vector<TimeFunction>> rigid(static_cast<std::size_t>(fields));
  for (int f = 0; f < fields; ++f) {
    const auto& m = spec.materials[c.by_material ? f : spec.bodies[f].material];
    if (m.model == MaterialModel::Rigid)
      rigid[f].assign(m.rigid_velocity.begin(), m.rigid_velocity.begin() + D);
  }
  sim.contact = MultiFieldContact<D>(c, fields, sim.grid.node_count, sim.grid.min_cell_size(), sim.mass_floor,
                                     std::move(rigid));
  sim.fields.resize(fields * sim.grid.node_count);
  sim.conditions.replicate(fields);
  for (std::size_t p = 0; p < sim.particles.size(); ++p) {  // rigid particles start at their velocity
    const int f = c.by_material ? sim.particles.material[p] : sim.particles.body[p];
    if (sim.contact.rigid(f)) sim.particles.v[p] = sim.contact.rigid_velocity(f, 0.0);
  }
}

/// Coupled heat conduction (HeatSpec): the materials' thermal constants and the particles'
/// initial temperatures T0 + amplitude sin(k . x + phase).
template <int D>
void set_up_heat(const Spec& spec, Simulation<D>& sim) {
  const HeatSpec& h = spec.heat;
  sim.heat = h;
  for (const auto& m : spec.materials) {
    sim.heat_capacity.push_back(m.heat_capacity);
    sim.conductivity.push_back(m.conductivity);
    const double bulk = m.lambda + 2.0 * m.mu / 3.0;  // 3-D bulk modulus K
    sim.expansion_modulus.push_back(h.thermoelastic ? 3.0 * bulk * m.thermal_expansion : 0.0);
    if (h.conduction && m.heat_capacity > 0.0)
      sim.max_diffusivity = std::max(sim.max_diffusivity, m.conductivity / (m.density * m.heat_capacity));
  }
  auto& ps = sim.particles;
  ps.has_temperature = true;
  ps.temperature.assign(ps.size(), h.initial_temperature);
  for (const auto& [body, T] : h.body_temperatures)
    for (std::size_t p = 0; p < ps.size(); ++p)
      if (ps.body[p] == body) ps.temperature[p] = T;
  if (!h.has_sine) return;
  Vec<D> k;
  for (int a = 0; a < D; ++a) k[a] = h.sine_wave_vector[a];
  for (std::size_t p = 0; p < ps.size(); ++p)
    ps.temperature[p] += h.sine_amplitude * std::sin(k.dot(ps.x[p]) + h.sine_phase);
}

}  // namespace

template <int D>
Simulation<D> build_simulation(const Spec& spec, const Communicator& comm) {
  Simulation<D> sim;
  sim.comm = comm;
  Vec<D> origin, h;
  std::array<int, D> cells{};
  for (int a = 0; a < D; ++a) {
    origin[a] = spec.grid.min[a];
    h[a] = spec.grid.cell_size[a];
    cells[a] = spec.grid.cells[a];
  }
  sim.grid = Grid<D>(origin, h, cells, ghost_layers(spec.solver.shape));
  sim.fields.resize(sim.grid.node_count);
  // CPDI2 domains are tracked by their corners, set up by the generators from the particle spacing.
  sim.particles.track_corners = spec.solver.shape == ShapeKind::CPDI2;

  for (const auto& m : spec.materials) sim.materials.push_back(make_material(m));
  set_state_layout<D>(sim.materials, sim.particles);
  if (auto empty_bodies = generate_particles(spec, sim); !empty_bodies.empty())
    throw InputError(std::move(empty_bodies));
  if (auto overlaps = overlapping_bodies<D>(spec, sim.particles, h, sim.comm); !overlaps.empty())
    throw InputError(std::move(overlaps));
  set_geostatic_stress<D>(sim.materials, spec.bodies, spec.loads.gravity, sim.particles);
  sim.particles.x0 = sim.particles.x;  // X_p and V_p(0): as generated, velocity noise included
  sim.particles.v0 = sim.particles.v;
  sort_by_cell(sim.grid, sim.particles);
  update_stress<D>(sim.materials, sim.particles);

  sim.conditions = VelocityConditions<D>(spec.conditions, sim.grid);
  for (int a = 0; a < D; ++a) sim.gravity[a] = spec.loads.gravity[a];
  sim.solver = spec.solver;
  // the heaviest particle of every rank (an implicit run of FE bodies alone has no particles)
  const double heaviest = sim.comm.max(
      sim.particles.size() == 0 ? 0.0
                                : *std::max_element(sim.particles.mass.begin(), sim.particles.mass.end()));
  sim.mass_floor = spec.solver.mass_tolerance * heaviest;
  sim.significant_mass = std::max(sim.mass_floor, 1e-12 * heaviest);
  sim.rigid_material.assign(spec.materials.size(), 0);
  for (std::size_t m = 0; m < spec.materials.size(); ++m)
    sim.rigid_material[m] = spec.materials[m].model == MaterialModel::Rigid ? 1 : 0;
  if (spec.contact.enabled) set_up_contact(spec, sim);
  if (spec.heat.enabled) set_up_heat(spec, sim);
  return sim;
}

template <int D>
double max_wave_speed(const Simulation<D>& sim) {
  double speed = 0.0;
  for (const auto& m : sim.materials) speed = std::max(speed, wave_speed<D>(m));
  return speed;
}

template <int D>
double stable_time_step(const Simulation<D>& sim, bool use_recorded) {
  if (sim.solver.dt) return *sim.solver.dt;
  const double recorded = sim.particles.recorded_wave_speed;
  double speed =
      use_recorded && recorded >= 0.0 ? recorded : max_current_wave_speed<D>(sim.materials, sim.particles);
  double fastest2 = 0.0;
  const auto n = static_cast<std::ptrdiff_t>(sim.particles.size());
#pragma omp parallel for schedule(static) if (n > kParallelMinimum) reduction(max : fastest2)
  for (std::ptrdiff_t p = 0; p < n; ++p) fastest2 = std::max(fastest2, sim.particles.v[p].squaredNorm());
  speed = sim.comm.max(std::max(speed, std::sqrt(fastest2)));  // every rank of a decomposed run: one dt
  const double h = sim.grid.min_cell_size();
  double dt = sim.solver.courant * h / speed;
  // Explicit conduction: forward Euler on the lumped capacity is stable for dt < 2 / lambda_max.
  // The mechanics' limit dt < C_crit h / c means lambda_max = 4 c^2 / (C_crit h)^2 per axis for
  // the wave operator; the heat operator has the diffusivity a = kappa / (rho C_V) in place of c^2,
  // summed over D axes, so dt = C^2 h^2 / (2 D a) keeps the same margin C / C_crit (squared).
  if (sim.max_diffusivity > 0.0)
    dt = std::min(dt, sim.solver.courant * sim.solver.courant * h * h / (2.0 * D * sim.max_diffusivity));
  return dt;
}

void check_setup(const Spec& input) {
  Spec spec = input;
  // An implicit run's conditions live on mesh boundaries (its solver checks their names), not on
  // the grid's faces: the particle set-up is checked without them.
  if (spec.solver.is_implicit()) spec.conditions.clear();
  switch (spec.grid.dim) {
    case 1:
      (void)build_simulation<1>(spec);
      break;
    case 3:
      (void)build_simulation<3>(spec);
      break;
    default:
      (void)build_simulation<2>(spec);
      break;
  }
}

template Simulation<1> build_simulation<1>(const Spec&, const Communicator&);
template Simulation<2> build_simulation<2>(const Spec&, const Communicator&);
template Simulation<3> build_simulation<3>(const Spec&, const Communicator&);
template double max_wave_speed<1>(const Simulation<1>&);
template double max_wave_speed<2>(const Simulation<2>&);
template double max_wave_speed<3>(const Simulation<3>&);
template double stable_time_step<1>(const Simulation<1>&, bool);
template double stable_time_step<2>(const Simulation<2>&, bool);
template double stable_time_step<3>(const Simulation<3>&, bool);

}  // namespace matpoint
