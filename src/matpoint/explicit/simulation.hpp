// Simulation: everything an explicit run evolves, built once from a validated Spec.
#pragma once

#include <functional>
#include <limits>
#include <vector>

#include "matpoint/explicit/contact.hpp"
#include "matpoint/grid/grid.hpp"
#include "matpoint/grid/grid_fields.hpp"
#include "matpoint/grid/owned_nodes.hpp"
#include "matpoint/grid/velocity_conditions.hpp"
#include "matpoint/io/spec.hpp"
#include "matpoint/material/material.hpp"
#include "matpoint/parallel/communicator.hpp"
#include "matpoint/particles/particle_set.hpp"

namespace matpoint {

template <int D>
struct Simulation {
  Grid<D> grid;
  GridFields<D> fields;
  ParticleSet<D> particles;
  std::vector<Material> materials;
  VelocityConditions<D> conditions;
  Vec<D> gravity = Vec<D>::Zero();
  SolverSpec solver;
  double mass_floor = 0.0;  // nodes at or below this mass are inactive
  // Nodes above this mass (1e-12 of the heaviest particle, or mass_floor) enter the dynamic FMPM
  // measures' node means (Nairn 2026 §3.4): a node that a particle barely reaches is active, but
  // its relative velocity change carries no information and would dominate a per-node mean.
  double significant_mass = 0.0;

  /// Optional body force per unit mass B(X, t), evaluated at each particle's Lagrangian position
  /// X_p (particles.x0) and the start-of-step time and added to the gravity (Gong 2015 extraction A7: the
  /// manufactured solutions' eqs. (4.39), (4.46)). Empty (the default): gravity only, no cost.
  std::function<Vec<D>(const Vec<D>& X, double t)> body_force;
  std::vector<Vec<D>> body_force_values;  // scratch: B(X_p, t) by storage index, for the scatter

  // Multimaterial contact (spec.contact): one grid velocity field per body (or material); `fields`
  // then holds fields x grid.node_count nodes. field_of maps a body (or material) to its field.
  bool has_contact = false;
  MultiFieldContact<D> contact;
  std::vector<int> field_of;
  bool fields_by_material = false;
  std::vector<char> rigid_material;  // by material: 1 for the rigid model
  double friction_work = 0.0;        // kinetic energy removed by Coulomb friction, accumulated

  // Coupled heat conduction (HeatSpec; explicit/heat_transport.hpp); particles.temperature holds T.
  HeatSpec heat;                          // heat.enabled false: none of this is used
  std::vector<double> heat_capacity;      // by material: C_V
  std::vector<double> conductivity;       // by material: kappa
  std::vector<double> expansion_modulus;  // by material: 3 K alpha (0: no thermoelastic coupling)
  double max_diffusivity = 0.0;           // max kappa / (rho C_V): the conduction step limit
  double boundary_heat = 0.0;             // heat in through the thermal conditions, accumulated

  double time = 0.0;
  long step = 0;
  double last_dt = 0.0;                      // the size of the last step taken (history.csv dt)
  double external_work = 0.0;                // gravity + moving walls, accumulated
  Vec<D> external_impulse = Vec<D>::Zero();  // gravity + grid conditions, accumulated
  // sum_i p_i - sum_p M_p V_p at the last momentum transfer: zero up to round-off with the
  // mass-weighted mapping, not with the MLS velocity of IMPM (Gong 2015 extraction A19).
  Vec<D> grid_momentum_difference = Vec<D>::Zero();

  // A decomposed explicit run (issue 23, docs/scale-out.md): the ranks, and the grid nodes this
  // rank owns (of its window). Each rank's `grid`
  // stores a window of the nodes, those its particles reach (Grid::window, fitted by the
  // ExplicitStepper); sums over nodes that are reported (history, condition impulses, grid modes)
  // count only the owned ones, so that a node two ranks store counts once. Serial: one rank that
  // stores and owns every node.
  Communicator comm;
  OwnedNodes owned_nodes;
  // The boxes the set-up generated this rank's particles for (BoxPartition::ints: every rank's
  // box of bricks); the stepper starts from them. Empty: serial.
  std::vector<int> partition;
  [[nodiscard]] bool owns_node(Index node) const { return owned_nodes.contains(node); }
};

/// Grid ghost layers needed by a basis.
int ghost_layers(ShapeKind shape);

/// Builds grid, particles (cell-sorted, initial stress from F = I), materials and conditions.
/// Throws InputError for bodies that produce no particle. `comm` with several ranks: a decomposed
/// explicit run, where each rank generates only its box's particles (a collective).
template <int D>
Simulation<D> build_simulation(const Spec& spec, const Communicator& comm = {});

/// The largest material wave speed (the speed of the Courant number).
/// Sets up the simulation of a validated spec (grid, particles, materials) and discards it: throws
/// InputError for what only the set-up finds (a body that holds no particle, overlapping bodies).
/// `matpoint check` runs it, so that check refuses everything `matpoint run` would refuse.
void check_setup(const Spec& spec);

template <int D>
double max_wave_speed(const Simulation<D>& sim);

/// Time step: the input's dt, or courant * h_min / max_p max(c_p, |V_p|) with each particle's
/// present wave speed c_p (Nairn 2026 §1.8; material/wave_speed.hpp). Recomputed every step.
/// With `use_recorded`, max_p c_p is the particles' recorded_wave_speed when it is known (the last
/// stress update's, the same value without a second pass over F); else it is computed.
template <int D>
double stable_time_step(const Simulation<D>& sim, bool use_recorded = false);

}  // namespace matpoint
