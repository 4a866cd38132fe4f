// shadowvol raster: the software rasterizer's triangle stage (setup -> raster), its buffers and
// counters. Depends on glm, oneTBB and core's polygon clipper only; knows nothing of meshes, scenes
// or shadow volumes.
//
// Owns: clipping in homogeneous space, snapping to a fixed-point grid, exact edge functions
// with a top-left fill rule, the per-pixel depth and signed-count buffers, the per-tile depth
// bounds (hi-z), and counters of the work done. Each draw sets its triangles up once, in chunks
// in parallel, then rasterizes bands of one tile row in parallel (oneTBB, a few bands a task);
// every band walks the triangles in order, so results and counters do not depend on the thread
// count. Within a tile, pixels are tested a tile row (8 pixels) at a time in SIMD vectors:
// coverage by 32-bit edge functions, depth in float from the tile's first pixel.
//
// Conventions:
//   - Input vertices are in clip space as core/projection.h makes it: x, y in [-w, w] and z in
//     [0, w] inside, infinite far, reversed depth. A point at infinity (w = 0 in eye space) lands
//     exactly on depth 0, so the far plane never clips and the only clip plane that changes what
//     is drawn is the near plane z <= w. Guard-band planes |x|, |y| <= kGuardBand * w keep
//     snapped coordinates inside the fixed-point range; they lie outside the viewport and change
//     no pixel.
//   - Window coordinates: x right, y down (row 0 is the top of the image); depth z / w in [0, 1],
//     1 on the near plane and 0 at infinity: nearer is greater. A pixel is covered when its
//     centre is inside the triangle, by the top-left rule on its edges.
//   - Facing: a triangle whose vertices run counter-clockwise as seen by the viewer (OpenGL's
//     default front face) is front-facing.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace shadowvol::raster {

// 1/256 pixel. The guard band, in units of half the viewport, keeps snapped coordinates within
// 8 viewports' span: below 2^17 pixels, 2^25 subpixels, for viewports up to 16384 = 2^14 pixels
// a side. So coordinate differences are below 2^25, edge functions (products of two) below 2^51
// in 64-bit integers, exactly; and the per-pixel 32-bit edge functions of raster.cpp's tile test
// below 2^30 (see there).
inline constexpr int kSubpixelBits = 8;
inline constexpr int kSubpixels = 1 << kSubpixelBits;
inline constexpr float kGuardBand = 8.0f;
inline constexpr int kMaxViewport = 16384;
// Tiles of 8 x 8 pixels, as in Laine 2005 §7 (per-tile culling, per-tile depth bounds).
inline constexpr int kTileSize = 8;

// Blocks of 8 x 8 tiles (64 x 64 pixels), the hi-z's coarser level: a count pass leaves a
// triangle out of a block row's eight tile rows at once where no block it crosses can hold a
// fragment that passes (a volume's long slivers cross hundreds of tiles that the finer level
// would each reject).
inline constexpr int kBlockTiles = 8;

// Depth bounds of the pixels of one tile, the hi-z. Two floats, 8 bytes: one cache line holds
// the bounds of eight tiles, a row of 64 pixels.
struct TileDepth {
  float zmin = 0.0f;
  float zmax = 0.0f;
};

// The count passes' work in one tile (Laine 2005 Fig. 1): its pixels that a volume primitive
// covered and that reached the depth test, and those whose count changed.
struct TileWork {
  std::uint32_t pixels_processed = 0;
  std::uint32_t pixels_updated = 0;
};

// A rectangle of pixels, [x0, x1) x [y0, y1), row 0 at the top.
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x0 >= x1 || y0 >= y1; }
  std::uint64_t area() const {
    return empty() ? 0 : std::uint64_t(x1 - x0) * std::uint64_t(y1 - y0);
  }
  bool operator==(const PixelRect&) const = default;
};

// The buffers of one frame. Row-major, row 0 at the top.
struct Target {
  static constexpr std::uint32_t kNoId = 0xffffffffu;
  int width = 0, height = 0;
  int tiles_x = 0, tiles_y = 0;
  int blocks_x = 0, blocks_y = 0;
  std::vector<float> depth;                // window depth, 0 = far (infinity)
  std::vector<std::int32_t> count;         // signed shadow-volume count
  std::vector<std::uint32_t> id;           // what the depth pass left visible: kNoId or an id
  std::vector<TileDepth> tile_depth;       // hi-z, valid after update_tile_depth()
  std::vector<TileDepth> block_depth;      // its coarser level (kBlockTiles), valid with it
  std::vector<TileDepth> block_row_depth;  // and per row of blocks
  // Per tile, row-major: what draw_counts did there, added up while the vector holds one entry
  // per tile (the caller sizes and clears it); empty, nothing is recorded.
  std::vector<TileWork> tile_work;
  // The draws' scissor (for a light's count passes, its reach: accel/light_reach.h): they leave
  // alone every tile wholly outside it and draw the rest whole. The whole image on a new target.
  PixelRect scissor;

