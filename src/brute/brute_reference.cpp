#include "brute/brute_reference.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

namespace shadowvol {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Shadow rays leave a surface, and stop short of a point light, by this fraction of the distances
// involved: thousands of double steps, far below any feature a float mesh can hold.
constexpr double kHair = 1e-9;

struct Triangle {
  glm::dvec3 a, e1, e2;  // corner a and the edges to b and c, eye-relative
};

struct Object {
  std::vector<Triangle> triangles;
  glm::dvec3 lo{kInfinity}, hi{-kInfinity};  // box of the triangles, padded by a hair
  bool transparent = false, casts = true, receives = true;
  glm::dvec3 transmittance{1.0};
};

struct Light {
  glm::dvec4 position;  // eye-relative; w = 0: a direction towards the light
  double range = kInfinity;
};

// Moller & Trumbore 1997, in double, edges included: the distance along `dir` to the triangle,
// or infinity.
double intersect(const glm::dvec3& origin, const glm::dvec3& dir, const Triangle& t) {
  const glm::dvec3 p = glm::cross(dir, t.e2);
  const double det = glm::dot(t.e1, p);
  if (det == 0.0) return kInfinity;  // edge-on or degenerate: no area to hit
  const glm::dvec3 s = origin - t.a;
  const double u = glm::dot(s, p) / det;
  if (!(u >= 0.0 && u <= 1.0)) return kInfinity;
  const glm::dvec3 q = glm::cross(s, t.e1);
  const double v = glm::dot(dir, q) / det;
  if (!(v >= 0.0 && u + v <= 1.0)) return kInfinity;
  return glm::dot(t.e2, q) / det;
}

// Whether the ray meets the box within [t0, t1] (slabs; a zero direction component is a slab the
// origin must lie in).
bool meets_box(const glm::dvec3& origin, const glm::dvec3& dir, const Object& o, double t0,
               double t1) {
  for (int k = 0; k < 3; ++k) {
    if (dir[k] == 0.0) {
      if (origin[k] < o.lo[k] || origin[k] > o.hi[k]) return false;
      continue;
    }
    double a = (o.lo[k] - origin[k]) / dir[k], b = (o.hi[k] - origin[k]) / dir[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a), t1 = std::min(t1, b);
    if (t0 > t1) return false;
  }
  return true;
}

class BruteReference final : public ReferenceSampler {
 public:
  BruteReference(const Scene& scene, int width, int height) : width_(width), height_(height) {
    const glm::dvec3 eye(scene.camera.position);
    forward_ = glm::normalize(glm::dvec3(scene.camera.target) - eye);
    right_ = glm::normalize(glm::cross(forward_, glm::dvec3(scene.camera.up)));
    up_ = glm::cross(right_, forward_);
    tan_half_ = std::tan(glm::radians(double(scene.camera.fov_y_degrees)) / 2.0);
    aspect_ = double(width) / double(height);
    near_ = scene.camera.near;
    for (const SceneLight& l : scene.lights) {
      const glm::dvec4 p(l.position);
      lights_.push_back({p.w != 0.0 ? glm::dvec4(glm::dvec3(p) / p.w - eye, 1.0) : p,
                         l.limited() ? double(l.range) : kInfinity});
    }
    for (const SceneObject& so : scene.objects) {
      Object o;
      o.transparent = so.material.transparent();
      o.casts = so.casts_shadows;
      o.receives = so.receives_shadows;
      o.transmittance = glm::dvec3(so.material.transmittance());
      const glm::dmat4 model(so.transform);
      std::vector<glm::dvec3> corners;
      corners.reserve(so.mesh->positions.size());
      for (const glm::vec3& p : so.mesh->positions) {
        const glm::dvec3 q = glm::dvec3(model * glm::dvec4(glm::dvec3(p), 1.0)) - eye;
        corners.push_back(q);
        o.lo = glm::min(o.lo, q), o.hi = glm::max(o.hi, q);
      }
      const std::vector<std::uint32_t>& idx = so.mesh->indices;
      for (std::size_t f = 0; f + 2 < idx.size(); f += 3) {
        const glm::dvec3 a = corners[idx[f]], b = corners[idx[f + 1]], c = corners[idx[f + 2]];
        o.triangles.push_back({a, b - a, c - a});
      }
      if (!corners.empty()) {
        const double pad = kHair * (glm::length(o.hi - o.lo) + glm::length(o.hi) +
                                    glm::length(o.lo));
        o.lo -= glm::dvec3(pad), o.hi += glm::dvec3(pad);
      }
      glass_ = glass_ || o.transparent;
      objects_.push_back(std::move(o));
    }
  }

