// shadowvol render: what a frame draws, decided once before any backend draws it.
//
// Owns: the eye-relative matrices of a frame, per object its transform and face ids, the groups
// of transparent casters, and per (light, object) a VolumePlan: the rule its volume is counted
// by (z-pass, z-fail or per tile by split planes), which caps count where, the pre-fill, the
// light in the object's space, the generator, the far plane and the depth bounds. The backends
// read the plan and derive nothing; what they share of shading is render/shading.h.
//
// Papers: GPU Gems 3 ch. 11 §11.2.3 (z-pass unless the volume may reach the near plane;
// accel/near_plane.h), Laine 2005 §4, §6 and §7 (split planes per part, depth bounds;
// accel/split_planes.h, accel/depth_bounds.h), Hornus et al. 2005 (ZP+), Kim, Kim & Turk 2008
// §2 (transparent casters in groups of one material).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "accel/light_reach.h"
#include "core/volume.h"
#include "raster/raster.h"
#include "render/frame.h"
#include "scene/scene.h"

namespace shadowvol {

// How the pixels of a volume choose between z-pass and z-fail.
enum class VolumeRule : std::uint8_t {
  zpass,  // every pixel counts the faces in front of its surface
  zfail,  // every pixel counts those behind it, caps included
  split,  // per tile, by the side of the part's split plane the tile's surfaces lie on
};

// How the tiles of one part of a volume choose their rule under VolumeRule::split. `plane`: its
// split plane in clip space (Laine 2005 §4: Point-Camera-Light or Point-Point-Light; or ours,
// `flat`, as the object's SplitPlaneChoice says). `candidates`: under SplitPlaneChoice::automatic
// and SplitPlanes::sampled, the planes (clip space) the software backend weighs by sampling the
// frame's tiles (soft/split_sampler.h), drawing by the cheapest: `plane` first, then both
// whole-volume rules and, but for flat parts, Point-Camera-Light turned, tilted and moved, and
// Point-Point-Light; else empty.
struct PartSplit {
  glm::vec4 plane{0.0f};
  std::vector<glm::vec4> candidates;
};

// What a volume's depth bounds are computed from.
struct DepthBoundsInputs {
  glm::vec3 lo{0.0f}, hi{0.0f};  // the object's bounding box
  glm::vec4 light{0.0f}, far_plane{0.0f};
  glm::mat4 view_proj{1.0f};
  raster::DepthBounds reach;  // the light's (LightReach::depth)
  bool operator==(const DepthBoundsInputs&) const = default;
};

// One object's volume for one light.
struct VolumePlan {
  VolumeRule rule = VolumeRule::zpass;
  // Z-pass counts start from the near-plane pre-fill (ZP+): under Method::zpass_prefill, and in
  // a split plane's z-pass tiles, where the volume may reach the near plane.
  bool prefill = false;
  // The caps count where z-fail does (VolumeRule::zfail, and a split plane's z-fail tiles).
  bool counts_caps = false;
  // A transparent caster is not in the depth buffer, so the surfaces seen through it lie behind
  // its light caps: its light caps count under every rule (Kim et al. §1.2, Fig. 5).
  bool light_caps_everywhere = false;
  // What the volume is built with, in the object's own space: the generator (resolved for the
  // object's mesh), caps (where any rule counts them or the pre-fill projects them), the far
  // plane, and under a split plane per part, each primitive's part.
  VolumeOptions build;
  glm::vec4 object_light{0.0f};  // the light in the object's own space
  // The far plane the volume ends on, eye-relative (core/volume.h): under Extrusion::bounded, a
  // plane beyond the scene and the near plane; else, and where no plane can end it well, the
  // plane at infinity.
  glm::vec4 far_plane = kPlaneAtInfinity;
  // Laine 2005 §7's depth bounds (set by plan_depth_bounds, for volumes not culled): the window
  // depths of the shadow volume of the object's bounding box (ended on the same far plane) where it
  // meets the view frustum. The software count passes skip every pixel whose stored depth lies
  // outside them. Empty (zmin > zmax) where the box's volume is out of view. Within the light's
  // reach (FramePlan::reach).
  raster::DepthBounds depth_bounds;
  // What depth_bounds was computed from: a plan reused for the next frame recomputes them only
  // where these changed (each takes a shadow volume of the box).
  std::optional<DepthBoundsInputs> depth_bounds_of;
  // Culled (the object casts no shadows, its box lies beyond the light's range, RenderOptions::
  // cull, or no strip of discrete clamping holds it; render/cc_shadow_volumes.h): no pixel's
  // count changes without it, so it is neither built nor counted.
  bool culled = false;
  // CC shadow volumes' sub-objects and continuous clamping (render/cc_shadow_volumes.h): with
  // leaves, the volume is built clamped (core/volume.h), in the object's space, and its dark caps,
  // which then lie among the receivers, count under every rule (and in the pre-fill).
  VolumeClamp clamp;
  // Discrete clamping: the runs of strips of the image the volume is drawn in, each drawn apart;
  // empty: drawn once, over the whole image.
  std::vector<raster::ScreenStrip> strips;
  // Under Method::automatic, where the object's volume may reach the near plane but only some of
  // its parts' do (Topology's parts, each bounded by its own sphere; GPU Gems 3 §11.2.3 per
  // part): per part, 1 to count it by z-fail (caps included), 0 by z-pass, for a backend that
  // counts parts apart (the volume is built with parts). Empty: counted by `rule` whole. `rule`
  // stays z-fail with caps, right for a backend that counts the volume whole.
  std::vector<std::uint8_t> part_zfail;
  // Under VolumeRule::split: one PartSplit per part of the object (Topology::vertex_part) under
  // SplitParts::each, or one for the whole volume; else empty.
  std::vector<PartSplit> split;

