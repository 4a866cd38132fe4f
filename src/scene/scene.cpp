#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/common.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "core/names.h"
#include "core/projection.h"
#include "core/shapes.h"
#include "scene/city.h"
#include "scene/night_street.h"

namespace shadowvol {

glm::mat4 Camera::view_from_eye() const {
  return glm::lookAt(glm::vec3(0.0f), target - position, up);
}

glm::mat4 eye_relative(const glm::mat4& transform, const glm::vec3& eye) {
  return glm::mat4(glm::translate(glm::dmat4(1.0), -glm::dvec3(eye)) * glm::dmat4(transform));
}

glm::vec4 eye_relative(const glm::vec4& point, const glm::vec3& eye) {
  const glm::dvec4 p(point);
  return glm::vec4(p - glm::dvec4(glm::dvec3(eye) * p.w, 0.0));
}

glm::mat4 Camera::projection(float aspect) const {
  return infinite_reversed_perspective(glm::radians(fov_y_degrees), aspect, near);
}

Scene scene_at_frame(const Scene& scene, int frame) {
  Scene s = scene;
  const float f = static_cast<float>(frame);
  const auto animated = [](const Animation& a, const glm::mat4& transform, float frames) {
    if (a.still()) return transform;
    return glm::translate(glm::mat4(1.0f), a.move * frames) * transform *
           glm::rotate(glm::mat4(1.0f), glm::radians(a.degrees_per_frame * frames), a.spin_axis);
  };
  for (SceneObject& o : s.objects) {
    if (o.node.bound()) {  // from the clip's start, so that frames add up exactly
      o.node.frame += frame;
      o.transform = animated(o.animation, o.node.transform_at(o.node.frame),
                             static_cast<float>(o.node.frame));
    } else {
      o.transform = animated(o.animation, o.transform, f);
    }
  }
  const auto turn_about_y = [f](float degrees_per_frame) {
    return glm::rotate(glm::mat4(1.0f), glm::radians(degrees_per_frame * f), glm::vec3(0, 1, 0));
  };
  for (SceneLight& l : s.lights)
    if (l.orbit_degrees_per_frame != 0.0f)
      l.position = turn_about_y(l.orbit_degrees_per_frame) * l.position;
  Camera& c = s.camera;
  if (c.orbit_degrees_per_frame != 0.0f) {  // the whole rig turns, up too: it stays valid
    const glm::mat4 turn = turn_about_y(c.orbit_degrees_per_frame);
    c.position = c.target + glm::vec3(turn * glm::vec4(c.position - c.target, 0.0f));
    c.up = glm::vec3(turn * glm::vec4(c.up, 0.0f));
  }
  c.position += c.move * f;
  c.target += c.move * f;
  return s;
}

std::string_view to_string(SplitPlaneChoice choice) {
  switch (choice) {
    case SplitPlaneChoice::automatic:
      return "auto";
    case SplitPlaneChoice::point_camera_light:
      return "pcl";
    case SplitPlaneChoice::point_point_light:
      return "ppl";
    case SplitPlaneChoice::flat:
      return "flat";
  }
  return "unknown";
}

Expected<SplitPlaneChoice> parse_split_plane_choice(std::string_view name) {
  return parse_name(name,
                    {SplitPlaneChoice::automatic, SplitPlaneChoice::point_camera_light,
                     SplitPlaneChoice::point_point_light, SplitPlaneChoice::flat},
                    "split plane");
}

SceneObject make_object(std::string name, Mesh mesh, const glm::mat4& transform,
                        const Material& material) {
  auto shared = std::make_shared<const Mesh>(std::move(mesh));
  auto topology = std::make_shared<const Topology>(build_topology(*shared));
  return {std::move(name), std::move(shared), std::move(topology), transform, material, {}};
}

void set_shading_normals(SceneObject& object, std::vector<glm::vec3> corner_normals) {
  object.shading = corner_normals.empty() || !object.mesh
                       ? nullptr
                       : std::make_shared<const ShadingNormals>(
                             make_shading_normals(*object.mesh, std::move(corner_normals)));
}

void shade_flat(Scene& scene) {
  for (SceneObject& o : scene.objects) o.shading = nullptr;
}

void make_opaque(Scene& scene) {
  for (SceneObject& o : scene.objects) o.material.opacity = 1.0f;
}

bool has_transparent_casters(const Scene& scene) {
  return std::any_of(scene.objects.begin(), scene.objects.end(),
                     [](const SceneObject& o) { return o.material.transparent(); });
}

namespace {

glm::mat4 place(glm::vec3 at, float yaw_degrees = 0.0f, glm::vec3 scale = glm::vec3(1.0f)) {
  glm::mat4 m = glm::translate(glm::mat4(1.0f), at);
  m = glm::rotate(m, glm::radians(yaw_degrees), glm::vec3(0, 1, 0));
  return glm::scale(m, scale);
}

// Turns +z (the open side of make_box(..., false), the axis of make_bumpy_torus) to +y.
const glm::mat4 kZUp = glm::rotate(glm::mat4(1.0f), glm::radians(-90.0f), glm::vec3(1, 0, 0));

void add_ground(Scene& s, float half_size = 7.0f) {
  s.objects.push_back(
      make_object("ground", make_ground(half_size), glm::mat4(1.0f), {0.75f, 0.75f, 0.72f}));
}

void add_demo_objects(Scene& s) {
  add_ground(s);
  s.objects.push_back(
      make_object("torus", make_bumpy_torus(96, 32, 0.9f, 0.3f),
                  place({-1.7f, 1.5f, 0.2f}, 20.0f) *
                      glm::rotate(glm::mat4(1.0f), glm::radians(-35.0f), glm::vec3(1, 0, 0)),
                  {0.85f, 0.35f, 0.25f}));
  s.objects.push_back(make_object("box", make_box(glm::vec3(-0.6f), glm::vec3(0.6f)),
                                  place({1.6f, 0.6f, 0.6f}, 30.0f), {0.3f, 0.55f, 0.85f}));
  s.objects.push_back(make_object("open_box",
                                  make_box({-0.7f, -0.7f, -0.5f}, {0.7f, 0.7f, 0.5f}, false),
                                  place({0.2f, 0.5f, -2.2f}, -15.0f) * kZUp, {0.9f, 0.75f, 0.3f}));
}

Scene demo() {
  Scene s;
  s.name = "demo";
  add_demo_objects(s);
  s.objects[1].animation = {{0.0f, 0.0f, 1.0f}, 3.0f, glm::vec3(0.0f)};  // the torus spins
  s.lights.push_back({{4.0f, 7.0f, 5.0f, 1.0f}, {1.0f, 0.97f, 0.9f}, 1.0f});
  s.camera = {{0.0f, 4.5f, 9.0f}, {0.0f, 0.6f, -0.3f}};
  return s;
}

Scene camera_in_shadow() {
  Scene s;
  s.name = "camera-in-shadow";
  add_ground(s);
  // A slab between the light and the eye: the eye sits in the slab's shadow volume.
  s.objects.push_back(make_object("slab", make_box({-3.0f, -0.2f, -3.0f}, {3.0f, 0.2f, 3.0f}),
                                  place({0.0f, 5.0f, 3.0f}), {0.5f, 0.5f, 0.55f}));
  s.objects.push_back(make_object("box", make_box(glm::vec3(-0.6f), glm::vec3(0.6f)),
                                  place({0.8f, 0.6f, -2.5f}, 25.0f), {0.3f, 0.55f, 0.85f}));
  s.objects.push_back(make_object("torus", make_bumpy_torus(64, 24, 0.8f, 0.28f),
                                  place({-1.5f, 0.35f, -1.5f}) * kZUp, {0.85f, 0.35f, 0.25f}));
  s.lights.push_back({{0.5f, 12.0f, 6.0f, 1.0f}, {1.0f, 1.0f, 1.0f}, 1.0f});
  s.camera = {{0.0f, 2.0f, 3.5f}, {0.0f, 0.3f, -3.0f}};
  return s;
}

Scene light_in_view() {
  Scene s;
  s.name = "light-in-view";
  add_ground(s);
  s.objects.push_back(make_object("torus", make_bumpy_torus(96, 32, 0.8f, 0.25f),
                                  place({0.0f, 0.9f, 0.0f}, 0.0f, glm::vec3(1.4f)) * kZUp,
                                  {0.85f, 0.35f, 0.25f}));
  for (int i = 0; i < 4; ++i) {
    const float a = glm::radians(45.0f + 90.0f * i);
    s.objects.push_back(make_object(
        "box" + std::to_string(i), make_box(glm::vec3(-0.35f), glm::vec3(0.35f)),
        place({2.2f * std::cos(a), 0.35f, 2.2f * std::sin(a)}, 10.0f * i), {0.3f, 0.55f, 0.85f}));
  }
  // The light hangs inside the torus, in view; the camera looks at it from close by.
  s.lights.push_back({{0.0f, 1.3f, 0.0f, 1.0f}, {1.0f, 0.95f, 0.85f}, 1.0f});
  s.camera = {{0.3f, 2.2f, 3.2f}, {0.0f, 1.0f, 0.0f}};
  return s;
}

Scene directional() {
  Scene s;
  s.name = "directional";
  add_demo_objects(s);
  s.lights.push_back({{0.45f, 1.0f, 0.35f, 0.0f}, {1.0f, 0.97f, 0.9f}, 1.0f});
  s.camera = {{0.0f, 4.5f, 9.0f}, {0.0f, 0.6f, -0.3f}};
  return s;
}

Mesh fin_box() {  // a closed box with a fin on one top edge: three faces on that edge
  Mesh m = make_box(glm::vec3(-0.5f), glm::vec3(0.5f));
  const auto base = static_cast<std::uint32_t>(m.positions.size());
  m.positions.emplace_back(0.0f, -1.2f, 1.0f);
  m.indices.insert(m.indices.end(), {4, 5, base});  // on edge 4-5 (top, front)
  return m;
}

Mesh flipped_box() {  // one triangle wound the wrong way: three inconsistent edges
  Mesh m = make_box(glm::vec3(-0.5f), glm::vec3(0.5f));
  std::swap(m.indices[4], m.indices[5]);
  return m;
}

Mesh coincident_box() {  // one face doubled, once each way
  Mesh m = make_box(glm::vec3(-0.5f), glm::vec3(0.5f));
  const std::vector<std::uint32_t> top(m.indices.begin() + 6, m.indices.begin() + 12);
  m.indices.insert(m.indices.end(), top.begin(), top.end());
  m.indices.insert(m.indices.end(), {top[0], top[2], top[1]});
  return m;
}

Mesh book() {  // four pages on one spine, with slivers and a collapsed triangle
  Mesh m;
  auto add = [&m](glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    m.positions.insert(m.positions.end(), {a, b, c});
    m.indices.insert(m.indices.end(), {base, base + 1, base + 2});
  };
  for (glm::vec3 tip : {glm::vec3(0.9f, 0.1f, 0), glm::vec3(0, 0.9f, 0.2f),
                        glm::vec3(-0.9f, 0.2f, 0), glm::vec3(0.1f, 0.6f, -0.8f)})
    add({0, 0, -0.6f}, {0, 0, 0.6f}, tip);
  add({0, 0, -0.6f}, {0, 0, 0}, {0, 0, 0.6f});             // zero area on the spine
  add({0.5f, 0.5f, 0}, {0.5f, 0.5f, 0}, {0, 0.9f, 0.2f});  // collapsed
  return m;
}

Scene nonmanifold() {
  Scene s;
  s.name = "nonmanifold";
  add_ground(s);
  s.objects.push_back(
      make_object("fin_box", fin_box(), place({-2.0f, 0.6f, 0.0f}, 25.0f), {0.85f, 0.35f, 0.25f}));
  s.objects.push_back(make_object("flipped_box", flipped_box(), place({0.0f, 0.6f, 0.8f}, -20.0f),
                                  {0.3f, 0.55f, 0.85f}));
  s.objects.push_back(make_object("coincident_box", coincident_box(),
                                  place({2.0f, 0.6f, 0.0f}, 40.0f), {0.4f, 0.75f, 0.4f}));
  s.objects.push_back(make_object(
      "book", book(), place({0.2f, 1.4f, -2.0f}, 30.0f, glm::vec3(1.5f)), {0.9f, 0.75f, 0.3f}));
  s.objects.push_back(make_object(
      "open_box", make_box({-0.6f, -0.6f, -0.4f}, {0.6f, 0.6f, 0.4f}, false),
      place({-1.0f, 1.6f, -1.2f}, 10.0f) * glm::rotate(glm::mat4(1.0f), 0.6f, glm::vec3(1, 0, 1)),
      {0.7f, 0.4f, 0.8f}));
  s.lights.push_back({{3.0f, 6.5f, 4.0f, 1.0f}, {1.0f, 0.97f, 0.9f}, 1.0f});
  s.camera = {{0.0f, 4.0f, 8.0f}, {0.0f, 0.6f, -0.5f}};
  return s;
}

// Kim, Kim & Turk 2008's transparent casters: closed, open and non-manifold, in colours that
// overlap (red over blue and green, amber over the rest), one opaque caster among them, on a
// white ground that shows the coloured light, under two lights.
Scene glass() {
  Scene s;
  s.name = "glass";
  s.objects.push_back(
      make_object("ground", make_ground(6.0f), glm::mat4(1.0f), {0.85f, 0.85f, 0.83f}));
  s.objects.push_back(make_object("ruby_ball", make_sphere(glm::vec3(0.0f), 0.65f, 24, 48),
                                  place({0.7f, 2.0f, -1.4f}), {{1.0f, 0.2f, 0.15f}, 0.45f}));
  s.objects.push_back(make_object("sapphire_box", make_box(glm::vec3(-0.5f), glm::vec3(0.5f)),
                                  place({0.2f, 0.9f, -0.3f}, 35.0f), {{0.2f, 0.45f, 1.0f}, 0.4f}));
  s.objects.push_back(make_object("emerald_cup",  // open: a box without its top
                                  make_box({-0.55f, -0.55f, -0.4f}, {0.55f, 0.55f, 0.4f}, false),
                                  place({1.5f, 1.1f, 0.7f}, -20.0f) * kZUp,
                                  {{0.25f, 1.0f, 0.35f}, 0.5f}));
  s.objects.push_back(make_object("amber_book",  // non-manifold: four pages on one spine
                                  book(), place({-1.4f, 1.9f, -0.2f}, 25.0f, glm::vec3(1.1f)),
                                  {{1.0f, 0.75f, 0.2f}, 0.55f}));
  s.objects.push_back(make_object("stone_torus", make_bumpy_torus(64, 24, 0.6f, 0.2f),
                                  place({-2.4f, 0.45f, -1.3f}, 30.0f) * kZUp,
                                  {0.55f, 0.55f, 0.6f}));
  // The main light behind the casters, so that their shadows fall towards the eye.
  s.lights.push_back({{1.5f, 6.0f, -3.5f, 1.0f}, {1.0f, 0.97f, 0.9f}, 0.8f});
  s.lights.push_back({{-4.5f, 5.5f, 2.5f, 1.0f}, {0.85f, 0.9f, 1.0f}, 0.25f});
  s.ambient = glm::vec3(0.1f);
  s.camera = {{0.0f, 4.6f, 8.2f}, {0.0f, 0.7f, -0.2f}};
  return s;
}

// Laine 2005's test scenes, in their spirit (Table 1): a light circling overhead, frame by
// frame, the camera turning about the casters and the knights turning, so that `bench --frames
// N` sees an animation.
constexpr SceneLight kCirclingLight = {{3.5f, 6.0f, 2.5f, 1.0f}, {1.0f, 0.97f, 0.9f}, 1.0f, 4.0f};
// Laine's viewpoint moves too (§7): the camera turns the other way, half as fast, so that over
// the light's full circle it sees the casters from half way round.
constexpr float kCameraOrbit = -2.0f;

Scene knight() {
  Scene s;
  s.name = "knight";
  add_ground(s, 5.0f);
  s.objects.push_back(
      make_object("knight", make_knight(), place({0.0f, 0.0f, 0.0f}, 20.0f), {0.7f, 0.72f, 0.78f}));
  s.objects.back().animation = {{0.0f, 1.0f, 0.0f}, 2.0f, glm::vec3(0.0f)};
  s.lights.push_back(kCirclingLight);
  s.camera = {{0.5f, 2.2f, 4.2f}, {0.0f, 1.0f, 0.0f}};
  s.camera.orbit_degrees_per_frame = kCameraOrbit;
  return s;
}

Scene knights16() {
  Scene s;
  s.name = "knights16";
  add_ground(s, 9.0f);
  const auto shared = std::make_shared<const Mesh>(make_knight());
  const auto topology = std::make_shared<const Topology>(build_topology(*shared));
  for (int i = 0; i < 16; ++i) {
    const float x = 1.6f * static_cast<float>(i % 4) - 2.4f,
                z = 1.6f * static_cast<float>(i / 4) - 2.4f;
    SceneObject knight{"knight" + std::to_string(i),
                       shared,
                       topology,
                       place({x, 0.0f, z}, 37.0f * static_cast<float>(i)),
                       {{0.7f, 0.72f, 0.78f}},
                       {}};
    knight.animation = {{0.0f, 1.0f, 0.0f}, i % 2 ? 2.0f : -2.0f, glm::vec3(0.0f)};
    s.objects.push_back(std::move(knight));
  }
  s.lights.push_back(kCirclingLight);
  s.camera = {{1.0f, 5.5f, 8.5f}, {0.0f, 0.6f, 0.0f}};
  s.camera.orbit_degrees_per_frame = kCameraOrbit;
  return s;
}

// CC shadow volumes' robot scene (Lloyd et al. 2004 §4, Fig. 6): a crowd of 96 robots marching
// across a large walled room, lit by a low light near one wall behind a row of crates, so that
// many robots stand in the crates' shadows or those of robots nearer the light: culling's case.
// About 100k triangles.
Scene robots() {
  Scene s;
  s.name = "robots";
  constexpr float kRoom = 20.0f;
  add_ground(s, kRoom);
  const glm::vec3 wall(0.7f, 0.68f, 0.62f);
  for (int i = 0; i < 4; ++i) {  // walls 4 units high, 0.4 thick, each an object of its own
    const bool along_x = i < 2;
    const float at = i % 2 ? kRoom : -kRoom - 0.4f;
    const glm::vec3 lo = along_x ? glm::vec3(-kRoom, 0.0f, at) : glm::vec3(at, 0.0f, -kRoom);
    const glm::vec3 hi =
        lo + (along_x ? glm::vec3(2.0f * kRoom, 4.0f, 0.4f) : glm::vec3(0.4f, 4.0f, 2.0f * kRoom));
    s.objects.push_back(
        make_object("wall" + std::to_string(i), make_box(lo, hi), glm::mat4(1.0f), wall));
  }
  // Crates stacked between the light and the crowd: what stands in their shadow is culled.
  for (int i = 0; i < 4; ++i)
    s.objects.push_back(make_object(
        "crate" + std::to_string(i), make_box({-1.3f, 0.0f, -1.3f}, {1.3f, 3.2f, 1.3f}),
        place({-11.0f, 0.0f, -9.0f + 6.0f * static_cast<float>(i)}, 10.0f * static_cast<float>(i)),
        {0.55f, 0.42f, 0.3f}));
  const auto shared = std::make_shared<const Mesh>(make_robot());
  const auto topology = std::make_shared<const Topology>(build_topology(*shared));
  for (int i = 0; i < 96; ++i) {
    const int row = i / 12, column = i % 12;
    const float x = 2.2f * static_cast<float>(row) - 9.0f + (column % 2 ? 0.5f : 0.0f);
    const float z = 2.3f * static_cast<float>(column) - 12.6f;
    const glm::vec3 colour =
        row % 2 ? glm::vec3(0.75f, 0.55f, 0.3f) : glm::vec3(0.45f, 0.6f, 0.75f);
    SceneObject robot{"robot" + std::to_string(i),
                      shared,
                      topology,
                      place({x, 0.0f, z}, 90.0f + 7.0f * static_cast<float>(i % 5)),
                      {colour},
                      {}};
    // The crowd marches towards the light, each row at its own pace.
    robot.animation.move = {-0.04f - 0.01f * static_cast<float>(row % 3), 0.0f, 0.0f};
    s.objects.push_back(std::move(robot));
  }
  s.lights.push_back({{-18.0f, 1.6f, 1.0f, 1.0f}, {1.0f, 0.95f, 0.85f}, 1.0f});
  // Above every shadow volume, so that z-pass is exact here too.
  s.camera = {{18.0f, 16.0f, 18.0f}, {-3.0f, 0.0f, -1.0f}};
  return s;
}

// CC shadow volumes' corridor (Lloyd et al. 2004 §4, Fig. 1): a long hall open to the sun, its
// roof carried by trusses that hold most of its triangles and cast their shadows down across empty
// space onto the floor and the walls, with purlins and bracing between them, lamps hung from
// every other truss and a few crates on the floor. The camera walks its length (a unit a frame:
// 48 frames from one end to the other), looking ahead and up: clamping's case. About 100k
// triangles.
Scene corridor() {
  Scene s;
  s.name = "corridor";
  constexpr float kHalfWidth = 4.5f, kHalfLength = 32.0f, kWallHeight = 8.0f;
  constexpr float kTrussY = 5.4f, kTrussHeight = 0.9f, kTrussDepth = 0.6f;
  constexpr int kTrusses = 24, kPanels = 12;
  const glm::vec3 concrete(0.62f, 0.6f, 0.57f), steel(0.45f, 0.5f, 0.55f);
  s.objects.push_back(make_object(
      "floor", make_box({-kHalfWidth, -0.3f, -kHalfLength}, {kHalfWidth, 0.0f, kHalfLength}),
      glm::mat4(1.0f), {0.7f, 0.68f, 0.64f}));
  for (const float side : {-1.0f, 1.0f}) {
    const float inner = side * kHalfWidth, outer = side * (kHalfWidth + 0.4f);
    s.objects.push_back(make_object(side < 0 ? "left_wall" : "right_wall",
                                    make_box({std::min(inner, outer), 0.0f, -kHalfLength},
                                             {std::max(inner, outer), kWallHeight, kHalfLength}),
                                    glm::mat4(1.0f), concrete));
  }
  const auto truss = std::make_shared<const Mesh>(
      make_truss(kHalfWidth, kTrussHeight, kTrussDepth, kPanels, 0.045f, 12));
  const auto truss_topology = std::make_shared<const Topology>(build_topology(*truss));
  const float spacing = 2.0f * (kHalfLength - 2.0f) / float(kTrusses - 1);
  auto truss_z = [&](int k) { return -kHalfLength + 2.0f + spacing * float(k); };
  for (int k = 0; k < kTrusses; ++k)
    s.objects.push_back({"truss" + std::to_string(k),
                         truss,
                         truss_topology,
                         glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, kTrussY, truss_z(k))),
                         {steel},
                         {}});
  // Purlins along the hall between the trusses' top panel points, and cross bracing in every
  // other bay: one long object, which CC splits into sub-objects.
  Mesh purlins;
  const float step = 2.0f * kHalfWidth / float(kPanels);
  for (int k = 0; k + 1 < kTrusses; ++k) {
    const float z0 = truss_z(k), z1 = truss_z(k + 1), y = kTrussY + kTrussHeight;
    for (int i = 0; i < kPanels; ++i) {
      const float x = -kHalfWidth + step * (float(i) + 0.5f);
      append_mesh(purlins, make_tube({x, y, z0 + 0.5f * kTrussDepth},
                                     {x, y, z1 - 0.5f * kTrussDepth}, 0.035f, 0.035f, 12));
    }
    if (k % 2 == 0)  // an X of rods, each in four lengths joined at turnbuckles
      for (const float side : {-1.0f, 1.0f}) {
        const glm::vec3 a{-side * (kHalfWidth - 0.5f), y, z0}, b{side * (kHalfWidth - 0.5f), y, z1};
        for (int j = 0; j < 4; ++j)
          append_mesh(purlins, make_tube(a + (b - a) * (float(j) / 4.0f),
                                         a + (b - a) * (float(j + 1) / 4.0f), 0.03f, 0.03f, 12));
      }
  }
  s.objects.push_back(make_object("purlins", std::move(purlins), glm::mat4(1.0f), steel));
  // Lamps on cables under every other truss.
  for (int k = 1; k < kTrusses; k += 2) {
    Mesh lamp = make_tube({0.0f, kTrussY, 0.0f}, {0.0f, kTrussY - 1.6f, 0.0f}, 0.015f, 0.015f, 6);
    append_mesh(lamp, make_sphere({0.0f, kTrussY - 1.85f, 0.0f}, 0.25f, 12, 16));
    s.objects.push_back(make_object("lamp" + std::to_string(k / 2), std::move(lamp),
                                    glm::translate(glm::mat4(1.0f), {1.2f, 0.0f, truss_z(k)}),
                                    {0.85f, 0.8f, 0.6f}));
  }
  for (int i = 0; i < 6; ++i) {
    const float z = -22.0f + 9.0f * float(i), x = i % 2 ? 2.6f : -2.8f;
    s.objects.push_back(make_object("crate" + std::to_string(i),
                                    make_box({-0.6f, 0.0f, -0.6f}, {0.6f, 1.1f, 0.6f}),
                                    place({x, 0.0f, z}, 17.0f * float(i)), {0.55f, 0.42f, 0.3f}));
  }
  // The sun, high and from the side, through the open roof.
  s.lights.push_back({{0.3f, 1.0f, 0.2f, 0.0f}, {1.0f, 0.96f, 0.88f}, 1.0f});
  s.ambient = glm::vec3(0.15f);
  s.camera = {{-1.4f, 1.7f, -28.0f}, {0.0f, 3.6f, -18.0f}};
  s.camera.fov_y_degrees = 60.0f;
  s.camera.move = {0.0f, 0.0f, 1.0f};
  return s;
}

