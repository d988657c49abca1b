// One explicit MPM time step in the update schemes of Nairn 2026 §2.1 (Table: USL, USF, USL+ = MUSL,
// USAVG). The step reads as the list of stages in DESIGN.md; every stage is a free function over
// plain arrays, and the stencils are evaluated once per step and reused by every transfer.
#pragma once

#include <algorithm>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <string>

#include "matpoint/core/errors.hpp"
#include "matpoint/explicit/deformation.hpp"
#include "matpoint/explicit/face_contact.hpp"
#include "matpoint/explicit/field_stencils.hpp"
#include "matpoint/explicit/fmpm.hpp"
#include "matpoint/explicit/gather.hpp"
#include "matpoint/explicit/grid_update.hpp"
#include "matpoint/explicit/heat_transport.hpp"
#include "matpoint/explicit/mls_mapping.hpp"
#include "matpoint/explicit/near_particles.hpp"
#include "matpoint/explicit/scatter.hpp"
#include "matpoint/explicit/simulation.hpp"
#include "matpoint/parallel/box_partition.hpp"
#include "matpoint/parallel/colour_hand_off.hpp"
#include "matpoint/parallel/particle_migration.hpp"
#include "matpoint/particles/generators.hpp"
#include "matpoint/shape/domain_motion.hpp"

namespace matpoint {

template <int D, class Stencils>
class ExplicitStepper {
 public:
  /// Particles are re-sorted by cell every `sort_interval` steps (memory locality only).
  static constexpr long sort_interval = 10;
  /// Multimaterial contact: one velocity field per body or material (field_stencils.hpp).
  static constexpr bool kFields = requires { Stencils::multi_field; };
  /// CPDI stencils (also inside the multi-field adapter) report domain corners outside the grid.
  static constexpr bool kCornersChecked = requires(const Stencils& s) { s.first_corner_outside; }
  || requires(const Stencils& s) { s.base.first_corner_outside; };

  explicit ExplicitStepper(Simulation<D>& sim)
      : s_(sim),
        whole_grid_(sim.grid),
        field_count_(static_cast<Index>(sim.fields.mass.size()) / std::max<Index>(1, sim.grid.node_count)),
        grid_(sim.grid),
        fmpm_(sim.solver.fmpm, sim.significant_mass),
        mls_(sim.solver.mls) {
    velocity_.resize(sim.fields.mass.size());
    if (sim.comm.distributed()) decompose();
    if constexpr (kFields) set_up_fields();
    if (sim.heat.enabled) heat_ = HeatTransport<D>(sim, kFields ? static_cast<int>(sim.field_of.size()) : 1);
    for (std::size_t p = 0; p < sim.particles.size(); ++p)
      if (sim.rigid_material.empty() || !sim.rigid_material[sim.particles.material[p]])
        total_mass_ += sim.particles.mass[p];
    const FmpmSpec& f = sim.solver.fmpm;
    if (f.period == FmpmPeriod::Courant)
      fmpm_period_ = f.period_value * sim.grid.min_cell_size() / max_wave_speed(sim);
    if (f.period == FmpmPeriod::Time) fmpm_period_ = f.period_value;
  }

