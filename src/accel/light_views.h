// shadowvol accel: the light's views in which CC shadow volumes cull and clamp casters (Lloyd,
// Wendt, Govindaraju and Manocha 2004, "CC Shadow Volumes", §3.1, §3.2 and §3.4), made
// conservative so that neither ever loses a shadow (the paper accepts sampling artifacts, §3.2.3
// and §5.1; we do not).
//
// A view is planar: a perspective frustum from a point light, fitted to the receivers' boxes
// where one holds them all, else a cube of six (§3.4); or an orthographic window along a
// directional light's rays. Depth is the distance along the view's axis, which grows along every
// ray from the light. Each pixel keeps two depths:
//   - occluder: over the opaque objects that cover the pixel's whole footprint (inner-conservative
//     coverage by the union of an object's faces, add_occluder), the least of their farthest depth
//     over it. Every ray through the pixel meets an opaque surface no farther than that. +inf
//     where none covers it.
//   - receiver: the farthest depth of a receiver in the pixel: a visible sample (the point a
//     pixel of the eye's image shows), splatted into every pixel whose footprint it is within
//     1/1000 pixel of, or a receiver triangle, outer-conservatively (any footprint it may touch,
//     at its farthest vertex's depth). -inf where none.
// A box is tested over the pixels its projection may touch, fattened by one pixel (the
// projection is computed in double from the eight corners, so its error is far below a pixel:
// the pixel of every ray through the box lies within the fattened rectangle), at its nearest
// depth less a tolerance of 1e-5 of the view's depth range (float positions, rounding of stored
// depths up and of the box's depth down, and the eye's rasterization of the samples all err far
// less). It is kept where some pixel has occluder >= that depth and receiver >= that depth.
//
// Layers (discrete clamping, §3.2.2): the receiver depths again per layer, a strip of the eye's
// image; a sample goes into the layers given with it, a receiver triangle into a range of them.
// A box tested in a layer is kept where some pixel of its rectangle has both depths (the
// occluder's, and the layer's receiver) at or beyond its nearest: the same test, over the
// receivers of one strip, so the argument below holds strip by strip.
//
// Light space (continuous clamping, §3.2.1): a box's rectangle on a view's image plane and its
// interval of depth along the view's axis, from its corners in double (light_box).
//
// Why that is exact. A caster C culled: at every pixel p of its rectangle either no receiver lies
// behind C's nearest depth there (so no visible point is in its shadow through p), or every ray
// through p meets an opaque surface before C. On such a ray take the nearest opaque surface F:
// at p the occluder depth is no nearer than F (every triangle covering p is at F or beyond along
// that ray), nor is the receiver in C's shadow, so F passes its own test at p and its volume
// shadows every point C's did. Transparent casters never occlude (what they shadow still gets
// light), but are culled by the same test.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <tbb/enumerable_thread_specific.h>

#include "core/topology.h"

namespace shadowvol {

struct Box {
  glm::dvec3 lo{0.0}, hi{0.0};  // eye-relative; lo > hi on some axis for an empty box
  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
};

// Layers [first, last] of the receiver depths (LightViews, discrete clamping); none where
// last < first.
struct LayerRange {
  std::uint16_t first = 1, last = 0;
};

// What a box's test in the light's views found.
enum class BoxVisibility : std::uint8_t {
  kept,       // some pixel may show it to the light with a receiver behind it (or untestable)
  in_shadow,  // every ray from the light to it meets an opaque surface first
  unseen,     // the light may see it, but no receiver lies behind it
};

class LightViews {
 public:
  // Fits the views of `light` (eye-relative, homogeneous: w = 0 directional) to the receivers'
  // boxes, `size` x `size` pixels each, and clears their depths (`depths`: else they have none,
  // and only a box's place in the views is tested). Nothing to fit (no receivers): every caster
  // is unseen.
  void fit(const glm::dvec4& light, const std::vector<Box>& receivers, int size, bool depths,
           int layers = 0);
  // One view (orthographic or fitted frustum), or six (a cube), or none without receivers.
  std::size_t view_count() const { return views_count_; }
  bool cube() const { return views_count_ == 6; }

  // Draws opaque objects into the occluder depths, each its topology's faces at `positions` (its
  // welded vertices, eye-relative), `box` their bounds, in parallel (oneTBB). A footprint counts
  // as covered where a point of it (its centre or a quarter point) lies inside one of the faces
  // and no edge that bounds the union of their projections (a silhouette seen from the light, a
  // boundary or an irregular edge) touches it: then every ray through it meets a face that
  // touches it, no farther than the farthest of those over it. So an object's faces cover
  // together what no single face does (the seams of a mesh), and a pinhole or a crack, bounded by
  // edges, stays open. Not drawn in a view whose near plane it crosses (a cut would bound it too).
  struct Occluder {
    const Topology* topology = nullptr;
    std::span<const glm::dvec3> positions;
    Box box;
  };
  void add_occluders(std::span<const Occluder> occluders);
  // Draws a visible sample or a receiver triangle into the receiver depths, and into layers
  // [layers.first, layers.last] of them (none: last < first). Eye-relative.
  void add_receiver_point(const glm::dvec3& p, LayerRange layers = {});
  // Many points at once, in parallel (oneTBB); those with a NaN or infinite x are skipped.
  // `layers`: one range per point, or empty for none.
  void add_receiver_points(std::span<const glm::dvec3> points,
                           std::span<const LayerRange> layers = {});
  void add_receiver_triangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                             LayerRange layers = {});
  // Whether the box may lie in any view: an occluder outside every view hides nothing tested.
  bool touches(const Box& box) const;