// `decomposed`: each connected part of the tree (a branch with its leaves) an object of its own,
// so that each gets its own split plane (Laine 2005 §6).
Scene tree(bool decomposed) {
  Scene s;
  s.name = decomposed ? "tree-decomposed" : "tree";
  add_ground(s, 7.0f);
  const glm::vec3 bark(0.55f, 0.42f, 0.3f);
  const glm::mat4 at = place({0.0f, 0.0f, 0.0f}, 0.0f, glm::vec3(1.3f));
  if (!decomposed) {
    s.objects.push_back(make_object("tree", make_tree(), at, bark));
  } else {
    int n = 0;
    for (Mesh& part : connected_parts(make_tree()))
      s.objects.push_back(make_object("branch" + std::to_string(n++), std::move(part), at, bark));
  }
  s.lights.push_back(kCirclingLight);
  s.camera = {{0.0f, 3.4f, 10.0f}, {0.0f, 2.5f, 0.0f}};
  s.camera.orbit_degrees_per_frame = kCameraOrbit;
  return s;
}

Scene tree_whole() { return tree(false); }
Scene tree_decomposed() { return tree(true); }

struct Builtin {
  std::string_view name;
  Scene (*make)();
};
constexpr Builtin kBuiltins[] = {
    {"demo", demo},
    {"camera-in-shadow", camera_in_shadow},
    {"light-in-view", light_in_view},
    {"directional", directional},
    {"nonmanifold", nonmanifold},
    {"glass", glass},
    {"knight", knight},
    {"knights16", knights16},
    {"robots", robots},
    {"corridor", corridor},
    {"tree", tree_whole},
    {"tree-decomposed", tree_decomposed},
    {"city", [] { return make_city(kDefaultCityBuildings, CityView::street); }},
    {"city-above", [] { return make_city(kDefaultCityBuildings, CityView::above); }},
    {"night-street", [] { return make_night_street(kDefaultStreetLamps); }}};

}  // namespace

