// output.probes (analysis/probes.hpp): which particle a probe follows, its history.csv columns and
// the values recorded, on hand-made particles (exact arithmetic).
#include <gtest/gtest.h>

#include "matpoint/analysis/probes.hpp"

namespace {

using namespace matpoint;

TEST(Probes, FollowTheNearestReferencePositionAndTheLowestIdOnATie) {
  const std::vector<Vec<2>> reference{{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}, {1.0, 1.0}};
  const std::vector<ProbeSpec> probes{{"a", {0.9, 0.2, 0}}, {"tie", {0.5, 0.5, 0}}, {"far", {5, 5, 0}}};
  EXPECT_EQ(probe_particle_ids<2>(reference, probes), (std::vector<long>{1, 0, 3}));
  // The same by the particles' reference positions X_p, stored in another order than their ids.
  ParticleSet<2> ps;
  for (const auto& X : reference) ps.add(X, Vec<2>(0, 0), 1.0, 1.0, Vec<2>(1, 1), 0, 0);
  ps.id = {3, 2, 1, 0};
  ps.x0 = {reference[3], reference[2], reference[1], reference[0]};
  ps.x = {Vec<2>(9, 9), Vec<2>(9, 9), Vec<2>(9, 9), Vec<2>(9, 9)};  // moved: only X_p counts
  EXPECT_EQ(probe_particle_ids<2>(ps, probes), (std::vector<long>{1, 0, 3}));
}

TEST(Probes, ColumnNamesPerDimension) {
  EXPECT_EQ(probe_column_names("p", 1),
            (std::vector<std::string>{"probe_p_x", "probe_p_ux", "probe_p_vx", "probe_p_sxx", "probe_p_J"}));
  EXPECT_EQ(probe_column_names("tip", 2),
            (std::vector<std::string>{"probe_tip_x", "probe_tip_y", "probe_tip_ux", "probe_tip_uy",
                                      "probe_tip_vx", "probe_tip_vy", "probe_tip_sxx", "probe_tip_syy",
                                      "probe_tip_sxy", "probe_tip_J"}));
  EXPECT_EQ(probe_column_names("q", 3).size(), 3u * 3u + 6u + 1u);
}

// The values follow the particle by its id, wherever sorting has put it in storage.
TEST(Probes, ValuesOfTheFollowedParticleAfterSorting) {
  ParticleSet<2> ps;
  for (int k = 0; k < 3; ++k) ps.add(Vec<2>(k, 0), Vec<2>(0, 0), 1.0, 1.0, Vec<2>(1, 1), 0, 0);
  const std::vector<Vec<2>> reference = ps.x;  // by id
  ps.id = {2, 0, 1};  // storage order as a sort by cell might leave it: id 1 is stored last,
  ps.x0 = {reference[2], reference[0], reference[1]};
  ps.x = {reference[2], reference[0], Vec<2>(1.5, 0.25)};  // moved and deformed
  ps.v[2] = Vec<2>(3, 4);
  ps.F[2] << 2, 0, 0, 1.5;
  ps.stress[2] << 10, 5, 5, 20;
  std::vector<double> values;
  append_probe_values<2>(ps, {1}, values);
  EXPECT_EQ(values, (std::vector<double>{1.5, 0.25, 0.5, 0.25, 3, 4, 10, 20, 5, 3}));
}

}  // namespace
