// Multimaterial contact on per-field grid velocities (Nairn 2026 §3.2; theory and references in
// docs/theory/contact.md). Each body (or material) is a field with its own copy of the N grid
// nodes (field f owns flat indices f N .. f N + N - 1, see field_stencils.hpp). A node where two
// or more fields have mass is a contact node; at each one the contact law of the pair turns
// dp0 = m_red (v_b - v_a), the change to the common velocity, into the applied change dp
// (contact_law.hpp). The law runs on the lumped momenta in tasks 1.a and 3.a and, inside the
// FMPM loop (Table 1 line (2)), on each increment by the "Net" (default) or "Evolving" method.
//   pair of deformable fields:  dp0 = m_a m_b / (m_a + m_b) (v_b - v_a),  +dp to a, -dp to b
//   deformable a and rigid b:   dp0 = m_a (v_b - v_a),                      +dp to a only
//   three or more fields:       dp0_a = m_a (v_com - v_a) for each field a  (NairnMPM's form)
#pragma once

#include <algorithm>
#include <array>
#include <limits>
#include <span>
#include <vector>

#include "matpoint/explicit/contact_law.hpp"
#include "matpoint/explicit/logistic_normal.hpp"
#include "matpoint/explicit/seen_particles.hpp"
#include "matpoint/grid/brick_schedule.hpp"
#include "matpoint/grid/grid.hpp"
#include "matpoint/grid/owned_nodes.hpp"
#include "matpoint/io/spec.hpp"
#include "matpoint/parallel/communicator.hpp"
#include "matpoint/particles/particle_set.hpp"

namespace matpoint {

template <int D>
class MultiFieldContact {
 public:
  MultiFieldContact() = default;

  /// `rigid_velocity[f]` is empty for a deformable field f.
  MultiFieldContact(const ContactSpec& spec, int fields, Index nodes, double cell_size, double mass_floor,
                    std::vector<std::vector<TimeFunction>> rigid_velocity)
      : spec_(spec),
        fields_(fields),
        nodes_(nodes),
        cell_size_(cell_size),
        mass_floor_(mass_floor),
        rigid_velocity_(std::move(rigid_velocity)),
        laws_(static_cast<std::size_t>(fields * fields), spec.law) {
    for (const auto& pair : spec.pairs) {
      laws_[pair.first * fields + pair.second] = pair.law;
      laws_[pair.second * fields + pair.first] = pair.law;
    }
  }

  [[nodiscard]] int fields() const { return fields_; }
  [[nodiscard]] Index field_nodes() const { return nodes_; }
  /// A decomposed run's rank stores another window of the grid: N nodes per field (the node
  /// arrays are filled anew every step).
  void use_window(Index nodes) { nodes_ = nodes; }
  [[nodiscard]] bool rigid(int f) const { return !rigid_velocity_[f].empty(); }
  [[nodiscard]] std::size_t contact_nodes() const { return entries_.size(); }

  /// A decomposed run (docs/scale-out.md §17 stage 3): the ranks decide together whether the
  /// normals' sums run (they are collectives: any rank with a contact node), and friction_work
  /// counts only the grid nodes (of N) this rank owns, so that a node two ranks store
  /// counts once when the ranks' works are added. Every rank finds the contact nodes among the
  /// nodes it stores, where the scatter's hand-off completed the sums.
  void decompose(const Communicator& comm, const OwnedNodes& owned) {
    comm_ = comm;
    counted_ = owned;
  }

  /// A decomposed run's logistic-regression normals (explicit/seen_particles.hpp): the nodes that
  /// this rank shares with each other rank, and the particles' sort keys (their
  /// serial storage order with the ids), which the fit of a shared node reads in merged order.
  void share_nodes(std::vector<SharedNodes<D>> shared, const std::vector<Index>* sort_keys) {
    shared_ = std::move(shared);
    sort_keys_ = sort_keys;
  }

  [[nodiscard]] Vec<D> rigid_velocity(int f, double t) const {
    Vec<D> v;
    for (int a = 0; a < D; ++a) v[a] = rigid_velocity_[f][a](t);
    return v;
  }

