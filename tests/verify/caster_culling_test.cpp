// CC shadow volumes' culling (render/cc_shadow_volumes.h, accel/light_views.h), on scenes made by
// hand so that what must be culled and what must be kept is known, on both backends; every
// frame is also checked against the ray-traced reference, which decides.
#include <gtest/gtest.h>

#include <string>

#include <glm/ext/matrix_transform.hpp>

#include "backend/backend.h"
#include "core/shapes.h"
#include "reference_check.h"
#include "scene/scene.h"
#include "trace/reference.h"
#include "verify/verify.h"

namespace shadowvol {
namespace {

constexpr int kWidth = 192, kHeight = 108;

glm::mat4 at(glm::vec3 p) { return glm::translate(glm::mat4(1.0f), p); }

// Ground, a light high above, the eye looking down at the middle.
Scene stage(std::string name) {
  Scene s;
  s.name = std::move(name);
  s.objects.push_back(
      make_object("ground", make_ground(6.0f), glm::mat4(1.0f), {0.8f, 0.8f, 0.8f}));
  s.lights.push_back({{0.0f, 10.0f, 0.0f, 1.0f}, {1.0f, 1.0f, 1.0f}, 1.0f});
  s.camera = {{0.0f, 6.0f, 8.0f}, {0.0f, 0.0f, 0.0f}};
  return s;
}

// A 4 x 4 plate at height 5 with a square hole of side `hole` in its middle (no hole: 0).
Mesh plate(float hole) {
  if (hole <= 0.0f) return make_box({-2.0f, 4.9f, -2.0f}, {2.0f, 5.1f, 2.0f});
  const float h = hole / 2;
  Mesh m;
  append_mesh(m, make_box({-2.0f, 4.9f, -2.0f}, {-h, 5.1f, 2.0f}));
  append_mesh(m, make_box({h, 4.9f, -2.0f}, {2.0f, 5.1f, 2.0f}));
  append_mesh(m, make_box({-h, 4.9f, -2.0f}, {h, 5.1f, -h}));
  append_mesh(m, make_box({-h, 4.9f, h}, {h, 5.1f, 2.0f}));
  return m;
}

class CasterCulling : public ::testing::TestWithParam<Backend> {
 protected:
  // Renders with culling by occlusion (light views of `light_view` pixels) and checks the frame
  // against the reference.
  Frame render(const Scene& scene, int light_view = 512, Cull cull = Cull::occlusion) {
    RenderOptions options{kWidth, kHeight, Method::automatic};
    options.cull = cull;
    options.light_view_size = light_view;
    auto made = make_renderer(GetParam());
    EXPECT_TRUE(made.ok()) << (made ? "" : made.error().message);
    if (!made) return {};
    return testing::render_checked(*made->renderer, scene, options);
  }
};

TEST_P(CasterCulling, CullsACasterWhollyInAnothersShadow) {
  Scene s = stage("in-shadow");
  s.objects.push_back(make_object("plate", plate(0.0f), glm::mat4(1.0f), {0.5f, 0.5f, 0.6f}));
  s.objects.push_back(make_object("box", make_box(glm::vec3(-0.3f), glm::vec3(0.3f)),
                                  at({0.5f, 2.5f, 0.5f}), {0.3f, 0.5f, 0.8f}));
  const Frame frame = render(s);
  ASSERT_EQ(frame.stats.culled_lights.size(), 3u);
  EXPECT_EQ(frame.stats.culled_lights[2], 1) << "the box lies in the plate's shadow";
  EXPECT_EQ(frame.stats.culled_lights[1], 0) << "the plate is lit";
  EXPECT_EQ(frame.stats.culled_lights[0], 0) << "the ground is lit";
  EXPECT_EQ(frame.stats.casters_culled_in_shadow, 1);
  EXPECT_GT(frame.stats.cull_queries, 0u);
  EXPECT_GT(frame.stats.light_views, 0);
}

TEST_P(CasterCulling, KeepsTheCasterBehindAPinhole) {
  Scene s = stage("pinhole");
  // The hole is far narrower than a pixel of the 64-pixel light view; the box under it shadows
  // what comes through.
  s.objects.push_back(make_object("plate", plate(0.05f), glm::mat4(1.0f), {0.5f, 0.5f, 0.6f}));
  s.objects.push_back(make_object("box", make_box(glm::vec3(-0.3f), glm::vec3(0.3f)),
                                  at({0.0f, 2.5f, 0.0f}), {0.3f, 0.5f, 0.8f}));
  const Frame frame = render(s, 64);
  ASSERT_EQ(frame.stats.culled_lights.size(), 3u);
  EXPECT_EQ(frame.stats.culled_lights[2], 0) << "light reaches the box through the hole";
}

TEST_P(CasterCulling, ATransparentOccluderCullsNothing) {
  Scene s = stage("glass-occluder");
  s.objects.push_back(
      make_object("glass", plate(0.0f), glm::mat4(1.0f), Material{{0.4f, 0.7f, 0.9f}, 0.5f}));
  s.objects.push_back(make_object("box", make_box(glm::vec3(-0.3f), glm::vec3(0.3f)),
                                  at({0.5f, 2.5f, 0.5f}), {0.3f, 0.5f, 0.8f}));
  const Frame frame = render(s);
  ASSERT_EQ(frame.stats.culled_lights.size(), 3u);
  EXPECT_EQ(frame.stats.culled_lights[2], 0) << "the glass lets light reach the box";
  EXPECT_EQ(frame.stats.casters_culled_in_shadow, 0);
}

TEST_P(CasterCulling, CullsACasterWhoseShadowIsUnseen) {
  Scene s = stage("unseen");
  s.camera = {{-3.0f, 4.0f, 6.0f}, {-3.0f, 0.0f, 0.0f}};  // looks at the left of the ground
  // Far to the right and out of view, with its shadow on the ground beside it: no pixel sees it.
  s.objects.push_back(make_object("box", make_box(glm::vec3(-0.3f), glm::vec3(0.3f)),
                                  at({5.0f, 1.0f, -1.0f}), {0.3f, 0.5f, 0.8f}));
  const Frame frame = render(s);
  ASSERT_EQ(frame.stats.culled_lights.size(), 2u);
  EXPECT_EQ(frame.stats.culled_lights[1], 1);
  EXPECT_EQ(frame.stats.casters_culled_unseen, 1);
  // Culling by the frustum alone keeps it: the ground's box, a receiver, lies under it.
  const Frame by_frustum = render(s, 512, Cull::frustum);
  EXPECT_EQ(by_frustum.stats.culled_lights[1], 0);
}

TEST_P(CasterCulling, KeepsACasterWhoseShadowFallsOnAThinReceiver) {
  Scene s = stage("thin-receiver");
  s.objects.clear();  // no ground: the shadow falls on a pole thinner than a light-view pixel
  s.objects.push_back(
      make_object("pole", make_tube({0.0f, 0.0f, 0.0f}, {0.0f, 3.0f, 0.0f}, 0.01f, 0.01f, 8),
                  glm::mat4(1.0f), {0.8f, 0.8f, 0.8f}));
  // The light from the side, so that the pole's side faces it; the box on the way from the
  // pole's middle to the light.
  s.lights[0].position = {3.0f, 10.0f, 0.0f, 1.0f};
  s.objects.push_back(make_object("box", make_box(glm::vec3(-0.3f), glm::vec3(0.3f)),
                                  at({1.5f, 5.75f, 0.0f}), {0.3f, 0.5f, 0.8f}));
  s.camera = {{0.4f, 1.6f, 0.3f}, {0.0f, 1.5f, 0.0f}};  // close to the pole, so pixels see it
  const Frame frame = render(s, 16);
  ASSERT_EQ(frame.stats.culled_lights.size(), 2u);
  EXPECT_EQ(frame.stats.culled_lights[1], 0);
}

INSTANTIATE_TEST_SUITE_P(Backends, CasterCulling, ::testing::Values(Backend::soft, Backend::gl),
                         [](const ::testing::TestParamInfo<Backend>& info) {
                           return std::string(info.param == Backend::soft ? "soft" : "gl");
                         });

}  // namespace
}  // namespace shadowvol