  Target();
  Target(int w, int h);
  Target(Target&&) noexcept;
  Target& operator=(Target&&) noexcept;
  ~Target();
  void clear_depth(float z = 0.0f);  // and the ids
  // Counts are zero on a new target and after take_nonzero_counts, so that a pass needs no clear.
  // Writes count != 0 per pixel into `nonzero` (width * height bytes, 1 or 0) and leaves every
  // count zero: one sweep over the buffer instead of a read and a clear.
  void take_nonzero_counts(std::span<std::uint8_t> nonzero);
  // The same over the tiles `within` meets only (a scissored pass's), leaving `nonzero` elsewhere
  // as it was: counts outside them must be zero.
  void take_nonzero_counts(std::span<std::uint8_t> nonzero, const PixelRect& within);
  // Adds count * per_count per pixel into `sum` (width * height entries) and leaves every count
  // zero: how a group of transparent casters' surface counts enter a light intensity map.
  void take_counts_into(std::span<glm::vec3> sum, const glm::vec3& per_count);
  // Recomputes every tile's and block's depth bounds from the depth buffer (after the depth
  // pass).
  void update_tile_depth();

  // What the draws set up, kept between them: on a warm target a draw allocates nothing, and
  // fresh pages would each cost a page fault.
  struct Scratch;
  std::unique_ptr<Scratch> scratch;
};

// Work counters of one frame or pass (the papers' fill measures). Added, never reset, by the
// draw functions. Given a fresh Counters, a draw's pixels_passed is its occlusion query: how
// many of its fragments passed the depth test (for the culling work of later issues).
struct Counters {
  std::uint64_t triangles_in = 0;
  std::uint64_t triangles_clipped = 0;  // needed clipping (near plane or guard band)
  std::uint64_t triangles_culled = 0;   // nothing left after clipping, zero area, or FaceCull
  // Triangles left out of a block row's tile rows at once by the hi-z's coarser level (count
  // passes of one rule for every tile); their tiles are not touched.
  std::uint64_t block_rows_skipped = 0;
  std::uint64_t tiles_touched = 0;     // tiles a triangle may cover (edge test at the corners)
  std::uint64_t tiles_skipped = 0;     // of those, rejected whole by hi-z or depth bounds
  std::uint64_t pixels_processed = 0;  // covered pixels that reached the depth test
  std::uint64_t pixels_passed = 0;     // of those, passed it (an occlusion query's answer)
  std::uint64_t count_updates = 0;     // count buffer writes

  Counters& operator+=(const Counters& other);
};

// Depth pass: triangles (3 clip-space vertices each), depth test greater (nearer), depth write,
// and the id first_id + t of triangle t written where it passes. Both facings are drawn.
void draw_depth(Target& target, std::span<const glm::vec4> triangles, std::uint32_t first_id,
                Counters& counters);

// Which facing of a triangle a depth pass leaves out (counted as culled): none, the back
// (clockwise on screen) or the front.
enum class FaceCull : std::uint8_t { none, back, front };

// The same, each triangle t with the id ids[t]: many objects' faces in one draw.
void draw_depth(Target& target, std::span<const glm::vec4> triangles,
                std::span<const std::uint32_t> ids, Counters& counters);
// The same from shared clip-space vertices, triangle t's corners vertices[indices[3 t + k]]: a
// mesh's vertices transformed once, and 12 bytes a triangle instead of 48; with `cull` (empty, or
// one per triangle), triangle t of facing cull[t] is left out.
void draw_depth(Target& target, std::span<const glm::vec4> vertices,
                std::span<const std::uint32_t> indices, std::span<const std::uint32_t> ids,
                Counters& counters, std::span<const FaceCull> cull = {});

// How a count pass uses the depth test (Everitt & Kilgard; GPU Gems 3 §11.2.1; Laine 2005).
enum class CountRule {
  zpass,  // fragments in front of the stored depth: front faces add the weight, back subtract
  zfail,  // fragments at or behind it: front faces subtract the weight, back faces add
  split,  // per tile, zpass or zfail by the side of a split plane the tile's surfaces lie on
  // Every covered pixel, whatever its depth: front faces add the weight, back faces subtract it
  // (the near-plane pre-fill of ZP+, render/near_plane_prefill.h). Depth bounds do not apply.
  prefill,
  // Fragments in front of the stored depth add the weight whichever way they face: how many
  // surfaces lie between the eye and the stored one (the transparent surfaces seen through).
  cover,
  // Fragments at or behind the stored depth add the weight whichever way they face: how many
  // surfaces lie beyond the stored one (what z-fail would count there; soft/split_sampler.h).
  behind,
  // Every covered pixel, whatever its depth, and nothing written: the draw's pixels_processed
  // (and pixels_passed) are its fill, CC shadow volumes' measure (Lloyd et al. 2004 §4: pixels
  // touched with the depth test off). Depth bounds do not apply.
  fill,
};