  /// Task 1.a set-up, once per step after the mass scatter: finds the contact nodes, their
  /// normals and (with the position criterion) whether the fields touch. `field_of(p)` is the
  /// field of particle p; nodes are the multi-field indices of `stencils`.
  template <class Stencils>
  void prepare(const Grid<D>& grid, const Stencils& stencils, const ParticleSet<D>& particles,
               const std::vector<double>& mass) {
    find_contact_nodes(mass);
    const long here = entries_.empty() ? 0 : 1;
    if ((comm_.distributed() ? comm_.max(here) : here) == 0) return;
    gradient_.assign(mass.size(), Vec<D>::Zero());
    const bool positions = spec_.separation.has_value();
    if (positions) position_.assign(mass.size(), Vec<D>::Zero());
    const bool by_volume = spec_.normals != ContactNormals::MassGradient;
    const bool logistic = spec_.normals == ContactNormals::Logistic;
    // The sums in the scatter's brick order (grid/brick_schedule.hpp): the same on any number of
    // threads and ranks (a decomposed run hands them on between the colours, as the masses).
    Vec<D>* const gradient = gradient_.data();
    Vec<D>* const position = positions ? position_.data() : nullptr;
    const auto nodes = static_cast<Index>(mass.size());
    const NodeArray written[2] = {{gradient->data(), D, nodes},
                                  {positions ? position->data() : nullptr, D, nodes}};
    const auto add_particle = [&](std::size_t p) {
      const double w = by_volume ? particles.volume(p) : particles.mass[p];
      const double m = particles.mass[p];
      const Vec<D>& x = particles.x[p];
      stencils.for_each_node(grid, p, [&](Index node, double N, const auto& dN) {
        gradient[node] += w * dN;
        if (positions) position[node] += (m * N) * x;
      });
    };
    stencils.brick_order().for_each_particle(add_particle,
                                             std::span<const NodeArray>(written, positions ? 2 : 1));
    if (logistic) collect_seen_particles(grid, stencils, particles);
    for (auto& e : entries_) {
      set_normal(e, mass);
      if (logistic && e.kind != Kind::Rest) set_logistic_normal(e, grid);
    }
  }

  /// The contact nodes of this step for coupled heat (thermal_contact.hpp): visit(node, a, b,
  /// in_contact) per entry, b = -1 for field a against all the others (three or more fields), and
  /// in_contact the mechanics' detection: always for stick, else where the fields touch.
  template <class Visit>
  void for_each_contact(Visit&& visit) const {
    for (const auto& e : entries_) visit(e.node, e.a, e.b, e.law.law == ContactLaw::Stick || e.touching);
  }

  /// Logistic-regression nodes whose fit failed and kept the average normal (diagnostics).
  [[nodiscard]] std::size_t logistic_fallbacks() const { return logistic_fallbacks_; }

  /// Sets the rigid fields' node values to their prescribed velocity at t (times the node mass
  /// when `x` holds momenta).
  void set_rigid(const std::vector<double>& mass, std::vector<Vec<D>>& x, double t, bool momentum) const {
    for (int f = 0; f < fields_; ++f) {
      if (!rigid(f)) continue;
      const Vec<D> v = rigid_velocity(f, t);
      for (Index i = f * nodes_; i < (f + 1) * nodes_; ++i)
        if (mass[i] > mass_floor_) x[i] = momentum ? Vec<D>(mass[i] * v) : v;
    }
  }

  /// Tasks 1.a / 3.a: the lumped contact law on momenta (`momentum` true) or velocities. Caches
  /// the Net / Evolving state of every contact node for the FMPM loop that may follow.
  /// `add_to_total`: the step's contact impulse (`total`, for the friction work) adds this
  /// correction to the earlier ones instead of starting from it. Task 3.a of an FMPM step needs it:
  /// there the particles take V = S v+(k), v+(k) = m~_k^-1 (p + f dt + ...), which keeps task 1.a's
  /// correction of p, so that correction reaches the bodies; on a FLIP step it cancels in the
  /// increment v+ - v of the particle update and only task 3.a's counts.
  void apply_lumped(const std::vector<double>& mass, std::vector<Vec<D>>& x, bool momentum,
                    bool add_to_total = false) {
    const auto velocity = [&](Index i) -> Vec<D> { return momentum ? Vec<D>(x[i] / mass[i]) : x[i]; };
    for (auto& e : entries_) {
      const Vec<D> dp0 = change_to_common(e, mass, velocity);
      const Vec<D> dp = law_change(e, dp0);
      e.applied = dp;
      e.prior = spec_.fmpm_method == ContactFmpmMethod::Net ? dp0 : Vec<D>(dp0 - dp);
      e.net = dp;
    }
    for (auto& e : entries_) {
      apply(e, e.applied, mass, x, momentum);
      e.total = add_to_total ? Vec<D>(e.total + e.applied) : e.applied;
    }
  }