  ReferenceSample sample(double x, double y) const override {
    ReferenceSample out;
    see_nothing(out);
    out.glass = out;
    const glm::dvec3 through = direction(x, y);
    const double length = glm::length(through);
    const glm::dvec3 dir = through / length;
    const double from = near_ * length;  // the near plane, along this ray
    struct Hit {
      double t = kInfinity;
      std::int32_t object = -1;
      std::uint32_t face = 0;
    } opaque, glass;
    for (std::size_t o = 0; o < objects_.size(); ++o) {
      const Object& object = objects_[o];
      Hit& nearest = object.transparent ? glass : opaque;
      if (!meets_box({}, dir, object, from, nearest.t)) continue;
      for (std::size_t f = 0; f < object.triangles.size(); ++f) {
        const double t = intersect({}, dir, object.triangles[f]);
        // Strictly nearer: of equal depths the first drawn (the lower ids) is kept.
        if (t >= from && t < nearest.t)
          nearest = {t, static_cast<std::int32_t>(o), static_cast<std::uint32_t>(f)};
      }
    }
    if (opaque.object >= 0) light(opaque.object, opaque.face, opaque.t, dir, out);
    if (glass.object >= 0 && glass.t < opaque.t) light(glass.object, glass.face, glass.t, dir, out.glass);
    return out;
  }

  std::vector<std::uint8_t> near_plane_shadowed(double x, double y) const override {
    std::vector<std::uint8_t> out(lights_.size(), 0);
    const glm::dvec3 pos = direction(x, y) * near_;
    for (std::size_t l = 0; l < lights_.size(); ++l) {
      const auto [d, distance] = towards(l, pos);
      glm::dvec3 passed(1.0);
      out[l] = blocked(pos, d, distance * (1.0 - kHair), true, passed);
    }
    return out;
  }

  bool face_nearer_within(double x, double y, std::int32_t object, std::uint32_t face,
                          double distance) const override {
    if (object < 0 || static_cast<std::size_t>(object) >= objects_.size()) return false;
    const Object& o = objects_[static_cast<std::size_t>(object)];
    if (face >= o.triangles.size()) return false;
    const Triangle& t = o.triangles[face];
    const glm::dvec3 c[3] = {t.a, t.a + t.e1, t.a + t.e2};
    return triangle_nearer_within(
        c, x, y, distance,
        [this](const glm::dvec3& p) {
          const double ahead = glm::dot(p, forward_);
          const double nx = glm::dot(p, right_) / ahead / (tan_half_ * aspect_);
          const double ny = glm::dot(p, up_) / ahead / tan_half_;
          return glm::dvec3((nx + 1.0) * 0.5 * width_, (1.0 - ny) * 0.5 * height_, ahead);
        },
        [this](double wx, double wy) { return glm::normalize(direction(wx, wy)); });
  }

  ReferenceSurface on_face_plane(double x, double y, std::int32_t object,
                                 std::uint32_t face) const override {
    ReferenceSurface out;
    see_nothing(out);
    if (object < 0 || static_cast<std::size_t>(object) >= objects_.size()) return out;
    const Object& o = objects_[static_cast<std::size_t>(object)];
    if (face >= o.triangles.size()) return out;
    const Triangle& tri = o.triangles[face];
    const glm::dvec3 through = direction(x, y);
    const double length = glm::length(through);
    const glm::dvec3 dir = through / length;
    const glm::dvec3 n = glm::cross(tri.e1, tri.e2);
    const double t = glm::dot(n, tri.a) / glm::dot(n, dir);
    if (!(t >= near_ * length && std::isfinite(t))) return out;
    light(object, face, t, dir, out);
    return out;
  }

 private:
  // No surface, every light's answer unlit, for light() to fill in.
  void see_nothing(ReferenceSurface& out) const {
    const std::size_t lights = lights_.size();
    out.faces_light.assign(lights, 0);
    out.shadowed.assign(lights, 0);
    out.grazing.assign(lights, 0);
    out.transmitted.assign(glass_ ? lights : 0, glm::vec3(0.0f));
    out.distance = kInfinity;
  }

