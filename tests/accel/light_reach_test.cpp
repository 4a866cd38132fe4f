// A light's reach (accel/light_reach.h): every point of its sphere that the camera sees lies in
// the scissor rectangle and the depth bounds, wherever the sphere lies; and the rectangle is
// tight where the sphere lies ahead.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>

#include "accel/light_reach.h"
#include "core/projection.h"

namespace shadowvol {
namespace {

constexpr int kWidth = 320, kHeight = 200;
constexpr float kNear = 0.1f;

struct Camera {
  glm::mat4 view, proj;
};

Camera camera() {
  const glm::mat4 view =
      glm::lookAt(glm::vec3(0.0f), glm::vec3(0.3f, -0.2f, -1.0f), glm::vec3(0, 1, 0));
  return {view, infinite_reversed_perspective(glm::radians(60.0f), float(kWidth) / float(kHeight),
                                              kNear)};
}

// Points of the ball, each seen through the camera: its pixel and window depth must lie within
// the reach; returns how many were seen.
int check_contains(const glm::vec3& centre, float range) {
  const Camera cam = camera();
  const LightReach reach =
      light_reach(glm::vec4(centre, 1.0f), range, cam.view, cam.proj, kNear, kWidth, kHeight);
  EXPECT_TRUE(reach.limited);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  int seen = 0;
  for (int i = 0; i < 20000; ++i) {
    glm::vec3 d(u(rng), u(rng), u(rng));
    if (glm::length(d) > 1.0f) continue;
    if (i % 2) d = glm::normalize(d);  // the surface too
    const glm::vec4 clip = cam.proj * cam.view * glm::vec4(centre + d * range, 1.0f);
    if (clip.w <= kNear || clip.z > clip.w) continue;  // behind the near plane
    const float x = (clip.x / clip.w + 1.0f) * 0.5f * kWidth;
    const float y = (1.0f - clip.y / clip.w) * 0.5f * kHeight;
    if (x < 0 || y < 0 || x >= kWidth || y >= kHeight) continue;
    ++seen;
    const int px = int(x), py = int(y);
    EXPECT_TRUE(px >= reach.scissor.x0 && px < reach.scissor.x1 && py >= reach.scissor.y0 &&
                py < reach.scissor.y1)
        << "pixel " << px << "," << py;
    const float z = clip.z / clip.w;
    EXPECT_TRUE(z >= reach.depth.zmin && z <= reach.depth.zmax) << z;
  }
  return seen;
}

TEST(LightReach, HoldsEverySeenPointOfItsSphere) {
  const glm::mat4 to_world = glm::inverse(camera().view);
  // Ahead, off to a side, crossing the near plane, around the eye.
  for (const glm::vec3 eye_space : {glm::vec3(0.5f, 0.2f, -12.0f), glm::vec3(-6.0f, 3.0f, -9.0f),
                                    glm::vec3(1.0f, -0.5f, -1.5f), glm::vec3(0.2f, 0.1f, 0.3f)}) {
    const glm::vec3 centre(to_world * glm::vec4(eye_space, 1.0f));
    EXPECT_GT(check_contains(centre, 2.5f), 100) << eye_space.z;
  }
}

TEST(LightReach, IsTightAheadAndEmptyBehind) {
  const Camera cam = camera();
  const glm::mat4 to_world = glm::inverse(cam.view);
  const glm::vec3 ahead(to_world * glm::vec4(0.0f, 0.0f, -20.0f, 1.0f));
  const LightReach small =
      light_reach(glm::vec4(ahead, 1.0f), 1.0f, cam.view, cam.proj, kNear, kWidth, kHeight);
  // A ball of radius 1 at distance 20 spans about 2 / 20 of f = 1.73 NDC units per 2: ~28 px.
  const int expected =
      int(std::ceil(1.0f / 20.0f * (1.0f / std::tan(glm::radians(30.0f))) * kHeight));
  EXPECT_LE(small.scissor.y1 - small.scissor.y0, expected + 4);
  EXPECT_GE(small.scissor.y1 - small.scissor.y0, expected - 2);
  EXPECT_LT(small.scissor.area(), std::uint64_t{kWidth} * kHeight / 20);
  const glm::vec3 behind(to_world * glm::vec4(0.0f, 0.0f, 20.0f, 1.0f));
  const LightReach none =
      light_reach(glm::vec4(behind, 1.0f), 5.0f, cam.view, cam.proj, kNear, kWidth, kHeight);
  EXPECT_TRUE(none.empty());
  const LightReach unlimited =
      light_reach(glm::vec4(ahead, 1.0f), INFINITY, cam.view, cam.proj, kNear, kWidth, kHeight);
  EXPECT_FALSE(unlimited.limited);
  EXPECT_EQ(unlimited.scissor, (raster::PixelRect{0, 0, kWidth, kHeight}));
}

TEST(LightReach, BoxMeetsSphere) {
  const glm::vec3 lo(0.0f), hi(1.0f);
  EXPECT_TRUE(box_meets_sphere(lo, hi, glm::vec3(0.5f), 0.1f));               // inside
  EXPECT_TRUE(box_meets_sphere(lo, hi, glm::vec3(2.0f, 0.5f, 0.5f), 1.0f));   // touching a face
  EXPECT_FALSE(box_meets_sphere(lo, hi, glm::vec3(2.0f, 2.0f, 2.0f), 1.7f));  // corner at 1.732
  EXPECT_TRUE(box_meets_sphere(lo, hi, glm::vec3(2.0f, 2.0f, 2.0f), 1.74f));
  EXPECT_FALSE(
      box_meets_sphere(glm::vec3(1.0f), glm::vec3(0.0f), glm::vec3(0.5f), 10.0f));  // empty
}

}  // namespace
}  // namespace shadowvol
