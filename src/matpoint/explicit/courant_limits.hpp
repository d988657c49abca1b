// Courant numbers above which explicit runs are known to go unstable, by transfer, from the
// measurements of docs/theory/stability.md (examples/gong-stability-1d, examples/fmpm-vibrating-bar).
// `matpoint run` warns when the input's Courant number exceeds the limit of its transfer.
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

/// The measured limit for the solver's transfer, or nothing when none is known (fixed dt, XPIC,
/// blended or periodic FMPM, whose limits lie above the plain FMPM(k) ones).
inline std::optional<CourantLimit> known_courant_limit(const SolverSpec& solver) {
  if (solver.dt) return std::nullopt;
  switch (solver.transfer) {
    case VelocityTransfer::FLIP:
    case VelocityTransfer::PIC:
    case VelocityTransfer::Blend:
      return CourantLimit{0.709,
                          "the 2h mode of 1-D linear MPM with one particle per cell, 1/sqrt(2) "
                          "(Gong 2015 ch. 7; examples/gong-stability-1d)"};
    case VelocityTransfer::FMPM: {
      const FmpmSpec& f = solver.fmpm;
      if (f.blend_with > 0 || f.period != FmpmPeriod::EveryStep) return std::nullopt;
      // Nairn 2026 §3.3 vibrating bar, 1-D CPDI, measured (examples/fmpm-vibrating-bar/README.md).
      static constexpr std::array<std::pair<int, double>, 8> kTable{{{1, 0.848},
                                                                     {2, 0.670},
                                                                     {3, 0.596},
                                                                     {4, 0.544},
                                                                     {8, 0.410},
                                                                     {16, 0.321},
                                                                     {40, 0.269},
                                                                     {80, 0.247}}};
      double limit = 0.24;  // the plateau for any higher order (Nairn: "C = 0.24 is safe for any k")
      for (const auto& [order, value] : kTable)
        if (order >= f.order) {  // the next tabulated order at or above k: limits fall with k
          limit = value;
          break;
        }
      std::ostringstream source;
      source << "FMPM(" << f.order << ") on the Nairn 2026 vibrating bar (examples/fmpm-vibrating-bar)";
      return CourantLimit{limit, source.str()};
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
