// The 1-D explicit runs (run_explicit_of_dim.hpp).
#include "matpoint/run/run_explicit_of_dim.hpp"

namespace matpoint::run_by_solver {
template RunResult run_explicit_of_dim<1>(const Spec&, const RunOptions&);
}  // namespace matpoint::run_by_solver