  /// Advances the simulation by dt; throws NumericalFailure naming step, time and particle.
  void step(double dt) {
    if (s_.step % sort_interval == 0) {
      if (!ranks_) {
        sort_by_cell(s_.grid, s_.particles);
      } else {
        std::vector<Index> keys;
        sort_by_cell(s_.grid, s_.particles, &keys);
        ranks_->migration.sorted(std::move(keys));
        rebalance();
      }
    }
    step_dt_ = dt;
    stencils_.evaluate(s_.grid, s_.particles);
    if (ranks_ && ranks_->hand_off.reach() != window_reach_) {  // the same decision on every rank
      window_reach_ = ranks_->hand_off.reach();
      fit_window();
      stencils_.evaluate(s_.grid, s_.particles);  // node indices in the new window
    }
    if (ranks_)  // the particles that arrived since the last sort, in the serial run's order
      brick_schedule().order_arrivals(ranks_->migration.keys(), s_.particles.id,
                                      ranks_->migration.sorted_prefix());
    if (const long p = first_corner_outside(stencils_); p >= 0) fail_corner_outside(p);
    if constexpr (kCornersChecked)  // a decomposed run: every rank stops before its scatters
      if (ranks_) settle_failures();
    if (s_.conditions.has_one_sided())
      mark_nodes_touching_faces(s_.grid, grid_, stencils_, s_.particles, s_.conditions);
    fmpm_now_ = fmpm_due(dt);
    const double t_new = s_.time + dt;
    switch (s_.solver.scheme) {  // the FMPM loops of eq. (3): USL 3.b; USF 1.c, 3.b; USL+ 3.b, 4.c; ...
      case UpdateScheme::USL:
        scatter<kScatterMass | kScatterMomentum | kScatterForce>();
        grid_velocity_update(dt, t_new);
        move_particles(dt, /*with_gradient=*/true);
        update_strain(dt);
        break;
      case UpdateScheme::USF:
        scatter<kScatterMass | kScatterMomentum>();
        strain_from_momentum(dt, s_.time);
        scatter<kScatterForce>();
        grid_velocity_update(dt, t_new);
        move_particles(dt, /*with_gradient=*/false);
        break;
      case UpdateScheme::USAVG:  // USF and USL halves, each with dt / 2
        scatter<kScatterMass | kScatterMomentum>();
        strain_from_momentum(0.5 * dt, s_.time);
        scatter<kScatterForce>();
        grid_velocity_update(dt, t_new);
        move_particles(dt, /*with_gradient=*/true);
        update_strain(0.5 * dt);
        break;
      case UpdateScheme::MUSL:  // USL+: strain from the momenta re-extrapolated from the new velocities
        scatter<kScatterMass | kScatterMomentum | kScatterForce>();
        grid_velocity_update(dt, t_new);
        move_particles(dt, /*with_gradient=*/false);
        scatter<kScatterMomentum>();
        strain_from_momentum(dt, t_new);
        break;
      case UpdateScheme::USAVGPlus:  // USF and USL+ halves, each with dt / 2
        scatter<kScatterMass | kScatterMomentum>();
        strain_from_momentum(0.5 * dt, s_.time);
        scatter<kScatterForce>();
        grid_velocity_update(dt, t_new);
        move_particles(dt, /*with_gradient=*/false);
        scatter<kScatterMomentum>();
        strain_from_momentum(0.5 * dt, t_new);
        break;
    }
    if (heat_.active()) {
      if (ranks_ && heat_.contact().conducts()) gather_near_domains();
      heat_.step(s_, grid_, stencils_, s_.particles, dt, t_new, s_.boundary_heat);
    }
    if (ranks_) {
      settle_failures();  // every rank stops together, with the first failing rank's message
      ranks_->migration.migrate(s_.particles);
    }
    s_.time = t_new;
    s_.last_dt = dt;
    ++s_.step;
  }

  [[nodiscard]] const Stencils& stencils() const { return stencils_; }
  /// The grid of the transfers: grid.node_count covers every field's nodes.
  [[nodiscard]] const Grid<D>& field_grid() const { return grid_; }
  [[nodiscard]] const FmpmStatistics& fmpm_statistics() const { return fmpm_.statistics(); }
  [[nodiscard]] const HeatTransport<D>& heat() const { return heat_; }
  [[nodiscard]] const MlsStatistics& mls_statistics() const { return mls_.statistics(); }
  /// Re-partitions of a decomposed run so far (solver.rebalance; 0 on one rank).
  [[nodiscard]] long repartitions() const { return ranks_ ? ranks_->repartitions : 0; }
  /// A decomposed run's hand-off and migration counts (null in a serial run).
  [[nodiscard]] const Traffic* halo_traffic() const { return ranks_ ? &ranks_->hand_off.traffic : nullptr; }
  [[nodiscard]] const Traffic* migration_traffic() const {
    return ranks_ ? &ranks_->migration.traffic : nullptr;
  }

  /// What the stepper carries from step to step besides the Simulation (checkpoints keep it).
  struct State {
    double next_fmpm_time = 0.0;  // periodic FMPM
    double total_mass = 0.0;      // summed in the particle order of the first step (this rank's)
    FmpmStatistics fmpm;
    // A decomposed run: the partition (BoxPartition::ints) and this rank's migration
    // state, by which the particles that arrived since the last sort take the serial order.
    std::vector<int> partition;
    std::vector<Index> sort_keys;
    std::size_t sorted_prefix = 0;
    long repartitions = 0, partitioned_at = 0;  // solver.rebalance: how many, and the last one's step
  };
  [[nodiscard]] State state() const {
    State out{next_fmpm_time_, total_mass_, fmpm_.statistics(), {}, {}, 0};
    if (ranks_) {
      out.partition = ranks_->partition.ints();
      out.sort_keys = ranks_->migration.keys();
      out.sorted_prefix = ranks_->migration.sorted_prefix();
      out.repartitions = ranks_->repartitions;
      out.partitioned_at = ranks_->partitioned_at;
    }
    return out;
  }
  /// A restart: the Simulation holds the checkpoint's particles (this rank's, in their stored
  /// order); a decomposed run takes the stored partition, not a recomputed one.
  void restore(const State& state) {
    next_fmpm_time_ = state.next_fmpm_time;
    total_mass_ = state.total_mass;
    fmpm_.restore_statistics(state.fmpm);
    if (ranks_ && !state.partition.empty()) {
      use_partition(BoxPartition<D>::from_ints(whole_grid_, state.partition));
      ranks_->migration.restore(state.sort_keys, state.sorted_prefix);
      ranks_->repartitions = state.repartitions;
      ranks_->partitioned_at = state.partitioned_at;
    }
  }

