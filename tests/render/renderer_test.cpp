// The renderer gives the same frame, counters included, whatever the thread count.
#include <gtest/gtest.h>

#include <array>
#include <string>

#include <tbb/global_control.h>

#include "render/heatmap.h"
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

// Per-tile work adds up to the frame's counters, and the heatmap shows it where it happened.
TEST(Renderer, TileWorkAddsUpToTheCountersAndTheHeatmapShowsIt) {
  auto scene = builtin_scene("demo");
  ASSERT_TRUE(scene.ok());
  for (Method method : {Method::zpass, Method::zfail, Method::split_plane, Method::zpass_prefill}) {
    SCOPED_TRACE(std::string(to_string(method)));
    RenderOptions options{203, 117, method, Generator::automatic};  // partial edge tiles
    SoftRenderer renderer;
    EXPECT_TRUE(renderer.render(*scene, options).tile_work.empty());  // not asked for
    options.tile_work = true;
    const Frame frame = renderer.render(*scene, options);
    ASSERT_EQ(frame.tile_work.size(), std::size_t{26 * 15});
    std::uint64_t processed = 0, updated = 0;
    for (const soft::TileWork& t : frame.tile_work) {
      processed += t.pixels_processed;
      updated += t.pixels_updated;
      EXPECT_LE(t.pixels_updated, t.pixels_processed);
    }
    EXPECT_EQ(processed, frame.stats.counts.pixels_processed);
    EXPECT_EQ(updated, frame.stats.counts.count_updates);
    EXPECT_GT(updated, 1000u);
    const Heatmap map = tile_work_heatmap(frame);
    ASSERT_EQ(map.image.width, 2 * 203 + 4);
    ASSERT_EQ(map.image.height, 117 + 4 + 12);
    EXPECT_GE(map.passes_at_top, 1.0);
    // A tile without work shows the grey scene; one with work, a colour.
    const auto rgb_at = [&](int x, int y) {
      const std::uint8_t* p = &map.image.rgba[4 * (static_cast<std::size_t>(y) * map.image.width + x)];
      return std::array<int, 3>{p[0], p[1], p[2]};
    };
    for (std::size_t t = 0; t < frame.tile_work.size(); ++t) {
      const int x = static_cast<int>(t % 26) * 8, y = static_cast<int>(t / 26) * 8;
      const auto c = rgb_at(x, y);
      if (frame.tile_work[t].pixels_processed == 0) {
        EXPECT_TRUE(c[0] == c[1] && c[1] == c[2]) << "tile " << t;
      } else if (frame.tile_work[t].pixels_processed >= 64) {
        EXPECT_FALSE(c[0] == c[1] && c[1] == c[2]) << "tile " << t;
      }
    }
  }
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
