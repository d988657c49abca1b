// A rank of a decomposed run generates only the particles of its slab (particles/generators.cpp,
// KeepParticle; docs/scale-out.md §5): the shares of a split must be the whole set's particles, each
// with the id, position, velocity (seeded noise included), mass and volume that it has when one set
// holds them all, so that no rank needs the whole set and the ids stay the generation order.
#include <gtest/gtest.h>

#include "matpoint/particles/generators.hpp"

namespace {

using namespace matpoint;

TEST(GenerationShare, TheSharesOfASplitAreTheWholeSetsParticles) {
  const Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(0.1, 0.1), {20, 20}, 1);
  BodySpec body;
  body.shape = BodyShape::Disk;
  body.center = {1.0, 1.0, 0.0};
  body.radius = 0.7;
  body.particles_per_cell = 2;
  body.velocity = {1.0, -2.0, 0.0};
  body.noise_amplitude = 0.3;
  body.noise_seed = 7;
  MaterialSpec material;
  material.density = 3.0;
  ParticleSet<2> whole;
  const std::size_t n = generate_body<2>(body, 0, material, grid, whole);
  ASSERT_EQ(whole.size(), n);
  ASSERT_NE(whole.v[n - 1][0], 1.0) << "the noise must be on for this test to have teeth";
  for (const double cut : {0.55, 1.0, 1.45}) {
    SCOPED_TRACE(cut);
    ParticleSet<2> below, above;
    EXPECT_EQ(generate_body<2>(body, 0, material, grid, below, [cut](const Vec<2>& x) { return x[1] < cut; }),
              n);
    EXPECT_EQ(
        generate_body<2>(body, 0, material, grid, above, [cut](const Vec<2>& x) { return x[1] >= cut; }), n);
    EXPECT_EQ(below.next_id, static_cast<long>(n));
    ASSERT_GT(below.size(), 0u);
    ASSERT_GT(above.size(), 0u);
    EXPECT_EQ(below.size() + above.size(), n);
    for (const ParticleSet<2>* share : {&below, &above})
      for (std::size_t p = 0; p < share->size(); ++p) {
        const auto q = static_cast<std::size_t>(share->id[p]);
        ASSERT_LT(q, n);
        EXPECT_EQ(share->x[p], whole.x[q]);
        EXPECT_EQ(share->v[p], whole.v[q])
            << "particle " << q << ": the noise must follow the generation order";
        EXPECT_EQ(share->mass[p], whole.mass[q]);
        EXPECT_EQ(share->volume0[p], whole.volume0[q]);
      }
  }
}

}  // namespace