 private:
  template <unsigned What>
  void scatter() {
    const std::vector<Vec<D>>* body = nullptr;
    if constexpr ((What & kScatterForce) != 0)
      if (s_.body_force) body = &evaluate_body_force();
    if (s_.solver.mapping == Mapping::MPM)
      scatter_to_grid<What>(grid_, stencils_, s_.particles, s_.gravity, s_.fields,
                            static_cast<const std::vector<Vec<D>>*>(nullptr), body);
    else
      scatter_mls<What>(body);
    if constexpr ((What & kScatterMass) != 0)
      if (s_.conditions.has_walls()) s_.conditions.select_wall_nodes(s_.time, s_.fields.mass, s_.mass_floor);
    if constexpr ((What & kScatterMomentum) != 0) record_momentum_difference();
    if constexpr (kFields && (What & kScatterMomentum) != 0) {  // task 1.a (and 4.b): lumped contact on p
      if constexpr ((What & kScatterMass) != 0)
        s_.contact.prepare(grid_, stencils_, s_.particles, s_.fields.mass);
      s_.contact.set_rigid(s_.fields.mass, s_.fields.momentum, s_.time, /*momentum=*/true);
      s_.contact.apply_lumped(s_.fields.mass, s_.fields.momentum, /*momentum=*/true);
    }
  }

  /// Gong 2015 §5.4 (IMPM): mass and forces by cell quadrature, velocity by MLS; §6.6 (improved
  /// CPDI, mapping mls_velocity): mass and forces through the stencils, velocity by MLS.
  template <unsigned What>
  void scatter_mls(const std::vector<Vec<D>>* body) {
    constexpr unsigned kMassForce = What & (kScatterMass | kScatterForce);
    if constexpr ((What & kScatterMass) != 0) step_start_x_ = s_.particles.x;  // for the re-extrapolation
    const std::vector<Vec<D>>* near_body = body;
    const ParticleSet<D>* near = nullptr;  // gathered once for both reconstructions
    if constexpr (kMassForce != 0) {
      if (s_.solver.mapping == Mapping::IMPM) {
        near = &mls_particles(near_body);
        mls_.template cell_quadrature<(What & kScatterMass) != 0, (What & kScatterForce) != 0>(
            s_.grid, *near, s_.gravity, near_body, s_.fields);
      } else {
        scatter_to_grid<kMassForce>(s_.grid, stencils_, s_.particles, s_.gravity, s_.fields,
                                    static_cast<const std::vector<Vec<D>>*>(nullptr), body);
      }
    }
    if constexpr ((What & kScatterMomentum) != 0) {
      // MUSL / USAVG+ re-extrapolation after the particles moved (What == kScatterMomentum):
      // standard MUSL maps the new particle velocities with the stencils and masses of the start
      // of the step, so the MLS fit uses the start-of-step positions too (fitting them at the
      // moved positions would shift the fitted field by dx and give L = A - A^2 dt for a linear
      // field v = A x).
      constexpr bool kAtStepStart = What == kScatterMomentum;
      if constexpr (kAtStepStart) std::swap(s_.particles.x, step_start_x_);
      if (near == nullptr) near = &mls_particles(near_body);
      mls_.node_momentum(s_.grid, *near, s_.fields.mass, s_.mass_floor, s_.fields.momentum);
      if constexpr (kAtStepStart) std::swap(s_.particles.x, step_start_x_);
    }
  }

  /// The particles that the MLS reconstructions read, binned by cell at their present positions:
  /// this rank's, and in a decomposed run also the other ranks' near its window, in the serial
  /// storage order (explicit/near_particles.hpp; a collective). `body`: the body forces of
  /// this rank's particles (or null), replaced by those of the particles returned.
  const ParticleSet<D>& mls_particles(const std::vector<Vec<D>>*& body) {
    if (!ranks_) {
      mls_.bin(s_.grid, s_.particles);
      return s_.particles;
    }
    const auto band_of = [this](int r) {
      return NearParticles<D>::mls_band(whole_grid_, stored_nodes_of(r));
    };
    mls_neighbours_.gather(s_.comm, whole_grid_, s_.particles, ranks_->migration.keys(), body, band_of);
    body = mls_neighbours_.body();
    mls_.bin(s_.grid, mls_neighbours_.particles(), mls_neighbours_.band());
    return mls_neighbours_.particles();
  }

