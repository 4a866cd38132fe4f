#include "render/renderer.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <chrono>
#include <cmath>
#include <string>

#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

namespace shadowvol {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Clip-space triangles of an object's mesh, 3 vertices each, in face order.
void clip_triangles(const SceneObject& o, const glm::mat4& mvp, std::vector<glm::vec4>& out) {
  out.clear();
  out.reserve(o.mesh->indices.size());
  for (std::uint32_t i : o.mesh->indices)
    out.push_back(mvp * glm::vec4(o.mesh->positions[i], 1.0f));
}

// Clip-space triangles of a primitive list (quads split by kQuadTriangles) and their weights.
void clip_volume(const PrimitiveList& list, int corners, const glm::mat4& mvp, int sign,
                 std::vector<glm::vec4>& tris, std::vector<std::int32_t>& weights) {
  const int per = corners == kQuadCorners ? 2 : 1;
  for (std::size_t p = 0; p < list.size(); ++p) {
    const glm::vec4* v = &list.vertices[p * static_cast<std::size_t>(corners)];
    for (int t = 0; t < per; ++t) {
      for (int k = 0; k < 3; ++k) tris.push_back(mvp * v[kQuadTriangles[3 * t + k]]);
      weights.push_back(sign * list.weights[p]);
    }
  }
}

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

glm::vec3 to_srgb(glm::vec3 linear) {
  for (int i = 0; i < 3; ++i) {
    const float c = std::clamp(linear[i], 0.0f, 1.0f);
    linear[i] = c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
  }
  return linear;
}

// Draws the segment a-b (clip space, w >= 0 allowed at one end) over the image, blended: clipped
// to the near plane (z >= -w) in homogeneous space, so that a ray to infinity ends at its
// vanishing point, then stepped pixel by pixel within the viewport.
void overlay_segment(Image& img, glm::vec4 a, glm::vec4 b, const glm::vec3& color) {
  const float da = a.z + a.w, db = b.z + b.w;
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

std::string_view to_string(Method method) {
  switch (method) {
    case Method::zpass:
      return "zpass";
    case Method::zfail:
      return "zfail";
    case Method::automatic:
      return "auto";
  }
  return "unknown";
}

Expected<Method> parse_method(std::string_view name) {
  for (Method m : {Method::zpass, Method::zfail, Method::automatic})
    if (name == to_string(m)) return m;
  return make_error("unknown method '" + std::string(name) + "': expected zpass, zfail or auto");
}

Expected<void> check_options(const RenderOptions& options) {
  if (options.width < 1 || options.height < 1 || options.width > soft::kMaxViewport ||
      options.height > soft::kMaxViewport)
    return make_error("image size " + std::to_string(options.width) + "x" +
                      std::to_string(options.height) + " is outside 1x1 .. " +
                      std::to_string(soft::kMaxViewport) + "x" +
                      std::to_string(soft::kMaxViewport));
  return {};
}

Frame Renderer::render(const Scene& scene, const RenderOptions& options) {
  assert(check_options(options).ok());
  const int w = options.width, h = options.height;
  const std::size_t pixels = static_cast<std::size_t>(w) * h;
  if (target_.width != w || target_.height != h) target_ = soft::Target(w, h);
  Frame frame;
  FrameStats& stats = frame.stats;
  const glm::mat4 view = scene.camera.view_from_eye();
  const glm::mat4 proj = scene.camera.projection(static_cast<float>(w) / static_cast<float>(h));
  const glm::mat4 view_proj = proj * view;  // of eye-relative space
  // Everything is drawn in eye-relative space (DESIGN.md "Numerics"): each object's transform
  // composed with the eye's translation in double, lights likewise.
  std::vector<glm::mat4> model(scene.objects.size());
  for (std::size_t o = 0; o < scene.objects.size(); ++o)
    model[o] = eye_relative(scene.objects[o].transform, scene.camera.position);

  // --- depth pass: ids are (first face id of the object) + face ---
  auto start = Clock::now();
  target_.clear_depth();
  std::vector<std::uint32_t> first_id(scene.objects.size() + 1, 0);
  std::vector<glm::vec4> tris;
  for (std::size_t o = 0; o < scene.objects.size(); ++o) {
    const SceneObject& object = scene.objects[o];
    first_id[o + 1] = first_id[o] + static_cast<std::uint32_t>(object.mesh->triangle_count());
    clip_triangles(object, view_proj * model[o], tris);
    soft::draw_depth(target_, tris, first_id[o], stats.depth);
    stats.triangles += object.mesh->triangle_count();
  }
  target_.update_tile_depth();
  frame.object.assign(pixels, -1);
  frame.face.assign(pixels, 0);
  for (std::size_t p = 0; p < pixels; ++p) {
    const std::uint32_t id = target_.id[p];
    if (id == soft::Target::kNoId) continue;
    const auto o = static_cast<std::size_t>(std::upper_bound(first_id.begin(), first_id.end(), id) -
                                            first_id.begin() - 1);
    frame.object[p] = static_cast<std::int32_t>(o);
    frame.face[p] = id - first_id[o];
  }
  stats.ms_depth = ms_since(start);

  // The near-plane rectangle (eye-relative space), for the per-object choice of method.
  const glm::mat4 inv_view_proj = glm::inverse(view_proj);
  std::array<glm::vec3, 4> near_rect;
  for (int i = 0; i < 4; ++i) {
    const glm::vec4 c =
        inv_view_proj * glm::vec4(i == 1 || i == 2 ? 1 : -1, i >= 2 ? 1 : -1, -1, 1);
    near_rect[i] = glm::vec3(c) / c.w;
  }

  // Each object's bounding sphere (eye-relative), once per frame, for the choice of method.
  struct Sphere {
    glm::vec3 centre;
    float radius;
  };
  std::vector<Sphere> bounds(scene.objects.size());
  if (options.method == Method::automatic)
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
      glm::vec3 lo(INFINITY), hi(-INFINITY);
      for (const glm::vec3& p : scene.objects[o].topology->positions) {
        const glm::vec3 q = glm::vec3(model[o] * glm::vec4(p, 1.0f));
        lo = glm::min(lo, q);
        hi = glm::max(hi, q);
      }
      bounds[o] = {(lo + hi) * 0.5f, glm::length(hi - lo) * 0.5f};
    }

  // --- per light: volumes, counts ---
  frame.shadowed.assign(scene.lights.size(), std::vector<std::uint8_t>(pixels, 0));
  cache_.resize(scene.lights.size());
  for (std::size_t l = 0; l < scene.lights.size(); ++l) {
    const glm::vec4 light = scene.lights[l].position;
    start = Clock::now();
    std::vector<CachedVolume>& cache = cache_[l];
    cache.resize(scene.objects.size());
    std::vector<VolumeJob> jobs;
    std::vector<bool> zfail(scene.objects.size());
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
      const SceneObject& object = scene.objects[o];
      if (options.method == Method::automatic) {
        zfail[o] = may_shadow_near_plane(bounds[o].centre, bounds[o].radius, near_rect,
                                         eye_relative(light, scene.camera.position));
      } else {
        zfail[o] = options.method == Method::zfail;
      }
      (zfail[o] ? stats.objects_zfail : stats.objects_zpass) += 1;
      const glm::vec4 object_light(glm::inverse(glm::dmat4(object.transform)) * glm::dvec4(light));
      const VolumeOptions volume_options{options.generator, static_cast<bool>(zfail[o])};
      CachedVolume& c = cache[o];
      if (c.topology == object.topology && c.light == object_light &&
          c.options.generator == volume_options.generator &&
          c.options.caps == volume_options.caps) {
        ++stats.volumes_reused;
        continue;
      }
      c.topology = object.topology;
      c.light = object_light;
      c.options = volume_options;
      jobs.push_back({c.topology.get(), object_light, volume_options, &c.volume});
      ++stats.volumes_built;
    }
    builder_.build(jobs);
    stats.ms_volumes += ms_since(start);

    start = Clock::now();
    target_.clear_count();
    std::vector<std::int32_t> weights;
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
      const SceneObject& object = scene.objects[o];
      const VolumeBuffer& v = cache[o].volume;
      stats.volume_primitives += v.primitive_count();
      const glm::mat4 mvp = view_proj * model[o];
      // A mirroring transform reverses every primitive's winding: negate the weights.
      const int sign = glm::determinant(glm::mat3(object.transform)) < 0.0f ? -1 : 1;
      tris.clear();
      weights.clear();
      clip_volume(v.sides, kQuadCorners, mvp, sign, tris, weights);
      if (zfail[o]) {
        clip_volume(v.light_caps, kTriangleCorners, mvp, sign, tris, weights);
        clip_volume(v.dark_caps, kTriangleCorners, mvp, sign, tris, weights);
      }
      // Depth bounds: the volume's nearest window depth (a triangle's depth is affine on the
      // screen, so its range is its vertices'; one behind the near plane reaches depth 0).
      soft::DepthBounds bounds{1.0f, 1.0f};
      for (const glm::vec4& c : tris)
        bounds.zmin =
            std::min(bounds.zmin, c.w <= 0.0f || c.z < -c.w ? 0.0f : (c.z / c.w + 1.0f) * 0.5f);
      soft::draw_counts(target_, tris, weights,
                        zfail[o] ? soft::CountRule::zfail : soft::CountRule::zpass, stats.counts,
                        bounds);
    }
    for (std::size_t p = 0; p < pixels; ++p) frame.shadowed[l][p] = target_.count[p] != 0;
    stats.ms_counts += ms_since(start);
  }

  // --- shading: ambient everywhere, each light where it is not shadowed ---
  start = Clock::now();
  frame.image = {w, h, std::vector<std::uint8_t>(pixels * 4)};
  std::vector<std::vector<glm::vec3>> world(scene.objects.size());  // vertices, once per frame
  for (std::size_t o = 0; o < scene.objects.size(); ++o) {
    const SceneObject& object = scene.objects[o];
    world[o].reserve(object.mesh->positions.size());
    for (const glm::vec3& p : object.mesh->positions)
      world[o].push_back(glm::vec3(model[o] * glm::vec4(p, 1.0f)));
  }
  const glm::dmat4 inv_vp(inv_view_proj);
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      const std::size_t p = static_cast<std::size_t>(y) * w + x;
      const float fade = 1.0f - float(y) / float(h);
      glm::vec3 color(0.16f + 0.10f * fade, 0.18f + 0.10f * fade, 0.22f);  // background
      if (frame.object[p] >= 0) {
        const auto o = static_cast<std::size_t>(frame.object[p]);
        const SceneObject& object = scene.objects[o];
        const std::uint32_t* f = &object.mesh->indices[3 * static_cast<std::size_t>(frame.face[p])];
        const glm::vec3& a = world[o][f[0]];
        glm::vec3 n = glm::cross(world[o][f[1]] - a, world[o][f[2]] - a);
        const float len = glm::length(n);
        n = len > 0.0f ? n / len : glm::vec3(0, 1, 0);
        const glm::dvec4 ndc((x + 0.5) / w * 2.0 - 1.0, 1.0 - (y + 0.5) / h * 2.0,
                             double(target_.depth[p]) * 2.0 - 1.0, 1.0);
        const glm::dvec4 at = inv_vp * ndc;
        const glm::vec3 pos = glm::vec3(glm::dvec3(at) / at.w);
        const glm::vec3 to_eye = glm::normalize(-pos);  // the eye is the origin
        if (glm::dot(n, to_eye) < 0.0f) n = -n;         // two-sided: light the side we see
        const glm::vec3 albedo = object.material.color;
        color = scene.ambient * albedo;
        for (std::size_t l = 0; l < scene.lights.size(); ++l) {
          if (frame.shadowed[l][p]) continue;
          const SceneLight& light = scene.lights[l];
          const glm::vec4 lp = eye_relative(light.position, scene.camera.position);
          const glm::vec3 to_light =
              glm::normalize(lp.w != 0.0f ? glm::vec3(lp) / lp.w - pos : glm::vec3(lp));
          const float lambert = glm::dot(n, to_light);
          if (lambert <= 0.0f) continue;
          const float spec =
              std::pow(std::max(0.0f, glm::dot(n, glm::normalize(to_light + to_eye))), 48.0f);
          color += light.color * light.intensity * (albedo * lambert + glm::vec3(0.25f * spec));
        }
      }
      const glm::vec3 srgb = to_srgb(color);
      for (int k = 0; k < 3; ++k)
        frame.image.rgba[4 * p + k] = static_cast<std::uint8_t>(std::lround(srgb[k] * 255.0f));
      frame.image.rgba[4 * p + 3] = 255;
    }
  });
  stats.ms_shade = ms_since(start);

  if (options.show_volumes) {
    const glm::vec3 colors[] = {{1.0f, 0.9f, 0.1f}, {0.2f, 0.9f, 1.0f}, {1.0f, 0.3f, 0.8f}};
    for (std::size_t l = 0; l < cache_.size(); ++l)
      for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        const glm::mat4 mvp = view_proj * model[o];
        const PrimitiveList& sides = cache_[l][o].volume.sides;
        for (std::size_t q = 0; q < sides.size(); ++q) {
          const glm::vec4* v = &sides.vertices[q * kQuadCorners];  // u, u_inf, v_inf, v
          const glm::vec4 u = mvp * v[0], u_inf = mvp * v[1], v_inf = mvp * v[2], w_ = mvp * v[3];
          const glm::vec3& c = colors[l % 3];
          overlay_segment(frame.image, u, w_, c);
          overlay_segment(frame.image, u, u_inf, c);
          overlay_segment(frame.image, w_, v_inf, c);
        }
      }
  }
  return frame;
}

}  // namespace shadowvol
