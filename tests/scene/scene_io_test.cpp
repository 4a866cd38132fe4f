// Scene files: the shipped example loads and matches the reference; every bad or missing value
// is refused with the file and the key path.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <utility>

#include <glm/common.hpp>

#include "scene/scene_io.h"

namespace shadowvol {
namespace {

std::filesystem::path write_temp(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("shadowvol_test_" + name + ".json");
  std::ofstream(path) << text;
  return path;
}

TEST(SceneFile, TheShippedExampleLoads) {
  auto scene = load_scene_file(std::string(SHADOWVOL_SOURCE_DIR) + "/scenes/knot.json");
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  EXPECT_EQ(scene->name, "knot");
  ASSERT_EQ(scene->objects.size(), 4u);
  EXPECT_EQ(scene->objects[1].name, "knot");
  EXPECT_EQ(scene->objects[1].mesh->triangle_count(), 5760u);  // meshes/ relative to the file
  EXPECT_NE(smooth_shading(scene->objects[1]), nullptr);       // a mesh file's object shades smooth
  EXPECT_EQ(scene->objects[0].shading, nullptr);               // a shape, flat
  ASSERT_EQ(scene->lights.size(), 2u);
  EXPECT_EQ(scene->lights[1].position.w, 0.0f);  // "direction": a directional light
}

TEST(SceneFile, AnimationSpinsMovesAndOrbits) {
  const auto path = write_temp("animated", R"({
    "camera": {"position": [0, 2, 5], "target": [0, 1, 0], "orbit": -90},
    "lights": [{"position": [4, 5, 0], "orbit": 90}],
    "objects": [{"shape": "box", "animation": {"spin": [0, 1, 0], "degrees_per_frame": 90,
                                               "move": [1, 0, 0]}}]})");
  auto scene = load_scene_file(path);
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  const Scene at = scene_at_frame(*scene, 1);
  // The box's +x axis turned to -z, its origin moved to (1, 0, 0); the light went to (0, 5, -4).
  const glm::vec4 x_axis = at.objects[0].transform * glm::vec4(1, 0, 0, 0);
  EXPECT_NEAR(x_axis.z, -1.0f, 1e-6f);
  EXPECT_NEAR(at.objects[0].transform[3].x, 1.0f, 1e-6f);
  EXPECT_NEAR(at.lights[0].position.z, -4.0f, 1e-5f);
  EXPECT_NEAR(at.lights[0].position.x, 0.0f, 1e-5f);
  // The camera turned the other way about the line x = z = 0: from +z to -x, still looking at
  // the target, from the same height.
  EXPECT_NEAR(at.camera.position.x, -5.0f, 1e-5f);
  EXPECT_NEAR(at.camera.position.y, 2.0f, 1e-6f);
  EXPECT_NEAR(at.camera.position.z, 0.0f, 1e-5f);
  EXPECT_EQ(at.camera.target, glm::vec3(0, 1, 0));
  EXPECT_EQ(scene_at_frame(*scene, 0).camera.position, scene->camera.position);
  EXPECT_EQ(scene_at_frame(*scene, 0).objects[0].transform, scene->objects[0].transform);
}

// The bounds of an object's mesh in world space at its transform.
std::pair<glm::vec3, glm::vec3> world_bounds(const SceneObject& o) {
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const glm::vec3& p : o.mesh->positions) {
    const glm::vec3 w(o.transform * glm::vec4(p, 1.0f));
    lo = glm::min(lo, w), hi = glm::max(hi, w);
  }
  return {lo, hi};
}
glm::vec3 world_centre(const SceneObject& o) {
  const auto [lo, hi] = world_bounds(o);
  return (lo + hi) * 0.5f;
}
const SceneObject& named(const Scene& scene, const std::string& name) {
  for (const SceneObject& o : scene.objects)
    if (o.name == name) return o;
  ADD_FAILURE() << "no object named " << name;
  return scene.objects.front();
}
void expect_near(const glm::vec3& a, const glm::vec3& b, float within) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(a[i], b[i], within) << "axis " << i;
}

