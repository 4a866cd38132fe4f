#include "accel/light_views.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cassert>
#include <cmath>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>

#include "core/clip_polygon.h"

namespace shadowvol {
namespace {

constexpr float kFar = std::numeric_limits<float>::infinity();
// A single frustum holds receivers up to this angle from its axis (tan = 4); wider, the cube.
constexpr double kMaxCosFromAxis = 0.2425;
// How near a sample must be to a pixel's edge to count in the pixel beyond it too, and how far
// inside a triangle's edges a footprint's corners must lie to count as covered: both far above
// the error of projecting in double, far below a pixel.
constexpr double kPixelSlack = 1e-3;

// The nearest float at or above d: a depth stored no nearer than it is.
float round_up(double d) {
  float f = static_cast<float>(d);
  if (static_cast<double>(f) < d) f = std::nextafter(f, kFar);
  return f;
}

std::array<glm::dvec3, 8> corners(const Box& box) {
  std::array<glm::dvec3, 8> c;
  for (int i = 0; i < 8; ++i)
    c[i] = {i & 1 ? box.hi.x : box.lo.x, i & 2 ? box.hi.y : box.lo.y, i & 4 ? box.hi.z : box.lo.z};
  return c;
}

// A triangle in a view's pixels: x, y and depth at each vertex.
using ScreenTriangle = std::array<glm::dvec3, 3>;

// Levels of 2x2 maxima over level 0 (size x size, already filled), in the storage the pyramid
// had: a frame of the same size allocates nothing.
void build_pyramid(std::vector<std::vector<float>>& pyramid, int size) {
  std::size_t level = 1;
  for (int w = size; w > 1; ++level) {
    const int n = (w + 1) / 2;
    if (pyramid.size() <= level) pyramid.emplace_back();
    const std::vector<float>& fine = pyramid[level - 1];
    std::vector<float>& coarse = pyramid[level];
    coarse.resize(static_cast<std::size_t>(n) * n);
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        float m = -kFar;
        for (int j = 0; j < 2; ++j)
          for (int i = 0; i < 2; ++i) {
            const int fx = 2 * x + i, fy = 2 * y + j;
            if (fx < w && fy < w) m = std::max(m, fine[static_cast<std::size_t>(fy) * w + fx]);
          }
        coarse[static_cast<std::size_t>(y) * n + x] = m;
      }
    w = n;
  }
  pyramid.resize(level);
}

}  // namespace

void LightViews::set_view(View& view, bool perspective, const glm::dvec3& origin,
                          const glm::dvec3& axis, const glm::dvec3& right_hint, bool depths) {
  view.perspective = perspective;
  view.origin = origin;
  view.axis = glm::normalize(axis);
  view.right = glm::normalize(glm::cross(right_hint, view.axis));
  view.up = glm::cross(view.axis, view.right);
  const std::size_t pixels = depths ? static_cast<std::size_t>(size_) * size_ : 0;
  view.seen.resize(std::max<std::size_t>(view.seen.size(), 1));
  view.seen[0].assign(pixels, kFar);
  view.receiver.assign(pixels, -kFar);
  const std::size_t layers = depths ? static_cast<std::size_t>(layers_) : 0;
  view.layer_receiver.resize(std::max(view.layer_receiver.size(), layers));
  view.layer_kept.resize(std::max(view.layer_kept.size(), layers));
  for (std::size_t k = 0; k < layers; ++k) view.layer_receiver[k].assign(pixels, -kFar);
}

