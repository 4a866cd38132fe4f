// shadowvol scene: what a frame draws. Objects (mesh + topology + transform + material),
// lights, a camera; and the built-in scenes, each one there to break something.
//
// Owns: the scene description and its invariants (every object's topology belongs to its mesh;
// lights are valid, see core/volume.h check_light). No rendering, no tracing.
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "core/expected.h"
#include "core/mesh.h"
#include "core/shading_normals.h"
#include "core/topology.h"
#include "scene/node_animation.h"

namespace shadowvol {

// A surface's colour and opacity. An opaque surface (opacity 1) blocks a light; a transparent one
// (opacity < 1) passes the fraction (1 - opacity) * color of it, per channel, and a light crossing
// n such surfaces keeps that fraction to the power n (Kim, Kim & Turk 2008 §2): a colored,
// partial shadow. Casters of one material form one group, counted together.
// An image a surface takes its colour from: 8-bit sRGB, rows from the top (as image files hold
// them), sampled bilinearly in linear light, repeating beyond [0, 1) (glTF's default wrap).
struct Texture {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  // width * height * 4
  std::string source;              // where it came from, for messages
};

struct Material {
  glm::vec3 color{0.8f};  // linear RGB albedo, and the filter colour of a transparent surface
  float opacity = 1.0f;   // in [0, 1]
  // The albedo is color times this map's colour at the surface's texture coordinates
  // (SceneObject::uvs); the light a transparent surface passes is not: shadows stay the
  // material's colour, as the reference traces them.
  std::shared_ptr<const Texture> base_color_map = nullptr;

  bool transparent() const { return opacity < 1.0f; }
  glm::vec3 transmittance() const { return (1.0f - opacity) * color; }
  bool operator==(const Material&) const = default;
};

// Motion per frame: frame f spins the object by f * degrees_per_frame about `spin_axis` (in its
// own space, through its origin) and then moves it by f * `move` (world space).
struct Animation {
  glm::vec3 spin_axis{0.0f, 1.0f, 0.0f};
  float degrees_per_frame = 0.0f;
  glm::vec3 move{0.0f};

  bool still() const { return degrees_per_frame == 0.0f && move == glm::vec3(0.0f); }
};

// How `--method spsv` builds an object's split plane (Laine 2005 §4): through the light, the
// object's centre line, and either orthogonal to the plane of that line and the camera
// (Point-Camera-Light, §4.1, the line through the mean of the object's vertices) or through the
// object's long axis (Point-Point-Light, §4.2, for long thin parts such as branches); or, ours,
// for a flat object such as a floor (`flat`), its own plane moved just past it away from the
// light, which leaves its whole volume on the far side. `auto` takes `ppl` for an object at
// least twice as long as it is wide, else `flat` for one a hundred times thinner than it is
// long, else `pcl`.
enum class SplitPlaneChoice : std::uint8_t {
  automatic,
  point_camera_light,
  point_point_light,
  flat
};
std::string_view to_string(SplitPlaneChoice choice);
Expected<SplitPlaneChoice> parse_split_plane_choice(std::string_view name);

struct SceneObject {
  std::string name;
  std::shared_ptr<const Mesh> mesh;          // object space
  std::shared_ptr<const Topology> topology;  // of *mesh, built once
  glm::mat4 transform{1.0f};                 // object space -> world space, at frame 0
  Material material;
  Animation animation;
  // Placed by a node of a moving hierarchy (a file's animation): at frame f its transform is
  // node.transform_at(f), which `animation` then moves as it moves any object. Unbound: the
  // object stays where `transform` puts it but for `animation`.
  NodeBinding node = {};
  SplitPlaneChoice split_plane = SplitPlaneChoice::automatic;
  // Who casts and who receives (Intel, "mainstream shadow volumes": only the geometry named as an
  // occluder occludes). An object that does not cast has no volume; one that does not receive is
  // lit by every light that reaches it, whatever lies between (it still casts, if it does).
  bool casts_shadows = true;
  bool receives_shadows = true;
  // Per triangle corner, in the mesh's own space, the normal the lit pass shades with and its
  // terminator offset (core/shading_normals.h); null, or any count but one per corner: flat,
  // each face its own normal. Shading only: shadows are the geometry's.
  std::shared_ptr<const ShadingNormals> shading = nullptr;
  // Per triangle corner, texture coordinates for material.base_color_map (v up: row 0 of the
  // image at v = 1); null, or any count but one per corner: no texture.
  std::shared_ptr<const std::vector<glm::vec2>> uvs = nullptr;
};
// The object's shading normals where it has them for every corner, else null (flat).
inline const ShadingNormals* smooth_shading(const SceneObject& object) {
  const ShadingNormals* s = object.shading.get();
  return s && object.mesh && s->normals.size() == object.mesh->indices.size() &&
                 s->offsets.size() == s->normals.size()
             ? s
             : nullptr;
}
// The object's texture coordinates where it has a map and coordinates for every corner, else
// null (the material's colour alone).
inline const std::vector<glm::vec2>* texture_coordinates(const SceneObject& object) {
  const std::vector<glm::vec2>* uv = object.uvs.get();
  return uv && object.material.base_color_map && object.mesh &&
                 uv->size() == object.mesh->indices.size()
             ? uv
             : nullptr;
}
// Shading normals for the object's mesh from per-corner normals (null where there are none).
void set_shading_normals(SceneObject& object, std::vector<glm::vec3> corner_normals);

// A point light's range: beyond it the light reaches nothing (render/shading.h's falloff is 0
// there), so no object wholly outside its sphere casts or receives anything of it.
inline constexpr float kUnlimitedRange = INFINITY;

struct SceneLight {
  glm::vec4 position{0.0f, 10.0f, 0.0f, 1.0f};  // world, homogeneous: w = 1 point, 0 directional
  glm::vec3 color{1.0f};
  float intensity = 1.0f;
  float orbit_degrees_per_frame = 0.0f;  // turns about the world's y axis, frame by frame
  // Point lights only: the radius it reaches (kUnlimitedRange: everywhere, without falloff).
  float range = kUnlimitedRange;