// scenes/meshes/turntable.gltf (scripts/make_turntable_gltf.py): a still pillar; a turntable
// node turning about y once in 2 s, carrying a red box at (1.5, 0.5, 0) and a blue one at
// (-1.5, 1, 0), scale 0.6, that rises to y = 2 and shrinks to 0.3 at 1 s ("Spin"); "Hop" lifts
// the red box by 1 in 1 s.
const std::string kTurntable = std::string(SHADOWVOL_SOURCE_DIR) + "/scenes/meshes/turntable.gltf";

TEST(MeshFileScene, AnimatedNodesMoveAtTheirClipsTimes) {
  auto loaded = load_scene(kTurntable);
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  const Scene& scene = loaded->scene;
  // What stays is an object per material; each moving node's triangles are objects of their own.
  ASSERT_EQ(scene.objects.size(), 4u);
  EXPECT_FALSE(named(scene, "turntable.gltf/Stone").node.bound());
  EXPECT_TRUE(named(scene, "turntable.gltf/Box/Red").node.bound());
  EXPECT_TRUE(named(scene, "turntable.gltf/Bob/Blue").node.bound());
  EXPECT_EQ(named(scene, "turntable.gltf/Box/Red").material.color, glm::vec3(0.8f, 0.1f, 0.1f));
  // Frame 15 at 30 frames a second: 0.5 s, a quarter turn, (x, y, z) -> (z, y, -x).
  const Scene at = scene_at_frame(scene, 15);
  expect_near(world_centre(named(at, "turntable.gltf/Box/Red")), {0.0f, 0.5f, -1.5f}, 1e-5f);
  // The blue box halfway up (y 1.5) and down in size (0.45), its own motion turned by its parent.
  const auto [lo, hi] = world_bounds(named(at, "turntable.gltf/Bob/Blue"));
  expect_near((lo + hi) * 0.5f, {0.0f, 1.5f, 1.5f}, 1e-5f);
  expect_near(hi - lo, glm::vec3(0.45f), 1e-5f);
  expect_near(world_centre(named(at, "turntable.gltf/Stone")), {0.0f, 1.0f, 0.0f}, 1e-6f);
  // 1.5 s: three quarters, between keys 90 degrees apart; 2 s, the whole turn: rest again, and
  // the clip repeats after it.
  expect_near(world_centre(named(scene_at_frame(scene, 45), "turntable.gltf/Box/Red")),
              {0.0f, 0.5f, 1.5f}, 1e-5f);
  expect_near(world_centre(named(scene_at_frame(scene, 60), "turntable.gltf/Box/Red")),
              {1.5f, 0.5f, 0.0f}, 1e-5f);
  EXPECT_EQ(scene_at_frame(scene, 75).objects[1].transform, at.objects[1].transform);
  // Frames add up: 7 frames on from frame 8 is frame 15.
  const Scene stepped = scene_at_frame(scene_at_frame(scene, 8), 7);
  for (std::size_t i = 0; i < at.objects.size(); ++i)
    EXPECT_EQ(stepped.objects[i].transform, at.objects[i].transform) << at.objects[i].name;
}

// What cannot be moved is drawn still and said: a channel for a node outside the file's scene,
// a node scaled to nothing at rest (its mesh at rest holds no shape to move).
TEST(MeshFileScene, WhatCannotBeAnimatedIsSaid) {
  auto other = load_scene(std::string(SHADOWVOL_TEST_DATA) + "/other_scenes_nodes.gltf");
  ASSERT_TRUE(other.ok()) << other.error().message;
  const auto said = [](const std::vector<std::string>& warnings, const std::string& what) {
    for (const std::string& w : warnings)
      if (w.find(what) != std::string::npos) return true;
    return false;
  };
  EXPECT_TRUE(said(other->warnings,
                   "animation 'Spin' moves node 'Bob', which the file does not "
                   "have; left out"));
  for (const SceneObject& o : other->scene.objects) EXPECT_FALSE(o.node.bound()) << o.name;
  auto flat = load_scene(std::string(SHADOWVOL_TEST_DATA) + "/flat_at_rest.gltf");
  ASSERT_TRUE(flat.ok()) << flat.error().message;
  EXPECT_TRUE(said(flat->warnings, "node 'Bob' is flat at rest (a scale of 0)"));
  EXPECT_FALSE(named(flat->scene, "flat_at_rest.gltf/Blue").node.bound());
  EXPECT_TRUE(named(flat->scene, "flat_at_rest.gltf/Box/Red").node.bound());
}