  /// A decomposed run with a heat contact conductance: the particles whose GIMP domains reach this
  /// rank's window, in the serial order (explicit/near_particles.hpp; a collective), for the
  /// contact's nodal volumes (ThermalContactCoupling::add_domain_volumes), with their field offsets and
  /// the band grid that holds their domain stencils.
  void gather_near_domains() {
    constexpr int kWidth = ThermalContactCoupling<D>::kWidestDomain;
    const auto band_of = [this](int r) {
      return NearParticles<D>::domain_band(whole_grid_, stored_nodes_of(r), kWidth);
    };
    heat_neighbours_.gather(s_.comm, whole_grid_, s_.particles, ranks_->migration.keys(), nullptr, band_of);
    const ParticleSet<D>& near = heat_neighbours_.particles();
    IndexBox<D> band = heat_neighbours_.band();  // cells; the nodes their domains reach:
    for (int a = 0; a < D; ++a) band.begin[a] -= kWidth, band.end[a] += kWidth;
    near_domains_.particles = &near;
    near_domains_.band = whole_grid_.window(band);
    near_domains_.offset.resize(near.size());
    const Index field_nodes = s_.grid.node_count;
    for (std::size_t p = 0; p < near.size(); ++p)
      near_domains_.offset[p] =
          s_.field_of[static_cast<std::size_t>(s_.fields_by_material ? near.material[p] : near.body[p])] *
          field_nodes;
    heat_.use_near_domains(&near_domains_);
  }

  /// This rank's share (its owned nodes of every field, its particles): the ranks' shares add up
  /// to the whole.
  void record_momentum_difference() {
    Vec<D> grid = Vec<D>::Zero(), particles = Vec<D>::Zero();
    const auto& momentum = s_.fields.momentum;
    const Index n = s_.grid.node_count;
    for (Index f = 0; f < static_cast<Index>(momentum.size()); f += n)
      s_.owned_nodes.for_each_run(n, [&](Index begin, Index end) {
        for (Index i = begin; i < end; ++i) grid += momentum[f + i];
      });
    for (std::size_t p = 0; p < s_.particles.size(); ++p)
      particles += s_.particles.mass[p] * s_.particles.v[p];
    s_.grid_momentum_difference = grid - particles;
  }

  /// A decomposed run (docs/scale-out.md): the boxes balanced by particle count that the set-up
  /// generated this rank's particles for (Simulation::partition), their sort keys, the owned
  /// nodes, and the hand-off between the colours of every particle-to-grid sum.
  void decompose() {
    if (s_.partition.empty())
      throw std::logic_error(
          "a decomposed run needs the set-up's partition (build_simulation with the ranks)");
    use_partition(BoxPartition<D>::from_ints(whole_grid_, s_.partition));
    ranks_->migration.start(s_.particles);
  }

  /// The partition's hand-off, migration and owned nodes (the particles are left as they are).
  /// The rank stores the whole grid until the first step's stencils tell how far they reach.
  void use_partition(BoxPartition<D> partition) {
    ranks_ = std::make_unique<Ranks>(s_.grid, std::move(partition), s_.comm);
    window_reach_ = {-1, -1};
    fit_window();
    brick_schedule().boundary = &ranks_->hand_off;
  }

  /// The grid window this rank stores (docs/scale-out.md §2): the box of nodes its particles'
  /// stencils reach under the reach every rank agreed on (window_reach_; the whole grid before the
  /// first agreement). Every node array and node
  /// list follows it: the grid's fields and scratch, the velocity and thermal conditions, the
  /// contact's and the stencils' node counts, the frictional heat that waits for the next step,
  /// the owned nodes and the hand-off's lists (rebuilt at the next agree_reach). Called when the
  /// partition or the agreed reach changes, between steps or right after the stencils' evaluation
  /// (which is then repeated), never while a node array holds a step's values.
  void fit_window() {
    const auto [below, above] = window_reach_;
    IndexBox<D> stored = stored_nodes_of(s_.comm.rank());
    if (stored.empty()) {  // a rank without cells: one node, never reached
      stored.begin.fill(0);
      stored.end.fill(1);
    }
    const Grid<D> old = s_.grid;
    s_.grid = whole_grid_.window(stored);
    const Index n = s_.grid.node_count;
    s_.fields.resize(field_count_ * n);
    velocity_.assign(static_cast<std::size_t>(field_count_ * n), Vec<D>::Zero());
    s_.conditions.use_window(s_.grid);
    grid_ = s_.grid;
    if constexpr (kFields) {
      stencils_.field_nodes = n;
      grid_.node_count = field_count_ * n;
      s_.contact.use_window(n);
    }
    if (heat_.active()) heat_.use_window(s_, old);
    ranks_->hand_off.partition_changed();
    claim_owned_nodes();
    if constexpr (kFields) share_contact_nodes(below, above);
  }