  bool limited() const { return position.w != 0.0f && range < kUnlimitedRange; }
};

struct Camera {
  glm::vec3 position{0.0f, 2.0f, 6.0f};
  glm::vec3 target{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fov_y_degrees = 45.0f;
  float near = 0.1f;  // the far plane is at infinity
  // Turns about the vertical line through `target`, frame by frame (position and up turn, the
  // target stays): Laine 2005's test animations move the viewpoint as well as the light.
  float orbit_degrees_per_frame = 0.0f;
  // Travels, frame by frame, by `move` (world space): position and target alike, after the
  // orbit (a walk along a path, as the paths of CC shadow volumes' measurements, §4).
  glm::vec3 move{0.0f};

  // The view of eye-relative space, where the eye is the origin: a rotation alone.
  // DESIGN.md "Numerics": geo-referenced models sit 1e5-1e6 units out, where float leaves
  // centimetre steps; subtracting the eye in double first keeps every pixel exact.
  glm::mat4 view_from_eye() const;
  // The project's projection, core/projection.h: infinite far, reversed depth (1 at the near
  // plane, 0 at infinity).
  glm::mat4 projection(float aspect) const;
};

struct Scene {
  std::string name;
  std::vector<SceneObject> objects;
  std::vector<SceneLight> lights;
  Camera camera;
  glm::vec3 ambient{0.12f};
};

// An object's transform into eye-relative space (world minus the eye), composed in double.
glm::mat4 eye_relative(const glm::mat4& transform, const glm::vec3& eye);
// A homogeneous world point or direction in eye-relative space, subtracted in double.
glm::vec4 eye_relative(const glm::vec4& point, const glm::vec3& eye);

// The scene as it stands at frame `frame` of its animation (frame 0 is the scene itself): objects
// bound to a file's nodes where the clip puts them, then every Animation, orbit and move.
// Cheap: meshes and topologies are shared, not copied.
Scene scene_at_frame(const Scene& scene, int frame);

// An object from a mesh: builds its topology (welding exactly).
SceneObject make_object(std::string name, Mesh mesh, const glm::mat4& transform,
                        const Material& material);
inline SceneObject make_object(std::string name, Mesh mesh, const glm::mat4& transform,
                               const glm::vec3& color) {
  return make_object(std::move(name), std::move(mesh), transform, Material{color});
}

// Every object shaded flat (`--flat`): its shading normals dropped.
void shade_flat(Scene& scene);
// Every object opaque (`--opaque`, a scene file's "opaque": true): opacity 1, colours kept, so
// that every caster casts a plain shadow whatever its file's material says of transparency.
void make_opaque(Scene& scene);
// Whether any object of the scene is transparent (Material::transparent).
bool has_transparent_casters(const Scene& scene);

// The built-in scenes:
//   demo              several objects, open and closed meshes, a ground plane, a point light;
//                     the torus spins (3 degrees a frame) for --frames
//   camera-in-shadow  the eye inside a shadow volume: z-pass must fail, z-fail and auto must not
//   light-in-view     a point light inside the view frustum, volumes crossing the near plane
//   directional       the demo objects under a directional light
//   nonmanifold       open, non-manifold, flipped-face, sliver and coincident-face casters
//   glass             colored transparent casters (closed, open, non-manifold) overlapping, an
//                     opaque one, a white ground and two lights: partial, colored shadows
//   corridor          trusses overhead (most of its 100k triangles) over a floor between walls,
//                     the camera walking its length: CC shadow volumes' clamping case
//   robots            a crowd of robots marching in a walled room, a low light behind crates:
//                     CC shadow volumes' culling case
//   city, city:N      a city of N buildings (10,000 and about 1.2M triangles by default; scene/
//                     city.h), seen walking down a street; city-above, city-above:N from above
Expected<Scene> builtin_scene(std::string_view name);
std::vector<std::string_view> builtin_scene_names();

// A stage for a bare mesh: the mesh (named `name`, in kStageColor), a ground plane just under
// its bounds, a point light above one side, and a camera framing it.
Scene default_stage(std::string name, Mesh mesh);
inline constexpr glm::vec3 kStageColor{0.8f, 0.55f, 0.35f};
// default_stage without the mesh's object: the ground, the light and the camera.
Scene stage_around(std::string name, const Mesh& mesh);

}  // namespace shadowvol