// A scene file places the file, picks its clip and its pace; its colour, where given, replaces
// the file's materials; null holds it still.
TEST(SceneFile, NamesAFilesClipAndPlacesItsHierarchy) {
  const auto path = write_temp("clips", R"({
    "camera": {"position": [0, 6, 11], "target": [0, 0.8, 0]},
    "lights": [{"position": [4, 9, 5]}],
    "objects": [
      {"name": "hop", "mesh": ")" + kTurntable +
                                            R"(", "clip": "Hop", "frames_per_second": 15,
       "transform": {"translate": [2.5, 0, 0], "rotate": [0, 90, 0], "scale": 0.8}},
      {"name": "still", "mesh": ")" + kTurntable +
                                            R"(", "clip": null, "color": [0, 1, 0]}]})");
  std::vector<std::string> warnings;
  auto scene = load_scene_file(path, &warnings);
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  EXPECT_TRUE(warnings.empty());
  // "Hop" moves only the red box; the file's materials name the objects.
  ASSERT_EQ(scene->objects.size(), 4u);
  EXPECT_FALSE(named(*scene, "hop/Blue").node.bound());
  EXPECT_FALSE(named(*scene, "hop/Stone").node.bound());
  EXPECT_TRUE(named(*scene, "hop/Box/Red").node.bound());
  // Held still, with the scene's colour: one object, the file whole.
  EXPECT_FALSE(named(*scene, "still").node.bound());
  EXPECT_EQ(named(*scene, "still").material.color, glm::vec3(0, 1, 0));
  // Frame 12 at 15 a second: 0.8 s, the box lifted from (1.5, 0.5, 0) to (1.5, 1.3, 0), then
  // placed: turned a quarter about y ((x, y, z) -> (z, y, -x)), scaled 0.8, moved 2.5 along x.
  const Scene at = scene_at_frame(*scene, 12);
  expect_near(world_centre(named(at, "hop/Box/Red")), {2.5f, 1.04f, -1.2f}, 1e-5f);
  expect_near(world_centre(named(at, "hop/Blue")), world_centre(named(*scene, "hop/Blue")), 0.0f);
  EXPECT_EQ(named(at, "still").transform, named(*scene, "still").transform);
  // The clip over (1 s, frame 15), it begins again: the box is back at rest.
  expect_near(world_centre(named(scene_at_frame(*scene, 15), "hop/Box/Red")),
              world_centre(named(*scene, "hop/Box/Red")), 1e-6f);
}

// A mesh file as a scene: its materials make its objects, its camera and lights replace the
// stage's; only the stage's ground is added.
TEST(MeshFileScene, TakesTheFilesMaterialsCamerasAndLights) {
  auto loaded = load_scene(std::string(SHADOWVOL_TEST_DATA) + "/materials.gltf");
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  const Scene& scene = loaded->scene;
  ASSERT_EQ(scene.objects.size(), 4u);
  std::vector<std::string> names;
  for (const SceneObject& o : scene.objects) names.push_back(o.name);
  EXPECT_EQ(names, (std::vector<std::string>{"materials.gltf/Red", "materials.gltf/BlueGlass",
                                             "materials.gltf/Floor", "ground"}));
  EXPECT_EQ(scene.objects[0].mesh->triangle_count(), 12u);
  EXPECT_FALSE(scene.objects[0].material.transparent());
  EXPECT_TRUE(scene.objects[1].material.transparent());  // alphaMode BLEND, alpha 0.4
  EXPECT_NEAR(scene.objects[1].material.opacity, 0.4f, 1e-6f);
  ASSERT_EQ(loaded->cameras.size(), 2u);
  EXPECT_EQ(scene.camera.position, loaded->cameras[0].camera.position);  // the first: ShotNode
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_NEAR(scene.lights[0].position.y, 4.0f, 1e-5f);

  ASSERT_TRUE(use_camera(*loaded, "SideNode").ok());
  EXPECT_EQ(loaded->scene.camera.position, loaded->cameras[1].camera.position);
  auto unknown = use_camera(*loaded, "Nope");
  ASSERT_FALSE(unknown.ok());
  EXPECT_EQ(unknown.error().message,
            "--camera Nope: no camera of that name; the scene's are ShotNode, SideNode");
}