  /// The nodes that rank r's window holds: those its particles' stencils reach under the agreed
  /// reach, the whole grid before the first agreement (none for a rank without cells).
  [[nodiscard]] IndexBox<D> stored_nodes_of(int r) const {
    const auto [below, above] = window_reach_;
    if (below < 0) return whole_grid_.stored_nodes();
    return ranks_->partition.stored_nodes_of(r, below, above);
  }

  /// The nodes this rank stores together with each other rank (for the logistic contact normals
  /// of the nodes near the rank boundaries: explicit/seen_particles.hpp).
  void share_contact_nodes(int below, int above) {
    std::vector<SharedNodes<D>> shared;
    const int me = s_.comm.rank();
    if (below >= 0)
      for (int r = 0; r < s_.comm.size(); ++r) {
        const IndexBox<D> nodes = ranks_->partition.shared_nodes_of(me, r, below, above);
        if (r != me && !nodes.empty()) shared.push_back({r, nodes});
      }
    s_.contact.share_nodes(std::move(shared), &ranks_->migration.keys());
  }

  /// This rank's owned nodes (the node sums it reports) under the present partition and window:
  /// at the start, after a re-partition, at a restart with the stored partition, and whenever the
  /// window changes.
  void claim_owned_nodes() {
    s_.owned_nodes = OwnedNodes::box(s_.grid, ranks_->partition.owned_nodes_of(s_.comm.rank()));
    s_.conditions.count_only(s_.owned_nodes);
    count_owned_nodes_only();
  }

  /// The owned nodes, to everything that counts owned nodes only besides the Simulation's
  /// conditions: the dynamic FMPM measure, the contact's friction work, the heat conditions.
  void count_owned_nodes_only() {
    fmpm_.decompose(s_.comm, s_.owned_nodes, s_.grid.node_count);
    mls_.count_only(s_.owned_nodes, ranks_->partition.cells_of(s_.comm.rank()));
    if constexpr (kFields) s_.contact.decompose(s_.comm, s_.owned_nodes);
    if (heat_.active()) heat_.count_only(s_);
  }

  /// Load balance (docs/scale-out.md §10), at a re-sort: when the busiest rank holds more than
  /// solver.rebalance.imbalance times the mean particle count (a max and a sum over the ranks),
  /// the particle count per brick of all ranks (one reduction of a value per brick) gives new
  /// boxes where the particles lie, and the particles move to their new ranks (the migration, with
  /// any destination). Arrivals keep their sort keys, so the storage order, and with it every
  /// result, stays the serial run's.
  void rebalance() {
    const RebalanceSpec& spec = s_.solver.rebalance;
    if (!spec.enabled || s_.step - ranks_->partitioned_at < spec.min_steps) return;
    const long own = static_cast<long>(s_.particles.size());
    const long busiest = s_.comm.max(own), total = s_.comm.sum(own);
    if (static_cast<double>(busiest) <= spec.imbalance * static_cast<double>(total) / s_.comm.size()) return;
    ranks_->partitioned_at = s_.step;  // also when the bricks allow no better cut: check again later
    BoxPartition<D>& partition = ranks_->partition;
    std::vector<double> count(partition.brick_count(), 0.0);
    for (const auto& x : s_.particles.x)
      count[static_cast<std::size_t>(partition.brick_of_cell(s_.grid.cell_coords(x)))] += 1.0;
    s_.comm.sum(count);  // particle counts: exact in doubles, the same on every rank
    std::vector<std::size_t> whole(count.size());
    for (std::size_t b = 0; b < count.size(); ++b) whole[b] = static_cast<std::size_t>(count[b]);
    auto cut = BoxPartition<D>::balanced(whole_grid_, whole, s_.comm.size());
    if (cut == partition) return;
    partition = std::move(cut);  // the hand-off and the migration hold a reference to it
    fit_window();                // the new box's nodes, under the reach agreed so far
    ranks_->migration.migrate(s_.particles);
    ++ranks_->repartitions;
  }

  /// The stencils' particle order (of the base stencils in a multi-field run).
  BrickSchedule<D>& brick_schedule() {
    if constexpr (kFields)
      return stencils_.base.bricks;
    else
      return stencils_.bricks;
  }

