#include "render/frame_plan.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "render/near_plane_prefill.h"
#include "scene/shapes.h"
#include "soft/clip_polygon.h"

namespace shadowvol {
namespace {

// May any point of the near-plane rectangle lie in the shadow of something inside the sphere?
// The points whose segment to the light meets the sphere form a cone (a cylinder for a
// directional light); its intersection with the near rectangle is non-empty iff the sphere
// meets the convex hull of the rectangle and the light (rectangle swept towards the light).
// Tested plane by plane against that hull: conservative (may say yes when the answer is no).
bool may_shadow_near_plane(const glm::vec3& centre, float radius,
                           const std::array<glm::vec3, 4>& rect, const glm::vec4& light) {
  const glm::vec3 inside = (rect[0] + rect[1] + rect[2] + rect[3]) * 0.25f;
  const bool point = light.w != 0.0f;
  const glm::vec3 l = glm::vec3(light) / (point ? light.w : 1.0f);
  auto outside = [&](glm::vec3 n, glm::vec3 on, glm::vec3 reference) {
    const float len = glm::length(n);
    if (len < 1e-12f) return false;  // degenerate plane: no verdict
    n /= len;
    if (glm::dot(n, reference - on) > 0.0f) n = -n;  // outward: away from the reference point
    return glm::dot(n, centre - on) > radius;
  };
  // The rectangle's plane bounds the hull on the side away from the light.
  const glm::vec3 rect_normal = glm::cross(rect[1] - rect[0], rect[3] - rect[0]);
  const glm::vec3 towards = point ? l - inside : l;
  if (glm::dot(rect_normal, towards) == 0.0f) return true;  // light in the near plane
  if (outside(rect_normal, rect[0], rect[0] + towards)) return false;
  for (int i = 0; i < 4; ++i) {
    const glm::vec3 a = rect[i], b = rect[(i + 1) % 4];
    const glm::vec3 n = glm::cross(b - a, point ? l - a : l);
    if (outside(n, a, inside + towards * 1e-3f)) return false;
  }
  return true;
}

// Laine 2005 §4.1, Eq. 4, eye-relative (the camera at the origin): the plane through the
// volume's centre line (from the light through p, or along a directional light) that is
// orthogonal to the plane of that line and the camera, so that it splits the volume in halves
// as the camera sees them; then (our alternatives, split_plane_candidates) `turn` radians about
// the centre line, where a quarter turn holds the camera, and `tilt` radians of the normal
// towards the centre line's direction, about p. Unit normal. Degenerate (zero) when the camera
// lies on the centre line, which the split test reads as z-fail everywhere: still exact.
glm::vec4 point_camera_light(const glm::vec3& p, const glm::vec4& light, double turn = 0.0,
                             double tilt = 0.0) {
  const glm::dvec3 centre(p);
  const glm::dvec3 along =
      light.w != 0.0f ? centre - glm::dvec3(light) / double(light.w) : -glm::dvec3(light);
  const glm::dvec3 towards_camera = glm::cross(-centre, along);  // normal of (camera, line)
  const glm::dvec3 laine = glm::cross(towards_camera, along);
  if (!(glm::length(laine) > 0.0)) return glm::vec4(0.0f);
  const glm::dvec3 turned =
      std::cos(turn) * glm::normalize(laine) + std::sin(turn) * glm::normalize(towards_camera);
  const glm::dvec3 normal = std::cos(tilt) * turned + std::sin(tilt) * glm::normalize(along);
  return glm::vec4(glm::vec3(normal), float(-glm::dot(normal, centre)));
}

// Laine 2005 §4.2, Eq. 5: the plane through the light and the two points p1 and p2 (the ends of
// a long thin object's axis), so that it runs inside the flat volume such an object casts.
// Degenerate (zero) when the light lies on the line p1 p2: z-fail everywhere, still exact.
glm::vec4 point_point_light(const glm::vec3& p1, const glm::vec3& p2, const glm::vec4& light) {
  const glm::dvec3 a(p1), b(p2);
  const glm::dvec3 normal = light.w != 0.0f ? glm::cross(a - glm::dvec3(light) / double(light.w),
                                                         b - glm::dvec3(light) / double(light.w))
                                            : glm::cross(b - a, glm::dvec3(light));
  return glm::vec4(glm::vec3(normal), float(-glm::dot(normal, a)));
}

// An object's centroid (the mean of its vertices, where Point-Camera-Light puts its point) and
// its principal axes, from the covariance of its vertices (in double): the long axis
// (the principal direction, by power iteration), its ends where the vertices' projections end,
// and whether the object is at least twice as long as it is wide (as far across as its farthest
// vertex from the axis); the thin axis (the least principal direction, by power iteration on
// trace - covariance, whose largest eigenvalue is the trace minus the least), the interval of
// the vertices' projections on it, and whether the object is flat: a hundred times thinner along
// it than long, and not elongated (a rod is thin across both of its short axes); and the radius
// of the sphere about its bounding box.
struct Shape {
  glm::vec3 centroid{0.0f};
  float radius = 0.0f;
  glm::vec3 p1{0.0f}, p2{0.0f};
  bool elongated = false;
  glm::dvec3 thin_axis{0.0};
  double thin_lo = 0.0, thin_hi = 0.0;
  bool flat = false;
};
glm::dvec3 principal_direction(const glm::dmat3& m) {
  glm::dvec3 dir(0.577, 0.578, 0.579);
  for (int i = 0; i < 64; ++i) {
    const glm::dvec3 next = m * dir;
    const double len = glm::length(next);
    if (!(len > 0.0)) return glm::dvec3(0.0);
    dir = next / len;
  }
  return dir;
}
Shape shape_of(const std::vector<glm::vec3>& points) {
  Shape shape;
  if (points.empty()) return shape;
  glm::dvec3 mean(0.0);
  glm::vec3 box_lo(INFINITY), box_hi(-INFINITY);
  for (const glm::vec3& p : points) {
    mean += glm::dvec3(p);
    box_lo = glm::min(box_lo, p);
    box_hi = glm::max(box_hi, p);
  }
  shape.radius = glm::length(box_hi - box_lo) * 0.5f;
  mean /= double(points.size());
  shape.centroid = glm::vec3(mean);
  glm::dmat3 covariance(0.0);
  for (const glm::vec3& p : points) {
    const glm::dvec3 d = glm::dvec3(p) - mean;
    covariance += glm::outerProduct(d, d);
  }
  const glm::dvec3 dir = principal_direction(covariance);
  if (dir == glm::dvec3(0.0)) return shape;  // all points coincide
  const double trace = covariance[0][0] + covariance[1][1] + covariance[2][2];
  const glm::dvec3 thin = principal_direction(glm::dmat3(trace) - covariance);
  double lo = INFINITY, hi = -INFINITY, width = 0.0;
  shape.thin_lo = INFINITY, shape.thin_hi = -INFINITY;
  for (const glm::vec3& p : points) {
    const glm::dvec3 d = glm::dvec3(p) - mean;
    const double t = glm::dot(d, dir);
    lo = std::min(lo, t);
    hi = std::max(hi, t);
    width = std::max(width, 2.0 * glm::length(d - t * dir));
    shape.thin_lo = std::min(shape.thin_lo, glm::dot(glm::dvec3(p), thin));
    shape.thin_hi = std::max(shape.thin_hi, glm::dot(glm::dvec3(p), thin));
  }
  shape.p1 = glm::vec3(mean + lo * dir);
  shape.p2 = glm::vec3(mean + hi * dir);
  shape.elongated = hi - lo >= 2.0 * width;
  shape.thin_axis = thin;
  shape.flat = !shape.elongated && thin != glm::dvec3(0.0) &&
               shape.thin_hi - shape.thin_lo <= 0.01 * (hi - lo);
  return shape;
}

// Ours, for a flat object: the plane across its thin axis, just past the object on the side away
// from the light (by a hundredth of its length), so that the object lies on the light's side and
// its whole volume on the other: pixels on the object take the rule that culls the volume. None
// where the light lies within the object's thickness (edge-on), or a directional light shines
// along the object.
std::optional<glm::vec4> flat_plane(const Shape& shape, const glm::vec4& light) {
  const glm::dvec3 n = shape.thin_axis;
  const double length = glm::length(glm::dvec3(shape.p2) - glm::dvec3(shape.p1));
  const double margin = 0.01 * length;
  double light_side = glm::dot(n, glm::dvec3(light));  // directional: + where it shines from
  if (light.w != 0.0f) {
    const double at = light_side / double(light.w);
    light_side = at > shape.thin_hi ? 1.0 : at < shape.thin_lo ? -1.0 : 0.0;
  }
  if (light_side > 0.0) return glm::vec4(glm::vec3(n), float(-(shape.thin_lo - margin)));
  if (light_side < 0.0) return glm::vec4(glm::vec3(n), float(-(shape.thin_hi + margin)));
  return std::nullopt;
}

// The planes SplitPlanes::sampled weighs against the object's own (world, eye-relative): both
// whole-volume rules (z-fail everywhere is the zero plane; z-pass everywhere is the plane
// w = -z, whose camera side holds every tile) and, but for a flat object, whose own plane already
// sends its whole volume behind the surfaces, Point-Camera-Light turned about the centre line
// in steps of 15 degrees, tilted towards and away from the light, moved across by a quarter and
// half of the object's radius, and Point-Point-Light: 39 planes (2 for a flat object).
std::vector<glm::vec4> split_plane_candidates(const Shape& shape, const glm::vec4& light) {
  std::vector<glm::vec4> planes{glm::vec4(0.0f), glm::vec4(0.0f, 0.0f, 1.0f, 1.0f)};
  if (shape.flat) return planes;
  constexpr double kDegree = std::numbers::pi / 180.0;
  for (int turn = -75; turn <= 90; turn += 15)
    planes.push_back(point_camera_light(shape.centroid, light, turn * kDegree));
  for (const int turn : {-30, 0, 30}) {
    const glm::vec4 turned = point_camera_light(shape.centroid, light, turn * kDegree);
    if (turned == glm::vec4(0.0f)) continue;
    for (const float across : {-0.5f, -0.25f, 0.25f, 0.5f})
      planes.push_back(turned + glm::vec4(0.0f, 0.0f, 0.0f, across * shape.radius));
    for (const int tilt : {-30, -15, 15, 30})
      planes.push_back(point_camera_light(shape.centroid, light, turn * kDegree, tilt * kDegree));
  }
  planes.push_back(point_point_light(shape.p1, shape.p2, light));
  return planes;
}

// The far plane that ends an object's bounded volume (core/volume.h, Extrusion::bounded),
// eye-relative: facing away from the light along the line from the light through the object's
// box centre (along a directional light's rays), a little beyond the farthest corner of `reach`
// (the scene's box and the near-plane rectangle, so that every receiver and the pre-fill's near
// plane lie on its kept side). The plane at infinity where a point light sits on one of the
// object's box corners or sees one more than 84 degrees from that line: rays that graze the
// plane would be extruded to huge coordinates.
glm::vec4 bounded_far_plane(const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& reach_lo,
                            const glm::vec3& reach_hi, const glm::vec4& light) {
  const glm::dvec3 centre = (glm::dvec3(lo) + glm::dvec3(hi)) * 0.5;
  const bool point = light.w != 0.0f;
  const glm::dvec3 l = glm::dvec3(light) / (point ? double(light.w) : 1.0);
  glm::dvec3 n = point ? centre - l : -l;
  if (!(glm::length(n) > 0.0)) return kPlaneAtInfinity;
  n = glm::normalize(n);
  auto corner = [](const glm::vec3& a, const glm::vec3& b, int i) {
    return glm::dvec3(i & 1 ? b.x : a.x, i & 2 ? b.y : a.y, i & 4 ? b.z : a.z);
  };
  constexpr double kMinCosine = 0.1;
  for (int i = 0; i < 8 && point; ++i) {
    const glm::dvec3 r = corner(lo, hi, i) - l;
    if (!(glm::dot(n, r) >= kMinCosine * glm::length(r)) || glm::length(r) == 0.0)
      return kPlaneAtInfinity;
  }
  double farthest = -INFINITY;
  for (int i = 0; i < 8; ++i)
    farthest = std::max(farthest, glm::dot(n, corner(reach_lo, reach_hi, i)));
  const double margin = 1e-2 * glm::length(glm::dvec3(reach_hi) - glm::dvec3(reach_lo)) + 1e-3;
  return glm::vec4(glm::vec3(n), float(-(farthest + margin)));
}

// Whether the segment from p towards the light (to it, for a point light; along it without end,
// for a directional one) meets the box [lo, hi]: the slab test, in double.
bool sees_box_towards_light(const glm::vec3& p, const glm::vec4& light, const glm::vec3& lo,
                            const glm::vec3& hi) {
  const bool point = light.w != 0.0f;
  const glm::dvec3 from(p);
  const glm::dvec3 d = point ? glm::dvec3(light) / double(light.w) - from : glm::dvec3(light);
  double t0 = 0.0, t1 = point ? 1.0 : INFINITY;
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0.0) {
      if (from[k] < lo[k] || from[k] > hi[k]) return false;
      continue;
    }
    double a = (lo[k] - from[k]) / d[k], b = (hi[k] - from[k]) / d[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  return t0 <= t1;
}

// Laine 2005 §7's depth bounds (FramePlan::depth_bounds). The box's volume, cut by the far plane,
// is convex (the hull of the box and its shadow on the plane), so where it meets the frustum its
// depths reach their extremes on its boundary, cut by the frustum's planes, or at a corner of
// the near rectangle inside it (depth 1); the far end of the frustum is at infinity (depth 0).
// Its boundary is the box's own volume, built by core like any other. Widened by a hair, as the
// rasterizer's depths may round past a vertex's.
soft::DepthBounds box_volume_depth_bounds(const glm::vec3& lo, const glm::vec3& hi,
                                          const glm::vec4& light, const glm::vec4& far_plane,
                                          const glm::mat4& view_proj,
                                          const std::array<glm::vec3, 4>& near_rect) {
  const soft::DepthBounds all{0.0f, 1.0f};
  if (light.w != 0.0f && sees_box_towards_light(glm::vec3(light) / light.w, light, lo, hi))
    return all;  // a point light in or on the box: its volume is everything around it
  const Mesh box = make_box(lo, hi);
  const Topology topology = build_topology(box);
  VolumeScratch scratch;
  VolumeBuffer volume;
  build_volume(topology, light, {Generator::standard, true, far_plane}, scratch, volume);
  soft::DepthBounds b{1.0f, 0.0f};
  auto add_triangle = [&](const glm::vec4& a, const glm::vec4& c, const glm::vec4& d) {
    std::array<glm::vec4, 9> v{view_proj * a, view_proj * c, view_proj * d};
    int n = 3;
    // The frustum: before the near plane (z <= w), within x and y (|x|, |y| <= w).
    const auto planes = {glm::vec4(0, 0, -1, 1), glm::vec4(-1, 0, 0, 1), glm::vec4(1, 0, 0, 1),
                         glm::vec4(0, -1, 0, 1), glm::vec4(0, 1, 0, 1)};
    for (const glm::vec4& plane : planes) {
      soft::clip_polygon(v, n, [&plane](const glm::vec4& x) { return glm::dot(plane, x); });
      if (n < 3) return;
    }
    for (int i = 0; i < n; ++i) {
      const float depth = v[i].w > 0.0f ? std::clamp(v[i].z / v[i].w, 0.0f, 1.0f) : 0.0f;
      b.zmin = std::min(b.zmin, depth);
      b.zmax = std::max(b.zmax, depth);
    }
  };
  auto add = [&](const PrimitiveList& list, int corners) {
    for (std::size_t p = 0; p < list.size(); ++p) {
      const glm::vec4* v = &list.vertices[p * static_cast<std::size_t>(corners)];
      for (int t = 0; t < (corners == kQuadCorners ? 2 : 1); ++t)
        add_triangle(v[kQuadTriangles[3 * t]], v[kQuadTriangles[3 * t + 1]],
                     v[kQuadTriangles[3 * t + 2]]);
    }
  };
  add(volume.sides, kQuadCorners);
  add(volume.light_caps, kTriangleCorners);
  add(volume.dark_caps, kTriangleCorners);
  for (const glm::vec3& c : near_rect)
    if (glm::dot(glm::vec3(far_plane), c) + far_plane.w <= 0.0f &&
        sees_box_towards_light(c, light, lo, hi))
      b = {std::min(b.zmin, 1.0f), 1.0f};
  if (b.zmin > b.zmax) return b;  // out of view
  constexpr float kSlack = 1e-5f;
  return {std::max(0.0f, b.zmin - kSlack), std::min(1.0f, b.zmax + kSlack)};
}

// Draws the segment a-b (clip space, w >= 0 allowed at one end) over the image, blended: clipped
// to the near plane (z <= w) in homogeneous space, so that a ray to infinity ends at its
// vanishing point, then stepped pixel by pixel within the viewport.
void overlay_segment(Image& img, glm::vec4 a, glm::vec4 b, const glm::vec3& color) {
  const float da = a.w - a.z, db = b.w - b.z;
  if (da < 0.0f && db < 0.0f) return;
  if (da < 0.0f) a = a + (b - a) * (da / (da - db));
  if (db < 0.0f) b = b + (a - b) * (db / (db - da));
  if (a.w <= 0.0f || b.w <= 0.0f) return;  // on the eye's plane: nothing to see
  const glm::vec2 pa((a.x / a.w + 1.0f) * 0.5f * img.width, (1.0f - a.y / a.w) * 0.5f * img.height);
  const glm::vec2 pb((b.x / b.w + 1.0f) * 0.5f * img.width, (1.0f - b.y / b.w) * 0.5f * img.height);
  const float length = std::max(std::abs(pb.x - pa.x), std::abs(pb.y - pa.y));
  const int steps = static_cast<int>(std::min(length, 8.0f * (img.width + img.height)));
  for (int i = 0; i <= steps; ++i) {
    const glm::vec2 p = steps == 0 ? pa : pa + (pb - pa) * (float(i) / float(steps));
    const int x = static_cast<int>(p.x), y = static_cast<int>(p.y);
    if (x < 0 || y < 0 || x >= img.width || y >= img.height) continue;
    std::uint8_t* px = &img.rgba[4 * (static_cast<std::size_t>(y) * img.width + x)];
    for (int k = 0; k < 3; ++k)
      px[k] = static_cast<std::uint8_t>(0.4f * px[k] + 0.6f * 255.0f * color[k]);
  }
}

}  // namespace

glm::vec4 FramePlan::object_far_plane(std::size_t l, std::size_t o) const {
  // Planes map from the eye-relative world to the object by the transpose of its model matrix.
  if (far_plane[l][o] == kPlaneAtInfinity) return kPlaneAtInfinity;
  return glm::vec4(glm::transpose(glm::dmat4(model[o])) * glm::dvec4(far_plane[l][o]));
}

std::pair<std::int32_t, std::uint32_t> FramePlan::object_of(std::uint32_t id) const {
  if (id >= first_id.back()) return {-1, 0};
  const auto o = std::upper_bound(first_id.begin(), first_id.end(), id) - first_id.begin() - 1;
  return {static_cast<std::int32_t>(o), id - first_id[static_cast<std::size_t>(o)]};
}

FramePlan plan_frame(const Scene& scene, const RenderOptions& options, FrameStats& stats) {
  FramePlan plan;
  const glm::mat4 view = scene.camera.view_from_eye();
  const glm::mat4 proj = scene.camera.projection(static_cast<float>(options.width) /
                                                 static_cast<float>(options.height));
  plan.view_proj = proj * view;
  plan.inv_view_proj = glm::inverse(plan.view_proj);
  const std::size_t objects = scene.objects.size();
  plan.model.resize(objects);
  plan.weight_sign.resize(objects);
  plan.first_id.assign(objects + 1, 0);
  for (std::size_t o = 0; o < objects; ++o) {
    const SceneObject& object = scene.objects[o];
    plan.model[o] = eye_relative(object.transform, scene.camera.position);
    plan.weight_sign[o] = glm::determinant(glm::mat3(object.transform)) < 0.0f ? -1 : 1;
    plan.first_id[o + 1] =
        plan.first_id[o] + static_cast<std::uint32_t>(object.mesh->triangle_count());
  }
  for (const SceneLight& light : scene.lights)
    plan.lights.push_back(eye_relative(light.position, scene.camera.position));
  plan.glass_group.assign(objects, -1);
  std::vector<Material> glass_materials;
  for (std::size_t o = 0; o < objects; ++o) {
    const Material& material = scene.objects[o].material;
    if (!material.transparent()) continue;
    const auto known = std::find(glass_materials.begin(), glass_materials.end(), material);
    plan.glass_group[o] = static_cast<int>(known - glass_materials.begin());
    if (known == glass_materials.end()) {
      glass_materials.push_back(material);
      plan.glass_log_transmittance.push_back(log_transmittance(material));
      plan.glass_members.emplace_back();
    }
    plan.glass_members[static_cast<std::size_t>(plan.glass_group[o])].push_back(o);
  }

  // The near-plane rectangle and each object's bounds, eye-relative, for the methods that
  // decide per object (and its long axis for split planes).
  std::array<glm::vec3, 4> near_rect;
  for (int i = 0; i < 4; ++i) {
    const glm::vec4 c =
        plan.inv_view_proj * glm::vec4(i == 1 || i == 2 ? 1 : -1, i >= 2 ? 1 : -1, 1, 1);
    near_rect[i] = glm::vec3(c) / c.w;
  }
  struct Bounds {
    glm::vec3 lo, hi;            // the bounding box
    glm::vec3 centre;            // of the box
    float radius;                // of the sphere about it
    std::vector<Shape> casters;  // for split planes: the whole object's shape, or each part's
  };
  std::vector<Bounds> bounds(objects);
  const bool bounded = options.extrusion == Extrusion::bounded;
  glm::vec3 reach_lo(INFINITY), reach_hi(-INFINITY);  // the scene and the near plane
  for (const glm::vec3& c : near_rect)
    reach_lo = glm::min(reach_lo, c), reach_hi = glm::max(reach_hi, c);
  for (std::size_t o = 0; o < objects; ++o) {
    const Topology& topo = *scene.objects[o].topology;
    const bool by_part = options.method == Method::split_plane &&
                         options.split_parts == SplitParts::each && topo.part_count() >= 2 &&
                         topo.part_count() <= kMaxSplitParts;
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    std::vector<std::vector<glm::vec3>> points(by_part ? topo.part_count() : 1);
    for (std::size_t v = 0; v < topo.positions.size(); ++v) {
      const glm::vec3 q = glm::vec3(plan.model[o] * glm::vec4(topo.positions[v], 1.0f));
      lo = glm::min(lo, q);
      hi = glm::max(hi, q);
      if (options.method != Method::split_plane) continue;
      if (!by_part)
        points[0].push_back(q);
      else if (topo.vertex_part[v] != Topology::kNoPart)
        points[topo.vertex_part[v]].push_back(q);
    }
    bounds[o] = {lo, hi, (lo + hi) * 0.5f, glm::length(hi - lo) * 0.5f, {}};
    if (options.method == Method::split_plane)
      for (const std::vector<glm::vec3>& part : points) bounds[o].casters.push_back(shape_of(part));
    reach_lo = glm::min(reach_lo, lo);
    reach_hi = glm::max(reach_hi, hi);
  }
  plan.far_plane.assign(scene.lights.size(), std::vector<glm::vec4>(objects, kPlaneAtInfinity));
  for (std::size_t l = 0; l < scene.lights.size() && bounded; ++l)
    for (std::size_t o = 0; o < objects; ++o)
      if (bounds[o].lo.x <= bounds[o].hi.x)  // an object with vertices
        plan.far_plane[l][o] =
            bounded_far_plane(bounds[o].lo, bounds[o].hi, reach_lo, reach_hi, plan.lights[l]);
  plan.depth_bounds.assign(scene.lights.size(), std::vector<soft::DepthBounds>(objects));
  for (std::size_t l = 0; l < scene.lights.size(); ++l)
    for (std::size_t o = 0; o < objects; ++o)
      if (bounds[o].lo.x <= bounds[o].hi.x)
        plan.depth_bounds[l][o] =
            box_volume_depth_bounds(bounds[o].lo, bounds[o].hi, plan.lights[l],
                                    plan.far_plane[l][o], plan.view_proj, near_rect);
  plan.zfail.assign(scene.lights.size(), std::vector<bool>(objects));
  plan.split.assign(scene.lights.size(), std::vector<std::vector<FramePlan::PartSplit>>(objects));
  plan.prefill.assign(scene.lights.size(), std::vector<bool>(objects));
  stats.zfail_lights.assign(objects, 0);
  const glm::mat4 plane_to_clip = glm::transpose(plan.inv_view_proj);  // planes map by M^-T
  const bool prefills =
      options.method == Method::split_plane || options.method == Method::zpass_prefill;
  for (std::size_t l = 0; l < scene.lights.size(); ++l) {
    const bool can_prefill =
        prefills && near_plane_prefill_possible(plan.lights[l], plan.view_proj);
    for (std::size_t o = 0; o < objects; ++o) {
      const bool reaches_near =
          options.method != Method::zpass && options.method != Method::zfail &&
          may_shadow_near_plane(bounds[o].centre, bounds[o].radius, near_rect, plan.lights[l]);
      const bool zfail = options.method == Method::zfail || (reaches_near && !can_prefill);
      plan.zfail[l][o] = zfail;
      plan.prefill[l][o] = reaches_near && can_prefill;
      const SplitPlaneChoice choice = scene.objects[o].split_plane;
      const bool automatic = choice == SplitPlaneChoice::automatic;
      // Under split_plane, casters holds the whole object or each of its parts (else nothing); a
      // volume drawn by z-fail whole (the light in the near plane) takes no plane.
      if (!zfail)
        for (const Shape& shape : bounds[o].casters) {
          std::optional<glm::vec4> plane;  // world, eye-relative
          if (choice == SplitPlaneChoice::flat || (automatic && shape.flat))
            plane = flat_plane(shape, plan.lights[l]);  // none edge-on: then as below
          if (!plane) {
            const bool ppl =
                choice == SplitPlaneChoice::point_point_light || (automatic && shape.elongated);
            plane = ppl ? point_point_light(shape.p1, shape.p2, plan.lights[l])
                        : point_camera_light(shape.centroid, plan.lights[l]);
          }
          FramePlan::PartSplit& split = plan.split[l][o].emplace_back();
          split.plane = plane_to_clip * *plane;
          if (automatic && options.split_planes == SplitPlanes::sampled) {
            split.candidates.assign(1, split.plane);
            for (const glm::vec4& candidate : split_plane_candidates(shape, plan.lights[l]))
              split.candidates.push_back(plane_to_clip * candidate);
          }
        }
      (zfail                       ? stats.objects_zfail
       : !plan.split[l][o].empty() ? stats.objects_split
                                   : stats.objects_zpass) += 1;
      stats.zfail_lights[o] += zfail;
    }
  }
  return plan;
}

Generator object_generator(const SceneObject& object, Generator requested) {
  return requested == Generator::automatic && object.material.transparent()
             ? Generator::multiplicity
             : requested;
}

glm::vec3 log_transmittance(const Material& material) {
  glm::vec3 out;
  for (int c = 0; c < 3; ++c) {
    const float t = material.transmittance()[c];
    out[c] = t > 0.0f ? std::max(std::log(t), kLogOfZero) : kLogOfZero;
  }
  return out;
}

glm::vec4 object_space_light(const SceneObject& object, const glm::vec4& light) {
  return glm::vec4(glm::inverse(glm::dmat4(object.transform)) * glm::dvec4(light));
}

std::vector<bool> VolumeCache::update(const Scene& scene, const FramePlan& plan, std::size_t light,
                                      Generator generator, FrameStats& stats) {
  if (cache_.size() < scene.lights.size()) cache_.resize(scene.lights.size());
  std::vector<Entry>& cache = cache_[light];
  cache.resize(scene.objects.size());
  std::vector<VolumeJob> jobs;
  std::vector<bool> rebuilt(scene.objects.size(), false);
  for (std::size_t o = 0; o < scene.objects.size(); ++o) {
    const SceneObject& object = scene.objects[o];
    const glm::vec4 object_light = object_space_light(object, scene.lights[light].position);
    const VolumeOptions options{object_generator(object, generator), plan.builds_caps(light, o),
                                plan.object_far_plane(light, o), plan.splits_by_part(light, o)};
    Entry& c = cache[o];
    if (c.topology == object.topology && c.light == object_light && c.options == options) {
      ++stats.volumes_reused;
      continue;
    }
    c.topology = object.topology;
    c.light = object_light;
    c.options = options;
    jobs.push_back({c.topology.get(), object_light, options, &c.volume});
    rebuilt[o] = true;
    ++stats.volumes_built;
  }
  builder_.build(jobs);
  return rebuilt;
}

void overlay_volumes(Image& image, const Scene& scene, const FramePlan& plan,
                     const VolumeCache& volumes) {
  const glm::vec3 colors[] = {{1.0f, 0.9f, 0.1f}, {0.2f, 0.9f, 1.0f}, {1.0f, 0.3f, 0.8f}};
  for (std::size_t l = 0; l < scene.lights.size(); ++l)
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
      const glm::mat4 mvp = plan.view_proj * plan.model[o];
      const PrimitiveList& sides = volumes.volume(l, o).sides;
      for (std::size_t q = 0; q < sides.size(); ++q) {
        const glm::vec4* v = &sides.vertices[q * kQuadCorners];  // u, u_inf, v_inf, v
        const glm::vec4 u = mvp * v[0], u_inf = mvp * v[1], v_inf = mvp * v[2], w = mvp * v[3];
        const glm::vec3& c = colors[l % 3];
        overlay_segment(image, u, w, c);
        overlay_segment(image, u, u_inf, c);
        overlay_segment(image, w, v_inf, c);
      }
    }
}

