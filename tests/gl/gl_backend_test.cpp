// The OpenGL backend's own behaviour: its settings, its volume cache, and that it leaves no
// OpenGL error behind. (Its shadows are verified against the reference in verify_test.cpp.)
#include <gtest/gtest.h>

#include "backend/backend.h"
#include "gl/objects.h"
#include "scene/scene.h"

namespace shadowvol::gl {
namespace {

std::unique_ptr<Renderer> make(GlSettings settings) {
  auto context = Context::create_headless();
  EXPECT_TRUE(context.ok()) << context.error().message;
  auto backend = GlBackend::create(settings, std::move(*context));
  EXPECT_TRUE(backend.ok()) << backend.error().message;
  return backend ? std::make_unique<Renderer>(std::move(*backend)) : nullptr;
}

GlBackend& gl_of(Renderer& renderer) { return static_cast<GlBackend&>(renderer.backend()); }

TEST(GlBackend, ReusesUploadedVolumesAndLeavesNoGlError) {
  auto scene = builtin_scene("demo");
  ASSERT_TRUE(scene.ok());
  auto renderer = make({});
  ASSERT_TRUE(renderer);
  const RenderOptions options{160, 90, Method::automatic, Generator::automatic};
  const Frame first = renderer->render(*scene, options);
  EXPECT_EQ(take_error(), "");
  EXPECT_EQ(first.stats.volumes_built, 4);
  const Frame second = renderer->render(*scene, options);
  EXPECT_EQ(second.stats.volumes_built, 0);
  EXPECT_EQ(second.stats.volumes_reused, 4);
  EXPECT_EQ(second.image.rgba, first.image.rgba);
  EXPECT_EQ(second.shadowed, first.shadowed);
  // Moving the box rebuilds and re-uploads its volume alone; the frame equals a fresh one's.
  scene->objects[2].transform[3] += glm::vec4(0.3f, 0.0f, 0.2f, 0.0f);
  const Frame third = renderer->render(*scene, options);
  EXPECT_EQ(third.stats.volumes_built, 1);
  EXPECT_NE(third.shadowed, first.shadowed);
  renderer.reset();
  auto fresh = make({});
  ASSERT_TRUE(fresh);
  EXPECT_EQ(fresh->render(*scene, options).shadowed, third.shadowed);
}

// The opaque depth pass in one multi-draw (GlBackend::draw_depth) and CPU volumes in multi-draws
// (count_volumes: per rule, per sign into the stencil, every weight into the additive target)
// give the ids, the image, the masks, the light map and the fill and stencil writes of drawing
// object by object, and no OpenGL error.
TEST(GlBackend, BatchedVolumesCountAsVolumeByVolume) {
  for (const CountTarget target : {CountTarget::stencil, CountTarget::additive})
    for (const char* name : {"demo", "camera-in-shadow", "glass", "nonmanifold", "city:48"}) {
      const Scene scene = *builtin_scene(name);
      RenderOptions options{160, 90, Method::automatic, Generator::automatic};
      options.count_fill = true;
      auto batched = make({VolumePath::cpu, target}), apart = make({VolumePath::cpu, target});
      ASSERT_TRUE(batched && apart);
      gl_of(*apart).set_batching(false);
      const Frame a = batched->render(scene, options), b = apart->render(scene, options);
      EXPECT_EQ(take_error(), "") << name;
      EXPECT_EQ(a.object, b.object) << name;  // the ids of one multi-draw's faces
      EXPECT_EQ(a.face, b.face) << name;
      EXPECT_EQ(a.image.rgba, b.image.rgba) << name;
      EXPECT_EQ(a.shadowed, b.shadowed) << name;
      EXPECT_EQ(a.glass.transmitted, b.glass.transmitted) << name;
      EXPECT_EQ(a.stats.fill, b.stats.fill) << name;
      EXPECT_EQ(a.stats.stencil_writes, b.stats.stencil_writes) << name;
    }
}

TEST(GlBackend, SwitchingVolumePathsKeepsTheShadows) {
  auto scene = builtin_scene("nonmanifold");
  ASSERT_TRUE(scene.ok());
  auto renderer = make({VolumePath::cpu, CountTarget::automatic});
  ASSERT_TRUE(renderer);
  const RenderOptions options{160, 90, Method::zfail, Generator::robust};
  const Frame cpu = renderer->render(*scene, options);
  gl_of(*renderer).set_settings({VolumePath::gpu, CountTarget::stencil});
  const Frame gpu = renderer->render(*scene, options);
  gl_of(*renderer).set_settings({VolumePath::cpu, CountTarget::additive});
  const Frame back = renderer->render(*scene, options);
  EXPECT_EQ(take_error(), "");
  EXPECT_EQ(back.shadowed, cpu.shadowed);
  std::size_t differ = 0;
  for (std::size_t p = 0; p < cpu.shadowed[0].size(); ++p)
    differ += cpu.shadowed[0][p] != gpu.shadowed[0][p];
  EXPECT_LT(differ, cpu.shadowed[0].size() / 200);  // facing rounds differently on the GPU
}

TEST(GlBackend, SettingsAreParsedAndCheckedWithClearMessages) {
  EXPECT_FALSE(
      check_settings({VolumePath::gpu, CountTarget::automatic}, Generator::multiplicity).ok());
  EXPECT_TRUE(check_settings({VolumePath::gpu, CountTarget::automatic}, Generator::robust).ok());
  EXPECT_TRUE(
      check_settings({VolumePath::cpu, CountTarget::stencil}, Generator::multiplicity).ok());
  EXPECT_FALSE(
      check_settings({VolumePath::vertex, CountTarget::automatic}, Generator::multiplicity).ok());
  EXPECT_TRUE(check_settings({VolumePath::vertex, CountTarget::stencil}, Generator::robust).ok());
  EXPECT_EQ(parse_volume_path("gpu").value(), VolumePath::gpu);
  EXPECT_EQ(parse_volume_path("vs").value(), VolumePath::vertex);
  EXPECT_EQ(parse_volume_path("gs").error().message,
            "unknown volume path 'gs': expected cpu, gpu or vs");
  EXPECT_EQ(parse_count_target("additive").value(), CountTarget::additive);
  EXPECT_EQ(parse_backend("auto").value(), Backend::automatic);
  EXPECT_EQ(parse_backend("dx12").error().message,
            "unknown backend 'dx12': expected soft, gl or auto");
  auto soft_gpu = make_renderer(Backend::soft, {VolumePath::gpu, CountTarget::automatic});
  ASSERT_FALSE(soft_gpu.ok());
  auto soft_vs = make_renderer(Backend::soft, {VolumePath::vertex, CountTarget::automatic});
  ASSERT_FALSE(soft_vs.ok());
  EXPECT_EQ(soft_vs.error().message,
            "volumes built in a shader (--volumes vs) need the gl backend");
  auto soft_stencil = make_renderer(Backend::soft, {VolumePath::cpu, CountTarget::stencil});
  ASSERT_FALSE(soft_stencil.ok());  // never ignored in silence
  EXPECT_EQ(soft_stencil.error().message,
            "counting in a target of gl's (--counts stencil) needs the gl backend");
}

}  // namespace
}  // namespace shadowvol::gl
