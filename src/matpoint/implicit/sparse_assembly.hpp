// Sparse assembly of element blocks into one global matrix and residual, generic over the
// formulation (Aulisa & Capodaglio's particle Newmark, Iaconeta's grid Newmark and the FEM coupling
// all assemble through it). A "block" is one element contribution: its list of global dofs and a
// kernel that fills its dense residual and Jacobian.
//   - The pattern is built once per active set (build(); the same blocks again keep it), with a
//     per-block map from local entries to value slots of the compressed matrix, so every Newton
//     iteration only refills values.
//   - Blocks are coloured so that blocks of one colour share no dof; each colour is assembled in
//     parallel (OpenMP) straight into the matrix. The sum into each slot runs in colour order, so
//     the result does not depend on the thread count (deterministic).
//   - Dirichlet dofs get identity rows and a zero residual (the Newton iterate already holds the
//     prescribed value, so its increment is 0).
#pragma once

#include <Eigen/SparseCore>
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "matpoint/core/types.hpp"

namespace matpoint::implicit {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

class SparseAssembly {
 public:
  /// The pattern of dof_count dofs with the blocks: block k's dofs are
  /// block_dofs[block_offsets[k] .. block_offsets[k + 1]). Every dof gets a diagonal entry.
  /// dirichlet: one flag per dof (may be empty). The same blocks and flags as the last build keep
  /// its pattern and pattern_version().
  void build(Index dof_count, std::span<const Index> block_offsets, std::span<const Index> block_dofs,
             std::span<const char> dirichlet);

  /// kernel(k, dofs, r, K) fills block k's residual r (size n) and, when K is not null, its
  /// Jacobian K (row-major n x n), both zeroed before the call; dofs are its global dofs. R gets
  /// the global residual; K (if given) the global Jacobian, with the pattern of build(). With
  /// `constrain` false the Dirichlet rows keep their values (the reactions).
  template <class Kernel>
  void assemble(Kernel&& kernel, Eigen::VectorXd& R, SparseMatrix* K, bool constrain = true) const;

  [[nodiscard]] Index dof_count() const { return dofs_; }
  [[nodiscard]] Index block_count() const { return static_cast<Index>(offsets_.size()) - 1; }
  [[nodiscard]] int colour_count() const { return static_cast<int>(colour_begin_.size()) - 1; }
  /// Changes whenever build() makes a new pattern: a linear solver redoes its symbolic analysis then.
  [[nodiscard]] std::uint64_t pattern_version() const { return version_; }
  /// An empty matrix with the pattern (values zero).
  [[nodiscard]] const SparseMatrix& pattern() const { return pattern_; }
  [[nodiscard]] std::span<const Index> block(Index k) const {
    return {dofs_list_.data() + offsets_[static_cast<std::size_t>(k)],
            static_cast<std::size_t>(offsets_[static_cast<std::size_t>(k) + 1] -
                                     offsets_[static_cast<std::size_t>(k)])};
  }
  /// Zero residual and identity rows on the Dirichlet dofs.
  void apply_dirichlet(Eigen::VectorXd& R, SparseMatrix* K) const;

 private:
  Index dofs_ = 0;
  std::uint64_t version_ = 0;
  std::vector<Index> offsets_{0}, dofs_list_;
  std::vector<Index> slot_offsets_;  // block k's slots: slots_[slot_offsets_[k] ..], n_k^2, row-major
  std::vector<int> slots_;
  std::vector<Index> colour_order_, colour_begin_;  // blocks sorted by colour
  std::vector<Index> dirichlet_dofs_;
  std::vector<char> dirichlet_flags_;  // build()'s flags, one per dof
  std::vector<int> dirichlet_row_slots_, dirichlet_diagonal_slots_;
  int max_block_ = 0;
  SparseMatrix pattern_;
};

template <class Kernel>
void SparseAssembly::assemble(Kernel&& kernel, Eigen::VectorXd& R, SparseMatrix* K, bool constrain) const {
  R.setZero(dofs_);
  if (K != nullptr) {
    // K keeps its storage while it has this pattern (every Newton iteration of a step).
    const bool same_pattern =
        K->isCompressed() && K->rows() == dofs_ && K->cols() == dofs_ &&
        K->nonZeros() == pattern_.nonZeros() &&
        std::equal(pattern_.outerIndexPtr(), pattern_.outerIndexPtr() + dofs_ + 1, K->outerIndexPtr()) &&
        std::equal(pattern_.innerIndexPtr(), pattern_.innerIndexPtr() + pattern_.nonZeros(),
                   K->innerIndexPtr());
    if (!same_pattern) *K = pattern_;
    std::fill(K->valuePtr(), K->valuePtr() + K->nonZeros(), 0.0);
  }
  double* values = K != nullptr ? K->valuePtr() : nullptr;
  for (std::size_t c = 0; c + 1 < colour_begin_.size(); ++c) {
    const Index first = colour_begin_[c], last = colour_begin_[c + 1];
#pragma omp parallel if (last - first > 8)
    {
      std::vector<double> r(static_cast<std::size_t>(max_block_)),
          k(values != nullptr ? static_cast<std::size_t>(max_block_) * max_block_ : 0);
#pragma omp for schedule(dynamic, 16)
      for (Index o = first; o < last; ++o) {
        const Index b = colour_order_[static_cast<std::size_t>(o)];
        const std::span<const Index> dofs = block(b);
        const std::size_t n = dofs.size();
        std::fill(r.begin(), r.begin() + static_cast<std::ptrdiff_t>(n), 0.0);
        if (values != nullptr) std::fill(k.begin(), k.begin() + static_cast<std::ptrdiff_t>(n * n), 0.0);
        kernel(b, dofs, r.data(), values != nullptr ? k.data() : nullptr);
        for (std::size_t i = 0; i < n; ++i) R[dofs[i]] += r[i];
        if (values != nullptr) {
          const int* slot = slots_.data() + slot_offsets_[static_cast<std::size_t>(b)];
          for (std::size_t e = 0; e < n * n; ++e) values[slot[e]] += k[e];
        }
      }
    }
  }
  if (constrain) apply_dirichlet(R, K);
}

}  // namespace matpoint::implicit