  /// The step's end in a decomposed run: when any rank failed in this step, every rank throws the
  /// failure of the lowest failing rank (the others finished the step, so no message is pending).
  void settle_failures() {
    constexpr long kNone = std::numeric_limits<long>::max();
    const long first = s_.comm.min(pending_failure_ ? static_cast<long>(s_.comm.rank()) : kNone);
    if (first == kNone) return;
    // One broadcast of both texts, separated by a NUL (neither contains one).
    const std::string both = s_.comm.broadcast(
        pending_failure_ ? pending_failure_->first + '\0' + pending_failure_->second : std::string(),
        static_cast<int>(first));
    const std::size_t split = std::min(both.find('\0'), both.size());
    throw NumericalFailure(s_.step + 1, s_.time + step_dt_, both.substr(0, split),
                           split < both.size() ? both.substr(split + 1) : std::string());
  }

  void set_up_fields() {
    stencils_.field_of = s_.field_of;
    stencils_.by_material = s_.fields_by_material;
    stencils_.field_nodes = s_.grid.node_count;
    grid_.node_count = static_cast<Index>(s_.fields.mass.size());
    fmpm_.set_increment_correction(
        [this](std::vector<Vec<D>>& dv) { s_.contact.correct_increment(s_.fields.mass, dv); });
  }

  /// Task 3.a: lumped contact on v+(1), then the conditions again where contact moved a
  /// constrained node, and the rigid fields' velocities; a = (v+ - v) / dt includes it all.
  void contact_after_update(double dt, double t_new, Vec<D>& impulse, double& work) {
    auto& f = s_.fields;
    s_.contact.set_rigid(f.mass, f.velocity_new, t_new, false);
    s_.contact.apply_lumped(f.mass, f.velocity_new, false, /*add_to_total=*/fmpm_now_);  // 1.a's reaches V
    if (!fmpm_now_) add_friction_work(f.velocity_new);  // FMPM: after the loop
    s_.conditions.apply(f.velocity_new, t_new, &f.mass, &impulse, &work);
    s_.contact.set_rigid(f.mass, f.velocity_new, t_new, false);
    const auto n = static_cast<std::ptrdiff_t>(f.mass.size());
#pragma omp parallel for schedule(static) if (n > kParallelMinimum)
    for (std::ptrdiff_t i = 0; i < n; ++i) f.acceleration[i] = (f.velocity_new[i] - f.velocity[i]) / dt;
  }

  /// Coulomb friction's work (history), and its heat at the contact nodes with coupled heat.
  void add_friction_work(const std::vector<Vec<D>>& velocity) {
    s_.friction_work += s_.contact.friction_work(s_.fields.mass, velocity);
    if (heat_.active() && s_.heat.friction)
      s_.contact.add_friction_heat(s_.fields.mass, velocity, heat_.node_heat());
  }

  /// Rigid particles keep their prescribed velocity exactly and no velocity gradient.
  void move_rigid_particles(double t_new) {
    auto& ps = s_.particles;
    for (std::size_t p = 0; p < ps.size(); ++p)
      if (s_.rigid_material[ps.material[p]]) {
        ps.v[p] = s_.contact.rigid_velocity(stencils_.field(p), t_new);
        ps.L[p].setZero();
      }
  }

  /// B(X_p, t) of every particle at the start of the step (Gong 2015 extraction A7).
  const std::vector<Vec<D>>& evaluate_body_force() {
    auto& b = s_.body_force_values;
    b.resize(s_.particles.size());
    for (std::size_t p = 0; p < b.size(); ++p) b[p] = s_.body_force(s_.particles.x0[p], s_.time);
    return b;
  }

  /// Periodic FMPM (Nairn 2026 §3.3, NairnMPM's rule): a step runs the loop when t + dt reaches
  /// the next FMPM time, which then moves to t + dt + T_X; the other steps are FLIP.
  bool fmpm_due(double dt) {
    const FmpmSpec& f = s_.solver.fmpm;
    if (s_.solver.transfer != VelocityTransfer::FMPM) return false;
    switch (f.period) {
      case FmpmPeriod::EveryStep:
        return true;
      case FmpmPeriod::Steps:
        return s_.step % static_cast<long>(f.period_value) == 0;
      case FmpmPeriod::Courant:
      case FmpmPeriod::Time:
        break;
    }
    if (s_.time + dt < next_fmpm_time_) return false;
    next_fmpm_time_ = s_.time + dt + fmpm_period_;
    return true;
  }