TEST(MeshFileScene, AFileWithoutMaterialsCamerasOrLightsKeepsTheStages) {
  auto loaded = load_scene(std::string(SHADOWVOL_TEST_DATA) + "/cube_quads.obj");
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  Mesh cube = load_mesh(std::string(SHADOWVOL_TEST_DATA) + "/cube_quads.obj")->mesh;
  const Scene stage = default_stage("cube_quads.obj", cube);
  ASSERT_EQ(loaded->scene.objects.size(), 2u);
  EXPECT_EQ(loaded->scene.objects[0].name, "cube_quads.obj");
  EXPECT_EQ(loaded->scene.objects[0].material, stage.objects[0].material);
  EXPECT_EQ(loaded->scene.camera.position, stage.camera.position);
  EXPECT_EQ(loaded->scene.lights.size(), stage.lights.size());
  auto none = use_camera(*loaded, "Any");
  ASSERT_FALSE(none.ok());
  EXPECT_EQ(none.error().message, "--camera Any: the scene has no cameras of its own");
}

// "opacity": below 1, a transparent caster whose shadow passes (1 - opacity) * color.
TEST(SceneFile, OpacityMakesATransparentCaster) {
  const auto path = write_temp("glass", R"({
    "camera": {"position": [0, 2, 5], "target": [0, 0, 0]},
    "lights": [{"position": [4, 5, 0]}],
    "objects": [{"shape": "box", "color": [1, 0.5, 0], "opacity": 0.25}, {"shape": "ground"}]})");
  auto scene = load_scene_file(path);
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  EXPECT_TRUE(scene->objects[0].material.transparent());
  EXPECT_EQ(scene->objects[0].material.transmittance(), glm::vec3(0.75f, 0.375f, 0.0f));
  EXPECT_FALSE(scene->objects[1].material.transparent());
  EXPECT_TRUE(has_transparent_casters(*scene));
}

TEST(SceneFile, OpaqueMakesEveryCasterOpaque) {
  const auto path = write_temp("opaque", R"({
    "camera": {"position": [0, 2, 5], "target": [0, 0, 0]}, "opaque": true,
    "lights": [{"position": [4, 5, 0]}],
    "objects": [{"shape": "box", "color": [1, 0.5, 0], "opacity": 0.25}, {"shape": "ground"}]})");
  auto scene = load_scene_file(path);
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  EXPECT_FALSE(has_transparent_casters(*scene));
  EXPECT_EQ(scene->objects[0].material.color, glm::vec3(1.0f, 0.5f, 0.0f));
  auto bad = load_scene_file(write_temp("opaque_bad", R"({
    "camera": {"position": [0, 2, 5], "target": [0, 0, 0]}, "opaque": "yes",
    "lights": [{"position": [4, 5, 0]}], "objects": [{"shape": "box"}]})"));
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("scene.opaque: expected true or false"), std::string::npos)
      << bad.error().message;
}

// "decompose": each connected part its own object (Laine 2005 §6), vertices that a file repeats
// per face joined by position: two faces written with six vertices are one part.
TEST(SceneFile, DecomposeMakesAnObjectPerConnectedPart) {
  const auto obj = std::filesystem::temp_directory_path() / "shadowvol_test_parts.obj";
  std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                        "v 1 0 0\nv 1 1 0\nv 0 1 0\n"
                        "v 5 0 0\nv 6 0 0\nv 5 1 0\n"
                        "f 1 2 3\nf 4 5 6\nf 7 8 9\n";
  const std::string scene_json = R"({
    "camera": {"position": [0, 2, 5], "target": [0, 0, 0]},
    "lights": [{"position": [4, 5, 0]}],
    "objects": [{"name": "pair", "mesh": ")" +
                                 obj.string() + R"(", "decompose": DECOMPOSE,
                 "split_plane": "ppl"}]})";
  const auto with = [&](const std::string& value) {
    std::string text = scene_json;
    text.replace(text.find("DECOMPOSE"), 9, value);
    return load_scene_file(write_temp("decompose_" + value, text));
  };
  auto whole = with("false");
  ASSERT_TRUE(whole.ok()) << whole.error().message;
  ASSERT_EQ(whole->objects.size(), 1u);
  EXPECT_EQ(whole->objects[0].name, "pair");
  auto parts = with("true");
  ASSERT_TRUE(parts.ok()) << parts.error().message;
  ASSERT_EQ(parts->objects.size(), 2u);
  EXPECT_EQ(parts->objects[0].name, "pair/1");
  EXPECT_EQ(parts->objects[0].mesh->triangle_count(), 2u);
  EXPECT_EQ(parts->objects[1].name, "pair/2");
  EXPECT_EQ(parts->objects[1].mesh->triangle_count(), 1u);
  EXPECT_EQ(parts->objects[1].split_plane, SplitPlaneChoice::point_point_light);
  auto bad = with("\"yes\"");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("objects[0].decompose: expected true or false"),
            std::string::npos)
      << bad.error().message;
}

