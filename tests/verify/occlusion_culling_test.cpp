// Hierarchical occlusion culling (render/occlusion_culling.h) on both backends: what it culls
// and keeps, against the frame drawn without it, and the reference.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <glm/ext/matrix_transform.hpp>

#include "accel/box_queries.h"
#include "accel/near_plane.h"
#include "backend/backend.h"
#include "core/shapes.h"
#include "reference_check.h"
#include "scene/city.h"
#include "scene/scene.h"
#include "test_meshes.h"
#include "trace/reference.h"
#include "verify/verify.h"

namespace shadowvol {
namespace {

constexpr int kWidth = 160, kHeight = 120;

using testing::renderer_for;

RenderOptions options_with(Occlusion occlusion, Method method = Method::automatic) {
  RenderOptions options{kWidth, kHeight, method, Generator::automatic};
  options.occlusion = occlusion;
  return options;
}

// A wall across the view at z = 0 (the eye at z = 10 looking down -z), a ground, and a
// sphere of 512 triangles (told apart by its count) behind the wall at z = -4; the light as
// given.
Scene walled(const glm::vec4& light, float wall_half_width = 20.0f) {
  Scene s;
  s.name = "walled";
  s.objects.push_back(
      make_object("ground", make_ground(30.0f), glm::mat4(1.0f), {0.7f, 0.7f, 0.7f}));
  s.objects.push_back(
      make_object("wall", make_box({-wall_half_width, 0.0f, -0.5f}, {wall_half_width, 6.0f, 0.5f}),
                  glm::mat4(1.0f), {0.6f, 0.5f, 0.4f}));
  s.objects.push_back(make_object("hidden", make_sphere({0.0f, 1.5f, -4.0f}, 1.0f, 16, 16),
                                  glm::mat4(1.0f), {0.3f, 0.5f, 0.8f}));
  s.lights.push_back({light, glm::vec3(1.0f), 1.0f});
  s.camera = {{0.0f, 3.0f, 10.0f}, {0.0f, 2.0f, 0.0f}};
  s.camera.fov_y_degrees = 50.0f;
  return s;
}
constexpr std::size_t kHidden = 2;

void expect_same_frame(const Frame& culled, const Frame& whole, const std::string& what) {
  EXPECT_EQ(culled.object, whole.object) << what;
  EXPECT_EQ(culled.face, whole.face) << what;
  EXPECT_EQ(culled.shadowed, whole.shadowed) << what;
  EXPECT_EQ(culled.image.rgba, whole.image.rgba) << what;
}

class OcclusionCulling : public ::testing::TestWithParam<Backend> {};

TEST_P(OcclusionCulling, ABoxBehindAWallIsLeftOutOfTheDepthPass) {
  // The light high in front of the wall: the sphere's shadow falls behind the wall too.
  const Scene scene = walled({0.0f, 30.0f, 20.0f, 1.0f});
  auto renderer = renderer_for(GetParam());
  ASSERT_TRUE(renderer);
  const Frame whole = renderer->render(scene, options_with(Occlusion::none));
  // Two frames of history: on a backend whose answers come later (gl), the first frame may query
  // the sphere before the wall is drawn and find it visible; the second then draws it, as CHC
  // draws what was visible last frame, and its query says hidden; the third culls it.
  for (int warm = 0; warm < 2; ++warm) renderer->render(scene, options_with(Occlusion::eye));
  const Frame culled = renderer->render(scene, options_with(Occlusion::eye));
  EXPECT_EQ(culled.stats.objects_culled, 1);
  EXPECT_EQ(culled.stats.objects_drawn, 2);
  EXPECT_EQ(whole.stats.triangles - culled.stats.triangles,
            scene.objects[kHidden].mesh->triangle_count());
  EXPECT_GT(culled.stats.queries, 0u);
  expect_same_frame(culled, whole, "eye");
}

TEST_P(OcclusionCulling, AHiddenCasterWhoseShadowShowsIsKept) {
  // A narrow wall and a low light to one side: the sphere's shadow reaches along the ground past
  // the wall's end, into view.
  const Scene scene = walled({-30.0f, 3.0f, -4.0f, 1.0f}, 4.0f);
  auto renderer = renderer_for(GetParam());
  ASSERT_TRUE(renderer);
  const Frame whole = renderer->render(scene, options_with(Occlusion::none));
  const Frame culled = renderer->render(scene, options_with(Occlusion::both));
  EXPECT_EQ(culled.stats.culled_lights[kHidden], 0);  // its extruded box shows
  expect_same_frame(culled, whole, "both");
  // It is in view: its shadow darkens pixels the sphere's shadow alone explains.
  Scene without = scene;
  without.objects.pop_back();
  const Frame unshadowed = renderer->render(without, options_with(Occlusion::none));
  EXPECT_NE(unshadowed.shadowed, whole.shadowed);
}

TEST_P(OcclusionCulling, AHiddenCasterWhoseShadowIsHiddenTooIsCulled) {
  const Scene scene = walled({0.0f, 30.0f, 20.0f, 1.0f});
  auto renderer = renderer_for(GetParam());
  ASSERT_TRUE(renderer);
  const Frame whole = renderer->render(scene, options_with(Occlusion::none));
  const Frame culled = renderer->render(scene, options_with(Occlusion::shadows));
  EXPECT_EQ(culled.stats.culled_lights[kHidden], 1);
  EXPECT_EQ(culled.stats.volumes_culled, 1);
  EXPECT_EQ(culled.stats.volumes_drawn, whole.stats.volumes_drawn - 1);
  expect_same_frame(culled, whole, "shadows");
}

// The eye in the shadow of a caster, the light inside a box: both are visible without a query,
// and the frame (z-fail, exact with the eye in shadow) is the one drawn without culling.
TEST_P(OcclusionCulling, TheEyeInAShadowAndTheLightInABoxAreTraversed) {
  Scene scene = *builtin_scene("camera-in-shadow");
  auto renderer = renderer_for(GetParam());
  ASSERT_TRUE(renderer);
  const Frame whole = renderer->render(scene, options_with(Occlusion::none, Method::zfail));
  const Frame culled = renderer->render(scene, options_with(Occlusion::both, Method::zfail));
  expect_same_frame(culled, whole, "eye in shadow");
  // A point light inside a hollow box around the sphere (open at the top toward the eye).
  Scene lit = walled({0.0f, 1.5f, -4.0f, 1.0f});
  lit.objects.push_back(make_object("lamp shade", make_box({-3, 0, -7}, {3, 3, -1}, false),
                                    glm::rotate(glm::mat4(1.0f), glm::radians(-90.0f), {1, 0, 0}),
                                    {0.9f, 0.9f, 0.9f}));
  const Frame lit_whole = renderer->render(lit, options_with(Occlusion::none));
  const Frame lit_culled = renderer->render(lit, options_with(Occlusion::both));
  expect_same_frame(lit_culled, lit_whole, "light in a box");
}

// The sphere moves up out from behind the wall and back: it is culled while hidden, and drawn the
// frame it shows; drawn one frame more after it hides again (CHC draws what was visible last
// frame, and its query then says hidden); every frame is the one drawn without culling.
TEST_P(OcclusionCulling, AMovingObjectLeavesAndEntersVisibilityAndTheFlagsFollow) {
  Scene scene = walled({0.0f, 30.0f, 20.0f, 1.0f});
  auto renderer = renderer_for(GetParam());
  auto reference = renderer_for(GetParam());
  ASSERT_TRUE(renderer && reference);
  const float heights[] = {0.0f, 0.0f, 6.0f, 6.0f, 0.0f, 0.0f, 0.0f};
  for (int warm = 0; warm < 2; ++warm)  // the history (see above)
    renderer->render(scene, options_with(Occlusion::eye));
  std::vector<int> culled;
  for (const float up : heights) {
    scene.objects[kHidden].transform = glm::translate(glm::mat4(1.0f), {0.0f, up, 0.0f});
    const Frame frame = renderer->render(scene, options_with(Occlusion::eye));
    expect_same_frame(frame, reference->render(scene, options_with(Occlusion::none)),
                      "height " + std::to_string(up));
    culled.push_back(frame.stats.objects_culled);
  }
  EXPECT_EQ(culled, (std::vector<int>{1, 1, 0, 0, 0, 1, 1}));
}

// Every built-in scene (the cities small) gives the frame drawn without culling, whatever is
// culled.
TEST_P(OcclusionCulling, EveryBuiltInSceneGivesTheFrameDrawnWithoutIt) {
  auto renderer = renderer_for(GetParam());
  ASSERT_TRUE(renderer);
  for (const std::string& name : testing::builtin_scenes_at_test_size()) {
    const Scene scene = *builtin_scene(name);
    const Frame whole = renderer->render(scene, options_with(Occlusion::none));
    for (const Occlusion o : {Occlusion::eye, Occlusion::shadows, Occlusion::both}) {
      const Frame culled = renderer->render(scene, options_with(o));
      expect_same_frame(culled, whole, name + " " + std::string(to_string(o)));
      EXPECT_EQ(culled.glass.shadowed, whole.glass.shadowed) << name;
      EXPECT_EQ(culled.stats.counts.count_updates, whole.stats.counts.count_updates) << name;
    }
  }
}

// The city from the street: most of it is culled, and it matches the reference.
TEST_P(OcclusionCulling, TheStreetCullsMostOfTheCityAndMatchesTheReference) {
  const Scene scene = scene_at_frame(*builtin_scene("city:480"), 3);
  auto renderer = renderer_for(GetParam());
  ASSERT_TRUE(renderer);
  const Frame frame = renderer->render(scene, options_with(Occlusion::both));
  EXPECT_GT(frame.stats.objects_culled, frame.stats.objects_drawn);
  EXPECT_GT(frame.stats.volumes_culled, frame.stats.volumes_drawn);
  auto traced = trace_reference(scene, kWidth, kHeight);
  ASSERT_TRUE(traced.ok());
  const Comparison c = compare(frame, *traced);
  EXPECT_EQ(c.mismatched_outside_band, 0u);
}

// The city's buildings merged into one mesh, seen from the street: the mesh's bounding sphere
// reaches the near plane's shadow, but most of its parts do not, and `auto` counts those by
// z-pass, exactly.
TEST_P(OcclusionCulling, OneMeshOfAWholeCityIsNotForcedToZFail) {
  const Scene city = scene_at_frame(*builtin_scene("city:96"), 2);
  const Scene merged = with_buildings_merged(city);
  auto renderer = renderer_for(GetParam());
  ASSERT_TRUE(renderer);
  const Frame automatic = renderer->render(merged, options_with(Occlusion::none));
  const Frame zfail = renderer->render(merged, options_with(Occlusion::none, Method::zfail));
  EXPECT_EQ(automatic.stats.zfail_lights.back(), 1);  // the merged mesh as a whole
  EXPECT_GT(automatic.stats.parts_zpass, 90);         // its buildings by z-pass, but those near
  if (GetParam() == Backend::soft) {                  // the backend that counts its work
    EXPECT_LT(automatic.stats.counts.pixels_processed, zfail.stats.counts.pixels_processed / 2);
  }
  EXPECT_EQ(automatic.shadowed, zfail.shadowed);
  auto traced = trace_reference(merged, kWidth, kHeight);
  ASSERT_TRUE(traced.ok());
  EXPECT_EQ(compare(automatic, *traced).mismatched_outside_band, 0u);
}

std::string backend_name(const ::testing::TestParamInfo<Backend>& info) {
  return info.param == Backend::soft ? "soft" : "gl";
}
INSTANTIATE_TEST_SUITE_P(Backends, OcclusionCulling, ::testing::Values(Backend::soft, Backend::gl),
                         backend_name);

// The query geometry's tests: the light in the box, the eye in its shadow, and a box far from
// both.
TEST(BoxQueries, TheLightInTheBoxOrTheEyeInItsShadowNeedNoQuery) {
  const std::array<glm::vec3, 4> near_rect = {
      glm::vec3(-0.1f, -0.1f, -0.1f), glm::vec3(0.1f, -0.1f, -0.1f), glm::vec3(0.1f, 0.1f, -0.1f),
      glm::vec3(-0.1f, 0.1f, -0.1f)};
  const glm::vec3 lo(-1.0f, -1.0f, -11.0f), hi(1.0f, 1.0f, -9.0f);
  EXPECT_TRUE(shadow_meets_near(lo, hi, {0.0f, 0.0f, -10.0f, 1.0f}, near_rect));  // light inside
  EXPECT_TRUE(shadow_meets_near(lo, hi, {0.0f, 0.0f, -30.0f, 1.0f}, near_rect));  // eye in shadow
  EXPECT_FALSE(shadow_meets_near(lo, hi, {0.0f, 30.0f, -10.0f, 1.0f}, near_rect));
  EXPECT_FALSE(box_meets_near(lo, hi, near_rect));
  EXPECT_TRUE(box_meets_near({-1, -1, -1}, {1, 1, 1}, near_rect));
  std::vector<glm::vec4> box, volume;
  box_query_triangles(lo, hi, box);
  shadow_query_triangles(lo, hi, {0.0f, 30.0f, -10.0f, 1.0f}, volume);
  EXPECT_EQ(box.size(), 36u);
  // The light above: the top face and its four edges extruded down.
  EXPECT_EQ(volume.size(), 6u + 4u * 6u);
  for (std::size_t v = 6; v < volume.size(); ++v)
    if (volume[v].w == 0.0f) {
      EXPECT_LT(volume[v].y, 0.0f);  // away from the light above
    }
}

}  // namespace
}  // namespace shadowvol