  /// Tasks 2.a-3.b: v(1) = p/m, v+(1) = (p + f dt)/m with the conditions, a = (v+(1) - v(1))/dt;
  /// then v+(k) from the FMPM loop (FMPM steps) or XPIC's m~_k^-1 p + a dt.
  void grid_velocity_update(double dt, double t_new) {
    Vec<D> impulse = Vec<D>::Zero();
    double work = 0.0;
    update_grid_velocities(s_.fields, dt, s_.mass_floor, s_.conditions, t_new, impulse, work,
                           s_.solver.constrain_old_velocity);
    if constexpr (kFields) contact_after_update(dt, t_new, impulse, work);
    if (fmpm_now_) {
      fmpm_.run(grid_, stencils_, s_.particles, s_.fields.mass, s_.mass_floor, s_.conditions, t_new,
                s_.fields.velocity_new, &impulse, &work);
      if constexpr (kFields) add_friction_work(s_.fields.velocity_new);
    } else if (s_.solver.transfer == VelocityTransfer::XPIC) {
      // The series on the old lumped velocities (§1.5). Its increments are zeroed on the condition
      // directions as FMPM's are (Table 2, bottom block), so that a condition node keeps v(1) and
      // ends at v(1) + a dt = v+(1), its prescribed value; the momentum and work that zeroing
      // removes are the conditions' and are counted as their impulse and work (our choice: the
      // paper gives XPIC only by reference; without it, walls would not hold exactly under XPIC).
      auto& vx = s_.fields.velocity_xpic;
      vx = s_.fields.velocity;
      fmpm_.run(grid_, stencils_, s_.particles, s_.fields.mass, s_.mass_floor, s_.conditions, t_new, vx,
                &impulse, &work);
      for (std::size_t i = 0; i < vx.size(); ++i) vx[i] += s_.fields.acceleration[i] * dt;
    }
    s_.external_impulse += impulse + total_mass_ * s_.gravity * dt;
    s_.external_work += work;
  }

  void move_particles(double dt, bool with_gradient) {
    TransferParameters transfer{s_.solver.transfer, s_.solver.position_alpha, s_.solver.flip_fraction,
                                s_.mass_floor};
    if (transfer.kind == VelocityTransfer::FMPM && !fmpm_now_)
      transfer.kind = VelocityTransfer::FLIP;  // periodic
    constexpr bool kTrackedDomains = requires {
      stencils_.move_domains(s_.grid, s_.fields, s_.particles, dt, DomainMotion<D>{});
    };
    if constexpr (kTrackedDomains) old_velocity_ = s_.particles.v;
    const auto result =
        gather_and_move(grid_, stencils_, s_.fields, s_.particles, transfer, dt, with_gradient, s_.gravity);
    if constexpr (kTrackedDomains) {  // CPDI2 corners (Gong 2015 eq. (6.28)) with the transfer's alpha
      const bool xpic = transfer.kind == VelocityTransfer::XPIC;
      const double flip = transfer.kind == VelocityTransfer::FLIP    ? 1.0
                          : transfer.kind == VelocityTransfer::Blend ? transfer.flip_fraction
                                                                     : 0.0;
      stencils_.move_domains(s_.grid, s_.fields, s_.particles, dt,
                             DomainMotion<D>{flip, transfer.alpha, xpic, &old_velocity_});
    }
    if constexpr (kFields) move_rigid_particles(s_.time + dt);
    s_.external_work += result.gravity_work;
    if (result.first_outside >= 0) fail_outside(result.first_outside);
    if (result.first_too_fast >= 0) {
      std::ostringstream what;
      what << "moved more than one cell in one step (velocity ("
           << s_.particles.v[result.first_too_fast].transpose() << "), dt = " << dt
           << "): the particle Courant number exceeds 1; reduce solver.courant or solver.dt";
      fail(result.first_too_fast, what.str());
    }
  }

  /// L from the lumped velocities p/m with the conditions at time t (USF task 1.b-1.d, MUSL 4.a-4.c),
  /// through the FMPM loop on FMPM steps (tasks 1.c and 4.c).
  void strain_from_momentum(double dt, double t) {
    lumped_velocity(s_.fields, s_.mass_floor, velocity_);
    s_.conditions.apply(velocity_, t);
    if (fmpm_now_)
      fmpm_.run(grid_, stencils_, s_.particles, s_.fields.mass, s_.mass_floor, s_.conditions, t, velocity_);
    gather_velocity_gradient(grid_, stencils_, velocity_, s_.particles, s_.fields.mass, s_.mass_floor);
    update_strain(dt);
  }

  void update_strain(double dt) {
    // F <- dF F (task 5), then the stress of the new F. Two passes: fusing them into update_stress
    // (its advance_F argument) measured 9-10 % slower on bench-2d (2.49 -> 2.72 s a run, session 17).
    update_deformation(s_.particles, dt, s_.solver.deformation_update);
    const ArtificialViscosity av{s_.solver.av_linear, s_.solver.av_quadratic, s_.grid.min_cell_size()};
    const long bad = update_stress<D>(s_.materials, s_.particles, av, dt);
    if (heat_.active()) {  // thermoelastic coupling (heat_transport.hpp)
      heat_.thermoelastic(s_, s_.particles, dt);
      heat_.thermal_stress(s_, s_.particles);
    }
    if (bad >= 0) {
      std::ostringstream what;
      const double J = s_.particles.F[bad].determinant();
      if (J > 0.0)
        what << "non-finite stress (det F = " << J << ")";
      else
        what << "det F = " << J << " (needs > 0)";
      fail(bad, what.str());
    }
  }

