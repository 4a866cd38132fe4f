#include "trace/reference.h"

#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include <embree3/rtcore.h>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

namespace shadowvol {
namespace {

struct DeviceDeleter {
  void operator()(RTCDevice d) const { rtcReleaseDevice(d); }
};
struct SceneDeleter {
  void operator()(RTCScene s) const { rtcReleaseScene(s); }
};
using Device = std::unique_ptr<RTCDeviceTy, DeviceDeleter>;
using EmbreeScene = std::unique_ptr<RTCSceneTy, SceneDeleter>;

std::string device_error(RTCDevice device) {
  const RTCError e = rtcGetDeviceError(device);
  return e == RTC_ERROR_NONE ? "" : "Embree error " + std::to_string(static_cast<int>(e));
}

// Eye-relative triangles of the scene (world minus the eye, in double: DESIGN.md "Numerics"),
// one Embree geometry per object (geometry id = object index).
Expected<EmbreeScene> build(RTCDevice device, const Scene& scene) {
  EmbreeScene es(rtcNewScene(device));
  rtcSetSceneFlags(es.get(), RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(es.get(), RTC_BUILD_QUALITY_HIGH);
  for (std::size_t o = 0; o < scene.objects.size(); ++o) {
    const SceneObject& object = scene.objects[o];
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0,
                                                          RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                          object.mesh->positions.size()));
    auto* i = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0,
                                                             RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                                             object.mesh->triangle_count()));
    if (v == nullptr || i == nullptr) {
      rtcReleaseGeometry(g);
      return make_error("Embree could not allocate the buffers of object '" + object.name + "'");
    }
    const glm::dmat4 model = glm::translate(glm::dmat4(1.0), -glm::dvec3(scene.camera.position)) *
                             glm::dmat4(object.transform);
    for (std::size_t k = 0; k < object.mesh->positions.size(); ++k) {
      const glm::vec3 p(model * glm::dvec4(glm::dvec3(object.mesh->positions[k]), 1.0));
      v[3 * k] = p.x, v[3 * k + 1] = p.y, v[3 * k + 2] = p.z;
    }
    for (std::size_t k = 0; k < object.mesh->indices.size(); ++k) i[k] = object.mesh->indices[k];
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(es.get(), g, static_cast<unsigned>(o));
    rtcReleaseGeometry(g);
  }
  rtcCommitScene(es.get());
  if (std::string e = device_error(device); !e.empty())
    return make_error(e + " while building the scene");
  return es;
}

}  // namespace

struct ReferenceTracer::State {
  Device device;
  EmbreeScene scene;
  int width = 0, height = 0;
  glm::dmat4 inv_view_proj{1.0};
  float near = 0.0f;
  std::vector<glm::dvec4> lights;  // eye-relative
};

ReferenceTracer::ReferenceTracer(std::unique_ptr<State> state) : state_(std::move(state)) {}
ReferenceTracer::~ReferenceTracer() = default;

Expected<std::shared_ptr<const ReferenceTracer>> ReferenceTracer::create(const Scene& scene,
                                                                         int width, int height) {
  auto state = std::make_unique<State>();
  state->device.reset(rtcNewDevice(nullptr));
  if (!state->device)
    return make_error("cannot create an Embree device (is libembree3 installed?)");
  auto built = build(state->device.get(), scene);
  if (!built) return built.error();
  state->scene = std::move(*built);
  state->width = width, state->height = height;
  state->inv_view_proj =
      glm::inverse(glm::dmat4(scene.camera.projection(float(width) / float(height))) *
                   glm::dmat4(scene.camera.view_from_eye()));
  state->near = scene.camera.near;
  for (const SceneLight& light : scene.lights)
    state->lights.emplace_back(eye_relative(light.position, scene.camera.position));
  return std::shared_ptr<const ReferenceTracer>(new ReferenceTracer(std::move(state)));
}

