// The bounce measures (analysis/bounce.hpp) on a rigid ball dropped from h0 onto a floor with a
// coefficient of restitution e: it first touches at sqrt(2 h0 / g), and bounce k rises to
// e^(2k) h0 (the speed after each impact is e times the speed before it).
#include <gtest/gtest.h>

#include <cmath>

#include "matpoint/analysis/bounce.hpp"

namespace matpoint {
namespace {

constexpr double kG = 9.81, kDrop = 1.0, kRestitution = 0.9, kSample = 1e-4;

/// The ball's centre (y, vy) at time t, the floor at y = 0.
std::array<double, 2> ball_at(double t) {
  const double fall = std::sqrt(2 * kDrop / kG);
  if (t <= fall) return {kDrop - 0.5 * kG * t * t, -kG * t};
  double start = fall, up = kRestitution * kG * fall;  // the present flight: its start, its speed up
  while (t > start + 2 * up / kG) {
    start += 2 * up / kG;
    up *= kRestitution;
  }
  const double s = t - start;
  return {up * s - 0.5 * kG * s * s, up - kG * s};
}

History ball_history(double end) {
  History h;
  for (double t = 0; t <= end; t += kSample) {
    const auto [y, vy] = ball_at(t);
    HistorySample s;
    s.time = t;
    s.body_com_position = {{0.0, y, 0.0}};
    s.body_com_velocity = {{0.0, vy, 0.0}};
    h.samples.push_back(s);
  }
  return h;
}

TEST(BounceMeasure, RigidBallFirstImpactAndApexesFollowTheRestitution) {
  Spec spec;
  spec.loads.gravity = {0.0, -kG, 0.0};
  const Bounces b = bounces_of_first_body(spec, ball_history(2.5));
  EXPECT_NEAR(b.first_impact_time, std::sqrt(2 * kDrop / kG), kSample);
  ASSERT_GE(b.apex_fractions.size(), 2U);
  // The lowest sample lies up to |v| dt above the floor: a fraction off by that over the drop.
  const double sampling = kG * std::sqrt(2 * kDrop / kG) * kSample / kDrop;
  EXPECT_NEAR(b.apex_fractions[0], std::pow(kRestitution, 2), sampling);
  EXPECT_NEAR(b.apex_fractions[1], std::pow(kRestitution, 4), sampling);
}

TEST(BounceMeasure, NoBounceWithoutGravityOrImpact) {
  Spec spec;  // no gravity: nothing to measure
  EXPECT_TRUE(std::isnan(bounces_of_first_body(spec, ball_history(0.3)).first_impact_time));
  spec.loads.gravity = {0.0, -kG, 0.0};  // a fall that never reaches the floor
  const Bounces b = bounces_of_first_body(spec, ball_history(0.3));
  EXPECT_TRUE(std::isnan(b.first_impact_time));
  EXPECT_TRUE(b.apex_fractions.empty());
}

}  // namespace
}  // namespace matpoint