void LightViews::fit(const glm::dvec4& light, const std::vector<Box>& receivers, int size,
                     bool depths, int layers) {
  size_ = size;
  layers_ = depths ? layers : 0;
  views_count_ = 0;
  kept_ = occluders_ = false;
  std::vector<glm::dvec3> points;
  for (const Box& box : receivers)
    if (!box.empty())
      for (const glm::dvec3& c : corners(box)) points.push_back(c);
  if (points.empty()) return;
  auto hint = [](const glm::dvec3& axis) {
    return std::abs(axis.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
  };
  auto fit_window = [&](View& view) {
    double reach = 0;
    view.u0 = view.v0 = INFINITY;
    view.u1 = view.v1 = -INFINITY;
    for (const glm::dvec3& p : points) {
      const glm::dvec3 rel = p - view.origin;
      const double d = view.perspective ? glm::dot(rel, view.axis) : 1.0;
      const double u = glm::dot(rel, view.right) / d, v = glm::dot(rel, view.up) / d;
      view.u0 = std::min(view.u0, u), view.u1 = std::max(view.u1, u);
      view.v0 = std::min(view.v0, v), view.v1 = std::max(view.v1, v);
      reach = std::max(reach, glm::length(rel));
    }
    // A window of no width (receivers edge-on to the light) still needs pixels.
    const double pad = 1e-6 * std::max({view.u1 - view.u0, view.v1 - view.v0, 1e-3});
    view.u0 -= pad, view.u1 += pad, view.v0 -= pad, view.v1 += pad;
    view.tolerance = 1e-5 * reach;
  };
  if (light.w == 0.0) {  // directional: rays run from the light's direction
    const glm::dvec3 axis = -glm::dvec3(light);
    View& view = next_view();
    set_view(view, false, glm::dvec3(0.0), axis, hint(glm::normalize(axis)), depths);
    fit_window(view);
    return;
  }
  const glm::dvec3 l = glm::dvec3(light) / light.w;
  glm::dvec3 sum(0.0);
  double farthest = 0;
  for (const glm::dvec3& p : points) {
    const double r = glm::length(p - l);
    farthest = std::max(farthest, r);
    if (r > 0) sum += (p - l) / r;
  }
  bool single = glm::length(sum) > 1e-9 * static_cast<double>(points.size());
  for (const Box& box : receivers)  // a receiver around the light: no frustum holds it
    single = single && (box.empty() || glm::any(glm::lessThan(l, box.lo)) ||
                        glm::any(glm::greaterThan(l, box.hi)));
  if (single) {
    const glm::dvec3 axis = glm::normalize(sum);
    double nearest = INFINITY;
    for (const glm::dvec3& p : points) {
      const double r = glm::length(p - l), d = glm::dot(p - l, axis);
      single = single && d > kMaxCosFromAxis * r;
      nearest = std::min(nearest, d);
    }
    if (single) {
      View& view = next_view();
      set_view(view, true, l, axis, hint(axis), depths);
      view.near = 1e-3 * nearest;
      fit_window(view);
      return;
    }
  }
  // A cube of six 90-degree frusta around the light (§3.4).
  const std::array<glm::dvec3, 6> axes{glm::dvec3(1, 0, 0), glm::dvec3(-1, 0, 0),
                                       glm::dvec3(0, 1, 0), glm::dvec3(0, -1, 0),
                                       glm::dvec3(0, 0, 1), glm::dvec3(0, 0, -1)};
  for (const glm::dvec3& axis : axes) {
    View& view = next_view();
    set_view(view, true, l, axis, hint(axis), depths);
    view.near = 1e-4 * farthest;
    view.u0 = view.v0 = -1.0;
    view.u1 = view.v1 = 1.0;
    view.tolerance = 1e-5 * farthest;
  }
}

glm::dvec3 LightViews::to_pixels(const View& view, const glm::dvec3& p, double d) const {
  const glm::dvec3 rel = p - view.origin;
  const double w = view.perspective ? d : 1.0;
  return {(glm::dot(rel, view.right) / w - view.u0) / (view.u1 - view.u0) * size_,
          (glm::dot(rel, view.up) / w - view.v0) / (view.v1 - view.v0) * size_, d};
}

bool LightViews::project(const View& view, const glm::dvec3& p, glm::dvec3& out) const {
  const double d = glm::dot(p - view.origin, view.axis);
  if (view.perspective && !(d >= view.near)) return false;
  out = to_pixels(view, p, d);
  return true;
}

bool LightViews::about_light(const Box& box) const {
  if (!cube()) return false;
  const double near = views_[0].near;
  const glm::dvec3 l = views_[0].origin;
  return glm::all(glm::lessThanEqual(box.lo - near, l)) &&
         glm::all(glm::greaterThanEqual(box.hi + near, l));
}

namespace {

// The triangle's part at or beyond the view's near plane, as a fan of screen triangles.
template <class Project>
int clip_to_screen(const std::array<glm::dvec3, 3>& tri, bool perspective, const glm::dvec3& origin,
                   const glm::dvec3& axis, double near, Project&& project,
                   std::array<ScreenTriangle, 2>& out) {
  std::array<glm::dvec3, 4> poly{tri[0], tri[1], tri[2]};
  int n = 3;
  if (perspective)
    clip_polygon(poly, n, [&](const glm::dvec3& p) { return glm::dot(p - origin, axis) - near; });
  if (n < 3) return 0;
  std::array<glm::dvec3, 4> screen;
  for (int i = 0; i < n; ++i) {
    const glm::dvec3 rel = poly[i] - origin;
    const double d = std::max(glm::dot(rel, axis), perspective ? near : -INFINITY);
    screen[i] = project(poly[i], d);
  }
  int m = 0;
  for (int i = 1; i + 1 < n; ++i) out[m++] = {screen[0], screen[i], screen[i + 1]};
  return m;
}

}  // namespace

namespace {

// Signed distance-like value of (x, y) from the line through u, w, times the segment's length.
double edge_value(const glm::dvec3& u, const glm::dvec3& w, double x, double y) {
  return (w.x - u.x) * (y - u.y) - (w.y - u.y) * (x - u.x);
}

// A triangle's edges as affine functions e(x, y) = a x + b y + c, positive inside, and the slack
// each must exceed (kPixelSlack times the edge's length, so that the test is one of distance).
struct TriangleEdges {
  std::array<double, 3> a{}, b{}, c{}, slack{};
  explicit TriangleEdges(const std::array<glm::dvec3, 3>& t, double area) {
    const double s = area > 0 ? 1.0 : -1.0;
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3& u = t[k];
      const glm::dvec3& w = t[(k + 1) % 3];
      a[k] = -s * (w.y - u.y);
      b[k] = s * (w.x - u.x);
      c[k] = s * ((w.y - u.y) * u.x - (w.x - u.x) * u.y);
      slack[k] = kPixelSlack * std::sqrt((w.x - u.x) * (w.x - u.x) + (w.y - u.y) * (w.y - u.y));
    }
  }
  // Whether the footprint [x, x+1] x [y, y+1] may touch the triangle: not when all four corners
  // lie beyond one edge by more than the slack (the corner farthest inside decides).
  bool may_touch(int x, int y) const {
    for (int k = 0; k < 3; ++k)
      if (a[k] * x + b[k] * y + c[k] + std::max(a[k], 0.0) + std::max(b[k], 0.0) < -slack[k])
        return false;
    return true;
  }
  // Whether the point lies inside, farther from every edge than the slack.
  bool holds(double x, double y) const {
    for (int k = 0; k < 3; ++k)
      if (!(a[k] * x + b[k] * y + c[k] > slack[k])) return false;
    return true;
  }
};

}  // namespace

