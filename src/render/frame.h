// shadowvol render: what a frame is and how it is asked for.
//
// Owns: the options a frame is drawn with (method, generator, extrusion, split planes) and their
// checks, and what a frame leaves behind: the image, per pixel the object and face it shows, per
// light whether it is lit (and how much light arrives through transparent casters), and the
// frame's stats. Papers: Intel "mainstream shadow volumes" and GPU Gems 3 ch. 11 (z-pass /
// z-fail, caps, extrusion to infinity, per-object choice of the method), Laine 2005 (split
// planes), Kim, Kim & Turk 2008 (transparent casters).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "core/expected.h"
#include "core/volume.h"
#include "raster/raster.h"
#include "scene/scene.h"

namespace shadowvol {

enum class Method : std::uint8_t {
  zpass,      // count volume faces in front of the surface; wrong when the eye is in a volume
  zfail,      // count those behind it (needs caps); right everywhere
  automatic,  // per object: z-pass unless its volume may reach the near plane (GPU Gems 3 §11.2.3)
  // Per tile: z-pass or z-fail by the side of a split plane through the volume (Laine 2005;
  // software backend only). Where a volume may reach the near plane, its z-pass tiles start from
  // the near-plane pre-fill (ZP+).
  split_plane,
  // Z-pass made exact by the near-plane pre-fill of ZP+ (Hornus et al. 2005) where a volume
  // may reach the near plane; with depth bounds, Laine 2005's first baseline (software only).
  zpass_prefill,
};
std::string_view to_string(Method method);
Expected<Method> parse_method(std::string_view name);
// Whether only the software backend draws `method` (it tests tiles against split planes, or
// pre-fills from the near plane).
inline bool soft_only(Method method) {
  return method == Method::split_plane || method == Method::zpass_prefill;
}

// How far volumes reach: to infinity (w = 0, with an infinite far plane or depth clamp; GPU Gems
// 3 §11.3.2), or bounded, ended on a plane just beyond the scene's bounds and closed by dark caps
// there (Laine 2005 §7 extrudes to the scene's extent). Bounded volumes cover less of the screen,
// give z-fail a far depth bound, and are exact wherever a receiver can be.
enum class Extrusion : std::uint8_t { infinite, bounded };
std::string_view to_string(Extrusion extrusion);
Expected<Extrusion> parse_extrusion(std::string_view name);

// How Method::split_plane gives an object with SplitPlaneChoice::automatic its split plane:
// Laine 2005 §4's rule of thumb (Point-Camera-Light, Point-Point-Light for elongated objects, our
// `flat` for flat ones), or that plane and 39 others (2 for flat objects) weighed per volume and
// frame by counting the volume's layers at one pixel in every 32 x 32 block
// (soft/split_sampler.h; the samples' work is in FrameStats::split_sampling), taking the
// cheapest.
enum class SplitPlanes : std::uint8_t { laine, sampled };
std::string_view to_string(SplitPlanes planes);
Expected<SplitPlanes> parse_split_planes(std::string_view name);

// Whether Method::split_plane gives each part of a caster (Topology's parts: faces joined through
// shared vertices) a split plane of its own, as Laine 2005 §6 decomposes casters into
// sub-objects, found here automatically: `each` (an object of 2 to kMaxSplitParts parts; one
// plane for an object of more, so that a triangle soup's thousands of parts do not each cost
// draws and a sampling), or one plane for the `whole` object. Parts cast their volumes apart from
// one another, so the side quads drawn are the same either way; the depth bounds stay the
// object's.
enum class SplitParts : std::uint8_t { each, whole };
inline constexpr std::size_t kMaxSplitParts = 64;
std::string_view to_string(SplitParts parts);
Expected<SplitParts> parse_split_parts(std::string_view name);

// CC shadow volumes' culling (Lloyd, Wendt, Govindaraju and Manocha 2004 §3.1; render/
// caster_culling.h): no volume is drawn for a caster whose shadow can change no pixel. `frustum`:
// the receivers are the objects whose box meets the view frustum, and a caster outside every
// light view fitted to them is culled. `occlusion`: the receivers are the objects the eye's image
// shows (and the transparent ones in the frustum), and a caster is culled where, in the light's
// view, every ray to its box is blocked by an opaque surface first (in shadow) or no receiver
// lies behind it (its shadow is unseen); conservative, so exact (accel/light_views.h).
enum class Cull : std::uint8_t { none, frustum, occlusion };
std::string_view to_string(Cull cull);
inline constexpr int kMinLightView = 16, kMaxLightView = 4096;
Expected<Cull> parse_cull(std::string_view name);

// Hierarchical occlusion culling (render/occlusion_culling.h) over the scene's BVH, by
// occlusion queries with coherence from frame to frame (Bittner et al. 2004, "CHC"). `eye`: the
// opaque layer's depth pass drawn front to back, leaving out objects whose (grown) box the depth
// drawn so far hides. `shadows`: per light, a volume is culled where its object's box extruded
// away from the light (GPU Gems 3 ch. 11 §11.3.3) holds no visible surface. `both`: the two.
// Conservative: the frame is the same as without it.
enum class Occlusion : std::uint8_t { none, eye, shadows, both };
std::string_view to_string(Occlusion occlusion);
Expected<Occlusion> parse_occlusion(std::string_view name);
inline bool culls_eye(Occlusion o) { return o == Occlusion::eye || o == Occlusion::both; }
inline bool culls_shadows(Occlusion o) { return o == Occlusion::shadows || o == Occlusion::both; }

// CC shadow volumes' clamping (Lloyd et al. 2004 §3.2; render/cc_shadow_volumes.h): volumes
// kept only where receivers may lie. `continuous` (§3.2.1): per caster (or sub-object), the
// intervals of depth along the light's view that hold receivers' boxes, each drawn as a segment
// closed by caps. `discrete` (§3.2.2, made conservative as §3.2.3 says): the image split into
// strips by planes through the eye; a caster's volume drawn only in the strips where, in the
// light's view, a visible sample of the strip may lie behind it. `both` (Fig. 2(d)): the
// continuous segments, drawn only in the discrete strips.
enum class Clamp : std::uint8_t { none, continuous, discrete, both };
std::string_view to_string(Clamp clamp);
Expected<Clamp> parse_clamp(std::string_view name);
inline bool clamps_continuous(Clamp c) { return c == Clamp::continuous || c == Clamp::both; }
inline bool clamps_discrete(Clamp c) { return c == Clamp::discrete || c == Clamp::both; }
// Discrete clamping's slices: the default from the sweep of `bench --suite cc` (docs/
// cc-shadow-volumes.md), and the most a light's view keeps layers for.
inline constexpr int kDefaultSlices = 1, kMaxSlices = 64;
Expected<void> check_slices(int slices);

struct RenderOptions {
  int width = 960;
  int height = 540;
  Method method = Method::automatic;
  Generator generator = Generator::automatic;
  Extrusion extrusion = Extrusion::infinite;
  SplitPlanes split_planes = SplitPlanes::sampled;
  SplitParts split_parts = SplitParts::each;
  Cull cull = Cull::none;
  Clamp clamp = Clamp::none;
  Occlusion occlusion = Occlusion::none;
  int slices = kDefaultSlices;  // discrete clamping's strips of the image
  // The side of each light view culling and clamping test in, in pixels (a cube's faces each).
  int light_view_size = 512;
  // The update manager (Intel, "Threading Shadow Volumes"): the CPU volumes that changed are
  // rebuilt on worker threads while the depth pass runs, and joined before the first count pass,
  // where nothing decided after the depth pass changes them (no culling, clamping or shadow
  // occlusion culling; else they are built per light, after it). Off: built per light, after.
  bool overlap_volumes = true;
  // Measures the fill of the volumes (FrameStats::fill, and stencil_writes on the gl backend)
  // in passes of their own, apart from the frame's times.
  bool count_fill = false;
  // Overlays the edges of every side quad (the silhouette edge and its two rays to infinity),
  // one colour per light, so that a person can see the volumes.
  bool show_volumes = false;
  // Software backend: record the count passes' work per 8x8 tile into Frame::tile_work (for
  // `render --heatmap`); the gl backend records none.
  bool tile_work = false;
  // With tile_work: also each object's volume's share, into Frame::object_tile_work (for the
  // suite's per-tile oracle, `bench --suite spsv`).
  bool tile_work_per_object = false;
  // Records per light which surfaces the lit pass takes as facing the light (SurfaceLayer::
  // faces_light), so that verify can compare a shading input no mask shows: a face whose normal
  // is lost lights nothing, whether in shadow or not. On the gl backend, a pass per light and
  // layer of its own, apart from the frame's times (in ms_readback).
  bool record_facing = false;
};

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  // 8-bit sRGB, row 0 at the top
};

