#include "trace/embree_baseline.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

#include <embree3/rtcore.h>
#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

namespace shadowvol {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

constexpr int kTile = 32;                  // pixels a side of a task's tile
constexpr int kPacketW = 4, kPacketH = 2;  // an 8-wide packet: 4 x 2 pixels
constexpr float kShadowEpsilon = 1e-4f;    // a shadow ray starts this far along (of its length)

}  // namespace

struct EmbreeBaseline::State {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  ~State() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

EmbreeBaseline::EmbreeBaseline(std::unique_ptr<State> state) : state_(std::move(state)) {}
EmbreeBaseline::~EmbreeBaseline() = default;

Expected<std::unique_ptr<EmbreeBaseline>> EmbreeBaseline::create() {
  auto state = std::make_unique<State>();
  state->device = rtcNewDevice(nullptr);
  if (!state->device)
    return make_error("cannot create an Embree device (is libembree3 installed?)");
  return std::unique_ptr<EmbreeBaseline>(new EmbreeBaseline(std::move(state)));
}

Expected<void> EmbreeBaseline::build(const Scene& scene, double& ms, Bvh bvh) {
  const auto start = Clock::now();
  State& s = *state_;
  if (s.scene) rtcReleaseScene(s.scene);
  s.scene = rtcNewScene(s.device);
  // A scene rebuilt each frame: Embree's documentation pairs the dynamic flag with low or
  // medium build quality; one kept: high quality, slower to build, faster to trace. Ray queries
  // stay coherent (packets) either way.
  const RTCBuildQuality quality =
      bvh == Bvh::rebuilt ? RTC_BUILD_QUALITY_MEDIUM : RTC_BUILD_QUALITY_HIGH;
  rtcSetSceneFlags(s.scene, bvh == Bvh::rebuilt ? RTC_SCENE_FLAG_DYNAMIC : RTC_SCENE_FLAG_NONE);
  rtcSetSceneBuildQuality(s.scene, quality);
  for (std::size_t o = 0; o < scene.objects.size(); ++o) {
    const SceneObject& object = scene.objects[o];
    const Mesh& mesh = *object.mesh;
    if (mesh.indices.empty()) continue;
    const glm::mat4 model = eye_relative(object.transform, scene.camera.position);
    RTCGeometry g = rtcNewGeometry(s.device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(g, quality);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.positions.size()));
    auto* i = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0,
                                                             RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                                             mesh.triangle_count()));
    if (!v || !i) {
      rtcReleaseGeometry(g);
      return make_error("Embree could not allocate the buffers of object " + object.name);
    }
    for (std::size_t p = 0; p < mesh.positions.size(); ++p) {
      const glm::vec3 q = glm::vec3(model * glm::vec4(mesh.positions[p], 1.0f));
      v[3 * p] = q.x, v[3 * p + 1] = q.y, v[3 * p + 2] = q.z;
    }
    std::copy(mesh.indices.begin(), mesh.indices.end(), i);
    rtcCommitGeometry(g);
    rtcAttachGeometry(s.scene, g);
    rtcReleaseGeometry(g);
  }
  rtcCommitScene(s.scene);
  if (const RTCError e = rtcGetDeviceError(s.device); e != RTC_ERROR_NONE)
    return make_error("Embree failed to build the scene (error " + std::to_string(int(e)) + ")");
  ms = ms_since(start);
  return {};
}