// Which tiles a draw counts in, by the rule a split plane picks for them (Laine 2005 §3.3): a
// volume's caps are needed only where z-fail counts, and a near-plane pre-fill (ZP+) only where
// z-pass does.
enum class SplitTiles { all, zfail_only, zpass_only };

// The split test of Laine 2005 §4.3 and §5.2, made once per tile: the tile takes z-pass when
// the point of its centre at the middle of its stored depths ((zmin + zmax) / 2 of its hi-z),
// (x, y, depth, 1) in normalized device coordinates, lies strictly on the camera's side of
// `plane` (a clip-space plane; the camera is the clip-space point (0, 0, 1, 0)), and z-fail
// otherwise. Any plane gives the right
// counts, since each tile's choice is the same for every draw of one volume; a plane through
// the middle of the volume makes most tiles need no count at all.
struct SplitPlane {
  glm::vec4 plane{0.0f};
  SplitTiles tiles = SplitTiles::all;
};
// The rule a split plane picks for a tile of `target` (tile_depth must be up to date).
CountRule split_rule(const Target& target, int tile_x, int tile_y, const glm::vec4& plane);

// A depth-bounds test (EXT_depth_bounds_test; McGuire et al. 2003): pixels whose stored depth
// lies outside [zmin, zmax] are left alone. For a shadow volume, its range of depths: a surface
// in front of the whole volume, or behind the whole of a bounded one, is outside it, and would
// otherwise be touched by every primitive only for their counts to cancel.
struct DepthBounds {
  float zmin = 0.0f;
  float zmax = 1.0f;
  bool operator==(const DepthBounds&) const = default;
};
// An occlusion query (GL_ANY_SAMPLES_PASSED): the covered pixels where a fragment of the
// triangles lies at or in front of the stored depth, and the stored depth within `bounds`;
// nothing is written. Both facings are drawn. The answer also goes into counters.pixels_passed.
// Valid during a depth pass (it tests the depths drawn so far; the hi-z need not be current).
// With `stop_at_first`, the bands stop taking triangles once a pixel has passed: the answer is
// then only whether any did (0, or at least 1).
std::uint64_t query(Target& target, std::span<const glm::vec4> triangles, DepthBounds bounds,
                    Counters& counters, bool stop_at_first = false);

// The window depths clip-space triangles reach (clamped to 0 .. 1 as drawn, widened by a hair
// for the rasterizer's rounding): a pixel whose stored depth lies outside them sees no primitive
// on one side of it, so a closed volume's count there is 0 under either rule, the near plane's
// cut included (vertices beyond it clamp to depth 1). Every depth {0, 1} if a vertex has w <= 0:
// behind the eye, its triangles' depths are not bounded by their vertices'.
DepthBounds reached_depths(std::span<const glm::vec4> triangles);

// A strip of the image a draw is limited to: the pixels whose centre has s = across . ndc in
// [lo, hi] (NDC: x right, y up, each -1 .. 1). CC shadow volumes' discrete clamping (Lloyd et al.
// 2004 §3.2.2) draws a volume only between slicing planes through the eye, which are lines on the
// image. Tested per pixel (and per tile, to skip or accept whole tiles), never by cutting
// triangles: a cut triangle would rasterize to other depths, and a light cap must keep those of
// its surface (DESIGN.md "Numerics").
struct ScreenStrip {
  glm::vec2 across{1.0f, 0.0f};
  float lo = -INFINITY, hi = INFINITY;
  bool whole() const { return lo == -INFINITY && hi == INFINITY; }
};

// Where every draw's clipper cuts a clip-space triangle by the near plane (the first plane it
// clips by): the edge the cut adds to the triangle, from where its boundary leaves the drawn side
// to where it comes back, so running the way the corners run; both the very vertices the clipper
// makes, bit for bit. False where the near plane does not cut it.
bool near_plane_cut(const glm::vec4* triangle, glm::vec4& leaves, glm::vec4& returns);

// Count pass: each triangle changes the count of the pixels it covers by its signed weight
// (weights[t], one per triangle), by the rule above, in one write; depth is not written. Tiles
// whose depth bounds prove that no pixel can pass the rule's test, or whose depths all lie
// outside `bounds`, are skipped whole. `split.plane` picks each tile's rule under
// CountRule::split, and limits any rule's draw to some tiles when split.tiles is not `all`.
// `strip`: the pixels it may change (ScreenStrip).
void draw_counts(Target& target, std::span<const glm::vec4> triangles,
                 std::span<const std::int32_t> weights, CountRule rule, Counters& counters,
                 DepthBounds bounds = {}, const SplitPlane& split = {},
                 const ScreenStrip& strip = {});

// The same over the whole image, each triangle t within its own depth bounds bounds[t]: many
// volumes counted by one rule in one draw, each kept to its own bounds.
void draw_counts(Target& target, std::span<const glm::vec4> triangles,
                 std::span<const std::int32_t> weights, std::span<const DepthBounds> bounds,
                 CountRule rule, Counters& counters);

}  // namespace shadowvol::raster
