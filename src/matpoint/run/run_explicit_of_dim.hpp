// The explicit run of one dimension, every basis (run_by_solver.hpp); included by
// run_explicit_1d.cpp, run_explicit_2d.cpp and run_explicit_3d.cpp, one instantiation each.
#pragma once

#include "matpoint/explicit/explicit_solver.hpp"
#include "matpoint/run/run_by_solver.hpp"
#include "matpoint/run/run_loop.hpp"
#include "matpoint/shape/cpdi_stencils.hpp"
#include "matpoint/shape/tensor_bases.hpp"
#include "matpoint/shape/tensor_stencils.hpp"

namespace matpoint::run_by_solver {

/// One explicit run of one basis through the shared loop.
template <int D, class Stencils>
RunResult run_with(const Spec& spec, const RunOptions& options) {
  ExplicitSolver<D, Stencils> solver(spec);  // may throw InputError: nothing written yet
  return run_loop<D>(spec, options, solver);
}

/// The basis's stencils, plain or (contact) shifted to each particle's velocity field.
template <int D, class Base>
RunResult run_with_fields(const Spec& spec, const RunOptions& options) {
  if constexpr (D > 1)
    if (spec.contact.enabled) return run_with<D, FieldStencils<D, Base>>(spec, options);
  return run_with<D, Base>(spec, options);
}

template <int D>
RunResult run_explicit_of_dim(const Spec& spec, const RunOptions& options) {
  switch (spec.solver.shape) {
    case ShapeKind::BSpline2:
      return run_with_fields<D, TensorStencils<D, QuadraticBSplineBasis>>(spec, options);
    case ShapeKind::BSpline3:
      return run_with_fields<D, TensorStencils<D, CubicBSplineBasis>>(spec, options);
    case ShapeKind::UGIMP:
      return run_with_fields<D, TensorStencils<D, UGimpBasis>>(spec, options);
    case ShapeKind::CpGIMP:
      return run_with_fields<D, TensorStencils<D, CpGimpBasis>>(spec, options);
    case ShapeKind::B2GIMP:
      return run_with_fields<D, TensorStencils<D, B2GimpBasis>>(spec, options);
    case ShapeKind::CPDI1:
      return run_with_fields<D, CpdiStencils<D, HatKernel, CpdiDomain::Parallelogram>>(spec, options);
    case ShapeKind::CPDI2:  // contact with tracked corners is refused by the input reader
      return run_with<D, CpdiStencils<D, HatKernel, CpdiDomain::Tracked>>(spec, options);
    case ShapeKind::B2CPDI:
      return run_with_fields<D, CpdiStencils<D, QuadraticKernel, CpdiDomain::Parallelogram>>(spec, options);
    case ShapeKind::Linear:
      break;
  }
  return run_with_fields<D, TensorStencils<D, LinearBasis>>(spec, options);
}

}  // namespace matpoint::run_by_solver
