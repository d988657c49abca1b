// Courant numbers above which explicit runs are known to go unstable, by basis and transfer,
// measured on the Nairn 2026 vibrating bar (scripts/courant_limits_by_basis.sh). `matpoint run`
// warns when the input's Courant number exceeds the limit measured for its basis and transfer,
// and says on what it was measured; where nothing was measured it says nothing (the energy-growth
// guard, run/energy_guard.hpp, stops a run that goes unstable all the same).
#pragma once

#include <array>
#include <optional>
#include <sstream>
#include <string>
#include <utility>

#include "matpoint/io/spec.hpp"

namespace matpoint {

struct CourantLimit {
  double value = 0;
  std::string source;
};

/// Measured limits of one basis on the Nairn 2026 §3.3 vibrating bar (1-D, 2 particles per cell,
/// USL, fixed end, 5 periods; scripts/courant_limits_by_basis.sh, docs/theory/courant_limits.md):
/// FLIP, then FMPM(k) for the orders of kFmpmOrders. 0: no limit could be measured.
struct BasisLimits {
  ShapeKind basis;
  const char* name;
  double flip;
  std::array<double, 8> fmpm;
};
inline constexpr std::array<int, 8> kFmpmOrders{1, 2, 3, 4, 8, 16, 40, 80};
// clang-format off
inline constexpr std::array<BasisLimits, 8> kMeasuredLimits{{
    {ShapeKind::UGIMP,    "uGIMP",    0.728, {0.720, 0.529, 0.453, 0.391, 0.269, 0.208, 0.131, 0.093}},
    {ShapeKind::CpGIMP,   "cpGIMP",   0.720, {0.705, 0.521, 0.430, 0.361, 0.261, 0.185, 0.116, 0.085}},
    {ShapeKind::BSpline2, "bspline2", 0.889, {0.950, 0.698, 0.560, 0.498, 0.368, 0.276, 0.185, 0.131}},
    {ShapeKind::BSpline3, "bspline3", 1.0,   {1.0,   0.950, 0.805, 0.728, 0.560, 0.445, 0.345, 0.284}},
    {ShapeKind::B2GIMP,   "B2GIMP",   0.988, {1.0,   0.820, 0.705, 0.636, 0.498, 0.399, 0.284, 0.208}},
    {ShapeKind::CPDI1,    "CPDI1",    0.828, {0.851, 0.667, 0.598, 0.544, 0.407, 0.322, 0.269, 0.246}},
    {ShapeKind::CPDI2,    "CPDI2",    0.828, {0.828, 0.659, 0.590, 0.537, 0.399, 0.315, 0.269, 0.246}},
    {ShapeKind::B2CPDI,   "B2CPDI",   1.0,   {1.0,   0.851, 0.736, 0.667, 0.545, 0.437, 0.330, 0.277}},
}};
// clang-format on

/// The measured limit for the solver's transfer and basis, or nothing when none is known (fixed
/// dt, XPIC, blended or periodic FMPM, whose limits lie above the plain FMPM(k) ones, FMPM with
/// linear hats, whose bar is unstable at any Courant number once its free end crosses cells, and
/// the MLS mappings). FLIP with linear hats has Gong's 1-D limit.
inline std::optional<CourantLimit> known_courant_limit(const SolverSpec& solver) {
  if (solver.dt || solver.mapping != Mapping::MPM) return std::nullopt;
  const BasisLimits* row = nullptr;
  for (const auto& r : kMeasuredLimits)
    if (r.basis == solver.shape) row = &r;
  const bool flip_like = solver.transfer == VelocityTransfer::FLIP || solver.transfer == VelocityTransfer::PIC ||
                         solver.transfer == VelocityTransfer::Blend;
  if (flip_like && solver.shape == ShapeKind::Linear)
    return CourantLimit{0.709,
                        "FLIP with linear hats: the 2h mode of 1-D linear MPM with one particle per cell, "
                        "1/sqrt(2) (Gong 2015 ch. 7; examples/gong-stability-1d)"};
  if (row == nullptr) return std::nullopt;
  std::ostringstream source;
  source << " with " << row->name << " on the Nairn 2026 §3.3 vibrating bar (1-D, 2 particles per cell; "
         << "docs/theory/courant_limits.md)";
  switch (solver.transfer) {
    case VelocityTransfer::FLIP:
    case VelocityTransfer::PIC:
    case VelocityTransfer::Blend:
      if (row->flip >= 1.0) return std::nullopt;
      return CourantLimit{row->flip, "FLIP" + source.str()};
    case VelocityTransfer::FMPM: {
      const FmpmSpec& f = solver.fmpm;
      if (f.blend_with > 0 || f.period != FmpmPeriod::EveryStep) return std::nullopt;
      // the next tabulated order at or above k (limits fall with k), else the highest order's
      double limit = row->fmpm.back();
      for (std::size_t j = 0; j < kFmpmOrders.size(); ++j)
        if (kFmpmOrders[j] >= f.order) {
          limit = row->fmpm[j];
          break;
        }
      if (limit >= 1.0) return std::nullopt;
      return CourantLimit{limit, "FMPM(" + std::to_string(f.order) + ")" + source.str()};
    }
    case VelocityTransfer::XPIC:
      break;
  }
  return std::nullopt;
}

/// A warning line when the Courant number exceeds the known limit, else an empty string.
inline std::string courant_warning(const SolverSpec& solver) {
  const auto limit = known_courant_limit(solver);
  if (!limit || solver.courant <= limit->value) return {};
  std::ostringstream out;
  out << "solver.courant = " << solver.courant << " exceeds " << limit->value
      << ", the stability limit measured for " << limit->source
      << "; the run may blow up (docs/theory/stability.md)";
  return out.str();
}

}  // namespace matpoint
