// The bounces of body 0 under gravity, read from its centre of mass in history.csv (Aulisa &
// Capodaglio Test D, Fig. 12: a disk dropped on a plate bounces back to the height it fell from).
// Heights are measured against gravity: h = -g.x_com / |g|.
//  - first impact: the time of the largest downward speed before the body first stops falling,
//    the moment the contact force starts to exceed gravity (free fall from a clearance c reaches
//    it at sqrt(2 c / |g|));
//  - apexes: the local maxima of h after that, where the upward velocity turns to <= 0 and h is at
//    least 5 % of the drop above the lowest point (a vibration resting on the plate is no bounce);
//  - apex fraction: (h_apex - h_min) / (h(0) - h_min), h_min the lowest height of the first impact:
//    the share of the drop's energy the bounce gives back (exact for a rigid body).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "matpoint/analysis/history.hpp"
#include "matpoint/io/spec.hpp"

namespace matpoint {

struct Bounces {
  double first_impact_time = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> apex_fractions;  // in time order
};

inline Bounces bounces_of_first_body(const Spec& spec, const History& h) {
  Bounces out;
  const auto& g = spec.loads.gravity;
  const double g_norm = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
  if (h.samples.size() < 3 || !(g_norm > 0) || h.samples.front().body_com_position.empty()) return out;
  const auto up = [&](const std::array<double, 3>& x) {
    return -(g[0] * x[0] + g[1] * x[1] + g[2] * x[2]) / g_norm;
  };
  const auto height = [&](std::size_t k) { return up(h.samples[k].body_com_position[0]); };
  const auto rise = [&](std::size_t k) { return up(h.samples[k].body_com_velocity[0]); };

  std::size_t k = 1, fastest = 0;
  for (; k < h.samples.size() && rise(k) < 0; ++k)
    if (rise(k) < rise(fastest)) fastest = k;
  if (k == h.samples.size()) return out;  // never stopped falling
  out.first_impact_time = h.samples[fastest].time;
  double lowest = height(k);
  for (std::size_t j = fastest; j < k; ++j) lowest = std::min(lowest, height(j));
  const double drop = height(0) - lowest;
  for (++k; k + 1 < h.samples.size(); ++k)
    if (rise(k - 1) > 0 && rise(k + 1) <= 0 && height(k) >= height(k - 1) && height(k) >= height(k + 1) &&
        height(k) - lowest > 0.05 * drop)
      out.apex_fractions.push_back((height(k) - lowest) / drop);
  return out;
}

}  // namespace matpoint
