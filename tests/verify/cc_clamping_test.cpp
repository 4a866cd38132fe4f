// CC shadow volumes' clamping (render/cc_shadow_volumes.h): on scenes made by hand, the plan's
// intervals and strips are what the paper's rules give, and every frame, on both backends,
// matches the ray-traced reference, which decides.
#include <gtest/gtest.h>

#include <string>

#include <glm/ext/matrix_transform.hpp>

#include "backend/backend.h"
#include "core/shapes.h"
#include "reference_check.h"
#include "render/cc_shadow_volumes.h"
#include "render/frame_plan.h"
#include "scene/scene.h"
#include "trace/reference.h"
#include "verify/verify.h"

namespace shadowvol {
namespace {

constexpr int kWidth = 192, kHeight = 108;

glm::mat4 at(glm::vec3 p) { return glm::translate(glm::mat4(1.0f), p); }

// A small box high over a plate, a light above them both, and a far marker that makes the scene
// wide, so that neither is large enough to be split into sub-objects.
Scene gap_scene() {
  Scene s;
  s.name = "gap";
  s.objects.push_back(make_object("plate", make_box({-2.0f, -0.1f, -2.0f}, {2.0f, 0.0f, 2.0f}),
                                  glm::mat4(1.0f), {0.8f, 0.8f, 0.8f}));
  s.objects.push_back(make_object("box", make_box(glm::vec3(-0.4f), glm::vec3(0.4f)),
                                  at({0.3f, 5.0f, 0.0f}), {0.3f, 0.5f, 0.8f}));
  s.objects.push_back(make_object("marker", make_box(glm::vec3(-0.2f), glm::vec3(0.2f)),
                                  at({40.0f, 0.2f, 0.0f}), {0.8f, 0.3f, 0.3f}));
  s.lights.push_back({{0.0f, 12.0f, 1.0f, 1.0f}, {1.0f, 1.0f, 1.0f}, 1.0f});
  s.camera = {{0.0f, 7.0f, 9.0f}, {0.0f, 2.0f, 0.0f}};
  return s;
}

class CcClamping : public ::testing::TestWithParam<Backend> {
 protected:
  // Renders the scene and checks it against the reference.
  Frame render(const Scene& scene, const RenderOptions& options) {
    auto made = make_renderer(GetParam());
    EXPECT_TRUE(made.ok()) << (made ? "" : made.error().message);
    if (!made) return {};
    return testing::render_checked(*made->renderer, scene, options);
  }
};

// The plan of a frame as CC makes it: the frame's ids give the visible samples.
FramePlan cc_plan(const Scene& scene, const RenderOptions& options, const Frame& frame,
                  const VolumeCosts& costs) {
  FrameStats stats;
  FramePlan plan = plan_frame(scene, options, stats);
  CcShadowVolumes cc;
  cc.apply(scene, options, plan, &frame, costs, true, stats);
  return plan;
}

// §3.2.1: the box's volume holds its own depths, then, over the empty gap, the plate's: two
// intervals, the second with caps of its own. Where drawing those caps costs more than the gap
// (V > R), one interval from the box down through the plate.
TEST_P(CcClamping, AReceiverBeyondAGapGetsAnIntervalOfItsOwn) {
  const Scene s = gap_scene();
  RenderOptions options{kWidth, kHeight, Method::automatic};
  options.clamp = Clamp::continuous;
  const Frame frame = render(s, options);
  EXPECT_GT(frame.stats.volumes_clamped, 0);
  const FramePlan gapped = cc_plan(s, options, frame, {1e-12, 1.0});  // every gap kept
  const VolumePlan& box = gapped.volume(0, 1);
  ASSERT_TRUE(box.clamped());
  ASSERT_EQ(box.clamp.leaf_count(), 1u);
  ASSERT_EQ(box.clamp.intervals.size(), 2u);
  EXPECT_EQ(box.clamp.intervals[0].begin, -INFINITY);
  EXPECT_LT(box.clamp.intervals[0].end, box.clamp.intervals[1].begin);
  EXPECT_TRUE(box.build.caps);
  const FramePlan merged = cc_plan(s, options, frame, {1.0, 1e-12});  // every gap too cheap
  ASSERT_EQ(merged.volume(0, 1).clamp.intervals.size(), 1u);
  EXPECT_EQ(merged.volume(0, 1).clamp.intervals[0].end, box.clamp.intervals[1].end);
  // The plate casts away from everything: its own depths alone.
  ASSERT_EQ(gapped.volume(0, 0).clamp.intervals.size(), 1u);
  // Both together, and under every method of the backend, still exact.
  options.clamp = Clamp::both;
  render(s, options);
  for (const Method m : {Method::zpass, Method::zfail}) {
    options.method = m;
    render(s, options);
  }
}

// §3.2.2: the image split into strips across the way the shadows run (from the light on the
// left: vertical strips); the box's volume is drawn only in the strips where a visible point may
// lie in its shadow, not in those left of it.
TEST_P(CcClamping, SlicesSkipEmptyStripsAndDrawOccupiedOnes) {
  Scene s = gap_scene();
  s.objects[1].transform = at({0.5f, 1.5f, 0.0f});
  s.lights[0].position = {-14.0f, 6.0f, 0.0f, 1.0f};
  RenderOptions options{kWidth, kHeight, Method::automatic};
  options.clamp = Clamp::discrete;
  options.slices = 8;
  const Frame frame = render(s, options);
  const FramePlan plan = cc_plan(s, options, frame, {});
  const VolumePlan& box = plan.volume(0, 1);
  ASSERT_FALSE(box.culled);
  ASSERT_EQ(box.strips.size(), 1u);         // one run of strips
  EXPECT_GT(box.strips[0].lo, -INFINITY);   // not from the image's left edge
  EXPECT_GT(box.strips[0].across.x, 0.9f);  // across the image, left to right
  EXPECT_TRUE(plan.volume(0, 2).culled);    // the marker: out of view, and its shadow too
  // Moved out of view with its shadow: no strip holds it, and it is not drawn at all.
  s.objects[1].transform = at({-30.0f, 1.5f, 0.0f});
  const Frame away = render(s, options);
  EXPECT_EQ(away.stats.volumes_clamped_away, frame.stats.volumes_clamped_away + 1);
  EXPECT_TRUE(cc_plan(s, options, away, {}).volume(0, 1).culled);
}

// The corridor over a stretch of its walk, one renderer keeping its sweep-and-prune order from
// frame to frame, culled and clamped both ways: every frame exact.
TEST_P(CcClamping, TheCorridorsWalkStaysExactFrameByFrame) {
  auto corridor = builtin_scene("corridor");
  ASSERT_TRUE(corridor.ok());
  auto made = make_renderer(GetParam());
  ASSERT_TRUE(made.ok());
  RenderOptions options{kWidth, kHeight, Method::automatic};
  options.cull = Cull::frustum;
  options.clamp = Clamp::both;
  for (int f = 0; f < 48; f += 12) {
    const Frame frame =
        testing::render_checked(*made->renderer, scene_at_frame(*corridor, f), options);
    EXPECT_GT(frame.stats.volumes_clamped, 10) << f;
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, CcClamping, ::testing::Values(Backend::soft, Backend::gl),
                         [](const ::testing::TestParamInfo<Backend>& info) {
                           return std::string(info.param == Backend::soft ? "soft" : "gl");
                         });

}  // namespace
}  // namespace shadowvol
