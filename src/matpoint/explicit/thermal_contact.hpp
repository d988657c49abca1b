// Heat across contact surfaces in coupled conduction (docs/theory/heat.md, "Contact"). With
// multi-field contact (contact.hpp) every field has its own nodal temperature; at the nodes where
// the mechanics finds fields in contact (stick: every shared node; the other laws: where the
// fields touch) the fields exchange heat by one of
//   perfect:      one temperature per node, T_i = sum_f c_f T_f / sum_f c_f, on T_i, on T+_i and on
//                 every FMPM(k) increment (the single nodal temperature of NairnMPM's conduction,
//                 which reproduces one body's conduction when the fields are one material);
//   conductance:  the flux h_c A_i (T_b - T_a) from b to a, with the nodal contact area A_i, an
//                 estimate of int_interface S_i dA, from the fields' nodal volumes
//                 V_f,i = sum_{p in f} int_{Omega_p} N_i, N_i the basis's grid function integrated
//                 exactly over each particle's domain (volumes() below)
//                 (V = V_a + V_b, f = min(V_a, V_b) / V):
//                   A_i = (V / h_n) K(r),   int_{-inf}^{r} K(s) ds = f,  r <= 0,
//                 K the basis's 1-D grid kernel (hat, quadratic or cubic B-spline; GIMP and CPDI
//                 average it over the particle domain) and h_n the cell size along the interface's
//                 normal. For an interface normal to a grid axis at distance d from node i, with the
//                 node's support shared by the two fields and the particle domains tiling them,
//                 the tensor product N_i = K(x_n / h_n) P(x_t)
//                 gives V = h_n int P, f = int_{d/h_n}^{inf} K (the tail beyond the interface, the
//                 smaller part), so r = -d / h_n and A_i = K(d / h_n) int P = int_interface N_i dA
//                 exactly; by the partition of unity the A_i sum to the interface's area at any
//                 offset in the cell. For the hat, r = sqrt(2 f) - 1 and A_i = sqrt(2 min(V_a, V_b) V) / h_n:
//                 NairnMPM's contact area (nairn-mpm-fea, NairnMPM/src/Nodes/CrackVelocityFieldMulti.cpp,
//                 CrackVelocityFieldMulti::GetContactArea, after Nairn 2013 on imperfect interfaces;
//                 for splines it fits the distance empirically, here K is inverted exactly). The
//                 two-node exchange c_a dT_a/dt = -c_b dT_b/dt = h_c A (T_b - T_a) is integrated
//                 exactly over the step,
//                 Q = (T_b - T_a) (1 - exp(-h_c A (1/c_a + 1/c_b) dt)) / (1/c_a + 1/c_b),
//                 unconditionally stable and tending to perfect contact as h_c grows;
//   insulated:    no exchange.
// A node of three or more fields: perfect contact mixes all of them; with a conductance each field
// exchanges with the others pooled (capacity-weighted, V_pool their volume) on half the area
// A(V_a, V_pool) (each interface is then seen from both sides). Fields without capacity (a rigid
// material without C_V) take no part.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "matpoint/explicit/contact.hpp"
#include "matpoint/explicit/field_stencils.hpp"
#include "matpoint/grid/grid.hpp"
#include "matpoint/io/spec.hpp"
#include "matpoint/particles/particle_set.hpp"
#include "matpoint/shape/cpdi_stencils.hpp"
#include "matpoint/shape/kernels.hpp"
#include "matpoint/shape/tensor_bases.hpp"
#include "matpoint/shape/tensor_stencils.hpp"

