// shadowvol render: what every backend decides the same way before it draws a frame.
//
// Owns: the eye-relative matrices of a frame, the per-object, per-light choice of z-pass or
// z-fail, the volume cache (volumes built on the CPU, rebuilt only when an object's light
// changes), the mapping from a depth pass's face ids back to (object, face), and the shading
// constants. Both backends call these, so that they draw the same volumes with the same method
// and light them the same way; only the drawing differs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "core/volume.h"
#include "render/renderer.h"
#include "render/volume_builder.h"
#include "scene/scene.h"

namespace shadowvol {

struct FramePlan {
  glm::mat4 view_proj{1.0f};  // of eye-relative space
  glm::mat4 inv_view_proj{1.0f};
  std::vector<glm::mat4> model;   // per object: its transform, eye-relative (DESIGN.md "Numerics")
  std::vector<int> weight_sign;   // per object: -1 where the transform mirrors (volume.h)
  std::vector<glm::vec4> lights;  // per light: its position, eye-relative
  // The depth pass gives face f of object o the id first_id[o] + f; first_id has one entry more
  // than there are objects, the total.
  std::vector<std::uint32_t> first_id;
  std::vector<std::vector<bool>> zfail;  // [light][object]: draw this volume by z-fail
  // Under Method::split_plane, how the tiles of one part of a volume choose their rule. `plane`:
  // its split plane in clip space (Laine 2005 §4: Point-Camera-Light or Point-Point-Light; or
  // ours, `flat`, as the object's SplitPlaneChoice says). `candidates`: under
  // SplitPlaneChoice::automatic and SplitPlanes::sampled, the planes (clip space) the software
  // backend weighs by sampling the frame's tiles (soft/split_sampler.h), drawing by the cheapest:
  // `plane` first, then both whole-volume rules and, but for flat parts, Point-Camera-Light
  // turned, tilted and moved, and Point-Point-Light; else empty.
  struct PartSplit {
    glm::vec4 plane{0.0f};
    std::vector<glm::vec4> candidates;
  };
  // [light][object]: under Method::split_plane, one PartSplit per part of the object
  // (Topology::vertex_part) under SplitParts::each, or one for the whole volume; none where the
  // volume is drawn by one rule whole.
  std::vector<std::vector<std::vector<PartSplit>>> split;
  // [light][object]: z-pass counts of this volume start from the near-plane pre-fill (ZP+):
  // under Method::zpass_prefill, and in a split plane's z-pass tiles, where the volume may
  // reach the near plane.
  std::vector<std::vector<bool>> prefill;
  // [light][object]: the far plane the volume ends on, eye-relative (core/volume.h): under
  // Extrusion::bounded, a plane beyond the scene and the near plane; else, and where no plane
  // can end it well, the plane at infinity.
  std::vector<std::vector<glm::vec4>> far_plane;
  // [light][object]: the depth bounds of the volume, as Laine 2005 §7 makes them for his
  // comparison methods: the window depths of the shadow volume of the object's bounding box
  // (ended on the same far plane) where it meets the view frustum. The software count passes
  // skip every pixel whose stored depth lies outside them. Empty (zmin > zmax) where the box's
  // volume is out of view.
  std::vector<std::vector<soft::DepthBounds>> depth_bounds;
  // Transparent casters (Kim, Kim & Turk 2008 §2): per object, the index of its material's group
  // in glass_log_transmittance, or -1 for an opaque object; per group (one per distinct
  // transparent material, in order of first use), the logarithm of its transmittance per channel
  // (kLogOfZero for a channel it passes none of): what each of its surfaces between a point and
  // the light adds to the point's log light intensity.
  std::vector<int> glass_group;
  std::vector<glm::vec3> glass_log_transmittance;
  std::vector<std::vector<std::size_t>> glass_members;  // per group: its objects, in order