// What drawing shadow volumes costs on a backend (CC shadow volumes §3.2.1's v and r): per
// vertex of a volume, and per pixel it covers, in milliseconds, as FrameBackend::
// measure_volume_costs finds them.
struct VolumeCosts {
  double ms_per_vertex = 0.0, ms_per_pixel = 0.0;
  bool measured() const { return ms_per_vertex > 0.0 || ms_per_pixel > 0.0; }
};

struct FrameStats {
  // ms_volumes: what the volumes cost the frame's own thread (with RenderOptions::overlap_volumes,
  // the wait for the builds at the join).
  double ms_depth = 0, ms_volumes = 0, ms_counts = 0, ms_shade = 0;
  // The CPU volumes' builds, wherever they ran, and of that the part that ran while the depth
  // pass did (RenderOptions::overlap_volumes): hidden behind it.
  double ms_volume_builds = 0, ms_volumes_hidden = 0;
  // Taking what the frame shows into Frame: ids, masks, light and image (the read-back verbs).
  double ms_readback = 0;
  // Measuring for the stats what is not the frame's work (RenderOptions::count_fill's passes,
  // tile work shared out by object), taken off the stage it happened in.
  double ms_measuring = 0;
  std::size_t triangles = 0;                 // scene triangles drawn in the depth pass
  std::size_t volume_primitives = 0;         // over all lights
  int objects_zpass = 0, objects_zfail = 0;  // over all lights
  int objects_split = 0;                     // over all lights: drawn by a split plane
  // Over all lights: parts of z-fail objects counted by z-pass (VolumePlan::part_zfail).
  int parts_zpass = 0;
  std::vector<int> zfail_lights;              // per object: lights it was drawn by z-fail for
  std::vector<int> culled_lights;             // per object: lights its volume was culled for
  int volumes_built = 0, volumes_reused = 0;  // over all lights: the volume cache at work
  // Culling (RenderOptions::cull), over all lights: casters culled because they lie in shadow
  // and because their shadow is unseen, the boxes' queries (one per light view tested in), the
  // light views made (1, or 6 for a cube), and the time it took.
  int casters_culled_in_shadow = 0, casters_culled_unseen = 0;
  std::uint64_t cull_queries = 0;
  int light_views = 0;
  double ms_cull = 0;
  // Hierarchical occlusion culling (RenderOptions::occlusion): the scene BVH's upkeep (refit, or
  // rebuilt where refits made it costlier: bvh_rebuilt) and the shadow queries' time (the eye's
  // queries are in ms_depth); nodes visited, queries issued and those whose answer was waited
  // for (not ready when asked), over the eye's walk and every light's; opaque objects left out of
  // the depth pass, and volumes culled by their extruded boxes (over all lights).
  double ms_bvh = 0, ms_occlusion = 0;
  int bvh_rebuilt = 0;
  std::uint64_t nodes_visited = 0, queries = 0, queries_waited = 0;
  int objects_culled = 0, volumes_culled = 0;
  // Objects drawn in the opaque depth pass, and volumes counted (over all lights).
  int objects_drawn = 0, volumes_drawn = 0;
  // Light ranges (SceneLight::range), over all lights: volumes of casters wholly beyond the range
  // (not built, not counted), and the pixels outside the lights' scissor rectangles, which their
  // count and lit passes leave alone.
  int volumes_out_of_range = 0;
  std::uint64_t scissor_pixels_saved = 0;
  // Sub-objects (CC §3, §3.3), over all lights: culled apart from the rest of their object.
  int sub_objects_culled = 0;
  // Clamping (RenderOptions::clamp), over all lights: the time it took (the light views' depths
  // too, where discrete clamping alone draws them); volumes whose segments
  // were clamped continuously; volumes no strip holds (not drawn); the segments drawn (a
  // volume's intervals over its sub-objects, times its strips; 1 for a volume drawn whole); the
  // discrete tests (a box in a strip, per light view); and the continuous overlap tests' pairs,
  // the insertion sorts' interchanges (temporal coherence) and intervals merged because V > R.
  double ms_clamp = 0;
  int volumes_clamped = 0, volumes_clamped_away = 0;
  std::uint64_t volume_segments = 0, slice_queries = 0;
  std::uint64_t clamp_pairs = 0, clamp_swaps = 0, intervals_merged_by_cost = 0;
  // RenderOptions::count_fill: the pixels the volumes drawn touch with the depth test off (CC
  // §4's fill), and those whose count they change (stencil writes; on the soft backend also
  // counts.count_updates, always).
  std::uint64_t fill = 0, stencil_writes = 0;
  // Continuous clamping's v and r, as the backend measured them (not added up over frames).
  VolumeCosts volume_costs;
  raster::Counters depth, counts;
  // Software backend, SplitPlanes::sampled: the split-plane sampler's own drawing (on a target of
  // one pixel per sampled tile), apart from `counts` and from the tile work, since its samples
  // are not the frame's pixels; what spsv cost in all is the two together.
  raster::Counters split_sampling;

