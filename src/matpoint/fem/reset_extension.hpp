// The reset displacement of the background grid in the coupled MPM-FEM method (Aulisa & Capodaglio
// eqs. (8a)-(10), extraction §1.1 and A14, A19): after every step the background grid is not reset to
// its undeformed nodes but to x~ = X + u_reset, where
//   u_reset = u^{n+1}                                   at the nodes of FE bodies (interface included)  (8a)
//   div(grad u_reset + grad u_reset^T) = 0             on the background grid                         (8b)
//   u_reset = 0                                         at the Dirichlet dofs of the domain boundary
// solved as the linear FE problem  sum_e int_e (grad U + grad U^T) : grad phi_I dX = 0  on the
// undeformed background elements (the authors' code, AssembleSolidDisp, 3 x 3 Gauss for Q9). The
// matrix never changes: it is factorised once (sparse Cholesky of the free dofs), and each step
// costs one solve with the FE displacements moved to the right-hand side.
#pragma once

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <limits>
#include <span>
#include <stdexcept>
#include <vector>

#include "matpoint/core/types.hpp"
#include "matpoint/fem/fe_body.hpp"
#include "matpoint/implicit/element_geometry.hpp"
#include "matpoint/mesh/mesh.hpp"

namespace matpoint::fem {

template <class E>
class ResetExtension {
 public:
  static constexpr int D = E::kDim;

  /// fe_nodes: per node, 1 at the nodes of FE bodies (their displacement is given); dirichlet: per
  /// dof, 1 where the domain boundary holds the component at 0; background: per element, 1 for the
  /// background grid (the elements the extension is solved on).
  ResetExtension(const mesh::Mesh<D>& mesh, std::span<const char> fe_nodes, std::span<const char> dirichlet,
                 std::span<const char> background);

  /// x~ of the background nodes from the FE bodies' nodal displacement u (per node; only the FE
  /// nodes are read): reference[n] = X_n + u_reset_n for every node not in an FE body.
  void apply(const std::vector<Vec<D>>& u, std::vector<Vec<D>>& reference) const;

  /// Free dofs (the unknowns of (8b)).
  [[nodiscard]] Index free_dofs() const { return static_cast<Index>(free_.size()); }

 private:
  const mesh::Mesh<D>& mesh_;
  std::vector<Index> number_;  // per dof: its index among the free dofs, -1 - (index among the FE dofs), or
                               // kHeld (a Dirichlet dof of a background node: 0)
  std::vector<Index> free_, given_;       // global dofs
  Eigen::SparseMatrix<double> coupling_;  // K_free,given
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> factor_;
  static constexpr Index kHeld = std::numeric_limits<Index>::min();
};

template <class E>
ResetExtension<E>::ResetExtension(const mesh::Mesh<D>& mesh, std::span<const char> fe_nodes,
                                  std::span<const char> dirichlet, std::span<const char> background)
    : mesh_(mesh) {
  const auto dofs = static_cast<std::size_t>(mesh.node_count()) * D;
  number_.assign(dofs, kHeld);
  for (std::size_t d = 0; d < dofs; ++d) {
    if (fe_nodes[d / D] != 0) {
      number_[d] = -1 - static_cast<Index>(given_.size());
      given_.push_back(static_cast<Index>(d));
    } else if (dirichlet[d] == 0) {
      number_[d] = static_cast<Index>(free_.size());
      free_.push_back(static_cast<Index>(d));
    }
  }
  // K_IJ (i, j components) = int (grad U + grad U^T) : grad phi_I  with U = phi_J e_j:
  //   (dphi_J/dx_k delta_ij + dphi_J/dx_i delta_jk) dphi_I/dx_k = delta_ij grad phi_I . grad phi_J +
  //   dphi_I/dx_j dphi_J/dx_i
  std::vector<Eigen::Triplet<double>> ff, fg;
  const auto& rule = mesh::gauss_rule<E>(E::kSimplex ? 2 * E::kDegree : E::kDegree + 1);
  for (Index e = 0; e < mesh.element_count(); ++e) {
    if (background[static_cast<std::size_t>(e)] == 0) continue;
    const auto nodes = mesh.element_nodes(e);
    const auto X = implicit::gather_nodes<E>(mesh.nodes, nodes);
    Eigen::Matrix<double, E::kNodes * D, E::kNodes* D> k = decltype(k)::Zero();
    for (std::size_t q = 0; q < rule.points.size(); ++q) {
      double det = 0.0;
      const auto G = implicit::physical_gradients<E>(X, rule.points[q], mesh.element_variant(e), &det);
      const double w = rule.weights[q] * det;
      for (int I = 0; I < E::kNodes; ++I)
        for (int J = 0; J < E::kNodes; ++J) {
          const double dot = G.row(I).dot(G.row(J));
          for (int i = 0; i < D; ++i)
            for (int j = 0; j < D; ++j)
              k(I * D + i, J * D + j) += w * ((i == j ? dot : 0.0) + G(I, j) * G(J, i));
        }
    }
    for (int a = 0; a < E::kNodes * D; ++a) {
      const Index row = number_[static_cast<std::size_t>(nodes[static_cast<std::size_t>(a / D)] * D + a % D)];
      if (row < 0) continue;  // an FE or held dof: no equation
      for (int b = 0; b < E::kNodes * D; ++b) {
        const Index col =
            number_[static_cast<std::size_t>(nodes[static_cast<std::size_t>(b / D)] * D + b % D)];
        if (col >= 0)
          ff.emplace_back(row, col, k(a, b));
        else if (col != kHeld)
          fg.emplace_back(row, -1 - col, k(a, b));
      }
    }
  }
  Eigen::SparseMatrix<double> K(free_dofs(), free_dofs());
  K.setFromTriplets(ff.begin(), ff.end());
  coupling_.resize(free_dofs(), static_cast<Index>(given_.size()));
  coupling_.setFromTriplets(fg.begin(), fg.end());
  if (free_dofs() > 0) {
    factor_.compute(K);
    if (factor_.info() != Eigen::Success)
      throw std::runtime_error(
          "the reset extension (8b) is singular: a part of the background grid is held neither by an FE "
          "body nor by a boundary condition");
  }
}

template <class E>
void ResetExtension<E>::apply(const std::vector<Vec<D>>& u, std::vector<Vec<D>>& reference) const {
  if (free_dofs() == 0) return;
  Eigen::VectorXd given(static_cast<Index>(given_.size()));
  for (std::size_t k = 0; k < given_.size(); ++k)
    given[static_cast<Index>(k)] = u[static_cast<std::size_t>(given_[k] / D)][given_[k] % D];
  const Eigen::VectorXd solution = factor_.solve(-(coupling_ * given));
  std::vector<char> fe(static_cast<std::size_t>(mesh_.node_count()), 0);
  for (const Index d : given_) fe[static_cast<std::size_t>(d / D)] = 1;
  for (std::size_t n = 0; n < fe.size(); ++n)
    if (fe[n] == 0) reference[n] = mesh_.nodes[n];  // held components stay at X
  for (std::size_t k = 0; k < free_.size(); ++k)
    reference[static_cast<std::size_t>(free_[k] / D)][free_[k] % D] += solution[static_cast<Index>(k)];
}

}  // namespace matpoint::fem