ReferenceSample ReferenceTracer::sample(double x, double y) const {
  const State& s = *state_;
  ReferenceSample out;
  out.faces_light.assign(s.lights.size(), 0);
  out.shadowed.assign(s.lights.size(), 0);
  // The ray through NDC (x / w * 2 - 1, 1 - y / h * 2), from the eye (eye-relative space: the
  // origin) through that point of the near plane (depth 1).
  const glm::dvec4 on_near = s.inv_view_proj * glm::dvec4(x / s.width * 2.0 - 1.0,
                                                          1.0 - y / s.height * 2.0, 1.0, 1.0);
  const glm::dvec3 dir = glm::normalize(glm::dvec3(on_near) / on_near.w);
  if (!std::isfinite(dir.x) || !std::isfinite(dir.y) || !std::isfinite(dir.z)) return out;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit hit{};
  hit.ray.dir_x = float(dir.x), hit.ray.dir_y = float(dir.y), hit.ray.dir_z = float(dir.z);
  hit.ray.tnear = s.near;
  hit.ray.tfar = std::numeric_limits<float>::infinity();
  hit.ray.mask = 0xffffffffu;
  hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(s.scene.get(), &context, &hit);
  if (hit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return out;
  out.object = static_cast<std::int32_t>(hit.hit.geomID);
  out.face = hit.hit.primID;
  const glm::dvec3 pos = dir * double(hit.ray.tfar);
  glm::dvec3 n = glm::normalize(glm::dvec3(hit.hit.Ng_x, hit.hit.Ng_y, hit.hit.Ng_z));
  if (glm::dot(n, dir) > 0.0) n = -n;  // the side the eye sees
  for (std::size_t l = 0; l < s.lights.size(); ++l) {
    const glm::dvec4& light = s.lights[l];
    const glm::dvec3 to_light =
        light.w != 0.0 ? glm::dvec3(light) / light.w - pos : glm::dvec3(light);
    const double distance =
        light.w != 0.0 ? glm::length(to_light) : std::numeric_limits<double>::infinity();
    const glm::dvec3 d = glm::normalize(to_light);
    if (glm::dot(n, d) <= 0.0) continue;  // faces away: not compared
    out.faces_light[l] = 1;
    // Start a hair off the surface, towards the light's side, to leave its own triangle.
    const double scale = std::max(1.0, glm::length(pos));
    const glm::dvec3 origin = pos + n * (1e-5 * scale);
    RTCRay shadow{};
    shadow.org_x = float(origin.x), shadow.org_y = float(origin.y), shadow.org_z = float(origin.z);
    shadow.dir_x = float(d.x), shadow.dir_y = float(d.y), shadow.dir_z = float(d.z);
    shadow.tnear = 0.0f;
    shadow.tfar = std::isinf(distance) ? std::numeric_limits<float>::infinity() : float(distance);
    shadow.mask = 0xffffffffu;
    rtcOccluded1(s.scene.get(), &context, &shadow);
    out.shadowed[l] = shadow.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
  }
  return out;
}

std::string ReferenceTracer::error() const { return device_error(state_->device.get()); }

Expected<ReferenceFrame> trace_reference(const Scene& scene, int width, int height) {
  auto tracer = ReferenceTracer::create(scene, width, height);
  if (!tracer) return tracer.error();
  ReferenceFrame ref;
  ref.width = width, ref.height = height;
  const std::size_t pixels = static_cast<std::size_t>(width) * height;
  ref.object.assign(pixels, -1);
  ref.face.assign(pixels, 0);
  ref.faces_light.assign(scene.lights.size(), std::vector<std::uint8_t>(pixels, 0));
  ref.shadowed.assign(scene.lights.size(), std::vector<std::uint8_t>(pixels, 0));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t p = static_cast<std::size_t>(y) * width + x;
      const ReferenceSample s = (*tracer)->sample(x + 0.5, y + 0.5);
      ref.object[p] = s.object;
      ref.face[p] = s.face;
      for (std::size_t l = 0; l < scene.lights.size(); ++l) {
        ref.faces_light[l][p] = s.faces_light[l];
        ref.shadowed[l][p] = s.shadowed[l];
      }
    }
  if (std::string e = (*tracer)->error(); !e.empty())
    return make_error(e + " while tracing");
  ref.tracer = std::move(*tracer);
  return ref;
}

}  // namespace shadowvol