  // Whether the volume of object o for light l counts its caps: z-fail does, and so do a split
  // plane's z-fail tiles. The volume is built with caps also where the pre-fill projects them.
  bool counts_caps(std::size_t l, std::size_t o) const {
    return zfail[l][o] || !split[l][o].empty();
  }
  // Whether the volume's parts are counted apart, each by its own split plane: the volume is
  // built with the part of each primitive (VolumeOptions::parts).
  bool splits_by_part(std::size_t l, std::size_t o) const { return split[l][o].size() > 1; }
  // A transparent caster is not in the depth buffer, so the surfaces seen through it lie behind
  // its light caps: its light caps count under every rule (Kim et al. §1.2, Fig. 5).
  bool counts_light_caps_everywhere(std::size_t o) const { return glass_group[o] >= 0; }
  bool builds_caps(std::size_t l, std::size_t o) const {
    return counts_caps(l, o) || prefill[l][o] || counts_light_caps_everywhere(o);
  }

  // far_plane[l][o] in the object's own space, where its volume is built.
  glm::vec4 object_far_plane(std::size_t l, std::size_t o) const;

  // (object, face) of a depth-pass id, or object -1 when the id is past the last face.
  std::pair<std::int32_t, std::uint32_t> object_of(std::uint32_t id) const;
};

// Decides everything above for this scene and these options. `auto` takes z-fail for an object
// only where its bounding sphere may put part of the near-plane rectangle in its shadow
// (GPU Gems 3 §11.2.3). `spsv` gives every object a split plane, and `zp+db` draws by z-pass;
// both pre-fill where `auto` would take z-fail, and take z-fail where the light lies in the near
// plane, which no pre-fill can see. Counts the objects of each method into stats.
FramePlan plan_frame(const Scene& scene, const RenderOptions& options, FrameStats& stats);

// The generator that builds an object's volume: `requested`, except that `automatic` takes
// multiplicity for a transparent object, whose every surface must count (standard counts only
// those facing the light; callers refuse it for scenes with transparent casters).
Generator object_generator(const SceneObject& object, Generator requested);

// A stand-in for log(0) in the light intensity map: finite, so that a surface entered and left
// again (+c, then -c) cancels exactly instead of giving inf - inf, and low enough that exp of
// any sum holding it is 0.
inline constexpr float kLogOfZero = -1000.0f;
glm::vec3 log_transmittance(const Material& material);

// The light in the object's own space (the inverse of its transform, in double), where its
// volume is built whether on the CPU or in a geometry shader.
glm::vec4 object_space_light(const SceneObject& object, const glm::vec4& light);

// The CPU-built volumes of the last frame, per light and object, in each object's own space.
class VolumeCache {
 public:
  // Rebuilds (in parallel) the volumes whose object's light, seen from the object, generator or
  // need of caps changed since the last call; counts built and reused into stats. Returns, per
  // object, whether its volume was rebuilt.
  std::vector<bool> update(const Scene& scene, const FramePlan& plan, std::size_t light,
                           Generator generator, FrameStats& stats);
  const VolumeBuffer& volume(std::size_t light, std::size_t object) const {
    return cache_[light][object].volume;
  }

 private:
  struct Entry {
    // Held, not just pointed to: while cached, no other topology can take its address.
    std::shared_ptr<const Topology> topology;
    glm::vec4 light{0.0f};
    VolumeOptions options;
    VolumeBuffer volume;
  };
  VolumeBuilder builder_;
  std::vector<std::vector<Entry>> cache_;  // [light][object]
};

// Draws the edges of every side quad of the cached volumes over the image (the silhouette edge
// and its two rays to infinity, clipped at the near plane), one colour per light.
void overlay_volumes(Image& image, const Scene& scene, const FramePlan& plan,
                     const VolumeCache& volumes);

// The shading both backends use (the OpenGL backend passes these to its shaders as uniforms):
// ambient * albedo, plus per unshadowed light Lambert + Blinn-Phong, lit on the side the eye
// sees; a vertical gradient behind everything; sRGB out.
namespace shading {
inline constexpr float kSpecular = 0.25f;
inline constexpr float kShininess = 48.0f;
inline constexpr glm::vec3 kBackgroundTop{0.26f, 0.28f, 0.22f};
inline constexpr glm::vec3 kBackgroundBottom{0.16f, 0.18f, 0.22f};
// The background at row y of h (row 0 at the top).
glm::vec3 background(int y, int h);
float to_srgb(float linear);
// lround(to_srgb(linear) * 255), exactly, by a search among the 255 linear values where the 8-bit
// code steps (found once): a frame encodes millions of channels, and pow is most of its cost.
std::uint8_t to_srgb8(float linear);
}  // namespace shading

}  // namespace shadowvol