  /// The friction work of a step: each Coulomb node's total tangential correction (the lumped one
  /// of task 3.a; on an FMPM step also task 1.a's and every increment's correction of the loop)
  /// times the slip left in `velocity`: v+(1) right after task 3.a on a FLIP step, the final v+(k)
  /// after an FMPM loop. A decomposed run: this rank's owned nodes only (decompose()).
  [[nodiscard]] double friction_work(const std::vector<double>& mass,
                                     const std::vector<Vec<D>>& velocity) const {
    const auto v = [&](Index i) -> Vec<D> { return velocity[i]; };
    double work = 0.0;
    for (const auto& e : entries_)
      if (e.law.law == ContactLaw::Coulomb && counted_.contains(e.node))
        work += slip_work(e, e.total, mass, v);
    return work;
  }

  /// The same frictional work node by node, added to `heat` (by multi-field node) as the heat of
  /// coupled conduction: half to each field of a pair, all of it to the deformable field against
  /// a rigid one or against the rest (our choice; Nairn 2026 §3.2.2 only says friction becomes heat).
  void add_friction_heat(const std::vector<double>& mass, const std::vector<Vec<D>>& velocity,
                         std::vector<double>& heat) const {
    const auto v = [&](Index i) -> Vec<D> { return velocity[i]; };
    for (const auto& e : entries_) {
      if (e.law.law != ContactLaw::Coulomb) continue;
      const double w = slip_work(e, e.total, mass, v);
      if (e.kind == Kind::Pair) {
        heat[at(e.a, e.node)] += 0.5 * w;
        heat[at(e.b, e.node)] += 0.5 * w;
      } else {
        heat[at(e.a, e.node)] += w;
      }
    }
  }

  /// FMPM loop line (2) on the increment dv(l) of every field: rigid fields get no increment, and
  /// each contact node the Net (or Evolving) correction of Nairn 2026 eq. (20).
  void correct_increment(const std::vector<double>& mass, std::vector<Vec<D>>& dv) {
    for (int f = 0; f < fields_; ++f)
      if (rigid(f))
        for (Index i = f * nodes_; i < (f + 1) * nodes_; ++i) dv[i].setZero();
    const auto increment = [&](Index i) -> Vec<D> { return dv[i]; };
    const bool net = spec_.fmpm_method == ContactFmpmMethod::Net;
    for (auto& e : entries_) {
      const Vec<D> dp0 = e.prior + change_to_common(e, mass, increment);  // eq. (20)
      const Vec<D> dp = law_change(e, dp0);
      e.applied = net ? Vec<D>(dp - e.net) : dp;  // Net: only the change of the total correction
      e.prior = net ? dp0 : Vec<D>(dp0 - dp);
      e.net = dp;
    }
    for (auto& e : entries_) {
      apply(e, e.applied, mass, dv, false);
      e.total += e.applied;
    }
  }

 private:
  enum class Kind { Pair, Rigid, Rest };
  struct Entry {
    Index node;  // the grid node (0 .. N - 1)
    int a, b;    // fields; b = -1 for Rest (a against all the others)
    Kind kind;
    ContactLawSpec law;
    Vec<D> normal = Vec<D>::Zero();  // from a to b
    bool touching = true;            // normal defined and, with the position criterion, gap closed
    Vec<D> prior = Vec<D>::Zero(), net = Vec<D>::Zero(), applied = Vec<D>::Zero();
    Vec<D> total = Vec<D>::Zero();  // every correction applied this step (the friction impulse)
  };

  [[nodiscard]] Index at(int f, Index node) const { return f * nodes_ + node; }

  void find_contact_nodes(const std::vector<double>& mass) {
    entries_.clear();
    std::vector<int> present;
    for (Index i = 0; i < nodes_; ++i) {
      present.clear();
      for (int f = 0; f < fields_; ++f)
        if (mass[at(f, i)] > mass_floor_) present.push_back(f);
      if (present.size() < 2) continue;
      const auto rigid_it = std::find_if(present.begin(), present.end(), [&](int f) { return rigid(f); });
      if (rigid_it != present.end()) {  // every deformable field against the (first) rigid one
        for (int f : present)
          if (!rigid(f)) entries_.push_back({i, f, *rigid_it, Kind::Rigid, laws_[f * fields_ + *rigid_it]});
      } else if (present.size() == 2) {
        entries_.push_back({i, present[0], present[1], Kind::Pair, laws_[present[0] * fields_ + present[1]]});
      } else {
        for (int f : present) {
          int heaviest = -1;  // the law of a and the heaviest other field
          for (int g : present)
            if (g != f && (heaviest < 0 || mass[at(g, i)] > mass[at(heaviest, i)])) heaviest = g;
          entries_.push_back({i, f, -1, Kind::Rest, laws_[f * fields_ + heaviest]});
        }
      }
    }
  }