// Who casts and receives, and a point light's range (Intel's occluders; GPU Gems 3 §11.2.3).
TEST(SceneFile, CasterFlagsAndLightRange) {
  const auto path = write_temp("flags", R"({
    "camera": {"position": [0, 2, 5], "target": [0, 0, 0]},
    "lights": [{"position": [4, 5, 0], "range": 12.5}, {"position": [0, 5, 0]}],
    "objects": [{"shape": "box", "casts_shadows": false},
                {"shape": "ground", "receives_shadows": false}, {"shape": "torus"}]})");
  auto scene = load_scene_file(path);
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  EXPECT_FALSE(scene->objects[0].casts_shadows);
  EXPECT_TRUE(scene->objects[0].receives_shadows);
  EXPECT_TRUE(scene->objects[1].casts_shadows);
  EXPECT_FALSE(scene->objects[1].receives_shadows);
  EXPECT_TRUE(scene->objects[2].casts_shadows && scene->objects[2].receives_shadows);
  EXPECT_EQ(scene->lights[0].range, 12.5f);
  EXPECT_TRUE(scene->lights[0].limited());
  EXPECT_FALSE(scene->lights[1].limited());
}

struct Bad {
  std::string name;
  std::string json;
  std::string message;  // after "<file>: " (the JSON parser's own detail may follow)
};

void PrintTo(const Bad& bad, std::ostream* os) { *os << bad.name; }

class SceneFileRefuses : public ::testing::TestWithParam<Bad> {};

TEST_P(SceneFileRefuses, WithTheKeyPath) {
  const auto path = write_temp(GetParam().name, GetParam().json);
  auto scene = load_scene_file(path);
  ASSERT_FALSE(scene.ok());
  const std::string expected = path.string() + ": " + GetParam().message;
  EXPECT_EQ(scene.error().message.substr(0, expected.size()), expected);
}

constexpr const char* kCamera = R"("camera": {"position": [0, 2, 5], "target": [0, 0, 0]})";
constexpr const char* kLight = R"("lights": [{"position": [1, 5, 1]}])";

