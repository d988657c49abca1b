// The particles of the active elements as quadrature points (Aulisa & Capodaglio eq. (20)): per
// particle, everything the residual needs that stays fixed during one step's Newton iterations
// (host element, shape values and reference gradients at xi_p, F_p^n, the known part of the
// Newmark acceleration, the receding switches), sorted by element so that each element reads its
// particles as one contiguous range.
#pragma once

#include <cstdint>
#include <vector>

#include "matpoint/core/types.hpp"
#include "matpoint/implicit/element_geometry.hpp"

namespace matpoint::implicit {

/// Newmark-beta parameters (eqs. (17)-(19)); the paper's tests use beta = 0.3, gamma = 0.5.
struct NewmarkParameters {
  double beta = 0.3;
  double gamma = 0.5;
};

/// Coefficients of the particle acceleration (21): a_p = u_p / (beta dt^2) + known, with
/// known = -v^n / (beta dt) - (1 - 2 beta) / (2 beta) a^n.
struct NewmarkCoefficients {
  double displacement;  // 1 / (beta dt^2)
  double velocity;      // -1 / (beta dt)
  double acceleration;  // -(1 - 2 beta) / (2 beta)
  NewmarkCoefficients(const NewmarkParameters& p, double dt)
      : displacement(1.0 / (p.beta * dt * dt)),
        velocity(-1.0 / (p.beta * dt)),
        acceleration(-(1.0 - 2.0 * p.beta) / (2.0 * p.beta)) {}
  template <int D>
  [[nodiscard]] Vec<D> known(const Vec<D>& v_old, const Vec<D>& a_old) const {
    return velocity * v_old + acceleration * a_old;
  }
};

template <class E>
struct ParticleQuadrature {
  static constexpr int kNodes = E::kNodes, kDim = E::kDim;
  /// Particles of block k (the k-th active element): [begin[k], begin[k + 1]).
  std::vector<Index> begin{0};
  std::vector<Index> particle;                      // index into the particle set
  std::vector<Eigen::Matrix<double, kNodes, 1>> N;  // N_I(xi_p), equal in all configurations
  std::vector<GradientMatrix<E>> G;                 // dN_I / dx~ at xi_p (reference configuration)
  std::vector<double> mass, volume0;
  std::vector<int> material;
  std::vector<Mat<kDim>> F_old;         // F_p^n
  std::vector<Vec<kDim>> known;         // eq. (21) without u~ minus b_p: known(v^n, a^n) - b_p
  std::vector<std::uint32_t> receding;  // bit f: the correction of face f is on (A4)
  std::vector<const double*> state;     // the material history of the step start (null: none)

  [[nodiscard]] Index blocks() const { return static_cast<Index>(begin.size()) - 1; }
  void clear() {
    begin.assign(1, 0);
    particle.clear(), N.clear(), G.clear(), mass.clear(), volume0.clear(), material.clear();
    F_old.clear(), known.clear(), receding.clear(), state.clear();
  }
  /// Appends one particle to the current (last) block.
  void add(Index p, const Vec<kDim>& xi, const NodeMatrix<E>& reference_nodes, mesh::ElementVariant variant,
           double m, double v0, int mat, const Mat<kDim>& F, const Vec<kDim>& known_minus_b,
           std::uint32_t receding_bits, const double* history = nullptr) {
    particle.push_back(p);
    N.push_back(E::values(xi, variant));
    G.push_back(physical_gradients<E>(reference_nodes, xi, variant));
    mass.push_back(m), volume0.push_back(v0), material.push_back(mat);
    F_old.push_back(F), known.push_back(known_minus_b), receding.push_back(receding_bits);
    state.push_back(history);
  }
  /// Closes the current block (its particles are those added since the last call).
  void close_block() { begin.push_back(static_cast<Index>(particle.size())); }
};

}  // namespace matpoint::implicit