void LightViews::add_occluders(std::span<const Occluder> occluders) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, occluders.size(), 1),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      OccluderScratch& scratch = scratch_.local();
                      for (std::size_t i = r.begin(); i != r.end(); ++i)
                        add_occluder(occluders[i], scratch);
                    });
}

void LightViews::add_occluder(const Occluder& occluder, OccluderScratch& scratch) {
  const Topology& topology = *occluder.topology;
  const std::span<const glm::dvec3> positions = occluder.positions;
  const Box& box = occluder.box;
  std::vector<IndexPair>& bounds = scratch.bounds;
  std::vector<glm::dvec3>& screen = scratch.screen;
  std::vector<double>& farthest = scratch.farthest;
  std::vector<std::uint8_t>& state = scratch.state;
  if (views_count_ == 0 || topology.face_count() == 0) return;
  // Edges where the faces do not lie on both sides, seen from the light: the plane through the
  // light and the edge has both third vertices on one side (a silhouette), or the edge has one
  // face, or three or more, or faces that run it the same way (irregular). Only these bound the
  // union of the faces' projections; elsewhere two faces cover both sides of the edge.
  const glm::dvec3 light = views_[0].perspective ? views_[0].origin : glm::dvec3(0.0);
  const bool directional = !views_[0].perspective;
  const glm::dvec3 ray = views_[0].axis;
  auto third = [&](std::uint32_t f, std::uint32_t a, std::uint32_t b) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = topology.face_vertices[3 * std::size_t{f} + k];
      if (v != a && v != b) return v;
    }
    return a;
  };
  bounds.clear();
  const std::size_t faces = topology.face_count();
  for (std::size_t e = 0; e < topology.edge_faces.size(); ++e) {
    const auto [a, b] = topology.edge_vertices[e];
    const auto [f0, f1] = topology.edge_faces[e];
    bool bounding = f1 >= faces;
    if (!bounding) {
      const glm::dvec3& pa = positions[a];
      const glm::dvec3 n = directional ? glm::cross(positions[b] - pa, ray)
                                       : glm::cross(pa - light, positions[b] - light);
      const double s0 = glm::dot(n, positions[third(f0, a, b)] - pa);
      const double s1 = glm::dot(n, positions[third(f1, a, b)] - pa);
      bounding = !((s0 > 0 && s1 < 0) || (s0 < 0 && s1 > 0));
    }
    if (bounding) bounds.push_back({a, b});
  }
  for (const IndexPair& edge : topology.irregular_vertices) bounds.push_back(edge);

  for (View& view : active()) {
    // Only an object wholly beyond the near plane: a cut would bound its projection too.
    Rect rect;
    bool untestable = false;
    if (!box_rect(view, box, rect, untestable) || untestable) continue;
    if (view.perspective)
      for (const glm::dvec3& c : corners(box))
        if (!(glm::dot(c - view.origin, view.axis) >= view.near)) untestable = true;
    if (untestable) continue;
    screen.resize(positions.size());
    for (std::size_t v = 0; v < positions.size(); ++v)
      screen[v] = to_pixels(view, positions[v], glm::dot(positions[v] - view.origin, view.axis));
    const int rw = rect.x1 - rect.x0 + 1, rh = rect.y1 - rect.y0 + 1;
    const std::size_t area_pixels = static_cast<std::size_t>(rw) * rh;
    farthest.assign(area_pixels, -INFINITY);
    state.assign(area_pixels, 0);  // bit 0: a face holds a point of it; bit 1: an edge bounds it
    auto at = [&](int x, int y) {
      return static_cast<std::size_t>(y - rect.y0) * rw + (x - rect.x0);
    };
    for (std::size_t f = 0; f < faces; ++f) {
      const std::uint32_t* fv = &topology.face_vertices[3 * f];
      const std::array<glm::dvec3, 3> t{screen[fv[0]], screen[fv[1]], screen[fv[2]]};
      const double area =
          (t[1].x - t[0].x) * (t[2].y - t[0].y) - (t[2].x - t[0].x) * (t[1].y - t[0].y);
      const double vertex_far = std::max({t[0].z, t[1].z, t[2].z});
      // 1/depth (perspective) or depth (orthographic) is affine in x, y over the face's plane.
      auto q_of = [&](const glm::dvec3& v) { return view.perspective ? 1.0 / v.z : v.z; };
      const double q0 = q_of(t[0]), q1 = q_of(t[1]), q2 = q_of(t[2]);
      const bool planar = area != 0.0;
      const double qx =
          planar ? ((q1 - q0) * (t[2].y - t[0].y) - (q2 - q0) * (t[1].y - t[0].y)) / area : 0;
      const double qy =
          planar ? ((q2 - q0) * (t[1].x - t[0].x) - (q1 - q0) * (t[2].x - t[0].x)) / area : 0;
      const int x0 = std::max(
          rect.x0, static_cast<int>(std::floor(std::min({t[0].x, t[1].x, t[2].x}) - kPixelSlack)));
      const int x1 = std::min(
          rect.x1, static_cast<int>(std::floor(std::max({t[0].x, t[1].x, t[2].x}) + kPixelSlack)));
      const int y0 = std::max(
          rect.y0, static_cast<int>(std::floor(std::min({t[0].y, t[1].y, t[2].y}) - kPixelSlack)));
      const int y1 = std::min(
          rect.y1, static_cast<int>(std::floor(std::max({t[0].y, t[1].y, t[2].y}) + kPixelSlack)));
      const TriangleEdges edges(t, area);
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          if (planar && !edges.may_touch(x, y)) continue;  // a degenerate one: its whole box
          // The face's farthest depth over the footprint: its plane's at the corners, and never
          // beyond its farthest vertex.
          double far = vertex_far;
          if (planar) {
            // Affine over the footprint: its extremes lie at the corners the slopes point to.
            const double q = q0 + qx * (x - t[0].x) + qy * (y - t[0].y);
            const double qmin = q + std::min(qx, 0.0) + std::min(qy, 0.0);
            const double qmax = q + std::max(qx, 0.0) + std::max(qy, 0.0);
            const double plane_far = view.perspective ? (qmin > 0 ? 1.0 / qmin : INFINITY) : qmax;
            far = std::min(far, plane_far);
          }
          const std::size_t i = at(x, y);
          farthest[i] = std::max(farthest[i], far);
          if (!planar) continue;
          // Some point of the footprint inside the face (its centre may lie on a shared edge):
          // with no bounding edge touching it, the whole footprint is then covered.
          const bool centre = edges.holds(x + 0.5, y + 0.5) || edges.holds(x + 0.25, y + 0.25) ||
                              edges.holds(x + 0.75, y + 0.25) || edges.holds(x + 0.25, y + 0.75) ||
                              edges.holds(x + 0.75, y + 0.75);
          if (centre) state[i] |= 1;
        }
    }
    // Every footprint a bounding edge may touch: row by row along the segment.
    for (const IndexPair& edge : bounds) {
      const glm::dvec3& a = screen[edge[0]];
      const glm::dvec3& b = screen[edge[1]];
      const double slack =
          kPixelSlack *
          std::max(1.0, std::sqrt((b.x - a.x) * (b.x - a.x) + (b.y - a.y) * (b.y - a.y)));
      const int y0 =
          std::max(rect.y0, static_cast<int>(std::floor(std::min(a.y, b.y) - kPixelSlack)));
      const int y1 =
          std::min(rect.y1, static_cast<int>(std::floor(std::max(a.y, b.y) + kPixelSlack)));
      for (int y = y0; y <= y1; ++y) {
        // The segment's x range within the row's band [y, y + 1], widened by the slack.
        double lo = std::min(a.x, b.x), hi = std::max(a.x, b.x);
        if (b.y != a.y) {
          const double ta = (y - kPixelSlack - a.y) / (b.y - a.y);
          const double tb = (y + 1 + kPixelSlack - a.y) / (b.y - a.y);
          const double t0 = std::clamp(std::min(ta, tb), 0.0, 1.0),
                       t1 = std::clamp(std::max(ta, tb), 0.0, 1.0);
          lo = std::min(a.x + (b.x - a.x) * t0, a.x + (b.x - a.x) * t1);
          hi = std::max(a.x + (b.x - a.x) * t0, a.x + (b.x - a.x) * t1);
        }
        const int x0 = std::max(rect.x0, static_cast<int>(std::floor(lo - kPixelSlack)));
        const int x1 = std::min(rect.x1, static_cast<int>(std::floor(hi + kPixelSlack)));
        for (int x = x0; x <= x1; ++x) {
          // Touched unless all four corners lie beyond the line on one side.
          double mn = INFINITY, mx = -INFINITY;
          for (int c = 0; c < 4; ++c) {
            const double v = edge_value(a, b, x + (c & 1), y + (c >> 1));
            mn = std::min(mn, v), mx = std::max(mx, v);
          }
          if (mn <= slack && mx >= -slack) state[at(x, y)] |= 2;
        }
      }
    }
    for (int y = rect.y0; y <= rect.y1; ++y)
      for (int x = rect.x0; x <= rect.x1; ++x) {
        const std::size_t i = at(x, y);
        if (state[i] != 1) continue;
        // Objects may be drawn from several threads at once: the minimum is taken atomically.
        std::atomic_ref<float> stored(view.seen[0][static_cast<std::size_t>(y) * size_ + x]);
        const float depth = round_up(farthest[i]);
        float now = stored.load(std::memory_order_relaxed);
        while (depth < now &&
               !stored.compare_exchange_weak(now, depth, std::memory_order_relaxed)) {
        }
      }
  }
}