  // After the occluders and receivers: builds the max-depth pyramids the tests read.
  // `occluders` / `receivers`: whether those depths take part (else they pass everywhere).
  void finish(bool occluders, bool receivers);
  // Tests a caster's box; counts one query per view it is tested in into `queries`.
  BoxVisibility test(const Box& box, std::uint64_t& queries) const;
  // Whether the box may shadow a receiver of `layer` (BoxVisibility::kept there).
  bool kept_in_layer(const Box& box, int layer, std::uint64_t& queries) const;
  int layers() const { return layers_; }

  // Light space. A box's rectangle on view v's image plane (u, v: the plane's own coordinates)
  // and its interval of depth along the view's axis. `caster`: the box must lie wholly in the
  // view (beyond its near plane, and for a cube's face within its window: its volume stays in
  // that frustum), else false. Otherwise (a receiver) its part beyond the near plane, the
  // rectangle cut to the window, where every caster's volume that a view holds meets it.
  struct LightBox {
    double u0, u1, v0, v1;  // image plane
    double z0, z1;          // depth
  };
  bool light_box(std::size_t view, const Box& box, bool caster, LightBox& out) const;
  // Depth in view v as an affine function of position: depth(x) = dot(plane, (x, 1)).
  glm::dvec4 depth_plane(std::size_t view) const;
  // The point at (u, v) of view's image plane and depth d.
  glm::dvec3 point(std::size_t view, double u, double v, double d) const;
  // The view that holds the direction from the light to p: a cube's face, else 0.
  std::size_t view_of(const glm::dvec3& p) const;

 private:
  struct View {
    bool perspective = true;
    glm::dvec3 origin{0.0}, right{0.0}, up{0.0}, axis{0.0};
    double u0 = -1, u1 = 1, v0 = -1, v1 = 1;  // the window on the image plane
    double near = 0;                          // perspective: the nearest depth it holds
    double tolerance = 0;                     // of depths: 1e-5 of its depth range
    std::vector<float> receiver;              // size * size, row-major
    // Levels of 2x2 maxima: [0] is per pixel, size * size, row-major. `seen`: the occluder depth
    // (drawn into seen[0]); `kept`: the lesser of occluder and receiver, so that a box is kept
    // where some texel reaches its depth in both.
    std::vector<std::vector<float>> seen, kept;
    // Per layer: its receivers' depths, and the pyramid of the lesser of them and the occluder.
    std::vector<std::vector<float>> layer_receiver;
    std::vector<std::vector<std::vector<float>>> layer_kept;
  };
  struct Rect {
    int x0, y0, x1, y1;  // inclusive pixel range
    double zmin;         // the box's nearest depth in the view, less the tolerance
  };
  // Pixel coordinates (x, y) of a point at depth d in a view, and d.
  glm::dvec3 to_pixels(const View& view, const glm::dvec3& p, double d) const;
  // Pixel coordinates (x, y) and depth of a point in a view; false behind its near plane.
  bool project(const View& view, const glm::dvec3& p, glm::dvec3& out) const;
  // Whether a cube's box lies about the light: in the near cube, in no face's frustum whole.
  bool about_light(const Box& box) const;
  // Into the receiver depths of one view (and of the layers), at every pixel within the slack
  // of the point.
  void splat_receiver(View& view, const glm::dvec3& p, LayerRange layers);
  // The box's pixels and nearest depth in a view: false where it lies outside it; `untestable`
  // where part of it lies in front of the near plane (it might cast there unseen by the view).
  bool box_rect(const View& view, const Box& box, Rect& rect, bool& untestable) const;
  void set_view(View& view, bool perspective, const glm::dvec3& origin, const glm::dvec3& axis,
                const glm::dvec3& right_hint, bool depths);
  // Whether some pixel of `rect` holds a depth >= rect.zmin in the pyramid (true for none).
  bool any_at_least(const std::vector<std::vector<float>>& pyramid, const Rect& rect) const;
  bool descend(const std::vector<std::vector<float>>& pyramid, const Rect& rect, int level, int tx,
               int ty) const;
  int level_width(int level) const { return (size_ + (1 << level) - 1) >> level; }

  std::span<View> active() { return {views_.data(), views_count_}; }
  std::span<const View> active() const { return {views_.data(), views_count_}; }
  // The next view of this fit, in the storage an earlier fit left: its depths keep their memory.
  View& next_view() {
    if (views_count_ == views_.size()) views_.emplace_back();
    return views_[views_count_++];
  }

  int size_ = 0;
  int layers_ = 0;
  std::vector<View> views_;  // [0, views_count_) are this fit's
  std::size_t views_count_ = 0;
  bool occluders_ = false, kept_ = false;  // what finish() built
  // add_occluder's scratch, one per thread: the bounding edges, the vertices in the view, and per
  // pixel of the object's rectangle the farthest depth and whether a face holds a point of it /
  // an edge bounds it.
  struct OccluderScratch {
    std::vector<IndexPair> bounds;
    std::vector<glm::dvec3> screen;
    std::vector<double> farthest;
    std::vector<std::uint8_t> state;
  };
  void add_occluder(const Occluder& occluder, OccluderScratch& scratch);
  tbb::enumerable_thread_specific<OccluderScratch> scratch_;
};

}  // namespace shadowvol