  // Adds every figure of `other` (zfail_lights element-wise): the stats of several frames.
  FrameStats& operator+=(const FrameStats& other);
};

// One layer of surfaces: what each pixel shows in it, and per light how much of the light
// reaches it there.
struct SurfaceLayer {
  std::vector<std::int32_t> object;  // per pixel: index into scene.objects, -1 for none
  std::vector<std::uint32_t> face;   // per pixel: face of that object
  // Per light, per pixel: 1 where the light does not arrive: the opaque casters' count != 0
  // (transparent casters never shadow fully; they are in `transmitted`), or the surface lies
  // beyond the light's range (SceneLight::range). 0 on objects that receive no shadows.
  std::vector<std::vector<std::uint8_t>> shadowed;
  // Scenes with transparent casters only, else empty: per light, per pixel, the fraction of the
  // light (linear RGB, per channel) that reaches the surface, the product of the transmittances
  // of the transparent surfaces between them (Kim, Kim & Turk 2008 §2); 0 where shadowed.
  std::vector<std::vector<glm::vec3>> transmitted;
  // RenderOptions::record_facing only, else empty: per light, per pixel, 1 where the lit pass
  // takes the surface as facing the light: its face's normal, turned to the side the eye sees,
  // points to the light's side, and the surface lies within the light's range. The light's
  // direct term applies only there (and where the mask is clear); the reference's faces_light
  // says the same.
  std::vector<std::vector<std::uint8_t>> faces_light;
};