INSTANTIATE_TEST_SUITE_P(
    BadFiles, SceneFileRefuses,
    ::testing::Values(
        Bad{"not_json", "{ camera: ", "scene: not valid JSON (parse error at line 1, column 3"},
        Bad{"syntax_in_a_light", R"({"camera": {"position": [0,2,5], "target": [0,0,0]},
              "lights": [{"position": [1, 5 1]}]})",
            "scene.lights[0].position[2]: not valid JSON (parse error at line 2"},
        // nlohmann throws out_of_range for a number beyond a double: named with its key path.
        Bad{"fov_past_a_double", R"({"camera": {"position": [0,2,5], "target": [0,0,0],
              "fov": 1e400}})",
            "scene.camera.fov: the number 1e400 is beyond the range of a double"},
        Bad{"negative_past_a_double", R"({"camera": {"position": [0,2,5], "target": [0,0,0]},
              "lights": [{"color": [1, 1, 1]}, {"position": [1, -1e400, 1]}]})",
            "scene.lights[1].position[1]: the number -1e400 is beyond the range of a double"},
        Bad{"integer_past_a_double",
            R"({"camera": {"position": [0,2,5], "target": [0,0,0]},
              "lights": [{"position": [0,5,0]}], "objects": [{"shape": "box", "transform":
              {"translate": [)"
            "1" +
                std::string(400, '0') + R"(, 0, 0]}}]})",
            "scene.objects[0].transform.translate[0]: the number 1" + std::string(400, '0') +
                " is beyond the range of a double"},
        Bad{"invalid_utf8",
            "{\"camera\": {\"position\": [0,2,5], \"target\": [0,0,0]}, \"lig\xff\": 1}",
            "scene: not valid JSON (parse error at line 1, column"},
        Bad{"range_of_a_direction",
            R"({"camera": {"position": [0,2,5], "target": [0,0,0]},
                "lights": [{"direction": [0,-1,0], "range": 5}], "objects": []})",
            "scene.lights[0].range: only a point light (position) has a range"},
        Bad{"zero_range",
            R"({"camera": {"position": [0,2,5], "target": [0,0,0]},
                "lights": [{"position": [0,5,0], "range": 0}], "objects": []})",
            "scene.lights[0].range: must be positive (leave it out for none)"},
        Bad{"casts_not_a_flag",
            R"({"camera": {"position": [0,2,5], "target": [0,0,0]},
                "lights": [{"position": [0,5,0]}],
                "objects": [{"shape": "box", "casts_shadows": 1}]})",
            "scene.objects[0].casts_shadows: expected true or false"},
        Bad{"no_camera", R"({"lights": [], "objects": []})", "scene.camera: missing"},
        Bad{"unknown_key", R"({"camera": {"position": [0,2,5], "target": [0,0,0], "zoom": 2}})",
            "scene.camera.zoom: unknown key (expected one of: position, target, up, fov, near, "
            "orbit, move)"},
        Bad{"short_vector", R"({"camera": {"position": [0, 2], "target": [0,0,0]}})",
            "scene.camera.position: expected 3 numbers [x, y, z], got array"},
        Bad{"up_along_view", R"({"camera": {"position": [0,2,5], "target": [0,50,5]}})",
            "scene.camera.up: parallel to the direction the camera looks in"},
        Bad{"no_lights", R"({"camera": {"position": [0,2,5], "target": [0,0,0]}, "objects": []})",
            "scene.lights: expected a list of at least one light"},
        Bad{"light_both", R"({"camera": {"position": [0,2,5], "target": [0,0,0]},
              "lights": [{"position": [1,1,1], "direction": [0,1,0]}], "objects": []})",
            "scene.lights[0]: give either position (a point light) or direction (a directional "
            "light)"},
        Bad{"zero_direction", R"({"camera": {"position": [0,2,5], "target": [0,0,0]},
              "lights": [{"direction": [0,0,0]}], "objects": []})",
            "scene.lights[0]: a directional light needs a direction: x, y and z are all 0"},
        Bad{"bad_scale", R"({"camera": {"position": [0,2,5], "target": [0,0,0]},
              "lights": [{"position": [1,5,1]}],
              "objects": [{"shape": "box"}, {"shape": "box", "transform": {"scale": "big"}}]})",
            "scene.objects[1].transform.scale: expected 3 numbers [x, y, z], got string"},
        Bad{"unknown_shape", R"({"camera": {"position": [0,2,5], "target": [0,0,0]},
              "lights": [{"position": [1,5,1]}], "objects": [{"shape": "teapot"}]})",
            "scene.objects[0].shape: unknown shape 'teapot' (expected box, open_box, ground, torus, "
            "bumpy_torus, tube or sphere)"},
        Bad{"missing_mesh", R"({"camera": {"position": [0,2,5], "target": [0,0,0]},
              "lights": [{"position": [1,5,1]}], "objects": [{"mesh": "/nonexistent/x.obj"}]})",
            "scene.objects[0].mesh: /nonexistent/x.obj: no such file"},
        Bad{"bad_color", R"({"camera": {"position": [0,2,5], "target": [0,0,0]},
              "lights": [{"position": [1,5,1]}], "objects": [{"shape": "box", "color": [1, -1, 0]}]})",
            "scene.objects[0].color: a colour channel must lie in [0, 1000]"},
        Bad{"bad_opacity", R"({"camera": {"position": [0,2,5], "target": [0,0,0]},
              "lights": [{"position": [1,5,1]}], "objects": [{"shape": "box", "opacity": 1.5}]})",
            "scene.objects[0].opacity: must lie in [0, 1] (1 is opaque)"},
        Bad{"bright_glass", R"({"camera": {"position": [0,2,5], "target": [0,0,0]},
              "lights": [{"position": [1,5,1]}],
              "objects": [{"shape": "box", "opacity": 0.5, "color": [2, 1, 1]}]})",
            "scene.objects[0].color: a transparent object's colour filters the light it passes, "
            "so each channel must lie in [0, 1]"},
        Bad{"unknown_clip",
            std::string(R"({"camera": {"position": [0,2,5], "target": [0,0,0]},
              "lights": [{"position": [1,5,1]}], "objects": [{"mesh": ")") +
                SHADOWVOL_SOURCE_DIR + R"(/scenes/meshes/turntable.gltf", "clip": "Walk"}]})",
            "scene.objects[0].clip: no animation named 'Walk'; the file's are 'Spin', 'Hop'"},
        Bad{"clip_of_a_still_file",
            std::string(R"({"camera": {"position": [0,2,5], "target": [0,0,0]},
              "lights": [{"position": [1,5,1]}], "objects": [{"mesh": ")") +
                SHADOWVOL_TEST_DATA + R"(/materials.gltf", "clip": "Spin"}]})",
            "scene.objects[0].clip: no animation named 'Spin'; the file has none"},
        Bad{"clip_not_a_name",
            std::string(R"({"camera": {"position": [0,2,5], "target": [0,0,0]},
              "lights": [{"position": [1,5,1]}], "objects": [{"mesh": ")") +
                SHADOWVOL_SOURCE_DIR + R"(/scenes/meshes/turntable.gltf", "clip": 0}]})",
            "scene.objects[0].clip: expected an animation's name, or null to hold the file still"},
        Bad{"zero_frames_per_second",
            std::string(R"({"camera": {"position": [0,2,5], "target": [0,0,0]},
              "lights": [{"position": [1,5,1]}], "objects": [{"mesh": ")") +
                SHADOWVOL_SOURCE_DIR + R"(/scenes/meshes/turntable.gltf",
                "frames_per_second": 0}]})",
            "scene.objects[0].frames_per_second: must be positive"},
        Bad{"clip_of_a_shape", R"({"camera": {"position": [0,2,5], "target": [0,0,0]},
              "lights": [{"position": [1,5,1]}], "objects": [{"shape": "box", "clip": "Spin"}]})",
            "scene.objects[0].clip: only a mesh file has animations of its own"}),
    [](const auto& info) { return info.param.name; });