namespace {

// Shadow rays from up to eight points (valid where mask[k] = -1) to one light, eye-relative;
// returns how many are blocked.
int occluded8(RTCScene scene, const glm::vec3 (&from)[8], const int (&valid)[8],
              const glm::vec4& light) {
  alignas(32) RTCRay8 ray;
  alignas(32) int mask[8];
  const bool point = light.w != 0.0f;
  const glm::vec3 l = point ? glm::vec3(light) / light.w : glm::vec3(light);
  for (int k = 0; k < 8; ++k) {
    const glm::vec3 d = point ? l - from[k] : l;
    mask[k] = valid[k];
    ray.org_x[k] = from[k].x, ray.org_y[k] = from[k].y, ray.org_z[k] = from[k].z;
    ray.dir_x[k] = d.x, ray.dir_y[k] = d.y, ray.dir_z[k] = d.z;
    ray.tnear[k] = kShadowEpsilon;
    ray.tfar[k] = point ? 1.0f - kShadowEpsilon : std::numeric_limits<float>::infinity();
    ray.time[k] = 0.0f;
    ray.mask[k] = 0xffffffffu;
    ray.id[k] = 0;
    ray.flags[k] = 0;
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  rtcOccluded8(mask, scene, &context, &ray);
  int blocked = 0;
  for (int k = 0; k < 8; ++k) blocked += valid[k] && ray.tfar[k] < 0.0f;
  return blocked;
}

// Calls per_tile(x0, y0, x1, y1) over the image's 32 x 32 tiles, in parallel.
template <class PerTile>
void for_each_tile(int width, int height, PerTile&& per_tile) {
  tbb::parallel_for(
      tbb::blocked_range2d<int>(0, (height + kTile - 1) / kTile, 0, (width + kTile - 1) / kTile),
      [&](const tbb::blocked_range2d<int>& r) {
        for (int ty = r.rows().begin(); ty < r.rows().end(); ++ty)
          for (int tx = r.cols().begin(); tx < r.cols().end(); ++tx)
            per_tile(tx * kTile, ty * kTile, std::min(width, (tx + 1) * kTile),
                     std::min(height, (ty + 1) * kTile));
      });
}

// The direction of the ray through the centre of pixel (px, py), eye-relative, not normalized.
glm::vec3 pixel_ray(const glm::mat4& inv_view_proj, int px, int py, int width, int height) {
  const glm::vec4 on_near =
      inv_view_proj * glm::vec4((float(px) + 0.5f) / float(width) * 2.0f - 1.0f,
                                1.0f - (float(py) + 0.5f) / float(height) * 2.0f, 1.0f, 1.0f);
  return glm::vec3(on_near) / on_near.w;
}

glm::mat4 inverse_view_proj(const Camera& camera, int width, int height) {
  return glm::inverse(camera.projection(float(width) / float(height)) * camera.view_from_eye());
}

}  // namespace

void visible_points(const Scene& scene, int width, int height, std::span<const std::int32_t> object,
                    std::span<const std::uint32_t> face, std::vector<glm::vec4>& points) {
  const glm::mat4 inv_view_proj = inverse_view_proj(scene.camera, width, height);
  std::vector<glm::mat4> models;
  for (const SceneObject& o : scene.objects)
    models.push_back(eye_relative(o.transform, scene.camera.position));
  points.resize(static_cast<std::size_t>(width) * height);
  tbb::parallel_for(0, height, [&](int y) {
    for (int x = 0; x < width; ++x) {
      const std::size_t p = static_cast<std::size_t>(y) * width + x;
      points[p] = glm::vec4(0.0f);
      if (object[p] < 0) continue;
      const auto o = static_cast<std::size_t>(object[p]);
      const Mesh& mesh = *scene.objects[o].mesh;
      const std::uint32_t* v = &mesh.indices[3 * std::size_t{face[p]}];
      const glm::vec3 a(models[o] * glm::vec4(mesh.positions[v[0]], 1.0f));
      const glm::vec3 b(models[o] * glm::vec4(mesh.positions[v[1]], 1.0f));
      const glm::vec3 c(models[o] * glm::vec4(mesh.positions[v[2]], 1.0f));
      const glm::vec3 n = glm::cross(b - a, c - a);
      const glm::vec3 d = pixel_ray(inv_view_proj, x, y, width, height);
      const float along = glm::dot(n, d);
      if (along == 0.0f) continue;  // seen edge-on: no point to aim from
      points[p] = glm::vec4(d * (glm::dot(n, a) / along), 1.0f);
    }
  });
}

EmbreeFrame EmbreeBaseline::trace(const Scene& scene, int width, int height) {
  const State& s = *state_;
  EmbreeFrame out;
  const glm::mat4 inv_view_proj = inverse_view_proj(scene.camera, width, height);
  const float near = scene.camera.near;
  // Primary rays: each hit's point (w = 1) or none (w = 0), per pixel.
  std::vector<glm::vec4> points(static_cast<std::size_t>(width) * height);
  std::atomic<std::uint64_t> hits{0};
  auto start = Clock::now();
  for_each_tile(width, height, [&](int x0, int y0, int x1, int y1) {
    std::uint64_t tile_hits = 0;
    for (int y = y0; y < y1; y += kPacketH)
      for (int x = x0; x < x1; x += kPacketW) {
        alignas(32) RTCRayHit8 rh;
        alignas(32) int valid[8];
        for (int k = 0; k < 8; ++k) {
          const int px = x + k % kPacketW, py = y + k / kPacketW;
          valid[k] = px < x1 && py < y1 ? -1 : 0;
          const glm::vec3 d = glm::normalize(pixel_ray(inv_view_proj, px, py, width, height));
          rh.ray.org_x[k] = rh.ray.org_y[k] = rh.ray.org_z[k] = 0.0f;
          rh.ray.dir_x[k] = d.x, rh.ray.dir_y[k] = d.y, rh.ray.dir_z[k] = d.z;
          rh.ray.tnear[k] = near;
          rh.ray.tfar[k] = std::numeric_limits<float>::infinity();
          rh.ray.time[k] = 0.0f;
          rh.ray.mask[k] = 0xffffffffu;
          rh.ray.id[k] = static_cast<unsigned>(k);
          rh.ray.flags[k] = 0;
          rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
        }
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        rtcIntersect8(valid, s.scene, &context, &rh);
        for (int k = 0; k < 8; ++k) {
          const int px = x + k % kPacketW, py = y + k / kPacketW;
          if (!valid[k]) continue;
          const bool hit = rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
          tile_hits += hit;
          const float t = rh.ray.tfar[k];
          points[static_cast<std::size_t>(py) * width + px] =
              hit ? glm::vec4(rh.ray.dir_x[k] * t, rh.ray.dir_y[k] * t, rh.ray.dir_z[k] * t, 1.0f)
                  : glm::vec4(0.0f);
        }
      }
    hits += tile_hits;
  });
  out.ms_primary = ms_since(start);
  out.hits = hits;
  out.ms_shadow = shadow_rays(scene, points, out.shadowed);
  return out;
}

double EmbreeBaseline::shadow_rays(const Scene& scene, std::span<const glm::vec4> points,
                                   std::uint64_t& shadowed) {
  const State& s = *state_;
  std::vector<glm::vec4> lights;
  for (const SceneLight& light : scene.lights)
    lights.push_back(eye_relative(light.position, scene.camera.position));
  std::atomic<std::uint64_t> blocked{0};
  const auto start = Clock::now();
  // Points in runs of 8 (their pixel order keeps packets coherent), runs spread over threads.
  const std::size_t runs = (points.size() + 7) / 8;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, runs, 64),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      std::uint64_t n = 0;
                      for (std::size_t run = r.begin(); run < r.end(); ++run) {
                        glm::vec3 from[8];
                        int valid[8];
                        bool any = false;
                        for (int k = 0; k < 8; ++k) {
                          const std::size_t p = 8 * run + static_cast<std::size_t>(k);
                          valid[k] = p < points.size() && points[p].w != 0.0f ? -1 : 0;
                          from[k] = valid[k] ? glm::vec3(points[p]) : glm::vec3(0.0f);
                          any = any || valid[k];
                        }
                        if (!any) continue;
                        for (const glm::vec4& light : lights)
                          n += static_cast<std::uint64_t>(occluded8(s.scene, from, valid, light));
                      }
                      blocked += n;
                    });
  shadowed = blocked;
  return ms_since(start);
}

}  // namespace shadowvol