// What a frame leaves behind besides the picture: what each pixel shows, and per light whether
// it is lit. The verifier compares these against the ray-traced reference. The layer the frame
// is (object, face, shadowed, transmitted) holds the opaque surfaces: transparent casters are
// seen through, so they are not in it.
struct Frame : SurfaceLayer {
  Image image;
  // Scenes with transparent casters, else empty: the nearest transparent surface in front of the
  // opaque one (object -1 where none), and the light its other layers and the other casters let
  // reach it (the paper's partial self-shadowing, §4-5).
  SurfaceLayer glass;
  FrameStats stats;
  // RenderOptions::tile_work, software backend: per 8x8 tile (raster::kTileSize), row-major, the
  // count passes' work over all lights; else empty.
  std::vector<raster::TileWork> tile_work;
  // RenderOptions::tile_work_per_object: per object, per tile, its volume's part of tile_work.
  std::vector<std::vector<raster::TileWork>> object_tile_work;
};

// A light view's side (RenderOptions::light_view_size) within [kMinLightView, kMaxLightView].
Expected<void> check_light_view_size(int size);
// Checks an options struct a person filled in: size within the rasterizer's limits, the light
// view's (check_light_view_size).
Expected<void> check_options(const RenderOptions& options);
// The range of a scene every stage draws exactly (docs/verification.md, "The range drawn exactly"):
// world coordinates (the camera, point lights, every object's box) within kMaxWorldCoordinate of
// the origin (beyond it Embree's float rays fail its own checks), and every object within
// kMaxDepthRange times the camera's near distance of the eye (beyond it float vertices and depths
// miss pixels of shadows on llvmpipe first, measured: a ground 2e5 times the near distance across).
inline constexpr double kMaxWorldCoordinate = 1e11;
inline constexpr double kMaxDepthRange = 2e6;
// Checks a frame a person asked for: the options (check_options), every light of the scene
// (check_light), a camera that makes a view (finite, a target apart from its position, an up
// off the view direction, fov in (0, 180), near > 0), the scene within the range above, and a
// generator exact on every object: one that counts every surface of its transparent casters,
// and not the standard one on a mesh other than a closed 2-manifold (check_generator).
Expected<void> check_frame(const Scene& scene, const RenderOptions& options);

}  // namespace shadowvol
