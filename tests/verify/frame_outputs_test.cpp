// What `render --mask`, `--depth`, `--ids` and `--samples` write, checked against the ray-traced
// reference and against values worked out by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "backend/backend.h"
#include "core/shapes.h"
#include "reference_check.h"
#include "render/frame_outputs.h"
#include "scene/scene.h"
#include "trace/reference.h"
#include "verify/verify.h"

namespace shadowvol {
namespace {

using testing::renderer_for;

// On every pixel where frame and reference see the same face, the mask says what the reference
// does: 128 where the surface faces away from the light, else 0 where it is shadowed and 255
// where lit; a shadow boundary's one-pixel band may differ (verify's rule). Beyond a light's
// range the mask says 0 (no light arrives), where the reference compares nothing.
TEST(ShadowMask, SaysWhatTheReferenceSeesOnEveryBackend) {
  for (const char* name : {"demo", "knight", "nonmanifold", "night-street:2"}) {
    const Scene scene = *builtin_scene(name);
    RenderOptions options{240, 135};
    const auto reference = trace_reference(scene, options.width, options.height);
    ASSERT_TRUE(reference.ok());
    for (Backend backend : {Backend::soft, Backend::gl}) {
      SCOPED_TRACE(std::string(name) + (backend == Backend::gl ? " gl" : " soft"));
      auto renderer = renderer_for(backend);
      ASSERT_TRUE(renderer);
      const Frame frame = renderer->render(scene, options);
      const Comparison c = compare(frame, *reference);
      for (std::size_t l = 0; l < scene.lights.size(); ++l) {
        const GreyImage mask = shadow_mask(scene, frame, l);
        ASSERT_EQ(mask.value.size(), frame.object.size());
        std::size_t same = 0, lit = 0, shadowed = 0, wrong = 0;
        for (std::size_t p = 0; p < mask.value.size(); ++p) {
          const std::uint8_t m = mask.value[p];
          if (frame.object[p] < 0) {
            EXPECT_EQ(m, kMaskNotFacing);
            continue;
          }
          if (frame.object[p] != reference->object[p] || frame.face[p] != reference->face[p])
            continue;
          ++same;
          lit += m == kMaskLit;
          shadowed += m == kMaskShadowed;
          const bool faces = reference->faces_light[l][p] != 0;
          const bool in_shadow = reference->shadowed[l][p] != 0;
          const bool band = c.verdict[p] == 1;
          if (faces)
            wrong += m == kMaskNotFacing || (!band && m != (in_shadow ? kMaskShadowed : kMaskLit));
          else
            wrong += m == kMaskLit || (m == kMaskShadowed && !scene.lights[l].limited());
        }
        EXPECT_GT(same, mask.value.size() / 4);
        EXPECT_GT(lit, 0u);
        EXPECT_GT(shadowed, 0u);
        EXPECT_EQ(wrong, 0u);
      }
    }
  }
}

// Looking straight down from 10 units onto the ground: the depth is 10 wherever it is seen, and
// the ids name it; the sky has no depth and id 0.
TEST(ViewDepthAndIds, AreExactOnAGroundSeenFromAbove) {
  Scene scene;
  scene.camera.position = {0.0f, 10.0f, 0.0f};
  scene.camera.target = {0.0f, 0.0f, 0.0f};
  scene.camera.up = {0.0f, 0.0f, -1.0f};
  scene.lights.push_back(SceneLight{});
  scene.objects.push_back(make_object("ground", make_ground(3.0f), glm::mat4(1.0f), Material{}));
  auto renderer = renderer_for(Backend::soft);
  ASSERT_TRUE(renderer);
  const Frame frame = renderer->render(scene, RenderOptions{64, 48});
  const DepthImage depth = view_depth(scene, frame);
  const Image ids = object_ids(frame);
  std::size_t ground = 0, sky = 0;
  for (std::size_t p = 0; p < frame.object.size(); ++p) {
    if (frame.object[p] == 0) {
      ++ground;
      EXPECT_NEAR(depth.depth[p], 10.0f, 1e-4f);
      EXPECT_EQ(ids.rgba[4 * p], 1);
    } else {
      ++sky;
      EXPECT_TRUE(std::isinf(depth.depth[p]));
      EXPECT_EQ(ids.rgba[4 * p], 0);
    }
    EXPECT_EQ(ids.rgba[4 * p + 1], 0);
    EXPECT_EQ(ids.rgba[4 * p + 3], 255);
  }
  EXPECT_GT(ground, 0u);
  EXPECT_GT(sky, 0u);
}

TEST(Supersampling, AveragesInLinearLight) {
  // One pixel of 2 x 2 samples, two black and two white: half the light, sRGB 188.
  Image samples{2, 2, {0, 0, 0, 255, 255, 255, 255, 255, 255, 255, 255, 255, 0, 0, 0, 255}};
  const Image pixel = resolve_samples(samples, 2);
  ASSERT_EQ(pixel.width, 1);
  ASSERT_EQ(pixel.height, 1);
  EXPECT_EQ(pixel.rgba[0], 188);
  EXPECT_EQ(pixel.rgba[3], 255);
  EXPECT_EQ(*samples_side(16, 960, 540), 4);
  EXPECT_EQ(*samples_side(1, 960, 540), 1);
  EXPECT_EQ(samples_side(5, 960, 540).error().message,
            "5 samples per pixel: give a square number from 1 to 64 (1, 4, 9, 16, 25, 36, 49 or "
            "64: a k x k grid in each pixel)");
  EXPECT_FALSE(samples_side(0, 960, 540).ok());
  EXPECT_FALSE(samples_side(81, 960, 540).ok());
  EXPECT_EQ(samples_side(64, 4096, 100).error().message,
            "64 samples per pixel of a 4096x100 picture are drawn at 32768x800, past the 16384 "
            "pixels a side the renderer draws");
}

}  // namespace
}  // namespace shadowvol
