// The software rasterizer's triangle stage: clip -> setup -> raster, per 8 x 8 tile.
// Stages named as llvmpipe names them; every constant says where it comes from (raster.h).
#include "soft/raster.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

#include <tbb/parallel_for.h>

namespace shadowvol::soft {

Target::Target(int w, int h)
    : width(w),
      height(h),
      tiles_x((w + kTileSize - 1) / kTileSize),
      tiles_y((h + kTileSize - 1) / kTileSize),
      depth(static_cast<std::size_t>(w) * h, 1.0f),
      count(static_cast<std::size_t>(w) * h, 0),
      id(static_cast<std::size_t>(w) * h, kNoId),
      tile_depth(static_cast<std::size_t>(tiles_x) * tiles_y) {
  assert(w > 0 && h > 0 && w <= kMaxViewport && h <= kMaxViewport);
}

void Target::clear_depth(float z) {
  std::fill(depth.begin(), depth.end(), z);
  std::fill(id.begin(), id.end(), kNoId);
  std::fill(tile_depth.begin(), tile_depth.end(), TileDepth{z, z});
}

void Target::clear_count() { std::fill(count.begin(), count.end(), 0); }

void Target::update_tile_depth() {
  for (int ty = 0; ty < tiles_y; ++ty)
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
}

namespace {

// --- clip ---------------------------------------------------------------------------------

// Signed distances to the clip planes, >= 0 inside: near (z >= -w), the four guard-band planes,
// and w > 0 (which a proper projection never reaches once the near plane has clipped; it keeps
// the division safe whatever the caller passes).
constexpr int kPlanes = 6;
inline float plane_distance(int plane, const glm::vec4& v) {
  switch (plane) {
    case 0:
      return v.z + v.w;
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

// Sutherland-Hodgman against every plane. Each new vertex is computed from the edge's inside
// vertex towards its outside one, whichever order the polygon runs it in: two triangles that
// share an edge then compute the same point, bit for bit, and stay watertight along the cut.
constexpr int kMaxPolygon = 3 + kPlanes;
struct Polygon {
  std::array<glm::vec4, kMaxPolygon> v;
  int n = 0;
};

bool clip(const glm::vec4* tri, Polygon& out, bool& clipped) {
  Polygon a, b;
  a.v[0] = tri[0], a.v[1] = tri[1], a.v[2] = tri[2], a.n = 3;
  clipped = false;
  for (int plane = 0; plane < kPlanes; ++plane) {
    float d[kMaxPolygon];
    bool any_out = false;
    for (int i = 0; i < a.n; ++i) {
      d[i] = plane_distance(plane, a.v[i]);
      any_out |= !(d[i] >= 0.0f);  // NaN counts as outside
    }
    if (!any_out) continue;
    clipped = true;
    b.n = 0;
    for (int i = 0; i < a.n; ++i) {
      const int j = (i + 1) % a.n;
      const bool in_i = d[i] >= 0.0f, in_j = d[j] >= 0.0f;
      if (in_i) b.v[b.n++] = a.v[i];
      if (in_i != in_j) {
        const int in = in_i ? i : j, out = in_i ? j : i;
        const float t = d[in] / (d[in] - d[out]);
        b.v[b.n++] = a.v[in] + (a.v[out] - a.v[in]) * t;
      }
    }
    std::swap(a, b);
    if (a.n < 3) return false;
  }
  out = a;
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
  std::int64_t bias[3];  // 0 on top-left edges, -1 elsewhere: the top-left fill rule
  double dzdx, dzdy;     // depth per pixel
  std::int64_t min_x, max_x, min_y, max_y;  // subpixel bounding box
};

ScreenVertex to_screen(const glm::vec4& c, int width, int height) {
  const double inv_w = 1.0 / c.w;
  const double sx = (c.x * inv_w + 1.0) * 0.5 * width * kSubpixels;
  const double sy = (1.0 - c.y * inv_w) * 0.5 * height * kSubpixels;
  const double z = (c.z * inv_w + 1.0) * 0.5;
  return {std::llround(sx), std::llround(sy), static_cast<float>(std::clamp(z, 0.0, 1.0))};
}

bool setup(const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c, Setup& s) {
  s.v[0] = a, s.v[1] = b, s.v[2] = c;
  s.area2 = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
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
  }
  const ScreenVertex& p = s.v[0];
  const double e1x = double(s.v[1].x - p.x), e1y = double(s.v[1].y - p.y);
  const double e2x = double(s.v[2].x - p.x), e2y = double(s.v[2].y - p.y);
  const double z1 = double(s.v[1].z) - p.z, z2 = double(s.v[2].z) - p.z;
  const double inv_area = 1.0 / double(s.area2);
  s.dzdx = (z1 * e2y - z2 * e1y) * inv_area * kSubpixels;
  s.dzdy = (z2 * e1x - z1 * e2x) * inv_area * kSubpixels;
  s.min_x = std::min({s.v[0].x, s.v[1].x, s.v[2].x});
  s.max_x = std::max({s.v[0].x, s.v[1].x, s.v[2].x});
  s.min_y = std::min({s.v[0].y, s.v[1].y, s.v[2].y});
  s.max_y = std::max({s.v[0].y, s.v[1].y, s.v[2].y});
  return true;
}

// Depth of the triangle's plane at pixel (px, py), evaluated directly (not incrementally), so
// that the same triangle gives the same depth at the same pixel in every pass. Clamped like a
// depth clamp.
inline float depth_at(const Setup& s, int px, int py) {
  const double x = (double(px) + 0.5) - double(s.v[0].x) / kSubpixels;
  const double y = (double(py) + 0.5) - double(s.v[0].y) / kSubpixels;
  return static_cast<float>(std::clamp(s.v[0].z + s.dzdx * x + s.dzdy * y, 0.0, 1.0));
}

// --- raster -------------------------------------------------------------------------------

// The edge functions at a pixel centre, plus their fill-rule bias: >= 0 inside.
inline std::int64_t edge_at(const Setup& s, int i, int px, int py) {
  const std::int64_t cx = (std::int64_t{px} << kSubpixelBits) + kSubpixels / 2;
  const std::int64_t cy = (std::int64_t{py} << kSubpixelBits) + kSubpixels / 2;
  return s.dx[i] * (cy - s.v[i].y) - s.dy[i] * (cx - s.v[i].x) + s.bias[i];
}

// Calls fragment(pixel_index, depth) for every covered pixel in tile rows [band_begin,
// band_end), tile by tile. Per tile, first the edge test (edge functions are linear, so the
// four corner pixel centres tell whether any pixel centre of the tile can be inside, and whether
// all are), then tile_test(hi-z bounds, the triangle's depth range over the tile).
template <class TileTest, class Fragment>
void raster(const Target& target, const Setup& s, int band_begin, int band_end, Counters& counters,
            TileTest&& tile_test, Fragment&& fragment) {
  const auto pixel_of = [](std::int64_t sub) { return (sub - kSubpixels / 2) >> kSubpixelBits; };
  const int px0 = static_cast<int>(std::max<std::int64_t>(0, pixel_of(s.min_x)));
  const int px1 = static_cast<int>(std::min<std::int64_t>(target.width - 1, pixel_of(s.max_x) + 1));
  const int py0 = static_cast<int>(
      std::max<std::int64_t>({0, pixel_of(s.min_y), std::int64_t{band_begin} * kTileSize}));
  const int py1 = static_cast<int>(std::min<std::int64_t>(
      {target.height - 1, pixel_of(s.max_y) + 1, std::int64_t{band_end} * kTileSize - 1}));
  if (px0 > px1 || py0 > py1) return;
  const float zlo_triangle = std::min({s.v[0].z, s.v[1].z, s.v[2].z});
  const float zhi_triangle = std::max({s.v[0].z, s.v[1].z, s.v[2].z});
  for (int ty = py0 / kTileSize; ty <= py1 / kTileSize; ++ty)
    for (int tx = px0 / kTileSize; tx <= px1 / kTileSize; ++tx) {
      const int x0 = std::max(px0, tx * kTileSize),
                x1 = std::min(px1, tx * kTileSize + kTileSize - 1);
      const int y0 = std::max(py0, ty * kTileSize),
                y1 = std::min(py1, ty * kTileSize + kTileSize - 1);
      bool outside = false, covers_all = true;
      for (int i = 0; i < 3 && !outside; ++i) {
        const std::int64_t e[4] = {edge_at(s, i, x0, y0), edge_at(s, i, x1, y0),
                                   edge_at(s, i, x0, y1), edge_at(s, i, x1, y1)};
        outside = e[0] < 0 && e[1] < 0 && e[2] < 0 && e[3] < 0;
        covers_all &= e[0] >= 0 && e[1] >= 0 && e[2] >= 0 && e[3] >= 0;
      }
      if (outside) continue;
      ++counters.tiles_touched;
      // The triangle's depth over the tile: its plane at the corner pixels, within its own range.
      const float c[4] = {depth_at(s, x0, y0), depth_at(s, x1, y0), depth_at(s, x0, y1),
                          depth_at(s, x1, y1)};
      const float zlo = std::max(zlo_triangle, std::min({c[0], c[1], c[2], c[3]}));
      const float zhi = std::min(zhi_triangle, std::max({c[0], c[1], c[2], c[3]}));
      if (!tile_test(target.tile_depth[static_cast<std::size_t>(ty) * target.tiles_x + tx], zlo,
                     zhi)) {
        ++counters.tiles_skipped;
        continue;
      }
      for (int py = y0; py <= y1; ++py) {
        std::int64_t e0 = edge_at(s, 0, x0, py), e1 = edge_at(s, 1, x0, py),
                     e2 = edge_at(s, 2, x0, py);
        const std::int64_t step0 = -s.dy[0] * kSubpixels, step1 = -s.dy[1] * kSubpixels,
                           step2 = -s.dy[2] * kSubpixels;
        for (int px = x0; px <= x1; ++px, e0 += step0, e1 += step1, e2 += step2) {
          if (!covers_all && (e0 < 0 || e1 < 0 || e2 < 0)) continue;
          ++counters.pixels_processed;
          fragment(static_cast<std::size_t>(py) * target.width + px, depth_at(s, px, py));
        }
      }
    }
}

struct Prepared {
  std::size_t triangle;
  Setup setup;
};

// Clips, projects and sets up every triangle of the batch, in order.
void prepare(const Target& target, std::span<const glm::vec4> triangles, Counters& counters,
             std::vector<Prepared>& out) {
  assert(triangles.size() % 3 == 0);
  out.clear();
  for (std::size_t t = 0; t < triangles.size() / 3; ++t) {
    ++counters.triangles_in;
    Polygon poly;
    bool clipped = false;
    if (!clip(&triangles[3 * t], poly, clipped)) {
      ++counters.triangles_clipped;
      ++counters.triangles_culled;
      continue;
    }
    counters.triangles_clipped += clipped;
    ScreenVertex screen[kMaxPolygon];
    for (int i = 0; i < poly.n; ++i) screen[i] = to_screen(poly.v[i], target.width, target.height);
    bool drawn = false;
    for (int i = 1; i + 1 < poly.n; ++i) {  // a fan: the clipped polygon is convex
      Prepared p{t, {}};
      if (!setup(screen[0], screen[i], screen[i + 1], p.setup)) continue;
      drawn = true;
      out.push_back(p);
    }
    counters.triangles_culled += !drawn;
  }
}

void add(Counters& to, const Counters& from) {
  to.tiles_touched += from.tiles_touched;
  to.tiles_skipped += from.tiles_skipped;
  to.pixels_processed += from.pixels_processed;
  to.pixels_passed += from.pixels_passed;
  to.count_updates += from.count_updates;
}

// Rasterizes the prepared triangles band by band (a band is a row of tiles), bands in parallel:
// each band sees every triangle in order, so a pixel's result does not depend on the threads.
template <class PerTriangle>
void for_each_band(const Target& target, const std::vector<Prepared>& prepared, Counters& counters,
                   PerTriangle&& per_triangle) {
  std::vector<Counters> band_counters(static_cast<std::size_t>(target.tiles_y));
  tbb::parallel_for(0, target.tiles_y, [&](int band) {
    Counters& c = band_counters[static_cast<std::size_t>(band)];
    const std::int64_t top = std::int64_t{band} * kTileSize * kSubpixels;
    const std::int64_t bottom = top + std::int64_t{kTileSize} * kSubpixels;
    for (const Prepared& p : prepared)
      if (p.setup.max_y >= top && p.setup.min_y < bottom) per_triangle(p, band, c);
  });
  for (const Counters& c : band_counters) add(counters, c);
}

}  // namespace

void draw_depth(Target& target, std::span<const glm::vec4> triangles, std::uint32_t first_id,
                Counters& counters) {
  std::vector<Prepared> prepared;
  prepare(target, triangles, counters, prepared);
  for_each_band(target, prepared, counters, [&](const Prepared& p, int band, Counters& c) {
    const auto id = static_cast<std::uint32_t>(first_id + p.triangle);
    raster(
        target, p.setup, band, band + 1, c, [](const TileDepth&, float, float) { return true; },
        [&](std::size_t pixel, float z) {
          if (z < target.depth[pixel]) {
            target.depth[pixel] = z;
            target.id[pixel] = id;
            ++c.pixels_passed;
          }
        });
  });
}

void draw_counts(Target& target, std::span<const glm::vec4> triangles,
                 std::span<const std::int32_t> weights, CountRule rule, Counters& counters,
                 DepthBounds bounds) {
  assert(weights.size() * 3 == triangles.size());
  std::vector<Prepared> prepared;
  prepare(target, triangles, counters, prepared);
  // A tile is skipped when no fragment can pass the rule's test (Laine 2005 §5): z-pass needs
  // some fragment nearer than some stored depth, z-fail some fragment at or behind one.
  auto tile_test = [rule, bounds](const TileDepth& tile, float zlo, float zhi) {
    if (tile.zmax < bounds.zmin || tile.zmin > bounds.zmax) return false;
    return rule == CountRule::zpass ? zlo < tile.zmax : zhi >= tile.zmin;
  };
  for_each_band(target, prepared, counters, [&](const Prepared& p, int band, Counters& c) {
    // z-pass: front faces in front of the surface add; z-fail: front faces behind it subtract.
    const std::int32_t facing = p.setup.front ? 1 : -1;
    const std::int32_t delta = (rule == CountRule::zpass ? 1 : -1) * facing * weights[p.triangle];
    if (delta == 0) return;
    raster(target, p.setup, band, band + 1, c, tile_test, [&](std::size_t pixel, float z) {
      const float stored = target.depth[pixel];
      if (stored < bounds.zmin || stored > bounds.zmax) return;
      const bool in_front = z < stored;
      if (in_front == (rule == CountRule::zpass)) {
        target.count[pixel] += delta;
        ++c.pixels_passed;
        ++c.count_updates;
      }
    });
  });
}

}  // namespace shadowvol::soft