  // Whether the parts are counted apart, each by its own split plane.
  bool by_part() const { return split.size() > 1; }
  bool clamped() const { return clamp.leaf_count() > 0; }
  bool by_part_rule() const { return !part_zfail.empty(); }
  // Whether the dark caps count where z-pass does too (not only where z-fail does).
  bool dark_caps_everywhere() const { return clamped(); }
  // Segments drawn: the clamp's intervals (or 1), once per strip (or once).
  std::size_t segments() const {
    return (clamped() ? clamp.intervals.size() : 1) * std::max<std::size_t>(strips.size(), 1);
  }
};

// One object of the frame.
struct ObjectPlan {
  glm::mat4 model{1.0f};  // its transform, eye-relative (DESIGN.md "Numerics")
  int weight_sign = 1;    // -1 where the transform mirrors (volume.h)
  // The depth pass gives face f the id first_id + f.
  std::uint32_t first_id = 0;
  int glass_group = -1;  // index into FramePlan::glass, or -1 for an opaque object
  bool receives = true;  // SceneObject::receives_shadows: its pixels' counts are cleared
  // Its bounding box, eye-relative (lo > hi for an object without vertices).
  glm::vec3 lo{0.0f}, hi{0.0f};
  // The back faces of its parts wound outwards (Topology::part_wound_outwards) are never the
  // nearest surface, so a depth pass may leave them out: it has such parts and its box lies
  // wholly beyond the near plane, so that every ray from the eye meets a front face of each first.
  bool back_faces_hidden = false;
};

// The transparent casters of one material (Kim, Kim & Turk 2008 §2): what each of their
// surfaces between a point and the light adds to the point's log light intensity.
struct GlassGroup {
  Material material;
  // The logarithm of the material's transmittance per channel (kLogOfZero for a channel it
  // passes none of).
  glm::vec3 log_transmittance{0.0f};
  std::vector<std::size_t> members;  // its objects, in order
};

struct FramePlan {
  glm::mat4 view_proj{1.0f};  // of eye-relative space
  glm::mat4 inv_view_proj{1.0f};
  std::vector<ObjectPlan> objects;
  std::vector<glm::vec4> lights;  // per light: its position, eye-relative
  // Per light: the scissor and depth bounds of its range (the whole image, all depths, for a
  // light without one); its count and lit passes stay within them.
  std::vector<LightReach> reach;
  bool any_non_receiver = false;    // some object does not receive shadows
  std::vector<GlassGroup> glass;    // in order of first use; empty without transparent casters
  std::uint32_t id_count = 0;       // the depth pass's ids are [0, id_count)
  std::vector<VolumePlan> volumes;  // [light * objects + object]

  const VolumePlan& volume(std::size_t light, std::size_t object) const {
    return volumes[light * objects.size() + object];
  }
  VolumePlan& volume(std::size_t light, std::size_t object) {
    return volumes[light * objects.size() + object];
  }
  bool has_glass() const { return !glass.empty(); }
  bool transparent(std::size_t object) const { return objects[object].glass_group >= 0; }
  // (object, face) of a depth-pass id, or object -1 when the id is past the last face.
  std::pair<std::int32_t, std::uint32_t> object_of(std::uint32_t id) const;
};

// Decides everything above for this scene and these options into `plan`, reusing its storage.
// `auto` takes z-fail for an object only where its bounding sphere may put part of the
// near-plane rectangle in its shadow (GPU Gems 3 §11.2.3), and then, for an object of several
// parts, only for the parts whose own spheres may (VolumePlan::part_zfail): one mesh of a whole
// city is not forced to z-fail. `spsv` gives every object a split
// plane, and `zp+db` draws by z-pass; both pre-fill where `auto` would take z-fail. A volume is
// culled where its object casts no shadows or lies wholly beyond the light's range. Counts the
// objects of each method, and the volumes out of range, into stats.
void plan_frame(const Scene& scene, const RenderOptions& options, FramePlan& plan,
                FrameStats& stats);
FramePlan plan_frame(const Scene& scene, const RenderOptions& options, FrameStats& stats);

// Laine 2005 §7's depth bounds (VolumePlan::depth_bounds) of light l's volumes that are not
// culled, within the light's reach, each recomputed only where its box, light, far plane, view or
// reach changed: after culling, so that a large scene pays for the volumes it draws, not for
// every object.
void plan_depth_bounds(FramePlan& plan, std::size_t light);

// The generator that builds an object's volume: `requested`, except that `automatic` takes
// multiplicity for a transparent object, whose every surface must count (standard counts only
// those facing the light; callers refuse it for scenes with transparent casters).
Generator object_generator(const SceneObject& object, Generator requested);

// A stand-in for log(0) in the light intensity map: finite, so that a surface entered and left
// again (+c, then -c) cancels exactly instead of giving inf - inf, and low enough that exp of
// any sum holding it is 0.
inline constexpr float kLogOfZero = -1000.0f;
glm::vec3 log_transmittance(const Material& material);

// A world point (homogeneous: w = 0 a direction) in the object's own space (the inverse of its
// transform, in double): the light, where its volume is built whether on the CPU or in a
// geometry shader, and the eye, against which the volume stages decide a face's side.
glm::vec4 object_space_point(const SceneObject& object, const glm::vec4& point);

}  // namespace shadowvol
