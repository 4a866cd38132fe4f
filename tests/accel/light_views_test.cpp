// accel/light_views.h: the conservative light views of CC culling, by hand-made geometry whose
// answer is known.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "accel/light_views.h"
#include "core/mesh.h"
#include "core/topology.h"

namespace shadowvol {
namespace {

const glm::dvec4 kOverhead{0.0, 1.0, 0.0, 0.0};  // a directional light straight above
const Box kGround{{-2.0, 0.0, -2.0}, {2.0, 0.0, 2.0}};
const Box kCaster{{-0.5, 1.0, -0.5}, {0.5, 1.5, 0.5}};

// A square at height 2 over [-3, 3]^2, as two triangles (`halves` 2) or one (`halves` 1).
Mesh square(int halves) {
  Mesh m;
  m.positions = {{-3, 2, -3}, {3, 2, -3}, {3, 2, 3}, {-3, 2, 3}};
  m.indices = {0, 2, 1};
  if (halves == 2) m.indices.insert(m.indices.end(), {0, 3, 2});
  return m;
}

struct Views {
  LightViews views;
  Topology topology;
  std::vector<glm::dvec3> positions;

  // The ground as the receiver (points on a grid), and `occluder` drawn, in a 64-pixel view.
  explicit Views(const Mesh* occluder, glm::dvec4 light = kOverhead) {
    views.fit(light, {kGround}, 64, true);
    for (double x = -1.95; x < 2.0; x += 0.1)
      for (double z = -1.95; z < 2.0; z += 0.1) views.add_receiver_point({x, 0.0, z});
    if (occluder) {
      topology = build_topology(*occluder);
      for (const glm::vec3& p : topology.positions) positions.emplace_back(p);
      const LightViews::Occluder o{&topology, positions, {{-3, 2, -3}, {3, 2, 3}}};
      views.add_occluders({&o, 1});
    }
    views.finish(true, true);
  }
  BoxVisibility test(const Box& box) {
    std::uint64_t queries = 0;
    const BoxVisibility v = views.test(box, queries);
    EXPECT_EQ(queries, 1u);
    return v;
  }
};

TEST(LightViews, AMeshCoversAcrossTheSeamsBetweenItsFaces) {
  // The caster's pixels straddle the square's diagonal, which neither triangle covers alone.
  const Mesh occluder = square(2);
  Views v(&occluder);
  EXPECT_EQ(v.test(kCaster), BoxVisibility::in_shadow);
}

TEST(LightViews, AnOpenEdgeBoundsWhatItCovers) {
  // One triangle: its diagonal is a boundary edge, and half the caster lies in the open.
  const Mesh occluder = square(1);
  Views v(&occluder);
  EXPECT_EQ(v.test(kCaster), BoxVisibility::kept);
}

TEST(LightViews, NothingBehindACasterLeavesItsShadowUnseen) {
  Views v(nullptr);
  EXPECT_EQ(v.test(kCaster), BoxVisibility::kept);
  // Under the ground, nothing lies behind it from the light.
  EXPECT_EQ(v.test({{-0.5, -2.0, -0.5}, {0.5, -1.0, 0.5}}), BoxVisibility::unseen);
  // Beside the receivers' window: no view holds it.
  std::uint64_t queries = 0;
  EXPECT_EQ(v.views.test({{5.0, 1.0, 5.0}, {6.0, 2.0, 6.0}}, queries), BoxVisibility::unseen);
  EXPECT_EQ(queries, 0u);
}

TEST(LightViews, APointLightAmongTheReceiversGetsACube) {
  LightViews views;
  views.fit({0.0, 1.0, 0.0, 1.0}, {{{-5, 0, -5}, {5, 4, 5}}}, 32, false);
  EXPECT_TRUE(views.cube());
  views.fit({0.0, 10.0, 0.0, 1.0}, {kGround}, 32, false);
  EXPECT_EQ(views.view_count(), 1u);
  views.fit({0.0, 10.0, 0.0, 1.0}, {}, 32, false);  // no receivers: nothing can be shadowed
  EXPECT_EQ(views.view_count(), 0u);
  std::uint64_t queries = 0;
  EXPECT_EQ(views.test(kCaster, queries), BoxVisibility::unseen);
}

}  // namespace
}  // namespace shadowvol
