// Caster flags and light ranges on both backends (SceneObject::casts_shadows, receives_shadows;
// SceneLight::range): the reference honours them, every frame matches it, and what they leave
// out is left out (volumes not built, pixels outside the scissor not touched, no light beyond
// the range).
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>

#include "backend/backend.h"
#include "reference_check.h"
#include "scene/night_street.h"
#include "scene/scene.h"
#include "trace/reference.h"

namespace shadowvol {
namespace {

constexpr int kWidth = 200, kHeight = 120;

using testing::renderer_for;

RenderOptions options() { return RenderOptions{kWidth, kHeight}; }

std::size_t object_index(const Scene& scene, const std::string& name) {
  for (std::size_t o = 0; o < scene.objects.size(); ++o)
    if (scene.objects[o].name == name) return o;
  ADD_FAILURE() << name;
  return 0;
}

// The pixels of the reference that show object o, face the light and are shadowed.
std::size_t shadowed_on(const ReferenceFrame& ref, std::size_t o) {
  std::size_t n = 0;
  for (std::size_t p = 0; p < ref.object.size(); ++p)
    n += ref.object[p] == static_cast<std::int32_t>(o) && ref.faces_light[0][p] &&
         ref.shadowed[0][p];
  return n;
}

class CastersAndRanges : public ::testing::TestWithParam<Backend> {};

TEST_P(CastersAndRanges, AnObjectThatCastsNoShadowsHasNoVolume) {
  auto renderer = renderer_for(GetParam());
  ASSERT_TRUE(renderer);
  Scene scene = *builtin_scene("demo");
  const std::size_t ground = object_index(scene, "ground"), box = object_index(scene, "box");
  const Frame casting = testing::render_checked(*renderer, scene, options());
  auto casting_ref = trace_reference(scene, kWidth, kHeight);
  scene.objects[box].casts_shadows = false;
  const Frame not_casting = testing::render_checked(*renderer, scene, options());
  auto not_casting_ref = trace_reference(scene, kWidth, kHeight);
  ASSERT_TRUE(casting_ref.ok() && not_casting_ref.ok());
  // The reference loses the box's shadow on the ground, and so does the frame.
  EXPECT_LT(shadowed_on(*not_casting_ref, ground) + 50, shadowed_on(*casting_ref, ground));
  EXPECT_EQ(not_casting.stats.volumes_drawn + 1, casting.stats.volumes_drawn);
  const auto shadowed = [](const Frame& f) {
    return std::count(f.shadowed[0].begin(), f.shadowed[0].end(), 1);
  };
  EXPECT_LT(shadowed(not_casting) + 50, shadowed(casting));
}

TEST_P(CastersAndRanges, AnObjectThatReceivesNoShadowsIsLitWhereverTheLightReaches) {
  auto renderer = renderer_for(GetParam());
  ASSERT_TRUE(renderer);
  Scene scene = *builtin_scene("demo");
  const std::size_t ground = object_index(scene, "ground");
  scene.objects[ground].receives_shadows = false;
  const Frame frame = testing::render_checked(*renderer, scene, options());
  std::size_t ground_pixels = 0;
  for (std::size_t p = 0; p < frame.object.size(); ++p)
    if (frame.object[p] == static_cast<std::int32_t>(ground)) {
      ++ground_pixels;
      EXPECT_EQ(frame.shadowed[0][p], 0) << p;
    }
  EXPECT_GT(ground_pixels, 1000u);
  // Its casts still fall on the others: the torus is shadowed somewhere.
  EXPECT_GT(std::count(frame.shadowed[0].begin(), frame.shadowed[0].end(), 1), 0);
}

TEST_P(CastersAndRanges, TransparentCastersHonourTheFlags) {
  auto renderer = renderer_for(GetParam());
  ASSERT_TRUE(renderer);
  Scene scene = *builtin_scene("glass");
  scene.objects[1].casts_shadows = false;
  scene.objects[2].receives_shadows = false;
  testing::render_checked(*renderer, scene, options());
}

// A light whose range takes in the box but not the torus: the torus's volume is not built, the
// count and lit passes keep to the scissor, and beyond the range the ground has ambient light
// alone.
TEST_P(CastersAndRanges, ALightOfLimitedRangeReachesOnlyItsSphere) {
  auto renderer = renderer_for(GetParam());
  ASSERT_TRUE(renderer);
  Scene scene = *builtin_scene("demo");
  scene.lights[0].position = {2.2f, 1.8f, 1.0f, 1.0f};  // beside the box
  scene.lights[0].range = 2.2f;
  scene.lights[0].intensity = 6.0f;
  const Frame frame = testing::render_checked(*renderer, scene, options());
  EXPECT_GE(frame.stats.volumes_out_of_range, 2);  // the torus and the open box
  EXPECT_GT(frame.stats.scissor_pixels_saved, std::uint64_t{kWidth} * kHeight / 4);
  EXPECT_EQ(frame.stats.volumes_drawn, 2);  // the box, the ground
  Scene dark = scene;
  dark.lights[0].intensity = 0.0f;
  const Frame ambient = renderer->render(dark, options());
  const auto ref = trace_reference(scene, kWidth, kHeight);
  ASSERT_TRUE(ref.ok());
  // Where the reference finds the surface beyond the range (it compares none there) the light
  // adds nothing; within it, somewhere, it does.
  std::size_t beyond = 0, lit_within = 0;
  for (std::size_t p = 0; p < frame.object.size(); ++p) {
    if (frame.object[p] < 0) continue;
    const bool same = std::equal(&frame.image.rgba[4 * p], &frame.image.rgba[4 * p + 3],
                                 &ambient.image.rgba[4 * p]);
    if (!ref->faces_light[0][p]) {
      beyond += same;
    } else {
      lit_within += !same;
    }
  }
  EXPECT_GT(beyond, 5000u);
  EXPECT_GT(lit_within, 500u);
}

TEST_P(CastersAndRanges, TheNightStreetMatchesTheReference) {
  auto renderer = renderer_for(GetParam());
  ASSERT_TRUE(renderer);
  const Scene scene = make_night_street(8);
  ASSERT_EQ(scene.lights.size(), 8u);
  const Frame frame = testing::render_checked(*renderer, scene, options());
  EXPECT_GT(frame.stats.volumes_out_of_range, 0);
  EXPECT_GT(frame.stats.scissor_pixels_saved, 0u);
  // Its lamps' globes cast no shadow: none of their volumes is drawn.
  const std::size_t objects = scene.objects.size();
  EXPECT_LT(frame.stats.volumes_drawn + frame.stats.volumes_out_of_range,
            static_cast<int>(objects * scene.lights.size()));
}

INSTANTIATE_TEST_SUITE_P(Backends, CastersAndRanges, ::testing::Values(Backend::soft, Backend::gl),
                         [](const auto& info) { return std::string(to_string(info.param)); });

}  // namespace
}  // namespace shadowvol