namespace matpoint {

/// The 1-D grid kernel of a contact run's stencils: the function whose tensor product the node
/// weights are (point bases) or whose average over the particle domain they are (GIMP, CPDI).
template <class Stencils>
struct GridKernelOf;
template <int D, class Base>
struct GridKernelOf<FieldStencils<D, Base>> : GridKernelOf<Base> {};
template <int D>
struct GridKernelOf<TensorStencils<D, LinearBasis>> {
  using type = HatKernel;
};
template <int D>
struct GridKernelOf<TensorStencils<D, QuadraticBSplineBasis>> {
  using type = QuadraticKernel;
};
template <int D>
struct GridKernelOf<TensorStencils<D, CubicBSplineBasis>> {
  using type = CubicKernel;
};
template <int D, class Kernel, DomainWidth Kind>
struct GridKernelOf<TensorStencils<D, GimpBasis<Kernel, Kind>>> {
  using type = Kernel;
};
template <int D, class Kernel, CpdiDomain Domain>
struct GridKernelOf<CpdiStencils<D, Kernel, Domain>> {
  using type = Kernel;
};

/// K(r) at the r <= 0 where the kernel's integral from -inf reaches f in [0, 1/2]: the kernel's
/// value at the interface seen from a node whose far side holds the fraction f of its volume.
template <class Kernel>
[[nodiscard]] double kernel_at_tail_fraction(double f) {
  f = std::clamp(f, 0.0, 0.5);
  if constexpr (std::is_same_v<Kernel, HatKernel>) {
    return std::sqrt(2.0 * f);  // (1 + r)^2 / 2 = f, K(r) = 1 + r
  } else {
    // Newton on the increasing integral, kept inside the bracket [lo, hi] by bisection.
    double lo = -Kernel::radius, hi = 0.0;
    double r = Kernel::radius * (std::sqrt(2.0 * f) - 1.0);
    for (int iteration = 0; iteration < 100; ++iteration) {
      const double excess = Kernel::integral(r) - f;
      if (excess > 0.0)
        hi = r;
      else
        lo = r;
      const double slope = Kernel::value(r);
      double next = slope > 0.0 ? r - excess / slope : 0.5 * (lo + hi);
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      const bool done = std::abs(next - r) <= 1e-15 * Kernel::radius || hi - lo <= 1e-15 * Kernel::radius;
      r = next;
      if (done) break;
    }
    return Kernel::value(r);
  }
}

/// The nodal contact area between two fields of volumes Va and Vb at a node, h_n the cell size
/// along the interface's normal: A = (Va + Vb) / h_n K(r), int_{-inf}^{r} K = min(Va, Vb) / (Va + Vb)
/// (file comment).
template <class Kernel>
[[nodiscard]] double nodal_contact_area(double Va, double Vb, double h_normal) {
  const double V = Va + Vb;
  if (!(V > 0.0)) return 0.0;
  return V / h_normal * kernel_at_tail_fraction<Kernel>(std::min(Va, Vb) / V);
}

/// The cell size along the unit normal n: the distance along n to the ellipse (ellipsoid) with the
/// cell sizes as semi-axes, 1 / |(n_k / h_k)|; h itself on a grid of square (cubic) cells and h_k
/// for n along axis k. `direction` need not be unit; a zero one gives the mean cell size.
template <int D>
[[nodiscard]] double cell_size_along(const Grid<D>& grid, const Vec<D>& direction) {
  if ((grid.h.array() == grid.h[0]).all()) return grid.h[0];
  const double length = direction.norm();
  if (!(length > 0.0)) return grid.h.mean();
  return length / direction.cwiseQuotient(grid.h).norm();
}

template <int D>
class ThermalContactCoupling {
 public:
  ThermalContactCoupling() = default;
  ThermalContactCoupling(ThermalContact mode, double conductance) : mode_(mode), conductance_(conductance) {}

  [[nodiscard]] bool perfect() const { return mode_ == ThermalContact::Perfect && !members_.empty(); }
  [[nodiscard]] bool conducts() const { return mode_ == ThermalContact::Conductance; }

  /// The widest domain stencil (cubic GIMP): how far a particle's domain reaches, in nodes.
  static constexpr int kWidestDomain = GimpBasis<CubicKernel, DomainWidth::Stretched>::width;

  /// A decomposed run (docs/scale-out.md §16): the particles whose domains reach this rank's
  /// window, its own and its neighbours' in the serial order (explicit/near_particles.hpp), with
  /// each one's field offset (field x nodes per field of the window), and the band grid (a window
  /// of the whole grid) where all their domain stencils lie. Null: serial.
  struct NearDomains {
    const ParticleSet<D>* particles = nullptr;
    std::vector<Index> offset;
    Grid<D> band;
  };
  void use_near(const NearDomains* near) { near_ = near; }

  /// Conductance: the sum of the nodal contact areas of the last exchange (m^2; m per unit
  /// thickness in 2-D), a pooled node's half areas included (diagnostics and tests).
  [[nodiscard]] double area() const { return area_; }

  /// This step's contact nodes from the mechanics' detection; only fields with capacity above
  /// `floor` take part.
  void prepare(const MultiFieldContact<D>& contact, const std::vector<double>& capacity, double floor) {
    members_.clear();
    start_.clear();
    pairs_.clear();
    area_ = 0.0;
    if (mode_ == ThermalContact::Insulated || contact.contact_nodes() == 0) return;
    const Index nodes = contact.field_nodes();
    field_nodes_ = nodes;
    fields_ = contact.fields();
    const auto has = [&](int f, Index node) { return capacity[f * nodes + node] > floor; };
    if (mode_ == ThermalContact::Perfect) {
      scratch_.clear();
      contact.for_each_contact([&](Index node, int a, int b, bool in_contact) {
        if (!in_contact) return;
        for (int f = 0; f < contact.fields(); ++f)  // b < 0: a against all the others
          if ((f == a || f == b || (b < 0 && f != a)) && has(f, node)) scratch_.emplace_back(node, f);
      });
      group(nodes);
      return;
    }
    contact.for_each_contact([&](Index node, int a, int b, bool in_contact) {
      if (in_contact && has(a, node) && (b < 0 || has(b, node))) pairs_.push_back({node, a, b});
    });
  }