void LightViews::add_receiver_points(std::span<const glm::dvec3> points,
                                     std::span<const LayerRange> layers) {
  assert(layers.empty() || layers.size() == points.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i)
                        if (std::isfinite(points[i].x))
                          add_receiver_point(points[i], layers.empty() ? LayerRange{} : layers[i]);
                    });
}

namespace {

// Raises the stored depth to `depth` at least; several threads may draw at once.
void raise_to(float& stored_depth, float depth) {
  std::atomic_ref<float> stored(stored_depth);
  float now = stored.load(std::memory_order_relaxed);
  while (now < depth && !stored.compare_exchange_weak(now, depth, std::memory_order_relaxed)) {
  }
}

}  // namespace

void LightViews::splat_receiver(View& view, const glm::dvec3& p, LayerRange layers) {
  glm::dvec3 s;
  if (!project(view, p, s)) return;
  const float depth = round_up(s.z);
  const int x0 = std::max(0, static_cast<int>(std::floor(s.x - kPixelSlack)));
  const int x1 = std::min(size_ - 1, static_cast<int>(std::floor(s.x + kPixelSlack)));
  const int y0 = std::max(0, static_cast<int>(std::floor(s.y - kPixelSlack)));
  const int y1 = std::min(size_ - 1, static_cast<int>(std::floor(s.y + kPixelSlack)));
  const int last = std::min<int>(layers.last, layers_ - 1);
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * size_ + x;
      raise_to(view.receiver[i], depth);
      for (int k = layers.first; k <= last; ++k) raise_to(view.layer_receiver[k][i], depth);
    }
}