  /// Normal from a to b: a's outward normal minus b's ("average", volume gradients), or the
  /// outward mass-gradient normal of one field: the rigid one, else the heavier one (a for Rest).
  void set_normal(Entry& e, const std::vector<double>& mass) {
    const Index ia = at(e.a, e.node);
    Vec<D> other = Vec<D>::Zero(), other_position = Vec<D>::Zero();
    double other_mass = 0.0;
    for (int g = 0; g < fields_; ++g) {
      const Index ig = at(g, e.node);
      if (g == e.a || (e.b >= 0 && g != e.b) || !(mass[ig] > mass_floor_)) continue;
      other += gradient_[ig];
      other_mass += mass[ig];
      if (!position_.empty()) other_position += position_[ig];
    }
    // gradient_ holds sum_p w_p grad S_pi = -grad m(x_i): the outward normal of each field.
    Vec<D> n;
    if (spec_.normals != ContactNormals::MassGradient)  // also the regression's fallback
      n = gradient_[ia] - other;
    else if (e.kind == Kind::Rigid || (e.kind == Kind::Pair && mass[at(e.b, e.node)] > mass[ia]))
      n = -other;
    else
      n = gradient_[ia];
    const double length = n.norm();
    e.touching = length > 0.0;
    if (!e.touching) return;
    e.normal = n / length;
    if (spec_.separation) {  // contact position criterion: the fields' mass centres at the node
      const double gap = (other_position / other_mass - position_[ia] / mass[ia]).dot(e.normal);
      e.touching = gap < *spec_.separation * cell_size_;
    }
  }

  /// Logistic regression: the particles that see each contact node (grid-node slots, reused), in
  /// the serial storage order; a decomposed run adds the other ranks' particles that see the nodes
  /// it shares with them and orders each list by (key, id), the serial order.
  template <class Stencils>
  void collect_seen_particles(const Grid<D>& grid, const Stencils& stencils,
                              const ParticleSet<D>& particles) {
    slot_of_node_.assign(static_cast<std::size_t>(nodes_), -1);
    slot_node_.clear();
    for (const auto& e : entries_)
      if (slot_of_node_[e.node] < 0) {
        slot_of_node_[e.node] = static_cast<int>(slot_node_.size());
        slot_node_.push_back(e.node);
      }
    if (seen_.size() < slot_node_.size()) seen_.resize(slot_node_.size());
    for (std::size_t k = 0; k < slot_node_.size(); ++k) seen_[k].clear();
    const bool keys = sort_keys_ != nullptr && comm_.distributed();
    for (std::size_t p = 0; p < particles.size(); ++p)
      stencils.for_each_node(grid, p, [&](Index node, double, const auto&) {
        const int slot = slot_of_node_[node % nodes_];
        if (slot < 0) return;
        seen_[static_cast<std::size_t>(slot)].push_back({keys ? (*sort_keys_)[p] : 0, particles.id[p],
                                                         static_cast<int>(node / nodes_), particles.x[p],
                                                         particles.F[p], particles.size0[p]});
      });
    if (!comm_.distributed()) return;
    seen_.resize(slot_node_.size());
    exchange_seen_particles<D>(comm_, grid, shared_, slot_node_, slot_of_node_, seen_);
    for (auto& list : seen_)
      std::sort(list.begin(), list.end(), [](const auto& a, const auto& b) { return a.before(b); });
  }

  /// Nairn's normal and gap: the regression normal of the particles of a (-1) and b (+1) that see
  /// the node, and delta_n = min_b (x . n - R(n)) - max_a (x . n + R(n)) with R(n) the deformed
  /// half-extent of the particle along n (extraction §2.5). In contact needs delta_n below
  /// `separation` cells (default 0). A failed fit keeps the average normal and its test.
  void set_logistic_normal(Entry& e, const Grid<D>& grid) {
    const Vec<D> origin = grid.node_position(e.node);
    const Vec<D> inverse_h = grid.h.cwiseInverse();
    const auto& seen = seen_[static_cast<std::size_t>(slot_of_node_[e.node])];
    points_.clear();
    for (const auto& s : seen) {
      if (s.field != e.a && s.field != e.b) continue;
      points_.push_back({(s.x - origin).cwiseProduct(inverse_h), s.field == e.a ? -1.0 : 1.0});
    }
    const auto fit = logistic_normal<D>(std::span<const LabelledPoint<D>>(points_));
    if (!fit.found) {
      // A node two ranks store fails on both: the rank that owns it counts it.
      if (counted_.contains(e.node)) ++logistic_fallbacks_;
      return;
    }
    e.normal = fit.normal;
    double a_front = -std::numeric_limits<double>::infinity(),
           b_back = std::numeric_limits<double>::infinity();
    for (const auto& s : seen) {
      if (s.field != e.a && s.field != e.b) continue;
      const double along = s.x.dot(e.normal);
      const double extent = s.half_extent(e.normal);
      if (s.field == e.a)
        a_front = std::max(a_front, along + extent);
      else
        b_back = std::min(b_back, along - extent);
    }
    e.touching = b_back - a_front < spec_.separation.value_or(0.0) * cell_size_;
  }