  /// Perfect contact: the capacity-weighted mean of `value` (temperatures or their increments)
  /// on every contact node.
  void mix(std::vector<double>& value, const std::vector<double>& capacity) const {
    for (std::size_t g = 0; g + 1 < start_.size(); ++g) {
      double heat = 0.0, total = 0.0;
      for (std::size_t k = start_[g]; k < start_[g + 1]; ++k) {
        heat += capacity[members_[k]] * value[members_[k]];
        total += capacity[members_[k]];
      }
      for (std::size_t k = start_[g]; k < start_[g + 1]; ++k) value[members_[k]] = heat / total;
    }
  }

  /// Conductance: adds each contact's exact two-node exchange over dt, as a mean heat flow (W),
  /// to `flow`.
  template <class Stencils>
  void exchange(const Grid<D>& grid, const Stencils& stencils, const ParticleSet<D>& ps,
                const std::vector<double>& T, const std::vector<double>& capacity, double floor, double dt,
                std::vector<double>& flow) {
    if constexpr (requires { Stencils::multi_field; }) {  // a single field has no contact
      using Kernel = typename GridKernelOf<Stencils>::type;
      if (pairs_.empty()) return;
      const Index field_nodes = field_nodes_;
      const int fields = fields_;
      volumes<Kernel>(grid, stencils, ps);
      for (const auto& c : pairs_) {
        const Index ia = c.a * field_nodes + c.node;
        if (c.b >= 0) {
          const Index ib = c.b * field_nodes + c.node;
          const double hn = cell_size_along(grid, Vec<D>(gradient_[ib] - gradient_[ia]));
          const double area = nodal_contact_area<Kernel>(volume_[ia], volume_[ib], hn);
          area_ += area;
          const double Q = exchanged(T[ib] - T[ia], capacity[ia], capacity[ib], area, dt);
          flow[ia] += Q / dt;
          flow[ib] -= Q / dt;
          continue;
        }
        double pool = 0.0, pool_heat = 0.0, pool_volume = 0.0;  // the other fields at the node, pooled
        Vec<D> pool_gradient = Vec<D>::Zero();
        for (int g = 0; g < fields; ++g) {
          const Index ig = g * field_nodes + c.node;
          if (g == c.a || !(capacity[ig] > floor)) continue;
          pool += capacity[ig];
          pool_heat += capacity[ig] * T[ig];
          pool_volume += volume_[ig];
          pool_gradient += gradient_[ig];
        }
        if (!(pool > 0.0)) continue;
        const double hn = cell_size_along(grid, Vec<D>(pool_gradient - gradient_[ia]));
        const double area = 0.5 * nodal_contact_area<Kernel>(volume_[ia], pool_volume, hn);
        area_ += area;
        const double Q = exchanged(pool_heat / pool - T[ia], capacity[ia], pool, area, dt);
        flow[ia] += Q / dt;
        for (int g = 0; g < fields; ++g) {
          const Index ig = g * field_nodes + c.node;
          if (g != c.a && capacity[ig] > floor) flow[ig] -= (Q / dt) * capacity[ig] / pool;
        }
      }
    }
  }

 private:
  struct Pair {
    Index node;
    int a, b;  // b = -1: a against the other fields pooled
  };

  /// Heat from b to a over dt: c_a dT_a/dt = h A (T_b - T_a) = -c_b dT_b/dt, integrated exactly.
  [[nodiscard]] double exchanged(double difference, double ca, double cb, double area, double dt) const {
    const double inverse = 1.0 / ca + 1.0 / cb;
    return difference * -std::expm1(-conductance_ * area * inverse * dt) / inverse;
  }

  /// scratch_ (node, field) -> members_ grouped by node (multi-field indices), groups of two or more.
  void group(Index nodes) {
    std::sort(scratch_.begin(), scratch_.end());
    scratch_.erase(std::unique(scratch_.begin(), scratch_.end()), scratch_.end());
    for (std::size_t k = 0; k < scratch_.size();) {
      std::size_t end = k;
      while (end < scratch_.size() && scratch_[end].first == scratch_[k].first) ++end;
      if (end - k >= 2) {
        if (start_.empty()) start_.push_back(0);
        for (std::size_t m = k; m < end; ++m)
          members_.push_back(scratch_[m].second * nodes + scratch_[m].first);
        start_.push_back(members_.size());
      }
      k = end;
    }
  }