void LightViews::add_receiver_point(const glm::dvec3& p, LayerRange layers) {
  if (!cube()) {
    for (View& view : active()) splat_receiver(view, p, layers);
    return;
  }
  // A cube face holds the directions whose largest component runs along its axis (faces
  // +x, -x, +y, -y, +z, -z); one a hair's breadth from an edge of it goes to the faces beyond
  // that edge too, for the slack there.
  const glm::dvec3 rel = p - views_[0].origin;
  const glm::dvec3 mag = glm::abs(rel);
  const int axis = mag.x >= mag.y && mag.x >= mag.z ? 0 : mag.y >= mag.z ? 1 : 2;
  const double largest = mag[axis];
  for (int k = 0; k < 3; ++k) {
    if (k != axis && mag[k] < (1.0 - 1e-5) * largest) continue;
    splat_receiver(views_[2 * k + (rel[k] < 0.0)], p, layers);
  }
}

void LightViews::add_receiver_triangle(const glm::dvec3& a, const glm::dvec3& b,
                                       const glm::dvec3& c, LayerRange layers) {
  const int last = std::min<int>(layers.last, layers_ - 1);
  for (View& view : active()) {
    auto to_screen = [&](const glm::dvec3& p, double d) { return to_pixels(view, p, d); };
    std::array<ScreenTriangle, 2> fan;
    const int parts = clip_to_screen({a, b, c}, view.perspective, view.origin, view.axis, view.near,
                                     to_screen, fan);
    for (int t = 0; t < parts; ++t) {
      const auto& [p0, p1, p2] = fan[t];
      const float depth = round_up(std::max({p0.z, p1.z, p2.z}));
      const double area = (p1.x - p0.x) * (p2.y - p0.y) - (p2.x - p0.x) * (p1.y - p0.y);
      const TriangleEdges edges(fan[t], area);
      const int x0 =
          std::max(0, static_cast<int>(std::floor(std::min({p0.x, p1.x, p2.x}) - kPixelSlack)));
      const int y0 =
          std::max(0, static_cast<int>(std::floor(std::min({p0.y, p1.y, p2.y}) - kPixelSlack)));
      const int x1 = std::min(
          size_ - 1, static_cast<int>(std::floor(std::max({p0.x, p1.x, p2.x}) + kPixelSlack)));
      const int y1 = std::min(
          size_ - 1, static_cast<int>(std::floor(std::max({p0.y, p1.y, p2.y}) + kPixelSlack)));
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          // A degenerate triangle keeps its whole box.
          if (area != 0.0 && !edges.may_touch(x, y)) continue;
          const std::size_t i = static_cast<std::size_t>(y) * size_ + x;
          view.receiver[i] = std::max(view.receiver[i], depth);
          for (int k = layers.first; k <= last; ++k)
            view.layer_receiver[k][i] = std::max(view.layer_receiver[k][i], depth);
        }
    }
  }
}