  // Through window point (x, y): forward plus the offsets on a plane at distance 1, so that the
  // point at parameter s lies s in front of the eye.
  glm::dvec3 direction(double x, double y) const {
    const double nx = x / width_ * 2.0 - 1.0, ny = 1.0 - y / height_ * 2.0;
    return forward_ + right_ * (nx * tan_half_ * aspect_) + up_ * (ny * tan_half_);
  }

  // The unit direction from pos towards light l, and the distance to it (infinite: directional).
  std::pair<glm::dvec3, double> towards(std::size_t l, const glm::dvec3& pos) const {
    const glm::dvec4& p = lights_[l].position;
    if (p.w == 0.0) return {glm::normalize(glm::dvec3(p)), kInfinity};
    const glm::dvec3 to = glm::dvec3(p) - pos;
    return {glm::normalize(to), glm::length(to)};
  }

  // Whether a caster (opaque; or any, with every_caster) crosses the ray within (0, tmax); the
  // transmittances of the transparent ones it crosses multiplied into `passed`.
  bool blocked(const glm::dvec3& origin, const glm::dvec3& dir, double tmax, bool every_caster,
               glm::dvec3& passed) const {
    for (const Object& object : objects_) {
      if (!object.casts || !meets_box(origin, dir, object, 0.0, tmax)) continue;
      for (const Triangle& tri : object.triangles) {
        const double t = intersect(origin, dir, tri);
        if (!(t > 0.0 && t < tmax)) continue;
        if (!object.transparent || every_caster) return true;
        passed *= object.transmittance;
      }
    }
    return false;
  }

  // The surface of face `face` of object `o` at distance t along the unit ray dir from the eye.
  void light(std::int32_t o, std::uint32_t face, double t, const glm::dvec3& dir,
             ReferenceSurface& out) const {
    const Object& object = objects_[static_cast<std::size_t>(o)];
    const Triangle& tri = object.triangles[face];
    out.object = o, out.face = face, out.distance = t;
    const glm::dvec3 pos = dir * t;
    glm::dvec3 n = glm::normalize(glm::cross(tri.e1, tri.e2));
    if (glm::dot(n, dir) > 0.0) n = -n;  // the side the eye sees
    for (std::size_t l = 0; l < lights_.size(); ++l) {
      const auto [d, distance] = towards(l, pos);
      const double cosine = glm::dot(n, d);
      out.grazing[l] = std::abs(cosine) < kGrazingCosine;
      if (!(cosine > 0.0)) continue;
      if (std::isfinite(lights_[l].range) && !(distance < lights_[l].range)) continue;
      out.faces_light[l] = 1;
      glm::dvec3 passed(1.0);
      if (object.receives) {
        const glm::dvec3 origin = pos + n * (kHair * glm::length(pos));
        const double reach =
            std::isinf(distance) ? kInfinity : distance - kHair * (glm::length(pos) + distance);
        if (blocked(origin, d, reach, false, passed)) {
          out.shadowed[l] = 1;
          continue;
        }
      }
      if (glass_) out.transmitted[l] = glm::vec3(passed);
    }
  }

  int width_, height_;
  glm::dvec3 forward_, right_, up_;
  double tan_half_ = 1.0, aspect_ = 1.0, near_ = 0.1;
  std::vector<Light> lights_;
  std::vector<Object> objects_;
  bool glass_ = false;
};

}  // namespace

Expected<std::shared_ptr<const ReferenceSampler>> make_brute_reference(const Scene& scene,
                                                                       int width, int height) {
  if (width <= 0 || height <= 0)
    return make_error("the brute-force reference needs a window of at least one pixel");
  return std::shared_ptr<const ReferenceSampler>(
      std::make_shared<const BruteReference>(scene, width, height));
}

Expected<ReferenceFrame> trace_brute_reference(const Scene& scene, int width, int height,
                                               const Progress& progress) {
  auto sampler = make_brute_reference(scene, width, height);
  if (!sampler) return sampler.error();
  return trace_frame(std::move(*sampler), width, height, scene.lights.size(),
                     has_transparent_casters(scene), progress);
}

}  // namespace shadowvol
