// The second reference (src/brute): hand-worked shadows, and agreement with the first (Embree)
// on every built-in scene, compared as verify compares a frame, band and all.
#include <gtest/gtest.h>

#include <string>

#include "brute/brute_reference.h"
#include "core/shapes.h"
#include "scene/scene.h"
#include "test_meshes.h"
#include "trace/reference.h"
#include "verify/verify.h"

namespace shadowvol {
namespace {

// A ground 20 across at y = 0, a 2 x 2 x 2 box over its middle (y 4..6), a point light at y =
// 10, and the eye at y = 20 looking straight down (fov 60, so the image's half-width at distance
// d is d tan 30 = 0.577 d). The box's top hides ndc |x| <= 1 / (14 * 0.577) = 0.124; its shadow
// on the ground, by its top edges, is |x| <= 1 * 10 / (10 - 6) = 2.5.
Scene box_over_ground(float opacity = 1.0f) {
  Scene s;
  s.objects.push_back(make_object("ground", make_ground(10.0f), glm::mat4(1.0f), glm::vec3(0.8f)));
  s.objects.push_back(make_object("box", make_box({-1, 4, -1}, {1, 6, 1}), glm::mat4(1.0f),
                                  glm::vec3(1.0f, 0.5f, 0.0f)));
  s.objects[1].material.opacity = opacity;
  s.lights.push_back({{0.0f, 10.0f, 0.0f, 1.0f}, glm::vec3(1.0f), 1.0f});
  s.camera = {{0.0f, 20.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, 60.0f, 0.1f};
  return s;
}

constexpr int kSide = 64;
std::size_t at(int x, int y) { return static_cast<std::size_t>(y) * kSide + x; }

TEST(BruteReference, SeesAndShadowsAsWorkedByHand) {
  auto ref = trace_brute_reference(box_over_ground(), kSide, kSide);
  ASSERT_TRUE(ref.ok()) << ref.error().message;
  // Pixel x = i is at ndc (i + 0.5) / 32 - 1, the ground point x = 20 * 0.577 * ndc.
  EXPECT_EQ(ref->object[at(32, 32)], 1);  // the box's top, lit from straight above
  EXPECT_EQ(ref->faces_light[0][at(32, 32)], 1);
  EXPECT_EQ(ref->shadowed[0][at(32, 32)], 0);
  EXPECT_EQ(ref->object[at(26, 32)], 0);  // ndc -0.172: the ground at x = -1.99, in the shadow
  EXPECT_EQ(ref->shadowed[0][at(26, 32)], 1);
  EXPECT_EQ(ref->object[at(24, 32)], 0);  // ndc -0.234: x = -2.71, past the shadow's edge
  EXPECT_EQ(ref->shadowed[0][at(24, 32)], 0);
  EXPECT_EQ(ref->object[at(8, 32)], 0);  // x = -8.48: lit ground
  EXPECT_EQ(ref->shadowed[0][at(8, 32)], 0);
  EXPECT_EQ(ref->object[at(2, 32)], -1);  // x = -10.6: past the ground's edge
  EXPECT_EQ(ref->near_plane_shadowed[0][at(32, 32)], 0);  // the eye is above the light
}

TEST(BruteReference, TransparentCastersPassTheirLightPerSurfaceCrossed) {
  auto ref = trace_brute_reference(box_over_ground(0.25f), kSide, kSide);
  ASSERT_TRUE(ref.ok()) << ref.error().message;
  // The ground at x = -1.99 sees the light through the box's top and bottom: 0.75 x colour,
  // twice. The glass layer in front of the centre's ground is the box's top.
  ASSERT_FALSE(ref->transmitted.empty());
  const glm::vec3 passed = ref->transmitted[0][at(26, 32)];
  EXPECT_NEAR(passed.r, 0.5625f, 1e-6f);
  EXPECT_NEAR(passed.g, 0.140625f, 1e-6f);
  EXPECT_NEAR(passed.b, 0.0f, 1e-6f);
  EXPECT_EQ(ref->object[at(32, 32)], 0);
  EXPECT_EQ(ref->glass.object[at(32, 32)], 1);
}

TEST(BruteReference, SaysWhereTheNearPlaneLiesInAShadow) {
  Scene scene = box_over_ground();
  // The eye under the box, in its shadow (|x| <= 2 at y = 2), looking along +x.
  scene.camera = {{0.0f, 2.0f, 0.0f}, {10.0f, 2.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 60.0f, 0.1f};
  auto brute = trace_brute_reference(scene, kSide, kSide);
  auto embree = trace_reference(scene, kSide, kSide);
  ASSERT_TRUE(brute.ok() && embree.ok());
  EXPECT_EQ(brute->near_plane_shadowed[0][at(32, 32)], 1);
  EXPECT_EQ(brute->near_plane_shadowed[0], embree->near_plane_shadowed[0]);
}

// Every built-in scene (the cities at 48 buildings), small: the two references, written apart,
// see the same surfaces, sides and shadows outside the one-pixel band.
class References : public ::testing::TestWithParam<std::string> {};

TEST_P(References, AgreeOnTheBuiltinScene) {
  auto scene = builtin_scene(GetParam());
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  constexpr int kWidth = 128, kHeight = 72;
  auto brute = trace_brute_reference(*scene, kWidth, kHeight);
  auto embree = trace_reference(*scene, kWidth, kHeight);
  ASSERT_TRUE(brute.ok()) << brute.error().message;
  ASSERT_TRUE(embree.ok()) << embree.error().message;
  const Comparison c = compare(as_frame(*brute), *embree);
  EXPECT_GT(c.pixels_compared, std::size_t{kWidth * kHeight / 4});
  EXPECT_EQ(c.mismatched_outside_band, 0u) << c.mismatched << " mismatched";
  EXPECT_LE(c.max_light_error_outside_band, kLightTolerance);
}

INSTANTIATE_TEST_SUITE_P(Builtin, References,
                         ::testing::ValuesIn(testing::builtin_scenes_at_test_size()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param;
                           for (char& ch : name)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return name;
                         });

}  // namespace
}  // namespace shadowvol