bool LightViews::box_rect(const View& view, const Box& box, Rect& rect, bool& untestable) const {
  untestable = false;
  const std::array<glm::dvec3, 8> c = corners(box);
  std::array<double, 8> d;
  int in_front = 0, beyond_light = 0;
  for (int i = 0; i < 8; ++i) {
    d[i] = glm::dot(c[i] - view.origin, view.axis);
    in_front += view.perspective ? d[i] >= view.near : 1;
    beyond_light += d[i] > 0.0;
  }
  // The corners, or a cube face's cut of the box: its corners beyond the near plane and the
  // points where its 12 edges cross it.
  std::array<glm::dvec3, 20> points;
  int count = 0;
  if (in_front == 8) {
    std::copy(c.begin(), c.end(), points.begin());
    count = 8;
  } else {
    // A single frustum holds every receiver, so what lies wholly behind the light shadows none;
    // a box partly in front of its near plane may (untestable). A cube face: the box's part
    // beyond the near plane (the rest lies in other faces: the near cube was tested first).
    if (!cube()) {
      untestable = beyond_light > 0;
      return false;
    }
    if (in_front == 0) return false;
    for (int i = 0; i < 8; ++i) {
      if (d[i] >= view.near) points[count++] = c[i];
      for (int axis = 0; axis < 3; ++axis) {
        const int j = i | (1 << axis);
        if (j == i) continue;
        if ((d[i] >= view.near) != (d[j] >= view.near)) {
          const double t = (view.near - d[i]) / (d[j] - d[i]);
          points[count++] = c[i] + (c[j] - c[i]) * t;
        }
      }
    }
  }
  double min_x = INFINITY, max_x = -INFINITY, min_y = INFINITY, max_y = -INFINITY;
  double zmin = INFINITY;
  for (int i = 0; i < count; ++i) {
    const double dp = std::max(glm::dot(points[i] - view.origin, view.axis),
                               view.perspective ? view.near : -INFINITY);
    const glm::dvec3 q = to_pixels(view, points[i], dp);
    min_x = std::min(min_x, q.x), max_x = std::max(max_x, q.x);
    min_y = std::min(min_y, q.y), max_y = std::max(max_y, q.y);
    zmin = std::min(zmin, dp);
  }
  // Fattened by a pixel, then cut to the window: pixels outside it hold no receiver.
  const double fx0 = std::floor(min_x) - 1, fx1 = std::floor(max_x) + 1;
  const double fy0 = std::floor(min_y) - 1, fy1 = std::floor(max_y) + 1;
  if (fx1 < 0 || fy1 < 0 || fx0 > size_ - 1 || fy0 > size_ - 1) return false;
  rect.x0 = static_cast<int>(std::max(0.0, fx0));
  rect.y0 = static_cast<int>(std::max(0.0, fy0));
  rect.x1 = static_cast<int>(std::min<double>(size_ - 1, fx1));
  rect.y1 = static_cast<int>(std::min<double>(size_ - 1, fy1));
  rect.zmin = zmin - view.tolerance;
  return true;
}