namespace shading {

glm::vec3 background(int y, int h) {
  const float fade = 1.0f - float(y) / float(h);
  return kBackgroundBottom + (kBackgroundTop - kBackgroundBottom) * fade;
}

float to_srgb(float linear) {
  const float c = std::clamp(linear, 0.0f, 1.0f);
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

std::uint8_t to_srgb8(float linear) {
  // Floats in [0, 1) fall into buckets by their top bits (2^15 neighbouring floats each), each
  // narrower than the gap between two codes' first values, so that a bucket's code is the code
  // of its least float, or one more from where the next code begins (steps[code]).
  constexpr int kDropBits = 15;
  constexpr std::uint32_t kOne = 0x3f800000u;  // the bits of 1.0f
  struct Table {
    std::array<std::uint8_t, (kOne >> kDropBits)> bucket_code;
    std::array<float, 256> steps;  // steps[k]: the least float whose code is more than k
  };
  static const Table table = [] {
    const auto code = [](float v) { return static_cast<int>(std::lround(to_srgb(v) * 255.0f)); };
    Table t{};
    for (int k = 0; k < 255; ++k) {
      float lo = 0.0f, hi = 1.0f;  // code(lo) <= k < code(hi)
      for (;;) {
        const float mid = lo + (hi - lo) * 0.5f;
        if (mid <= lo || mid >= hi) break;  // lo and hi are neighbouring floats
        (code(mid) > k ? hi : lo) = mid;
      }
      t.steps[static_cast<std::size_t>(k)] = hi;
    }
    t.steps[255] = INFINITY;
    for (std::uint32_t b = 0; b < t.bucket_code.size(); ++b)
      t.bucket_code[b] = static_cast<std::uint8_t>(code(std::bit_cast<float>(b << kDropBits)));
    return t;
  }();
  if (!(linear > 0.0f)) return 0;  // NaN too, as to_srgb's clamp makes it
  if (!(linear < 1.0f)) return 255;
  const std::uint8_t c = table.bucket_code[std::bit_cast<std::uint32_t>(linear) >> kDropBits];
  return static_cast<std::uint8_t>(c + (linear >= table.steps[c]));
}

}  // namespace shading
}  // namespace shadowvol
