// The Embree baseline (trace/embree_baseline.h) traces the frame the renderer draws: as many
// pixels see a surface, and about as many are in shadow, as in the soft backend's frame.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "scene/scene.h"
#include "soft/soft_backend.h"
#include "trace/embree_baseline.h"

namespace shadowvol {
namespace {

TEST(EmbreeBaseline, TracesTheFrameTheRendererDraws) {
  const Scene scene = *builtin_scene("demo");
  constexpr int kWidth = 160, kHeight = 90;
  Renderer renderer = soft::soft_renderer();
  const Frame frame = renderer.render(scene, {kWidth, kHeight});
  std::uint64_t seen = 0, shadowed = 0;
  for (std::size_t p = 0; p < frame.object.size(); ++p) {
    seen += frame.object[p] >= 0;
    shadowed += frame.object[p] >= 0 && frame.shadowed[0][p];
  }
  auto embree = EmbreeBaseline::create();
  ASSERT_TRUE(embree.ok());
  double ms = -1.0;
  ASSERT_TRUE((*embree)->build(scene, ms).ok());
  EXPECT_GE(ms, 0.0);
  const EmbreeFrame e = (*embree)->trace(scene, kWidth, kHeight);
  EXPECT_NEAR(double(e.hits), double(seen), 0.01 * double(seen));
  EXPECT_GT(shadowed, 300u);
  // Shadow rays count surfaces facing away from the light as shadowed where something blocks
  // them; the mask holds the same, so the two agree but at shadow boundaries.
  EXPECT_NEAR(double(e.shadowed), double(shadowed), 0.05 * double(shadowed));
  // A BVH kept (high quality) traces the same frame as one rebuilt every frame.
  ASSERT_TRUE((*embree)->build(scene, ms, EmbreeBaseline::Bvh::kept).ok());
  const EmbreeFrame kept = (*embree)->trace(scene, kWidth, kHeight);
  EXPECT_EQ(kept.hits, e.hits);
  EXPECT_EQ(kept.shadowed, e.shadowed);
}

// The hybrid: shadow rays from the points rebuilt from the frame's object and face ids find the
// frame's shadows, and the points lie where Embree's primary rays hit.
TEST(EmbreeBaseline, HybridShadowRaysFromTheDepthPassFindTheMask) {
  const Scene scene = *builtin_scene("demo");
  constexpr int kWidth = 160, kHeight = 90;
  Renderer renderer = soft::soft_renderer();
  const Frame frame = renderer.render(scene, {kWidth, kHeight});
  std::vector<glm::vec4> points;
  visible_points(scene, kWidth, kHeight, frame.object, frame.face, points);
  ASSERT_EQ(points.size(), frame.object.size());
  std::uint64_t shadowed = 0;
  for (std::size_t p = 0; p < points.size(); ++p) {
    EXPECT_EQ(points[p].w != 0.0f, frame.object[p] >= 0) << "pixel " << p;
    shadowed += frame.object[p] >= 0 && frame.shadowed[0][p];
  }
  auto embree = EmbreeBaseline::create();
  ASSERT_TRUE(embree.ok());
  double ms = -1.0;
  ASSERT_TRUE((*embree)->build(scene, ms).ok());
  std::uint64_t blocked = 0;
  EXPECT_GE((*embree)->shadow_rays(scene, points, blocked), 0.0);
  EXPECT_GT(shadowed, 300u);
  EXPECT_NEAR(double(blocked), double(shadowed), 0.05 * double(shadowed));
}

}  // namespace
}  // namespace shadowvol