  /// Names which of the two the gather saw: a non-finite velocity or position, or a particle
  /// outside the grid (with the grid's extent).
  void fail_outside(long p) {
    std::ostringstream what;
    const auto& v = s_.particles.v[p];
    if (!v.allFinite() || !s_.particles.x[p].allFinite())
      what << "has a non-finite velocity (" << v.transpose() << ") or position";
    else
      what << "left the grid domain [" << s_.grid.origin.transpose() << "] to ["
           << s_.grid.domain_max().transpose() << "] (velocity (" << v.transpose() << "))";
    fail(p, what.str());
  }

  /// CPDI stencils (also inside the multi-field adapter) report domains that outgrew the grid.
  template <class S>
  static long first_corner_outside(const S& stencils) {
    if constexpr (requires { stencils.base; })
      return first_corner_outside(stencils.base);
    else if constexpr (requires { stencils.first_corner_outside; })
      return stencils.first_corner_outside;
    else
      return -1;
  }

  void fail_corner_outside(long p) {
    const auto& F = s_.particles.F[p];
    std::ostringstream what;
    what << "has a domain corner more than one cell outside the grid [" << s_.grid.origin.transpose()
         << "] to [" << s_.grid.domain_max().transpose() << "] (deformation gradient F = [";
    for (int r = 0; r < D; ++r) what << (r > 0 ? "; " : "") << F.row(r);
    what << "], det F = " << F.determinant()
         << "): its CPDI domain outgrew the grid; enlarge the grid, or refine if F is not physical";
    fail(p, what.str());  // a decomposed run: settled right after the stencils (step())
  }

  /// Stops the run naming particle p. A decomposed run finishes the step first (the other ranks
  /// wait for this one's messages) and stops at its end (settle_failures).
  void fail(long p, const std::string& what) {
    std::ostringstream entity;
    entity << "particle " << s_.particles.id[p] << " (body " << s_.particles.body[p] << ") at x = ("
           << s_.particles.x[p].transpose() << ")";
    if (!ranks_) throw NumericalFailure(s_.step + 1, s_.time + step_dt_, entity.str(), what);
    if (!pending_failure_) pending_failure_.emplace(entity.str(), what);
  }

  /// A decomposed run's partition, hand-off and migration (null in a serial run).
  struct Ranks {
    Ranks(const Grid<D>& grid, BoxPartition<D> boxes, const Communicator& comm)
        : partition(std::move(boxes)), hand_off(grid, partition, comm), migration(grid, partition, comm) {}
    BoxPartition<D> partition;
    ColourHandOff<D> hand_off;
    ParticleMigration<D> migration;
    long partitioned_at = 0;  // the step of the last re-partition (0: the start)
    long repartitions = 0;
  };

  Simulation<D>& s_;
  Grid<D> whole_grid_;  // every node: the grid a decomposed run's windows are cut from
  Index field_count_;   // grid velocity fields (bodies or materials in contact; 1 without contact)
  std::pair<int, int> window_reach_{-1, -1};  // the agreed reach the window was fitted to
  std::unique_ptr<Ranks> ranks_;
  std::optional<std::pair<std::string, std::string>> pending_failure_;  // entity, what
  Stencils stencils_;
  Grid<D> grid_;                      // s_.grid, with node_count over every field of a contact run
  std::vector<Vec<D>> velocity_;      // scratch node velocities for USF / MUSL
  std::vector<Vec<D>> old_velocity_;  // CPDI2: V^n of every particle, for its corners' motion
  std::vector<Vec<D>> step_start_x_;  // MLS mapping: positions of the start of the step
  FmpmLoop<D> fmpm_;
  MlsMapping<D> mls_;
  NearParticles<D> mls_neighbours_;   // a decomposed run: the particles the MLS mappings read
  NearParticles<D> heat_neighbours_;  // and those whose domains the heat contact conductance reads
  typename ThermalContactCoupling<D>::NearDomains near_domains_;
  HeatTransport<D> heat_;     // inactive unless the input has a "heat" section
  bool fmpm_now_ = false;     // this step runs the FMPM loop
  double fmpm_period_ = 0.0;  // periodic FMPM by time or Courant units
  double next_fmpm_time_ = 0.0;
  double total_mass_ = 0.0;
  double step_dt_ = 0.0;
};

}  // namespace matpoint
