// The renderer gives the same frame, counters included, whatever the thread count.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include "render/soft_renderer.h"
#include "scene/scene.h"

namespace shadowvol {
namespace {

TEST(Renderer, FrameDoesNotDependOnTheThreadCount) {
  auto scene = builtin_scene("light-in-view");
  ASSERT_TRUE(scene.ok());
  const RenderOptions options{200, 120, Method::automatic, Generator::automatic};
  std::vector<Frame> frames;
  for (int threads : {1, 2, 4}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    SoftRenderer renderer;
    frames.push_back(renderer.render(*scene, options));
  }
  for (std::size_t i = 1; i < frames.size(); ++i) {
    EXPECT_EQ(frames[i].image.rgba, frames[0].image.rgba);
    EXPECT_EQ(frames[i].shadowed, frames[0].shadowed);
    EXPECT_EQ(frames[i].stats.counts.count_updates, frames[0].stats.counts.count_updates);
    EXPECT_EQ(frames[i].stats.counts.tiles_skipped, frames[0].stats.counts.tiles_skipped);
    EXPECT_EQ(frames[i].stats.depth.pixels_passed, frames[0].stats.depth.pixels_passed);
  }
  EXPECT_GT(frames[0].stats.counts.count_updates, 1000u);
}

TEST(Renderer, ReusesTheVolumesOfObjectsWhoseLightDidNotMove) {
  auto scene = builtin_scene("demo");
  ASSERT_TRUE(scene.ok());
  const RenderOptions options{160, 90, Method::automatic, Generator::automatic};
  SoftRenderer renderer;
  const Frame first = renderer.render(*scene, options);
  EXPECT_EQ(first.stats.volumes_built, 4);
  EXPECT_EQ(first.stats.volumes_reused, 0);
  const Frame second = renderer.render(*scene, options);
  EXPECT_EQ(second.stats.volumes_built, 0);
  EXPECT_EQ(second.stats.volumes_reused, 4);
  EXPECT_EQ(second.image.rgba, first.image.rgba);
  // Move the box: only its volume is rebuilt, and the frame equals a fresh renderer's.
  scene->objects[2].transform[3] += glm::vec4(0.3f, 0.0f, 0.2f, 0.0f);
  const Frame third = renderer.render(*scene, options);
  EXPECT_EQ(third.stats.volumes_built, 1);
  EXPECT_EQ(third.stats.volumes_reused, 3);
  SoftRenderer fresh;
  EXPECT_EQ(third.image.rgba, fresh.render(*scene, options).image.rgba);
  EXPECT_NE(third.image.rgba, first.image.rgba);
  // Moving the light rebuilds them all.
  scene->lights[0].position.x += 0.5f;
  EXPECT_EQ(renderer.render(*scene, options).stats.volumes_built, 4);
}

TEST(Renderer, OptionsOutsideTheRasterizersLimitsAreRefused) {
  EXPECT_TRUE(check_options({640, 480}).ok());
  EXPECT_FALSE(check_options({0, 480}).ok());
  EXPECT_FALSE(check_options({640, 5000}).ok());
  auto method = parse_method("zfast");
  ASSERT_FALSE(method.ok());
  EXPECT_EQ(method.error().message, "unknown method 'zfast': expected zpass, zfail, auto, spsv or zp+db");
}

}  // namespace
}  // namespace shadowvol
