// DESIGN.md's invariant, as tests: every built-in scene with every method, and real meshes on
// their default stage, against the ray-traced reference. The reference decides; nothing here
// compares against an earlier output of our own rasterizer.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <tuple>

#include <glm/ext/matrix_transform.hpp>

#include "render/soft_renderer.h"
#include "scene/mesh_io.h"
#include "scene/scene.h"
#include "scene/scene_io.h"
#include "trace/reference.h"
#include "verify/verify.h"

namespace shadowvol {
namespace {

// Small images keep the suite quick under the sanitizers; every pixel is still compared.
constexpr int kWidth = 192, kHeight = 108;

Comparison verify(const Scene& scene, Method method, Generator generator = Generator::automatic) {
  SoftRenderer renderer;
  const Frame frame = renderer.render(scene, {kWidth, kHeight, method, generator});
  auto reference = trace_reference(scene, kWidth, kHeight);
  EXPECT_TRUE(reference.ok()) << (reference ? "" : reference.error().message);
  if (!reference) return {};
  return compare(frame, *reference);
}

using SceneMethod = std::tuple<std::string, Method>;
class BuiltinScenes : public ::testing::TestWithParam<SceneMethod> {};

TEST_P(BuiltinScenes, MatchTheReferenceOutsideTheOnePixelBand) {
  const auto& [name, method] = GetParam();
  auto scene = builtin_scene(name);
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  const Comparison c = verify(*scene, method);
  EXPECT_GT(c.pixels_compared, std::size_t{kWidth * kHeight / 4});
  if (name == "camera-in-shadow" && method == Method::zpass) {
    // The eye sits inside a shadow volume: z-pass counts from the eye and must get it wrong.
    EXPECT_GT(c.mismatched_outside_band, c.pixels_compared / 2);
  } else {
    EXPECT_EQ(c.mismatched_outside_band, 0u) << c.mismatched << " mismatched in all";
  }
}

INSTANTIATE_TEST_SUITE_P(
    AllMethods, BuiltinScenes,
    ::testing::Combine(::testing::Values("demo", "camera-in-shadow", "light-in-view", "directional",
                                         "nonmanifold"),
                       ::testing::Values(Method::zpass, Method::zfail, Method::automatic)),
    [](const auto& info) {
      std::string name =
          std::get<0>(info.param) + "_" + std::string(to_string(std::get<1>(info.param)));
      for (char& ch : name)
        if (ch == '-') ch = '_';
      return name;
    });

TEST(BuiltinScenes, EveryGeneratorMatchesOnTheNonManifoldScene) {
  auto scene = builtin_scene("nonmanifold");
  ASSERT_TRUE(scene.ok());
  for (Generator g : {Generator::robust, Generator::multiplicity})
    for (Method m : {Method::zpass, Method::zfail}) {
      const Comparison c = verify(*scene, m, g);
      EXPECT_EQ(c.mismatched_outside_band, 0u) << to_string(g) << " " << to_string(m);
    }
}

TEST(BuiltinScenes, AnimatedFramesMatchTheReference) {
  auto scene = builtin_scene("demo");
  ASSERT_TRUE(scene.ok());
  for (int f : {7, 45})
    for (Method m : {Method::zpass, Method::zfail})
      EXPECT_EQ(verify(scene_at_frame(*scene, f), m).mismatched_outside_band, 0u) << f;
}

TEST(BuiltinScenes, UnknownNamesAreRefusedWithTheList) {
  auto scene = builtin_scene("dmeo");
  ASSERT_FALSE(scene.ok());
  EXPECT_EQ(scene.error().message,
            "unknown scene 'dmeo': the built-in scenes are demo, camera-in-shadow, light-in-view, "
            "directional, nonmanifold");
}

TEST(SceneFiles, TheShippedExampleMatchesTheReference) {
  auto scene = load_scene_file(std::string(SHADOWVOL_SOURCE_DIR) + "/scenes/knot.json");
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  for (Method m : {Method::zpass, Method::zfail, Method::automatic})
    EXPECT_EQ(verify(*scene, m).mismatched_outside_band, 0u) << to_string(m);
}

// Geo-referenced data sits 1e5-1e6 units from the origin, where float steps are centimetres:
// the renderer and the reference both work relative to the eye (DESIGN.md "Numerics").
TEST(SceneFiles, FarFromTheOriginStillMatchesTheReference) {
  auto scene = load_scene_file(std::string(SHADOWVOL_SOURCE_DIR) + "/scenes/knot.json");
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  for (float distance : {1e5f, 1e6f}) {
    Scene far = *scene;
    const glm::vec3 offset(distance, 0.0f, -distance);
    for (SceneObject& o : far.objects)
      o.transform = glm::translate(glm::mat4(1.0f), offset) * o.transform;
    for (SceneLight& l : far.lights) l.position += glm::vec4(offset * l.position.w, 0.0f);
    far.camera.position += offset;
    far.camera.target += offset;
    for (Method m : {Method::zpass, Method::zfail}) {
      const Comparison c = verify(far, m);
      EXPECT_GT(c.pixels_compared, std::size_t{kWidth * kHeight / 2});
      EXPECT_EQ(c.mismatched_outside_band, 0u) << distance << " " << to_string(m);
    }
  }
}

class RealMeshes : public ::testing::TestWithParam<std::string> {};

TEST_P(RealMeshes, OnTheirDefaultStageMatchTheReference) {
  const std::filesystem::path path = GetParam();
  auto loaded = load_mesh(path);
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  const Scene scene = default_stage(path.filename().string(), std::move(loaded->mesh));
  for (Method m : {Method::zpass, Method::zfail}) {
    const Comparison c = verify(scene, m);
    EXPECT_GT(c.pixels_compared, 1000u);
    EXPECT_EQ(c.mismatched_outside_band, 0u) << to_string(m);
  }
}

INSTANTIATE_TEST_SUITE_P(Files, RealMeshes,
                         ::testing::Values(std::string(SHADOWVOL_SOURCE_DIR) +
                                               "/scenes/meshes/torus_knot.obj",
                                           std::string(SHADOWVOL_TEST_DATA) + "/open_box.ply",
                                           std::string(SHADOWVOL_TEST_DATA) + "/fin.stl"),
                         [](const auto& info) {
                           std::string n = std::filesystem::path(info.param).stem().string();
                           for (char& ch : n)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return n;
                         });

}  // namespace

void PrintTo(Method m, std::ostream* os) { *os << to_string(m); }

}  // namespace shadowvol