  template <class Velocity>
  Vec<D> change_to_common(const Entry& e, const std::vector<double>& mass, const Velocity& v) const {
    const Index ia = at(e.a, e.node);
    const double ma = mass[ia];
    switch (e.kind) {
      case Kind::Pair: {
        const Index ib = at(e.b, e.node);
        const double mb = mass[ib];
        return (ma * mb / (ma + mb)) * (v(ib) - v(ia));
      }
      case Kind::Rigid:
        return ma * (v(at(e.b, e.node)) - v(ia));
      case Kind::Rest:
        break;
    }
    Vec<D> momentum = Vec<D>::Zero();
    double total = 0.0;
    for (int g = 0; g < fields_; ++g) {
      const Index ig = at(g, e.node);
      if (!(mass[ig] > mass_floor_)) continue;
      momentum += mass[ig] * v(ig);
      total += mass[ig];
    }
    return ma * (momentum / total - v(ia));
  }

  /// Stick applies everywhere (no detection); the other laws only where the fields touch.
  [[nodiscard]] Vec<D> law_change(const Entry& e, const Vec<D>& dp0) const {
    if (e.law.law == ContactLaw::Stick) return dp0;
    if (!e.touching) return Vec<D>::Zero();
    return contact_momentum_change<D>(e.law, dp0, e.normal);
  }

  void apply(const Entry& e, const Vec<D>& dp, const std::vector<double>& mass, std::vector<Vec<D>>& x,
             bool momentum) const {
    const Index ia = at(e.a, e.node);
    x[ia] += momentum ? dp : Vec<D>(dp / mass[ia]);
    if (e.kind != Kind::Pair) return;
    const Index ib = at(e.b, e.node);
    x[ib] -= momentum ? dp : Vec<D>(dp / mass[ib]);
  }

  /// Friction work of one step at a node: the tangential change dp_t (the friction impulse,
  /// +dp_t on a) times the relative tangential velocity left after the correction (the slip
  /// rate), dp_t . (v_b - v_a)_after >= 0; zero where the law sticks (Nairn, Bardenhagen & Smith
  /// 2018: frictional heating = friction force x slip).
  template <class Velocity>
  [[nodiscard]] double slip_work(const Entry& e, const Vec<D>& impulse, const std::vector<double>& mass,
                                 const Velocity& v) const {
    if (!e.touching) return 0.0;
    const Vec<D> dp_t = impulse - impulse.dot(e.normal) * e.normal;
    const Index ia = at(e.a, e.node);
    double m_eff = mass[ia];  // change_to_common = m_eff (v_b - v_a)
    if (e.kind == Kind::Pair) {
      const double mb = mass[at(e.b, e.node)];
      m_eff = mass[ia] * mb / (mass[ia] + mb);
    }
    return std::max(0.0, dp_t.dot(change_to_common(e, mass, v)) / m_eff);
  }

  ContactSpec spec_;
  int fields_ = 1;
  Index nodes_ = 0;
  double cell_size_ = 0.0;
  double mass_floor_ = 0.0;
  std::vector<std::vector<TimeFunction>> rigid_velocity_;  // by field; empty: deformable
  std::vector<ContactLawSpec> laws_;                       // by field pair (a * fields + b)
  std::vector<Entry> entries_;
  std::vector<Vec<D>> gradient_, position_;         // by multi-field node: sum w_p grad S, sum M_p S x_p
  std::vector<int> slot_of_node_;                   // logistic regression: grid node -> slot, or -1
  std::vector<Index> slot_node_;                    // by slot: its grid node
  std::vector<std::vector<SeenParticle<D>>> seen_;  // by slot: the particles that see the node
  std::vector<SharedNodes<D>> shared_;              // a decomposed run: the nodes shared per rank
  const std::vector<Index>* sort_keys_ = nullptr;   // a decomposed run: the particles' sort keys
  std::vector<LabelledPoint<D>> points_;            // scratch for one fit
  std::size_t logistic_fallbacks_ = 0;
  Communicator comm_;   // a decomposed run's ranks (decompose()); one rank by default
  OwnedNodes counted_;  // friction_work's nodes
};

}  // namespace matpoint
