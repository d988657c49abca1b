#include "matpoint/implicit/sparse_assembly.hpp"

#include <algorithm>
#include <atomic>
#include <bit>

namespace matpoint::implicit {

namespace {

/// Greedy colouring: each block takes the lowest colour that none of its dofs has seen (a
/// structured Q9 mesh needs 4; a meshfree point's cloud of ~25 nodes, hundreds). The colours seen at
/// a dof are bit sets of 64 colours per word, a word added when all earlier ones are full.
/// Returns the colour of every block.
std::vector<int> colour_blocks(Index dof_count, std::span<const Index> offsets, std::span<const Index> dofs) {
  std::vector<std::vector<std::uint64_t>> used;  // used[w][dof]: colours 64 w .. 64 w + 63
  std::vector<int> colour(offsets.size() - 1);
  for (std::size_t b = 0; b + 1 < offsets.size(); ++b) {
    for (std::size_t w = 0;; ++w) {
      if (w == used.size()) used.emplace_back(static_cast<std::size_t>(dof_count), 0);
      std::uint64_t taken = 0;
      for (Index i = offsets[b]; i < offsets[b + 1]; ++i)
        taken |= used[w][static_cast<std::size_t>(dofs[static_cast<std::size_t>(i)])];
      if (~taken == 0) continue;
      const int c = std::countr_one(taken);
      colour[b] = static_cast<int>(64 * w) + c;
      for (Index i = offsets[b]; i < offsets[b + 1]; ++i)
        used[w][static_cast<std::size_t>(dofs[static_cast<std::size_t>(i)])] |= std::uint64_t{1} << c;
      break;
    }
  }
  return colour;
}

}  // namespace

void SparseAssembly::build(Index dof_count, std::span<const Index> block_offsets,
                           std::span<const Index> block_dofs, std::span<const char> dirichlet) {
  std::vector<char> flags(static_cast<std::size_t>(dof_count), 0);
  std::copy_n(dirichlet.begin(), std::min(dirichlet.size(), flags.size()), flags.begin());
  // The same blocks and Dirichlet dofs as the present pattern (a meshfree body whose clouds did
  // not change over the step, an active set that stayed): keep it, and its version, so that the
  // linear solver keeps its symbolic analysis too.
  if (version_ != 0 && dof_count == dofs_ && std::ranges::equal(block_offsets, offsets_) &&
      std::ranges::equal(block_dofs, dofs_list_) && flags == dirichlet_flags_)
    return;
  dirichlet_flags_ = std::move(flags);
  dofs_ = dof_count;
  offsets_.assign(block_offsets.begin(), block_offsets.end());
  dofs_list_.assign(block_dofs.begin(), block_dofs.end());
  const std::size_t blocks = offsets_.size() - 1;

  // Pattern: every (row, column) pair of every block, plus the diagonal.
  std::vector<Eigen::Triplet<double, int>> entries;
  max_block_ = 0;
  for (std::size_t b = 0; b < blocks; ++b) {
    const auto d = block(static_cast<Index>(b));
    max_block_ = std::max(max_block_, static_cast<int>(d.size()));
    for (const Index i : d)
      for (const Index j : d) entries.emplace_back(static_cast<int>(i), static_cast<int>(j), 0.0);
  }
  for (Index i = 0; i < dof_count; ++i) entries.emplace_back(static_cast<int>(i), static_cast<int>(i), 0.0);
  pattern_.resize(dof_count, dof_count);
  pattern_.setFromTriplets(entries.begin(), entries.end());
  pattern_.makeCompressed();
  std::fill(pattern_.valuePtr(), pattern_.valuePtr() + pattern_.nonZeros(), 0.0);

  // Slot of (row, column): binary search in the column's sorted row indices.
  const int* outer = pattern_.outerIndexPtr();
  const int* inner = pattern_.innerIndexPtr();
  const auto slot_of = [&](Index row, Index col) {
    const int* first = inner + outer[col];
    const int* last = inner + outer[col + 1];
    return static_cast<int>(std::lower_bound(first, last, static_cast<int>(row)) - inner);
  };
  slot_offsets_.assign(blocks + 1, 0);
  for (std::size_t b = 0; b < blocks; ++b) {
    const auto n = static_cast<Index>(block(static_cast<Index>(b)).size());
    slot_offsets_[b + 1] = slot_offsets_[b] + n * n;
  }
  slots_.resize(static_cast<std::size_t>(slot_offsets_.back()));
  for (std::size_t b = 0; b < blocks; ++b) {
    const auto d = block(static_cast<Index>(b));
    int* s = slots_.data() + slot_offsets_[b];
    for (std::size_t i = 0; i < d.size(); ++i)
      for (std::size_t j = 0; j < d.size(); ++j) *s++ = slot_of(d[i], d[j]);
  }

  // Colours, and the blocks listed colour by colour (ascending block id within a colour).
  const std::vector<int> colour = colour_blocks(dof_count, offsets_, dofs_list_);
  const int colours = blocks == 0 ? 0 : *std::max_element(colour.begin(), colour.end()) + 1;
  colour_begin_.assign(static_cast<std::size_t>(colours) + 1, 0);
  for (const int c : colour) ++colour_begin_[static_cast<std::size_t>(c) + 1];
  for (int c = 0; c < colours; ++c)
    colour_begin_[static_cast<std::size_t>(c) + 1] += colour_begin_[static_cast<std::size_t>(c)];
  colour_order_.resize(blocks);
  std::vector<Index> next(colour_begin_.begin(), colour_begin_.end() - 1);
  for (std::size_t b = 0; b < blocks; ++b)
    colour_order_[static_cast<std::size_t>(next[static_cast<std::size_t>(colour[b])]++)] =
        static_cast<Index>(b);

  // Dirichlet rows: every slot in those rows, and their diagonal slots.
  dirichlet_dofs_.clear(), dirichlet_row_slots_.clear(), dirichlet_diagonal_slots_.clear();
  std::vector<char> is_dirichlet(static_cast<std::size_t>(dof_count), 0);
  for (Index i = 0; i < dof_count && static_cast<std::size_t>(i) < dirichlet.size(); ++i)
    if (dirichlet[static_cast<std::size_t>(i)] != 0) {
      is_dirichlet[static_cast<std::size_t>(i)] = 1;
      dirichlet_dofs_.push_back(i);
      dirichlet_diagonal_slots_.push_back(slot_of(i, i));
    }
  for (Index col = 0; col < dof_count; ++col)
    for (int s = outer[col]; s < outer[col + 1]; ++s)
      if (is_dirichlet[static_cast<std::size_t>(inner[s])] != 0) dirichlet_row_slots_.push_back(s);
  // A number no other pattern of this process had: solvers compare it to skip the symbolic analysis.
  static std::atomic<std::uint64_t> patterns{0};
  version_ = ++patterns;
}

void SparseAssembly::apply_dirichlet(Eigen::VectorXd& R, SparseMatrix* K) const {
  for (const Index d : dirichlet_dofs_) R[d] = 0.0;
  if (K == nullptr) return;
  double* values = K->valuePtr();
  for (const int s : dirichlet_row_slots_) values[s] = 0.0;
  for (const int s : dirichlet_diagonal_slots_) values[s] = 1.0;
}

}  // namespace matpoint::implicit