// Whatever kind of nlohmann error escapes the reader, the message names the key path, the kind
// and nlohmann's detail without its "[json.exception...]" prefix.
TEST(SceneFile, EveryJsonErrorKindIsDescribed) {
  using nlohmann::json;
  const auto described = [](auto&& provoke) {
    try {
      provoke();
    } catch (const json::exception& e) {
      return describe_json_error(e, "scene.objects[2]");
    }
    return std::string("nothing thrown");
  };
  const std::string parse = described([] { [[maybe_unused]] const json j = json::parse("[1,"); });
  EXPECT_EQ(parse.rfind("scene.objects[2]: not valid JSON (parse error at line 1", 0), 0u) << parse;
  const std::string type =
      described([] { [[maybe_unused]] const auto s = json(1).get<std::string>(); });
  EXPECT_EQ(type,
            "scene.objects[2]: a value of the wrong type (type must be string, but is number)");
  const std::string range = described([] { [[maybe_unused]] const json j = json::array().at(3); });
  EXPECT_EQ(range, "scene.objects[2]: a value out of range (array index 3 is out of range)");
  const std::string overflow =
      described([] { [[maybe_unused]] const json j = json::parse("[-1e999]"); });
  EXPECT_EQ(overflow, "scene.objects[2]: the number -1e999 is beyond the range of a double");
  const std::string iterator = described([] {
    json a = json::array({1}), b = json::array({2});
    a.erase(b.begin());
  });
  EXPECT_EQ(iterator.rfind("scene.objects[2]: an invalid position (iterator does not fit", 0), 0u)
      << iterator;
  const std::string other = described([] {
    [[maybe_unused]] const json j =
        json::object().patch(json::parse(R"([{"op": "test", "path": "/a", "value": 1}])"));
  });
  EXPECT_EQ(other.rfind("scene.objects[2]: a JSON error (", 0), 0u) << other;
  EXPECT_NE(other.find("unsuccessful"), std::string::npos) << other;
}

}  // namespace
}  // namespace shadowvol