  /// V_f,i = sum_{p in f} V_p Sbar_pi and g_f,i = sum_{p in f} V_p grad Sbar_pi by multi-field node,
  /// with Sbar_pi the average of the grid kernel's N_i over the particle's axis-aligned domain
  /// (cpGIMP's: the initial edge lengths stretched by |F_aa|), integrated exactly by the kernel's
  /// integral whatever the basis's own stencil: so V_f,i = int_f N_i where the domains tile the
  /// field. (The basis's point weights, V_p S_pi, would integrate N_i by the particles' midpoint
  /// rule: exact for the hat with the particles inside cells, but for the B-splines the summed
  /// area of a straight interface would come out 1.1 % (quadratic) and 0.8 % (cubic) short at 4
  /// particles per cell and direction, 4.4 % and 3.2 % at 2, computed off-line.) g_b - g_a points
  /// along the interface's normal (for h_n).
  template <class Kernel, class Stencils>
  void volumes(const Grid<D>& grid, const Stencils& stencils, const ParticleSet<D>& ps) {
    if (near_ != nullptr)  // a decomposed run: its own and its neighbours' particles, serial order
      add_domain_volumes<Kernel>(grid, near_->band, *near_->particles,
                                 [&](std::size_t p) { return near_->offset[p]; });
    else
      add_domain_volumes<Kernel>(grid, grid, ps, [&](std::size_t p) { return stencils.offset[p]; });
  }
  /// The sums of volumes() over the particles `ps` in their order, their domain stencils evaluated
  /// on `domains_grid` (this rank's `grid` itself, or a decomposed run's band grid that holds the
  /// near particles' stencils), into the nodes of `grid` (node_count over every field; `offset(p)`:
  /// particle p's field offset). The nodes of the band outside this rank's window are left out;
  /// a band node's window index is found by its coordinates.
  template <class Kernel, class Offset>
  void add_domain_volumes(const Grid<D>& grid, const Grid<D>& domains_grid, const ParticleSet<D>& ps,
                          Offset&& offset) {
    auto& domains = domain_stencils<Kernel>();
    domains.evaluate(domains_grid, ps);
    volume_.assign(static_cast<std::size_t>(grid.node_count), 0.0);
    gradient_.assign(static_cast<std::size_t>(grid.node_count), Vec<D>::Zero());
    const bool band = &domains_grid != &grid;
    for (std::size_t p = 0; p < ps.size(); ++p) {
      const double V = ps.volume(p);
      domains.for_each_node(domains_grid, p, [&](Index node, double N, const Vec<D>& dN) {
        if (band) node = domains_grid.node_index_in(grid, node);
        if (node < 0 || node >= field_nodes_) return;  // not in this rank's window
        node += offset(p);                             // on the particle's field
        volume_[node] += V * N;
        gradient_[node] += V * dN;
      });
    }
  }

  /// The stretched-GIMP stencils of Kernel over the particles' domains (kept: evaluated each step).
  template <class Kernel>
  TensorStencils<D, GimpBasis<Kernel, DomainWidth::Stretched>>& domain_stencils() {
    static_assert(std::is_same_v<Kernel, HatKernel> || std::is_same_v<Kernel, QuadraticKernel> ||
                  std::is_same_v<Kernel, CubicKernel>);
    return std::get<TensorStencils<D, GimpBasis<Kernel, DomainWidth::Stretched>>>(domain_stencils_);
  }

  ThermalContact mode_ = ThermalContact::Insulated;
  double conductance_ = 0.0;
  const NearDomains* near_ = nullptr;  // a decomposed run's near particles (use_near)
  double area_ = 0.0;                  // the last exchange's summed contact area
  Index field_nodes_ = 0;              // the contact's nodes per field
  int fields_ = 0;
  std::vector<std::pair<Index, int>> scratch_;  // (grid node, field) in perfect contact
  std::vector<Index> members_;                  // multi-field nodes of each group, by group
  std::vector<std::size_t> start_;              // group g: members_[start_[g] .. start_[g + 1])
  std::vector<Pair> pairs_;                     // conductance: the contacts of this step
  std::vector<double> volume_;                  // V_f,i
  std::vector<Vec<D>> gradient_;                // g_f,i
  std::tuple<TensorStencils<D, GimpBasis<HatKernel, DomainWidth::Stretched>>,
             TensorStencils<D, GimpBasis<QuadraticKernel, DomainWidth::Stretched>>,
             TensorStencils<D, GimpBasis<CubicKernel, DomainWidth::Stretched>>>
      domain_stencils_;  // the particles' domains (volumes()), one per kernel
};

}  // namespace matpoint
