// The software rasterizer's triangle stage: clip -> setup -> raster, per 8 x 8 tile.
// Stages named as llvmpipe names them; every constant says where it comes from (raster.h).
#include "raster/raster.h"

// The tile-row vectors below are passed between functions of this file only, all inlined; GCC's
// note that a 32-byte vector argument's ABI differs with and without AVX concerns no caller.
#pragma GCC diagnostic ignored "-Wpsabi"

#include <algorithm>
#include <array>
#include <atomic>
#include <cassert>
#include <cmath>
#include <cstring>
#include <type_traits>

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "core/clip_polygon.h"

#ifdef __AVX__
#include <immintrin.h>
#endif

namespace shadowvol::raster {

Counters& Counters::operator+=(const Counters& other) {
  triangles_in += other.triangles_in;
  triangles_clipped += other.triangles_clipped;
  triangles_culled += other.triangles_culled;
  block_rows_skipped += other.block_rows_skipped;
  tiles_touched += other.tiles_touched;
  tiles_skipped += other.tiles_skipped;
  pixels_processed += other.pixels_processed;
  pixels_passed += other.pixels_passed;
  count_updates += other.count_updates;
  return *this;
}

namespace {

// --- clip ---------------------------------------------------------------------------------

// Signed distances to the clip planes, >= 0 inside: near (z <= w), the four guard-band planes,
// and w > 0 (which a proper projection never reaches once the near plane has clipped; it keeps
// the division safe whatever the caller passes).
constexpr int kPlanes = 6;
inline float plane_distance(int plane, const glm::vec4& v) {
  switch (plane) {
    case 0:
      return v.w - v.z;
    case 1:
      return kGuardBand * v.w - v.x;
    case 2:
      return kGuardBand * v.w + v.x;
    case 3:
      return kGuardBand * v.w - v.y;
    case 4:
      return kGuardBand * v.w + v.y;
    default:
      return v.w - 1e-30f;
  }
}

// Clipped against every plane in turn (clip_polygon.h: watertight along every cut).
constexpr int kMaxPolygon = 3 + kPlanes;
struct Polygon {
  std::array<glm::vec4, kMaxPolygon> v;
  int n = 0;
};

bool clip(const glm::vec4* tri, Polygon& out, bool& clipped) {
  out.v[0] = tri[0], out.v[1] = tri[1], out.v[2] = tri[2], out.n = 3;
  clipped = false;
  for (int plane = 0; plane < kPlanes; ++plane) {
    clipped |= clip_polygon(out.v, out.n,
                            [plane](const glm::vec4& v) { return plane_distance(plane, v); });
    if (out.n < 3) return false;
  }
  return true;
}

// --- setup --------------------------------------------------------------------------------

struct ScreenVertex {
  std::int64_t x, y;  // subpixels, y down
  float z;            // window depth
};

struct Setup {
  ScreenVertex v[3];
  std::int64_t area2;  // > 0 after ordering: clockwise on screen (y down)
  bool front;          // counter-clockwise as the viewer sees it (OpenGL's front face)
  // Edge i runs v[i] -> v[(i + 1) % 3]; E_i(P) = dx_i (Py - y_i) - dy_i (Px - x_i), inside >= 0.
  std::int64_t dx[3], dy[3];
  std::int64_t bias[3];       // 0 on top-left edges, -1 elsewhere: the top-left fill rule
  double dzdx, dzdy;          // depth per pixel
  double x_per_y[3];          // edge i's slope dx/dy, 0 for a horizontal edge
  std::int64_t min_y, max_y;  // subpixel rows of the bounding box: which bands it meets
};

// The nearest integer, ties to even (the default rounding mode), by adding and taking away
// 1.5 * 2^52: exact for |x| < 2^51, far beyond the guard band's subpixels (2^25), and without
// llround's library call (two per vertex of every triangle).
inline std::int64_t round_to_integer(double x) {
  constexpr double kShifter = 6755399441055744.0;  // 1.5 * 2^52
  return static_cast<std::int64_t>((x + kShifter) - kShifter);
}

ScreenVertex to_screen(const glm::vec4& c, int width, int height) {
  const double inv_w = 1.0 / c.w;
  const double sx = (c.x * inv_w + 1.0) * 0.5 * width * kSubpixels;
  const double sy = (1.0 - c.y * inv_w) * 0.5 * height * kSubpixels;
  const double z = c.z * inv_w;
  return {round_to_integer(sx), round_to_integer(sy), static_cast<float>(std::clamp(z, 0.0, 1.0))};
}

// Twice the signed area of a screen triangle, in subpixels squared (exact: 64-bit integers).
inline std::int64_t area2(const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c) {
  return (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
}

bool setup(const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c, Setup& s) {
  s.v[0] = a, s.v[1] = b, s.v[2] = c;
  s.area2 = area2(a, b, c);
  if (s.area2 == 0) return false;
  // A triangle the viewer sees counter-clockwise (front-facing) has negative area here, since
  // y points down. Swap two vertices of those, so that every triangle is rasterized one way; the
  // swap depends only on the vertices, so a triangle drawn twice is rasterized identically.
  s.front = s.area2 < 0;
  if (s.area2 < 0) {
    std::swap(s.v[1], s.v[2]);
    s.area2 = -s.area2;
  }
  for (int i = 0; i < 3; ++i) {
    const ScreenVertex& p = s.v[i];
    const ScreenVertex& q = s.v[(i + 1) % 3];
    s.dx[i] = q.x - p.x;
    s.dy[i] = q.y - p.y;
    // Top edge: horizontal with the interior below; left edge: running up. (Clockwise, y down.)
    const bool top_left = s.dy[i] < 0 || (s.dy[i] == 0 && s.dx[i] > 0);
    s.bias[i] = top_left ? 0 : -1;
    s.x_per_y[i] = s.dy[i] == 0 ? 0.0 : double(s.dx[i]) / double(s.dy[i]);
  }
  const ScreenVertex& p = s.v[0];
  const double e1x = double(s.v[1].x - p.x), e1y = double(s.v[1].y - p.y);
  const double e2x = double(s.v[2].x - p.x), e2y = double(s.v[2].y - p.y);
  const double z1 = double(s.v[1].z) - p.z, z2 = double(s.v[2].z) - p.z;
  const double inv_area = 1.0 / double(s.area2);
  s.dzdx = (z1 * e2y - z2 * e1y) * inv_area * kSubpixels;
  s.dzdy = (z2 * e1x - z1 * e2x) * inv_area * kSubpixels;
  s.min_y = std::min({s.v[0].y, s.v[1].y, s.v[2].y});
  s.max_y = std::max({s.v[0].y, s.v[1].y, s.v[2].y});
  return true;
}

// Depth of the triangle's plane at the centre of pixel (px, py), unclamped.
inline double plane_depth(const Setup& s, int px, int py) {
  const double x = (double(px) + 0.5) - double(s.v[0].x) / kSubpixels;
  const double y = (double(py) + 0.5) - double(s.v[0].y) / kSubpixels;
  return s.v[0].z + s.dzdx * x + s.dzdy * y;
}

// --- raster -------------------------------------------------------------------------------

// The edge functions at a pixel centre, plus their fill-rule bias: >= 0 inside.
inline std::int64_t edge_at(const Setup& s, int i, int px, int py) {
  const std::int64_t cx = (std::int64_t{px} << kSubpixelBits) + kSubpixels / 2;
  const std::int64_t cy = (std::int64_t{py} << kSubpixelBits) + kSubpixels / 2;
  return s.dx[i] * (cy - s.v[i].y) - s.dy[i] * (cx - s.v[i].x) + s.bias[i];
}

// The pixel columns [px0, px1] that a triangle can cover in the rows [y0, y1]: the x extent of
// its intersection with the slab of those rows' pixel centres, widened by a pixel for rounding.
// A thin triangle that crosses the screen touches few tiles of each band, not its bounding box.
// With kDepths, also the range [zlo, zhi] of its plane's depth over that intersection (a convex
// polygon: its corners are where the edges enter and leave the slab), unclamped.
struct SlabExtent {
  int px0 = 0, px1 = 0;
  double zlo = HUGE_VAL, zhi = -HUGE_VAL;
};
template <bool kDepths>
bool slab_extent(const Setup& s, int y0, int y1, int width, SlabExtent& out) {
  const double top = double(y0) * kSubpixels + kSubpixels / 2;
  const double bottom = double(y1) * kSubpixels + kSubpixels / 2;
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  const auto corner = [&](double x, double y) {
    lo = std::min(lo, x);
    hi = std::max(hi, x);
    if constexpr (kDepths) {
      const double z =
          s.v[0].z +
          (s.dzdx * (x - double(s.v[0].x)) + s.dzdy * (y - double(s.v[0].y))) / kSubpixels;
      out.zlo = std::min(out.zlo, z);
      out.zhi = std::max(out.zhi, z);
    }
  };
  // A triangle wholly within the slab (most small ones) is its own intersection with it.
  const bool within = double(s.min_y) >= top && double(s.max_y) <= bottom;
  for (int i = 0; within && i < 3; ++i) corner(double(s.v[i].x), double(s.v[i].y));
  for (int i = 0; !within && i < 3; ++i) {
    const ScreenVertex& p = s.v[i];
    const ScreenVertex& q = s.v[(i + 1) % 3];
    const double a = std::max<double>(std::min(p.y, q.y), top);
    const double b = std::min<double>(std::max(p.y, q.y), bottom);
    if (a > b) continue;  // the edge misses the slab
    if (p.y == q.y) {
      corner(double(p.x), double(p.y));
      corner(double(q.x), double(q.y));
      continue;
    }
    for (const double y : {a, b}) corner(double(p.x) + (y - double(p.y)) * s.x_per_y[i], y);
  }
  if (lo > hi) return false;
  const auto pixel_of = [](double sub) { return (sub - kSubpixels / 2) / kSubpixels; };
  out.px0 = static_cast<int>(std::max(0.0, std::floor(pixel_of(lo)) - 1.0));
  out.px1 = static_cast<int>(std::min(double(width - 1), std::ceil(pixel_of(hi)) + 1.0));
  return out.px0 <= out.px1;
}

// Per-pixel depths are float, from the tile's first pixel: z = (z_tile + dz/dy j) + dz/dx i,
// clamped to [0, 1] like a depth clamp. Every rounding step is monotonic in i and in j, so over a
// tile the extremes lie at its corners; the same triangle gives the same depth at the same pixel
// in every pass, since tiles lie on a fixed grid. Tile tests widen the corner range by kDepthSlack
// where they clamp it to the triangle's vertex depths, which the float steps may overshoot.
inline constexpr float kDepthSlack = 1e-6f;

// --- lanes: a tile row of pixels in one vector (GCC/Clang vector extensions, which compile to
// the build's SIMD width: AVX2 or AVX-512 with SHADOWVOL_NATIVE, pairs of SSE2 ops without) ---

using Mask = std::int32_t __attribute__((vector_size(kTileSize * sizeof(std::int32_t))));
using Floats = float __attribute__((vector_size(kTileSize * sizeof(float))));
inline constexpr Mask kLaneIndex = {0, 1, 2, 3, 4, 5, 6, 7};
inline constexpr Floats kLaneOffset = {0, 1, 2, 3, 4, 5, 6, 7};
static_assert(kTileSize == 8, "kLaneIndex and kLaneOffset list one lane per tile column");

// The first `lanes` elements of a row of a buffer; at the right edge of the image a row is
// shorter than a tile, and nothing past it may be read or written (another band owns it).
// `lanes` is std::integral_constant<int, kTileSize> for whole rows, so that they compile to one
// vector load or store, or an int otherwise.
template <class V, class T, class Lanes>
V load_row(const T* p, Lanes lanes) {
  V v{};
  std::memcpy(&v, p, static_cast<std::size_t>(lanes) * sizeof(T));
  return v;
}
template <class V, class T, class Lanes>
void store_row(T* p, const V& v, Lanes lanes) {
  std::memcpy(p, &v, static_cast<std::size_t>(lanes) * sizeof(T));
}
using WholeRow = std::integral_constant<int, kTileSize>;

// Whether any lane of a mask is set: one vptest where the build has AVX.
inline bool any(const Mask& m) {
#ifdef __AVX__
  __m256i v;
  std::memcpy(&v, &m, sizeof v);
  return !_mm256_testz_si256(v, v);
#else
  using Words = std::uint64_t __attribute__((vector_size(sizeof(Mask))));
  Words w;
  std::memcpy(&w, &m, sizeof w);
  std::uint64_t bits = 0;
  for (std::size_t i = 0; i < sizeof(Mask) / sizeof(std::uint64_t); ++i) bits |= w[i];
  return bits != 0;
#endif
}

// Adds up masks (-1 per true lane) lane-wise; total() is the number of true lanes seen.
struct LaneCount {
  Mask sum{};
  void add(const Mask& m) { sum -= m; }
  std::uint64_t total() const {
    std::int32_t t = 0;
    for (int i = 0; i < kTileSize; ++i) t += sum[i];
    return static_cast<std::uint64_t>(t);
  }
};

// What a tile test decides from the tile's depth bounds: no pixel can pass the pass's depth
// tests; every covered pixel passes them (their stored depths need not be read); each pixel's
// depth must be tested, its stored depth lying within the pass's depth bounds (test_depth); or
// both must be tested; and, for a count pass, by which rule (zpass or zfail).
enum class TileVerdict { skip, test, test_depth, accept };
template <TileVerdict verdict>
using Checks = std::integral_constant<TileVerdict, verdict>;
struct TileDecision {
  TileVerdict verdict;
  CountRule rule;
};

struct TileDepthPlane {
  float z_tile, dzdx, dzdy;
  float at(int i, int j) const { return std::clamp((z_tile + dzdy * j) + dzdx * i, 0.0f, 1.0f); }
};

// Rasterizes one triangle over tile row `band`. For every row of every tile that it may cover,
// calls row(first, covered, z, lanes, checks, rule): pixels first .. first + lanes - 1 of the
// buffers, the mask of those whose centres it covers (-1 or 0; no lane past the image's right
// edge is set), its depth there, the tile's verdict as Checks<> (accept, test_depth or test: what
// each pixel still needs), and the tile's rule; row returns the mask of those that passed, for
// the counters.
//
// Per tile, first the edge test: edge functions are linear, so the tile's corner pixel centres
// tell whether any pixel centre of the tile can be inside, and whether all are (then no edge is
// evaluated per pixel). Then tile_test(hi-z bounds, the triangle's depth range over the tile)
// gives the tile's TileVerdict. Pixels are then tested a tile row at a time with 32-bit edge
// functions: within a tile that an edge cuts, E = E0 + 256 k, with k = dx j - dy i for i, j < 8
// and |dx|, |dy| < 2^25 (raster.h), so |k| < 14 * 2^25 < 2^29; E >= 0 exactly when
// floor(E0 / 256) + k >= 0, and floor(E0 / 256), the edge within a tile's reach of the tile's
// first pixel, is below 2^29 there too: the sum stays below 2^30. `work`: the band's TileWork
// entries, or null to record none. A ScreenStrip in pixels: s at the centre of pixel (px, py) is
// ds_dx px + ds_dy py + s0.
struct StripInPixels {
  double ds_dx = 0, ds_dy = 0, s0 = 0;
  float lo = -INFINITY, hi = INFINITY;
  bool whole = true;
  StripInPixels() = default;
  StripInPixels(const ScreenStrip& strip, int width, int height)
      : ds_dx(2.0 * strip.across.x / width),
        ds_dy(-2.0 * strip.across.y / height),
        s0(strip.across.x * (1.0 / width - 1.0) + strip.across.y * (1.0 - 1.0 / height)),
        lo(strip.lo),
        hi(strip.hi),
        whole(strip.whole()) {}
  double at(int px, int py) const { return ds_dx * px + ds_dy * py + s0; }
};

template <class TileTest, class Row>
void raster(const Target& target, const Setup& s, int band, Counters& counters, TileWork* work,
            const StripInPixels& strip, TileTest&& tile_test, Row&& row) {
  const int y0 = band * kTileSize, y1 = std::min(target.height, y0 + kTileSize) - 1;
  const PixelRect& scissor = target.scissor;
  if (scissor.empty() || y1 < scissor.y0 || y0 >= scissor.y1) return;
  SlabExtent extent;
  if (!slab_extent<false>(s, y0, y1, target.width, extent)) return;
  // The tiles the scissor meets, whole.
  const int px0 = std::max(extent.px0, scissor.x0 / kTileSize * kTileSize);
  const int px1 = std::min(extent.px1, (scissor.x1 - 1) / kTileSize * kTileSize + kTileSize - 1);
  if (px0 > px1) return;
  const Floats ds_lane = static_cast<float>(strip.ds_dx) * kLaneOffset;
  const float zlo_triangle = std::min({s.v[0].z, s.v[1].z, s.v[2].z}) - kDepthSlack;
  const float zhi_triangle = std::max({s.v[0].z, s.v[1].z, s.v[2].z}) + kDepthSlack;
  const int rows = y1 - y0 + 1;
  const std::size_t width = static_cast<std::size_t>(target.width);  // a local: see draw_counts
  const float dzdx = static_cast<float>(s.dzdx), dzdy = static_cast<float>(s.dzdy);
  const Floats dz_lane = dzdx * kLaneOffset;
  // The depth at the first pixel of tile tx, in double: z_band + dz_tile tx.
  const double z_band = plane_depth(s, 0, y0), dz_tile = s.dzdx * kTileSize;
  // Per edge: its value at the first pixel of tile px0 / kTileSize in row y0, the step from one
  // tile to the next, and how far above and below that value the tile's other pixels reach
  // (taken over whole tiles: at the image's right edge the test is only more cautious).
  std::int64_t edge[3], tile_step[3], reach_up[3], reach_down[3];
  for (int k = 0; k < 3; ++k) {
    const std::int64_t across = std::int64_t{kTileSize - 1} * -s.dy[k] * kSubpixels;
    const std::int64_t down = std::int64_t{rows - 1} * s.dx[k] * kSubpixels;
    edge[k] = edge_at(s, k, px0 / kTileSize * kTileSize, y0);
    tile_step[k] = std::int64_t{kTileSize} * -s.dy[k] * kSubpixels;
    reach_up[k] = std::max<std::int64_t>(across, 0) + std::max<std::int64_t>(down, 0);
    reach_down[k] = std::min<std::int64_t>(across, 0) + std::min<std::int64_t>(down, 0);
  }
  LaneCount covered_count, passed_count;
  for (int tx = px0 / kTileSize; tx <= px1 / kTileSize;
       ++tx, edge[0] += tile_step[0], edge[1] += tile_step[1], edge[2] += tile_step[2]) {
    const int x0 = tx * kTileSize, lanes = std::min(target.width - x0, kTileSize);
    if (edge[0] + reach_up[0] < 0 || edge[1] + reach_up[1] < 0 || edge[2] + reach_up[2] < 0)
      continue;  // outside one edge
    // The strip: the tile outside it is skipped, inside it taken whole, else tested per pixel.
    Mask strip_rows[kTileSize];
    if (!strip.whole) {
      const double s00 = strip.at(x0, y0), s10 = strip.at(x0 + lanes - 1, y0),
                   s01 = strip.at(x0, y0 + rows - 1), s11 = strip.at(x0 + lanes - 1, y0 + rows - 1);
      const double smin = std::min({s00, s10, s01, s11}), smax = std::max({s00, s10, s01, s11});
      if (smax < strip.lo || smin > strip.hi) continue;
      const bool partial = smin < strip.lo || smax > strip.hi;
      for (int j = 0; j < rows; ++j) {
        const Floats at = static_cast<float>(strip.at(x0, y0 + j)) + ds_lane;
        strip_rows[j] = partial ? (at >= strip.lo) & (at <= strip.hi) : Mask{} - 1;
      }
    }
    std::int32_t q[3], step_i[3], step_j[3];
    bool interior = true;
    for (int k = 0; k < 3; ++k) {
      // An edge with the whole tile inside is left out of the pixel test (0 is inside).
      const bool all_inside = edge[k] + reach_down[k] >= 0;
      interior &= all_inside;
      q[k] = all_inside ? 0 : static_cast<std::int32_t>(edge[k] >> kSubpixelBits);
      step_i[k] = all_inside ? 0 : static_cast<std::int32_t>(-s.dy[k]);
      step_j[k] = all_inside ? 0 : static_cast<std::int32_t>(s.dx[k]);
    }
    ++counters.tiles_touched;
    const TileDepthPlane plane{static_cast<float>(z_band + dz_tile * tx), dzdx, dzdy};
    const float c[4] = {plane.at(0, 0), plane.at(lanes - 1, 0), plane.at(0, rows - 1),
                        plane.at(lanes - 1, rows - 1)};
    const float zlo = std::max(zlo_triangle, std::min({c[0], c[1], c[2], c[3]}));
    const float zhi = std::min(zhi_triangle, std::max({c[0], c[1], c[2], c[3]}));
    // (Not a structured binding: clang before 16 cannot capture one in the lambda below.)
    const TileDecision tested = tile_test(tx, band, zlo, zhi);
    const TileVerdict verdict = tested.verdict;
    const CountRule rule = tested.rule;
    if (verdict == TileVerdict::skip) {
      ++counters.tiles_skipped;
      continue;
    }
    const auto rows_of_tile = [&](auto lanes, auto checks, auto inside) {
      const Mask in_image = kLaneIndex < static_cast<int>(lanes);
      // The edge functions of row j, stepped from row to row (exact: integers).
      Mask e0 = q[0] + step_i[0] * kLaneIndex, e1 = q[1] + step_i[1] * kLaneIndex,
           e2 = q[2] + step_i[2] * kLaneIndex;
      const Mask down0 = Mask{} + step_j[0], down1 = Mask{} + step_j[1], down2 = Mask{} + step_j[2];
      for (int j = 0; j < rows; ++j, e0 += down0, e1 += down1, e2 += down2) {
        Mask covered = strip.whole ? in_image : in_image & strip_rows[j];
        if constexpr (!inside) covered &= (e0 | e1 | e2) >= 0;
        if (!any(covered)) continue;
        const Floats z = (plane.z_tile + dzdy * j) + dz_lane;
        covered_count.add(covered);
        passed_count.add(row(static_cast<std::size_t>(y0 + j) * width + x0, covered,
                             z < 0.0f   ? 0.0f
                             : z > 1.0f ? 1.0f
                                        : z,
                             lanes, checks, rule));
      }
    };
    using No = std::false_type;
    using Yes = std::true_type;
    const Mask covered_before = covered_count.sum, passed_before = passed_count.sum;
    const auto whole_rows = [&](auto checks) {
      interior ? rows_of_tile(WholeRow{}, checks, Yes{}) : rows_of_tile(WholeRow{}, checks, No{});
    };
    if (lanes < kTileSize)
      rows_of_tile(lanes, Checks<TileVerdict::test>{}, No{});
    else if (verdict == TileVerdict::accept)
      whole_rows(Checks<TileVerdict::accept>{});
    else if (verdict == TileVerdict::test_depth)
      whole_rows(Checks<TileVerdict::test_depth>{});
    else
      whole_rows(Checks<TileVerdict::test>{});
    if (work != nullptr) {
      work[tx].pixels_processed +=
          static_cast<std::uint32_t>(LaneCount{covered_count.sum - covered_before}.total());
      work[tx].pixels_updated +=
          static_cast<std::uint32_t>(LaneCount{passed_count.sum - passed_before}.total());
    }
  }
  counters.pixels_processed += covered_count.total();
  counters.pixels_passed += passed_count.total();
}

struct Prepared {
  std::size_t triangle;
  Setup setup;
};

struct BandRange {
  int first, last;  // tile rows a set-up triangle's bounding box overlaps; last < first: none
};

// A draw's triangles are set up in chunks of this many, chunks in parallel: set-up was the one
// serial stage of a draw (0.85 ms of light-in-view's 12 ms count pass at 1080p, as measured).
inline constexpr std::size_t kSetupChunk = 512;

// What one chunk of a draw's triangles became, in order: the set-up triangles (a clipped one may
// give several, a culled one none), the tile rows each overlaps, and the chunk's counters.
struct SetupChunk {
  std::vector<Prepared> prepared;
  std::vector<BandRange> ranges;
  Counters counters;
};

}  // namespace

struct Target::Scratch {
  // The chunks of the last draw: the first `chunks` entries (kept between draws, with their
  // storage, so that a warm target allocates nothing).
  std::vector<SetupChunk> setup;
  std::size_t chunks = 0;
  std::vector<Counters> band_counters;
};

Target::Target() = default;
Target::Target(Target&&) noexcept = default;
Target& Target::operator=(Target&&) noexcept = default;
Target::~Target() = default;

Target::Target(int w, int h)
    : width(w),
      height(h),
      tiles_x((w + kTileSize - 1) / kTileSize),
      tiles_y((h + kTileSize - 1) / kTileSize),
      tile_depth(static_cast<std::size_t>(tiles_x) * tiles_y) {
  // Side by side: each page's first touch is a page fault.
  const auto pixels = static_cast<std::size_t>(w) * h;
  tbb::parallel_invoke([&] { depth.assign(pixels, 0.0f); }, [&] { count.assign(pixels, 0); },
                       [&] { id.assign(pixels, kNoId); });
  blocks_x = (tiles_x + kBlockTiles - 1) / kBlockTiles;
  blocks_y = (tiles_y + kBlockTiles - 1) / kBlockTiles;
  block_depth.resize(static_cast<std::size_t>(blocks_x) * blocks_y);
  block_row_depth.resize(static_cast<std::size_t>(blocks_y));
  scissor = {0, 0, w, h};
  assert(w > 0 && h > 0 && w <= kMaxViewport && h <= kMaxViewport);
}

void Target::clear_depth(float z) {
  std::fill(depth.begin(), depth.end(), z);
  std::fill(id.begin(), id.end(), kNoId);
  std::fill(tile_depth.begin(), tile_depth.end(), TileDepth{z, z});
  std::fill(block_depth.begin(), block_depth.end(), TileDepth{z, z});
  std::fill(block_row_depth.begin(), block_row_depth.end(), TileDepth{z, z});
}

// Sweeps the buffer band by band, in parallel, as the draws use it.
void Target::take_nonzero_counts(std::span<std::uint8_t> nonzero) {
  take_nonzero_counts(nonzero, {0, 0, width, height});
}

void Target::take_nonzero_counts(std::span<std::uint8_t> nonzero, const PixelRect& within) {
  assert(nonzero.size() == count.size());
  // The tiles the rectangle meets, whole, as a scissored draw counts them.
  const int x0 = std::max(0, within.x0) / kTileSize * kTileSize;
  const int x1 = std::min(width, (within.x1 + kTileSize - 1) / kTileSize * kTileSize);
  const int y0 = std::max(0, within.y0) / kTileSize;
  const int y1 = std::min(tiles_y, (within.y1 + kTileSize - 1) / kTileSize);
  if (within.empty() || x0 >= x1) return;
  tbb::parallel_for(y0, y1, [&](int band) {
    for (int y = band * kTileSize; y < std::min(height, (band + 1) * kTileSize); ++y) {
      const std::size_t row = static_cast<std::size_t>(y) * width;
      for (std::size_t p = row + x0; p < row + x1; ++p) {
        nonzero[p] = count[p] != 0;
        count[p] = 0;
      }
    }
  });
}

void Target::take_counts_into(std::span<glm::vec3> sum, const glm::vec3& per_count) {
  assert(sum.size() == count.size());
  tbb::parallel_for(0, tiles_y, [&](int band) {
    const auto first = static_cast<std::size_t>(band) * kTileSize * width;
    const auto end = std::min(count.size(), first + std::size_t{kTileSize} * width);
    for (std::size_t p = first; p < end; ++p) {
      if (count[p] != 0) sum[p] += static_cast<float>(count[p]) * per_count;
      count[p] = 0;
    }
  });
}

void Target::update_tile_depth() {
  tbb::parallel_for(0, tiles_y, [&](int ty) {
    for (int tx = 0; tx < tiles_x; ++tx) {
      TileDepth bounds{1.0f, 0.0f};
      for (int y = ty * kTileSize; y < std::min(height, (ty + 1) * kTileSize); ++y)
        for (int x = tx * kTileSize; x < std::min(width, (tx + 1) * kTileSize); ++x) {
          const float z = depth[static_cast<std::size_t>(y) * width + x];
          bounds.zmin = std::min(bounds.zmin, z);
          bounds.zmax = std::max(bounds.zmax, z);
        }
      tile_depth[static_cast<std::size_t>(ty) * tiles_x + tx] = bounds;
    }
  });
  std::fill(block_depth.begin(), block_depth.end(), TileDepth{1.0f, 0.0f});
  for (int ty = 0; ty < tiles_y; ++ty)
    for (int tx = 0; tx < tiles_x; ++tx) {
      const TileDepth& tile = tile_depth[static_cast<std::size_t>(ty) * tiles_x + tx];
      TileDepth& block =
          block_depth[static_cast<std::size_t>(ty / kBlockTiles) * blocks_x + tx / kBlockTiles];
      block = {std::min(block.zmin, tile.zmin), std::max(block.zmax, tile.zmax)};
    }
  std::fill(block_row_depth.begin(), block_row_depth.end(), TileDepth{1.0f, 0.0f});
  for (int by = 0; by < blocks_y; ++by)
    for (int bx = 0; bx < blocks_x; ++bx) {
      const TileDepth& block = block_depth[static_cast<std::size_t>(by) * blocks_x + bx];
      TileDepth& row = block_row_depth[static_cast<std::size_t>(by)];
      row = {std::min(row.zmin, block.zmin), std::max(row.zmax, block.zmax)};
    }
}

namespace {

Target::Scratch& scratch_of(Target& target) {
  if (!target.scratch) target.scratch = std::make_unique<Target::Scratch>();
  return *target.scratch;
}

// A draw's triangles: a list of three clip-space corners each, or shared clip-space vertices and
// three indices each (a mesh's vertices transformed once, not once per triangle using them).
struct Triangles {
  std::span<const glm::vec4> points;       // the corners, or the vertices
  std::span<const std::uint32_t> indices;  // empty for a list
  std::size_t size() const { return (indices.empty() ? points.size() : indices.size()) / 3; }
  void corners(std::size_t t, glm::vec4 (&out)[3]) const {
    for (std::size_t k = 0; k < 3; ++k)
      out[k] = indices.empty() ? points[3 * t + k] : points[indices[3 * t + k]];
  }
};

// Clips, projects and sets up triangles [first, first + count) of a draw, chunks of kSetupChunk
// in parallel, into the scratch's chunks, in order, with the tile rows each set-up triangle
// overlaps.
void prepare(Target& target, const Triangles& triangles, std::size_t first, std::size_t count,
             Counters& counters, std::span<const FaceCull> cull) {
  Target::Scratch& scratch = scratch_of(target);
  const std::size_t n = first + count;
  scratch.chunks = (count + kSetupChunk - 1) / kSetupChunk;
  if (scratch.setup.size() < scratch.chunks) scratch.setup.resize(scratch.chunks);
  constexpr std::int64_t kBandHeight = std::int64_t{kTileSize} * kSubpixels;
  const auto band_of = [](std::int64_t y) {  // floor division: y may be negative
    return (y >= 0 ? y : y - kBandHeight + 1) / kBandHeight;
  };
  tbb::parallel_for(std::size_t{0}, scratch.chunks, [&](std::size_t c) {
    SetupChunk& chunk = scratch.setup[c];
    chunk.prepared.clear();
    chunk.ranges.clear();
    chunk.counters = {};
    for (std::size_t t = first + c * kSetupChunk; t < std::min(n, first + (c + 1) * kSetupChunk);
         ++t) {
      ++chunk.counters.triangles_in;
      Polygon poly;
      bool clipped = false;
      glm::vec4 corners[3];
      triangles.corners(t, corners);
      if (!clip(corners, poly, clipped)) {
        ++chunk.counters.triangles_clipped;
        ++chunk.counters.triangles_culled;
        continue;
      }
      chunk.counters.triangles_clipped += clipped;
      ScreenVertex screen[kMaxPolygon];
      for (int i = 0; i < poly.n; ++i)
        screen[i] = to_screen(poly.v[i], target.width, target.height);
      bool drawn = false;
      for (int i = 1; i + 1 < poly.n; ++i) {  // a fan: the clipped polygon is convex
        Prepared p{t, {}};
        // The facing first, as setup finds it (negative area: front), so that a culled
        // triangle costs no setup.
        if (!cull.empty() && cull[t] != FaceCull::none &&
            cull[t] ==
                (area2(screen[0], screen[i], screen[i + 1]) < 0 ? FaceCull::front : FaceCull::back))
          continue;
        if (!setup(screen[0], screen[i], screen[i + 1], p.setup)) continue;
        drawn = true;
        const std::int64_t first =
            std::clamp<std::int64_t>(band_of(p.setup.min_y), 0, target.tiles_y);
        const std::int64_t last =
            std::clamp<std::int64_t>(band_of(p.setup.max_y), -1, target.tiles_y - 1);
        chunk.prepared.push_back(p);
        chunk.ranges.push_back({static_cast<int>(first), static_cast<int>(last)});
      }
      chunk.counters.triangles_culled += !drawn;
    }
  });
  for (std::size_t c = 0; c < scratch.chunks; ++c) counters += scratch.setup[c].counters;
}

// Bands per task of for_each_band: one row of blocks. The triangles' band ranges are scanned
// once per task, not once per band, and a frame of 1080 rows still splits into 17 tasks for the
// cores to share.
inline constexpr int kBandsPerTask = kBlockTiles;

// Rasterizes the triangles prepare() set up, band by band (a band is a row of tiles), a row of
// blocks' bands per task, tasks in parallel: each band sees every triangle in order, so a
// pixel's result does not depend on the threads. Each task scans the compact lists of the
// triangles' band ranges, not their setups, and takes each triangle over its bands in the task,
// in turn, where in_block_row(triangle, block row, first band, last band) says it may draw there.
template <class PerTriangle, class InBlockRow>
void for_each_band(Target& target, Counters& counters, PerTriangle&& per_triangle,
                   InBlockRow&& in_block_row) {
  Target::Scratch& scratch = scratch_of(target);
  scratch.band_counters.assign(static_cast<std::size_t>(target.tiles_y), Counters{});
  const int tasks = (target.tiles_y + kBandsPerTask - 1) / kBandsPerTask;
  tbb::parallel_for(0, tasks, [&](int task) {
    const int first = task * kBandsPerTask;
    const int last = std::min(first + kBandsPerTask, target.tiles_y) - 1;
    for (std::size_t c = 0; c < scratch.chunks; ++c) {
      const SetupChunk& chunk = scratch.setup[c];
      for (std::size_t t = 0; t < chunk.prepared.size(); ++t) {
        const BandRange& range = chunk.ranges[t];
        const int from = std::max(first, range.first), to = std::min(last, range.last);
        if (from > to) continue;
        if (!in_block_row(chunk.prepared[t], task, from, to)) {
          ++scratch.band_counters[static_cast<std::size_t>(from)].block_rows_skipped;
          continue;
        }
        for (int band = from; band <= to; ++band)
          per_triangle(chunk.prepared[t], band,
                       scratch.band_counters[static_cast<std::size_t>(band)]);
      }
    }
  });
  for (const Counters& c : scratch.band_counters) counters += c;
}
// A draw's triangles a batch at a time: set up (prepare), then rasterized band by band
// (for_each_band). A set-up triangle takes some 200 bytes: a large mesh's batches reuse a few MB,
// warm in cache, rather than one setup array of its size, first touched page by page.
inline constexpr std::size_t kBatchTriangles = std::size_t{1} << 15;

template <class PerTriangle, class InBlockRow>
void draw_in_batches(Target& target, const Triangles& triangles, Counters& counters,
                     std::span<const FaceCull> cull, PerTriangle&& per_triangle,
                     InBlockRow&& in_block_row) {
  const std::size_t n = triangles.size();
  for (std::size_t first = 0; first < n; first += kBatchTriangles) {
    prepare(target, triangles, first, std::min(kBatchTriangles, n - first), counters, cull);
    for_each_band(target, counters, per_triangle, in_block_row);
  }
}
template <class PerTriangle>
void draw_in_batches(Target& target, const Triangles& triangles, Counters& counters,
                     std::span<const FaceCull> cull, PerTriangle&& per_triangle) {
  draw_in_batches(target, triangles, counters, cull, per_triangle,
                  [](const Prepared&, int, int, int) { return true; });
}

// The coarser hi-z (kBlockTiles): whether a fragment of the triangle in bands [first, last] of
// block row `row` may pass a depth test against some block it crosses there, within `bounds`:
// z-pass's (nearer than the stored depth) or z-fail's (at or behind it). Its depth range over its
// part of those rows, within its vertices' depths as a tile test takes it, is widened by what the
// float steps to a pixel's depth may add: four roundings, each below 2^-24 of the plane's size
// within a tile of that part, a millionth of it in all.
bool may_pass_in_blocks(const Target& target, const Setup& s, int row, int first, int last,
                        const DepthBounds& bounds, bool zpass) {
  // First the whole row against the triangle's vertices' depths: no slab to find.
  const TileDepth& in_row = target.block_row_depth[static_cast<std::size_t>(row)];
  const float vertices_lo = std::min({s.v[0].z, s.v[1].z, s.v[2].z}) - kDepthSlack;
  const float vertices_hi = std::max({s.v[0].z, s.v[1].z, s.v[2].z}) + kDepthSlack;
  if (in_row.zmax < bounds.zmin || in_row.zmin > bounds.zmax ||
      !(zpass ? vertices_hi > in_row.zmin : vertices_lo <= in_row.zmax))
    return false;
  const int y0 = first * kTileSize, y1 = std::min(target.height, (last + 1) * kTileSize) - 1;
  SlabExtent e;
  if (!slab_extent<true>(s, y0, y1, target.width, e)) return false;
  const double size = std::max(std::abs(e.zlo), std::abs(e.zhi)) +
                      2.0 * kTileSize * (std::abs(s.dzdx) + std::abs(s.dzdy));
  const double slack = kDepthSlack + 1e-6 * size;
  const float zlo = static_cast<float>(std::max<double>(vertices_lo, e.zlo - slack));
  const float zhi = static_cast<float>(std::min<double>(vertices_hi, e.zhi + slack));
  constexpr int kBlockPixels = kTileSize * kBlockTiles;
  for (int bx = e.px0 / kBlockPixels; bx <= e.px1 / kBlockPixels; ++bx) {
    const TileDepth& block =
        target.block_depth[static_cast<std::size_t>(row) * target.blocks_x + bx];
    if (block.zmax < bounds.zmin || block.zmin > bounds.zmax) continue;
    if (zpass ? zhi > block.zmin : zlo <= block.zmax) return true;
  }
  return false;
}

// The depth pass, triangle t with the id id_of(t).
template <class IdOf>
void depth_pass(Target& target, const Triangles& triangles, Counters& counters, IdOf id_of,
                std::span<const FaceCull> cull = {}) {
  draw_in_batches(target, triangles, counters, cull, [&](const Prepared& p, int band, Counters& c) {
    const std::uint32_t id = id_of(p.triangle);
    float* depth = target.depth.data();
    std::uint32_t* ids = target.id.data();
    raster(
        target, p.setup, band, c, nullptr, StripInPixels{},
        [](int, int, float, float) {
          return TileDecision{TileVerdict::test, CountRule::zpass};
        },
        [depth, ids, id](std::size_t first, const Mask& covered, const Floats& z, auto lanes,
                         auto /*checks: always test*/, CountRule) {
          const Floats stored = load_row<Floats>(depth + first, lanes);
          const Mask pass = covered & (z > stored);
          store_row(depth + first, pass ? z : stored, lanes);
          const Mask old_ids = load_row<Mask>(ids + first, lanes);
          store_row(ids + first, pass ? Mask{} + static_cast<std::int32_t>(id) : old_ids, lanes);
          return pass;
        });
  });
}

}  // namespace

void draw_depth(Target& target, std::span<const glm::vec4> triangles, std::uint32_t first_id,
                Counters& counters) {
  depth_pass(target, {triangles, {}}, counters,
             [first_id](std::size_t t) { return static_cast<std::uint32_t>(first_id + t); });
}

void draw_depth(Target& target, std::span<const glm::vec4> triangles,
                std::span<const std::uint32_t> ids, Counters& counters) {
  assert(ids.size() * 3 == triangles.size());
  depth_pass(target, {triangles, {}}, counters, [ids](std::size_t t) { return ids[t]; });
}

void draw_depth(Target& target, std::span<const glm::vec4> vertices,
                std::span<const std::uint32_t> indices, std::span<const std::uint32_t> ids,
                Counters& counters, std::span<const FaceCull> cull) {
  assert(ids.size() * 3 == indices.size());
  assert(cull.empty() || cull.size() == ids.size());
  depth_pass(
      target, {vertices, indices}, counters, [ids](std::size_t t) { return ids[t]; }, cull);
}

std::uint64_t query(Target& target, std::span<const glm::vec4> triangles, DepthBounds bounds,
                    Counters& counters, bool stop_at_first) {
  const std::uint64_t passed_before = counters.pixels_passed;
  // Skips a tile only where every fragment lies behind every stored depth; the hi-z's nearest
  // depth may be stale (older, farther) during a depth pass, which only skips less.
  auto tile_test = [&target](int tx, int band, float, float zhi) {
    const TileDepth& tile = target.tile_depth[static_cast<std::size_t>(band) * target.tiles_x + tx];
    return TileDecision{zhi < tile.zmin ? TileVerdict::skip : TileVerdict::test, CountRule::zpass};
  };
  std::atomic<bool> found{false};
  draw_in_batches(
      target, {triangles, {}}, counters, {}, [&](const Prepared& p, int band, Counters& c) {
        if (stop_at_first && found.load(std::memory_order_relaxed)) return;
        const float* depth = target.depth.data();
        raster(target, p.setup, band, c, nullptr, StripInPixels{}, tile_test,
               [depth, bounds, &found](std::size_t first, const Mask& covered, const Floats& z,
                                       auto lanes, auto, CountRule) {
                 const Floats stored = load_row<Floats>(depth + first, lanes);
                 const Mask pass =
                     covered & (z >= stored) & (stored >= bounds.zmin) & (stored <= bounds.zmax);
                 if (any(pass)) found.store(true, std::memory_order_relaxed);
                 return pass;
               });
      });
  return counters.pixels_passed - passed_before;
}

CountRule split_rule(const Target& target, int tile_x, int tile_y, const glm::vec4& plane) {
  const TileDepth& tile =
      target.tile_depth[static_cast<std::size_t>(tile_y) * target.tiles_x + tile_x];
  const float x =
      (float(tile_x * kTileSize) + kTileSize / 2.0f) / float(target.width) * 2.0f - 1.0f;
  const float y =
      1.0f - (float(tile_y * kTileSize) + kTileSize / 2.0f) / float(target.height) * 2.0f;
  // Laine 2005 Eq. 8 at the middle of the tile's depth range: the side of the plane the point
  // lies on, against the camera's side, sign(plane.z). Laine tests the farthest depth (favouring
  // z-fail where the plane cuts the tile's range) and calls the choice arbitrary; the middle
  // favours neither, and did better on each of the suite's scenes (README).
  const float middle = 0.5f * (tile.zmin + tile.zmax);
  const float side = plane.x * x + plane.y * y + plane.z * middle + plane.w;
  const bool camera_side = (plane.z > 0.0f && side > 0.0f) || (plane.z < 0.0f && side < 0.0f);
  return camera_side ? CountRule::zpass : CountRule::zfail;
}

DepthBounds reached_depths(std::span<const glm::vec4> triangles) {
  DepthBounds b{1.0f, 0.0f};
  for (const glm::vec4& c : triangles) {
    if (!(c.w > 0.0f)) return {};
    const float z = std::clamp(c.z / c.w, 0.0f, 1.0f);
    b.zmin = std::min(b.zmin, z);
    b.zmax = std::max(b.zmax, z);
  }
  if (b.zmin > b.zmax) return b;  // nothing drawn
  constexpr float kSlack = 1e-5f;
  return {std::max(0.0f, b.zmin - kSlack), std::min(1.0f, b.zmax + kSlack)};
}

namespace {

// A count pass, triangle t within the depth bounds bounds_of(t).
template <class BoundsOf>
void count_pass(Target& target, std::span<const glm::vec4> triangles,
                std::span<const std::int32_t> weights, CountRule rule, Counters& counters,
                BoundsOf bounds_of, const SplitPlane& split, const ScreenStrip& strip) {
  assert(weights.size() * 3 == triangles.size());
  assert(target.tile_work.empty() ||
         target.tile_work.size() == static_cast<std::size_t>(target.tiles_x) * target.tiles_y);
  // A tile is skipped when no fragment can pass the rule's test (Laine 2005 §5): z-pass needs
  // some fragment nearer (greater) than some stored depth, z-fail some fragment at or behind
  // one. It is accepted whole when every fragment passes against every stored depth, within the
  // bounds. The split plane's pick comes first: a draw limited to the other rule's tiles skips
  // the tile, and the split rule takes the pick as the tile's rule. A pre-fill takes every tile.
  auto tile_test = [&target, rule, &split](const DepthBounds& bounds, int tx, int band, float zlo,
                                           float zhi) {
    const TileDepth& tile = target.tile_depth[static_cast<std::size_t>(band) * target.tiles_x + tx];
    CountRule tile_rule = rule;
    if (rule == CountRule::split || split.tiles != SplitTiles::all) {
      const CountRule picked = split_rule(target, tx, band, split.plane);
      if (split.tiles != SplitTiles::all &&
          (split.tiles == SplitTiles::zpass_only) != (picked == CountRule::zpass))
        return TileDecision{TileVerdict::skip, picked};
      if (rule == CountRule::split) tile_rule = picked;
    }
    if (tile_rule == CountRule::prefill || tile_rule == CountRule::fill)
      return TileDecision{TileVerdict::accept, tile_rule};
    if (tile.zmax < bounds.zmin || tile.zmin > bounds.zmax)
      return TileDecision{TileVerdict::skip, tile_rule};
    const bool within_bounds = bounds.zmin <= tile.zmin && tile.zmax <= bounds.zmax;
    // cover tests depth as z-pass does, behind as z-fail does
    const bool zpass = tile_rule != CountRule::zfail && tile_rule != CountRule::behind;
    const bool some = zpass ? zhi > tile.zmin : zlo <= tile.zmax;
    const bool all = zpass ? zlo > tile.zmax : zhi <= tile.zmin;
    return TileDecision{!some                  ? TileVerdict::skip
                        : all && within_bounds ? TileVerdict::accept
                        : within_bounds        ? TileVerdict::test_depth
                                               : TileVerdict::test,
                        tile_rule};
  };
  const std::uint64_t passed_before = counters.pixels_passed;
  const StripInPixels strip_in_pixels(strip, target.width, target.height);
  // Rules that test depth alike on every tile may leave a triangle out of a block row at once.
  const bool blockwise =
      split.tiles == SplitTiles::all && (rule == CountRule::zpass || rule == CountRule::zfail ||
                                         rule == CountRule::cover || rule == CountRule::behind);
  const bool zpass_test = rule == CountRule::zpass || rule == CountRule::cover;
  const auto in_block_row = [&](const Prepared& p, int row, int first, int last) {
    return !blockwise ||
           may_pass_in_blocks(target, p.setup, row, first, last, bounds_of(p.triangle), zpass_test);
  };
  draw_in_batches(
      target, {triangles, {}}, counters, {},
      [&](const Prepared& p, int band, Counters& c) {
        // z-pass (and prefill): front faces in front of the surface add; z-fail: front faces behind
        // it subtract; cover and behind: every face in front of it, or behind it, adds.
        const bool unsigned_faces = rule == CountRule::cover || rule == CountRule::behind;
        const std::int32_t front_delta =
            (p.setup.front || unsigned_faces ? 1 : -1) * weights[p.triangle];
        if (front_delta == 0) return;
        const float* depth = target.depth.data();
        std::int32_t* count = target.count.data();
        const DepthBounds bounds = bounds_of(p.triangle);
        TileWork* work = target.tile_work.empty()
                             ? nullptr
                             : &target.tile_work[static_cast<std::size_t>(band) * target.tiles_x];
        raster(
            target, p.setup, band, c, work, strip_in_pixels,
            [&tile_test, &bounds](int tx, int band, float zlo, float zhi) {
              return tile_test(bounds, tx, band, zlo, zhi);
            },
            // By value: the stores into count may alias anything an int32 reference names.
            [depth, count, bounds, front_delta](std::size_t first, const Mask& covered,
                                                const Floats& z, auto lanes, auto checks,
                                                CountRule tile_rule) {
              // Depth as z-pass tests it: prefill and cover too; behind tests as z-fail does.
              const bool zpass = tile_rule != CountRule::zfail && tile_rule != CountRule::behind;
              const std::int32_t delta = tile_rule == CountRule::zfail ? -front_delta : front_delta;
              if (tile_rule == CountRule::fill) return covered;  // touched, nothing written
              if constexpr (checks == TileVerdict::accept) {
                store_row(count + first, load_row<Mask>(count + first, lanes) + (covered & delta),
                          lanes);
                return covered;
              }
              const Floats stored = load_row<Floats>(depth + first, lanes);
              const Mask in_front = z > stored;
              Mask pass = covered & (zpass ? in_front : ~in_front);
              if constexpr (checks == TileVerdict::test)
                pass &= (stored >= bounds.zmin) & (stored <= bounds.zmax);
              store_row(count + first, load_row<Mask>(count + first, lanes) + (pass & delta),
                        lanes);
              return pass;
            });
      },
      in_block_row);
  if (rule != CountRule::fill)
    counters.count_updates += counters.pixels_passed - passed_before;  // every pass writes
}

}  // namespace

bool near_plane_cut(const glm::vec4* triangle, glm::vec4& leaves, glm::vec4& returns) {
  float d[3];
  for (int k = 0; k < 3; ++k) d[k] = plane_distance(0, triangle[k]);
  bool left = false, came_back = false;
  for (int i = 0; i < 3; ++i) {  // clip_polygon's walk, its crossings computed as it does
    const int j = (i + 1) % 3;
    const bool in_i = d[i] >= 0.0f, in_j = d[j] >= 0.0f;
    if (in_i && !in_j) leaves = plane_crossing(triangle[i], triangle[j], d[i], d[j]), left = true;
    if (!in_i && in_j)
      returns = plane_crossing(triangle[j], triangle[i], d[j], d[i]), came_back = true;
  }
  return left && came_back;
}

void draw_counts(Target& target, std::span<const glm::vec4> triangles,
                 std::span<const std::int32_t> weights, CountRule rule, Counters& counters,
                 DepthBounds bounds, const SplitPlane& split, const ScreenStrip& strip) {
  count_pass(
      target, triangles, weights, rule, counters, [bounds](std::size_t) { return bounds; }, split,
      strip);
}

void draw_counts(Target& target, std::span<const glm::vec4> triangles,
                 std::span<const std::int32_t> weights, std::span<const DepthBounds> bounds,
                 CountRule rule, Counters& counters) {
  assert(bounds.size() == weights.size());
  count_pass(target, triangles, weights, rule, counters,
             [bounds](std::size_t t) { return bounds[t]; }, {}, {});
}

}  // namespace shadowvol::raster