bool LightViews::touches(const Box& box) const {
  if (box.empty()) return false;
  for (const View& view : active()) {
    Rect rect;
    bool untestable = false;
    if (box_rect(view, box, rect, untestable) || untestable) return true;
  }
  return about_light(box);
}

void LightViews::finish(bool occluders, bool receivers) {
  occluders_ = occluders;
  kept_ = occluders || receivers;
  for (View& view : active()) {
    if (!kept_) continue;
    // seen[0] holds the occluders drawn (+inf everywhere without them).
    const std::vector<float>& seen = view.seen[0];
    view.kept.resize(std::max<std::size_t>(view.kept.size(), 1));
    std::vector<float>& kept = view.kept[0];
    kept.resize(seen.size());
    for (std::size_t i = 0; i < kept.size(); ++i)
      kept[i] = receivers ? std::min(seen[i], view.receiver[i]) : seen[i];
    if (occluders) build_pyramid(view.seen, size_);
    build_pyramid(view.kept, size_);
    const std::vector<float>& occluder = view.seen[0];  // the pyramid may have moved it
    tbb::parallel_for(0, layers_, [&](int k) {
      std::vector<std::vector<float>>& layer = view.layer_kept[k];
      layer.resize(std::max<std::size_t>(layer.size(), 1));
      layer[0].resize(occluder.size());
      const std::vector<float>& receiver = view.layer_receiver[k];
      for (std::size_t i = 0; i < occluder.size(); ++i)
        layer[0][i] = std::min(occluder[i], receiver[i]);
      build_pyramid(layer, size_);
    });
  }
}

bool LightViews::descend(const std::vector<std::vector<float>>& pyramid, const Rect& rect,
                         int level, int tx, int ty) const {
  if (pyramid[level][static_cast<std::size_t>(ty) * level_width(level) + tx] <
      static_cast<float>(rect.zmin))
    return false;
  if (level == 0) return true;
  const int below = level - 1, w = level_width(below);
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const int cx = 2 * tx + i, cy = 2 * ty + j;
      if (cx >= w || cy >= w || cx < (rect.x0 >> below) || cx > (rect.x1 >> below) ||
          cy < (rect.y0 >> below) || cy > (rect.y1 >> below))
        continue;
      if (descend(pyramid, rect, below, cx, cy)) return true;
    }
  return false;
}

bool LightViews::any_at_least(const std::vector<std::vector<float>>& pyramid,
                              const Rect& rect) const {
  int level = 0;
  while (
      level + 1 < static_cast<int>(pyramid.size()) &&
      ((rect.x1 >> level) - (rect.x0 >> level) > 2 || (rect.y1 >> level) - (rect.y0 >> level) > 2))
    ++level;
  for (int ty = rect.y0 >> level; ty <= rect.y1 >> level; ++ty)
    for (int tx = rect.x0 >> level; tx <= rect.x1 >> level; ++tx)
      if (descend(pyramid, rect, level, tx, ty)) return true;
  return false;
}