Scene stage_around(std::string name, const Mesh& mesh) {
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const glm::vec3& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const glm::vec3 centre = (lo + hi) * 0.5f;
  const float size = std::max(glm::length(hi - lo), 1e-6f);
  Scene s;
  s.name = std::move(name);
  const glm::vec3 floor(centre.x, lo.y - 0.001f * size, centre.z);
  s.objects.push_back(make_object("ground", make_ground(2.0f * size),
                                  glm::translate(glm::mat4(1.0f), floor), {0.75f, 0.75f, 0.72f}));
  s.lights.push_back(
      {glm::vec4(centre + glm::vec3(0.6f, 1.4f, 0.8f) * size, 1.0f), {1, 0.97f, 0.9f}, 1.0f});
  s.camera = {centre + glm::vec3(0.0f, 0.7f, 1.6f) * size, centre, {0, 1, 0}, 45.0f, 0.01f * size};
  return s;
}

Scene default_stage(std::string name, Mesh mesh) {
  Scene s = stage_around(name, mesh);
  s.objects.insert(s.objects.begin(),
                   make_object(std::move(name), std::move(mesh), glm::mat4(1.0f), kStageColor));
  return s;
}

std::vector<std::string_view> builtin_scene_names() {
  std::vector<std::string_view> names;
  for (const Builtin& b : kBuiltins) names.push_back(b.name);
  return names;
}

Expected<Scene> builtin_scene(std::string_view name) {
  if (is_city_name(name)) return city_by_name(name);
  if (is_night_street_name(name)) return night_street_by_name(name);
  for (const Builtin& b : kBuiltins)
    if (b.name == name) return b.make();
  std::string known;
  for (const Builtin& b : kBuiltins) known += (known.empty() ? "" : ", ") + std::string(b.name);
  return make_error("unknown scene '" + std::string(name) + "': the built-in scenes are " + known +
                    " (city:N and city-above:N: a city of N buildings; night-street:N: N lamps)");
}

}  // namespace shadowvol
