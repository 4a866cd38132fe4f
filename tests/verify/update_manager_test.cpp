// The update manager (RenderOptions::overlap_volumes; Intel, "Threading Shadow Volumes"): the
// volumes built on a worker thread beside the depth pass give the frames the volumes built after
// it give, on both backends, frame after frame of an animation; only changed volumes are rebuilt.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "backend/backend.h"
#include "reference_check.h"
#include "scene/scene.h"

namespace shadowvol {
namespace {

constexpr int kWidth = 200, kHeight = 120;

using testing::renderer_for;

class UpdateManager : public ::testing::TestWithParam<Backend> {};

TEST_P(UpdateManager, BuildsBesideTheDepthPassGiveTheSameFrames) {
  auto overlapped = renderer_for(GetParam()), serial = renderer_for(GetParam());
  ASSERT_TRUE(overlapped && serial);
  const Scene scene = *builtin_scene("demo");  // the torus spins: its volume changes each frame
  RenderOptions beside{kWidth, kHeight}, after{kWidth, kHeight};
  after.overlap_volumes = false;
  for (int f = 0; f < 3; ++f) {
    const Scene at = scene_at_frame(scene, f);
    const Frame a =
        f == 2 ? testing::render_checked(*overlapped, at, beside) : overlapped->render(at, beside);
    const Frame b = serial->render(at, after);
    EXPECT_EQ(a.shadowed, b.shadowed) << f;
    EXPECT_EQ(a.image.rgba, b.image.rgba) << f;
    EXPECT_EQ(a.stats.volumes_built, b.stats.volumes_built) << f;
    EXPECT_EQ(a.stats.volumes_reused, b.stats.volumes_reused) << f;
    // After the first frame only the torus's volume changes.
    if (f > 0) {
      EXPECT_EQ(a.stats.volumes_built, 1) << f;
    }
    EXPECT_GT(a.stats.ms_volume_builds, 0.0);
    EXPECT_GE(a.stats.ms_volumes_hidden, 0.0);
    EXPECT_LE(a.stats.ms_volumes_hidden, a.stats.ms_volume_builds);
    EXPECT_EQ(b.stats.ms_volumes_hidden, 0.0);  // built after the depth pass: nothing hidden
  }
}

// Where culling or clamping decide after the depth pass which volumes are drawn and how, the
// volumes are built after it, as they must be: nothing is hidden.
TEST_P(UpdateManager, CullingAndClampingBuildAfterTheDepthPass) {
  auto renderer = renderer_for(GetParam());
  ASSERT_TRUE(renderer);
  RenderOptions options{kWidth, kHeight};
  options.cull = Cull::occlusion;
  const Frame frame = testing::render_checked(*renderer, *builtin_scene("robots"), options);
  EXPECT_GT(frame.stats.volumes_built, 0);
  EXPECT_EQ(frame.stats.ms_volumes_hidden, 0.0);
}

// A scene of many lights: every light's volumes built beside the depth pass, joined once.
TEST_P(UpdateManager, ManyLightsBuildTogether) {
  auto overlapped = renderer_for(GetParam()), serial = renderer_for(GetParam());
  ASSERT_TRUE(overlapped && serial);
  const Scene scene = *builtin_scene("night-street:6");
  RenderOptions after{kWidth, kHeight};
  after.overlap_volumes = false;
  const Frame a = testing::render_checked(*overlapped, scene, RenderOptions{kWidth, kHeight});
  const Frame b = serial->render(scene, after);
  EXPECT_EQ(a.shadowed, b.shadowed);
  EXPECT_EQ(a.image.rgba, b.image.rgba);
  EXPECT_EQ(a.stats.volumes_built, b.stats.volumes_built);
}

INSTANTIATE_TEST_SUITE_P(Backends, UpdateManager, ::testing::Values(Backend::soft, Backend::gl),
                         [](const auto& info) { return std::string(to_string(info.param)); });

}  // namespace
}  // namespace shadowvol