bool LightViews::kept_in_layer(const Box& box, int layer, std::uint64_t& queries) const {
  assert(layer >= 0 && layer < layers_);
  if (box.empty() || views_count_ == 0) return false;
  if (about_light(box)) return true;
  for (const View& view : active()) {
    Rect rect;
    bool untestable = false;
    if (!box_rect(view, box, rect, untestable)) {
      if (untestable) return true;
      continue;
    }
    ++queries;
    if (any_at_least(view.layer_kept[static_cast<std::size_t>(layer)], rect)) return true;
  }
  return false;
}

bool LightViews::light_box(std::size_t v, const Box& box, bool caster, LightBox& out) const {
  const View& view = views_[v];
  if (box.empty()) return false;
  const std::array<glm::dvec3, 8> c = corners(box);
  std::array<double, 8> d;
  int beyond = 0;
  for (int i = 0; i < 8; ++i) {
    d[i] = glm::dot(c[i] - view.origin, view.axis);
    beyond += !view.perspective || d[i] >= view.near;
  }
  if (beyond == 0 || (caster && beyond < 8)) return false;
  // The corners beyond the near plane and where the box's edges cross it.
  std::array<glm::dvec3, 20> points;
  std::array<double, 20> depth;
  int n = 0;
  for (int i = 0; i < 8; ++i) {
    const bool in = !view.perspective || d[i] >= view.near;
    if (in) points[n] = c[i], depth[n++] = d[i];
    for (int axis = 0; axis < 3 && beyond < 8; ++axis) {
      const int j = i | (1 << axis);
      if (j == i || in == (d[j] >= view.near)) continue;
      const double t = (view.near - d[i]) / (d[j] - d[i]);
      points[n] = c[i] + (c[j] - c[i]) * t, depth[n++] = view.near;
    }
  }
  out = {INFINITY, -INFINITY, INFINITY, -INFINITY, INFINITY, -INFINITY};
  for (int i = 0; i < n; ++i) {
    const glm::dvec3 rel = points[i] - view.origin;
    const double w = view.perspective ? depth[i] : 1.0;
    const double u = glm::dot(rel, view.right) / w, vv = glm::dot(rel, view.up) / w;
    out.u0 = std::min(out.u0, u), out.u1 = std::max(out.u1, u);
    out.v0 = std::min(out.v0, vv), out.v1 = std::max(out.v1, vv);
    out.z0 = std::min(out.z0, depth[i]), out.z1 = std::max(out.z1, depth[i]);
  }
  if (caster)  // a cube's face holds a caster's volume only where it holds the caster whole
    return !cube() ||
           (out.u0 >= view.u0 && out.u1 <= view.u1 && out.v0 >= view.v0 && out.v1 <= view.v1);
  out.u0 = std::max(out.u0, view.u0), out.u1 = std::min(out.u1, view.u1);
  out.v0 = std::max(out.v0, view.v0), out.v1 = std::min(out.v1, view.v1);
  return out.u0 <= out.u1 && out.v0 <= out.v1;
}

glm::dvec4 LightViews::depth_plane(std::size_t v) const {
  const View& view = views_[v];
  return {view.axis, -glm::dot(view.axis, view.origin)};
}

glm::dvec3 LightViews::point(std::size_t v, double u, double w, double d) const {
  const View& view = views_[v];
  const double scale = view.perspective ? d : 1.0;
  return view.origin + view.axis * d + (view.right * u + view.up * w) * scale;
}

std::size_t LightViews::view_of(const glm::dvec3& p) const {
  if (!cube()) return 0;
  const glm::dvec3 rel = p - views_[0].origin;
  const glm::dvec3 mag = glm::abs(rel);
  const int axis = mag.x >= mag.y && mag.x >= mag.z ? 0 : mag.y >= mag.z ? 1 : 2;
  return static_cast<std::size_t>(2 * axis + (rel[axis] < 0.0));
}

BoxVisibility LightViews::test(const Box& box, std::uint64_t& queries) const {
  if (box.empty() || views_count_ == 0) return BoxVisibility::unseen;
  if (about_light(box)) return BoxVisibility::kept;
  bool in_view = false, seen = false;
  for (const View& view : active()) {
    Rect rect;
    bool untestable = false;
    if (!box_rect(view, box, rect, untestable)) {
      if (untestable) return BoxVisibility::kept;
      continue;
    }
    in_view = true;
    ++queries;
    if (!kept_ || any_at_least(view.kept, rect)) return BoxVisibility::kept;
    seen = seen || !occluders_ || any_at_least(view.seen, rect);
  }
  return in_view && !seen ? BoxVisibility::in_shadow : BoxVisibility::unseen;
}

}  // namespace shadowvol
