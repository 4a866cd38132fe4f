#include "trace/reference.h"

#include <algorithm>
#include <cmath>
#include <compare>
#include <limits>
#include <memory>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
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
  const bool filtered = has_transparent_casters(scene) ||
                        std::any_of(scene.objects.begin(), scene.objects.end(),
                                    [](const SceneObject& o) { return !o.casts_shadows; });
  rtcSetSceneFlags(es.get(), filtered
                                 ? RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION
                                 : RTC_SCENE_FLAG_ROBUST);
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

// The hits a ray's filter saw on transparent geometry. The context comes first, so that the
// filter, which Embree hands the context, can find the rest (Embree's documented idiom).
struct GlassContext {
  RTCIntersectContext context;
  const std::vector<std::uint8_t>* transparent;  // per geometry (object)
  // Per geometry, whether the ray passes through it unseen (a shadow ray, objects that cast no
  // shadows); or null.
  const std::vector<std::uint8_t>* ignored = nullptr;
  struct Hit {
    unsigned geometry, primitive;
    float t;
    glm::vec3 normal;
    auto operator<=>(const Hit& o) const {
      return std::tie(geometry, primitive) <=> std::tie(o.geometry, o.primitive);
    }
    bool operator==(const Hit& o) const {
      return geometry == o.geometry && primitive == o.primitive;
    }
  };
  std::vector<Hit> hits;
};

// Rejects every candidate hit on an ignored geometry; records every one on a transparent
// geometry and rejects it, so that the ray goes on; hits on opaque geometry are kept as Embree
// found them.
void see_through_glass(const RTCFilterFunctionNArguments* args) {
  auto* glass = reinterpret_cast<GlassContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const unsigned geometry = RTCHitN_geomID(args->hit, args->N, i);
    if (glass->ignored != nullptr && (*glass->ignored)[geometry]) {
      args->valid[i] = 0;
      continue;
    }
    if (!(*glass->transparent)[geometry]) continue;
    glass->hits.push_back(
        {geometry,
         RTCHitN_primID(args->hit, args->N, i),
         RTCRayN_tfar(args->ray, args->N, i),
         {RTCHitN_Ng_x(args->hit, args->N, i), RTCHitN_Ng_y(args->hit, args->N, i),
          RTCHitN_Ng_z(args->hit, args->N, i)}});
    args->valid[i] = 0;
  }
}

}  // namespace

struct ReferenceTracer::State {
  Device device;
  EmbreeScene scene;
  int width = 0, height = 0;
  glm::dmat4 inv_view_proj{1.0};
  float near = 0.0f;
  std::vector<glm::dvec4> lights;         // eye-relative
  std::vector<double> ranges;             // per light: SceneLight::range (infinite: none)
  bool glass = false;                     // any transparent caster
  bool filtered = false;                  // a filter is needed: glass, or objects not casting
  std::vector<std::uint8_t> transparent;  // per object
  std::vector<std::uint8_t> none_transparent;  // per object, all 0: every caster blocks
  std::vector<std::uint8_t> not_casting, not_receiving;  // per object
  std::vector<glm::dvec3> transmittance;                 // per object
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
  for (const SceneLight& light : scene.lights) {
    state->lights.emplace_back(eye_relative(light.position, scene.camera.position));
    state->ranges.push_back(light.limited() ? double(light.range) : INFINITY);
  }
  state->glass = has_transparent_casters(scene);
  for (const SceneObject& object : scene.objects) {
    state->not_casting.push_back(!object.casts_shadows);
    state->not_receiving.push_back(!object.receives_shadows);
    state->filtered = state->filtered || !object.casts_shadows;
    state->transparent.push_back(object.material.transparent());
    state->none_transparent.push_back(0);
    state->transmittance.emplace_back(object.material.transmittance());
  }
  return std::shared_ptr<const ReferenceTracer>(new ReferenceTracer(std::move(state)));
}

namespace {

// The ray through window point (x, y): through NDC (x / w * 2 - 1, 1 - y / h * 2), from the eye
// (eye-relative space: the origin) through that point of the near plane (depth 1); unit length.
glm::dvec3 ray_direction(const glm::dmat4& inv_view_proj, int width, int height, double x,
                         double y) {
  const glm::dvec4 on_near =
      inv_view_proj * glm::dvec4(x / width * 2.0 - 1.0, 1.0 - y / height * 2.0, 1.0, 1.0);
  return glm::normalize(glm::dvec3(on_near) / on_near.w);
}

// A shadow ray from `origin` along the unit d towards a light `distance` from `pos`: up to a hair
// short of a point light, so that a surface through the light itself (a lamp on a table) shadows
// only where rays cross it beyond the light (docs/volumes.md, "A light on a surface"); the hair is
// many float steps of the coordinates involved.
RTCRay shadow_ray(const glm::dvec3& origin, const glm::dvec3& pos, const glm::dvec3& d,
                  double distance) {
  RTCRay shadow{};
  shadow.org_x = float(origin.x), shadow.org_y = float(origin.y), shadow.org_z = float(origin.z);
  shadow.dir_x = float(d.x), shadow.dir_y = float(d.y), shadow.dir_z = float(d.z);
  shadow.tnear = 0.0f;
  shadow.tfar = std::isinf(distance) ? std::numeric_limits<float>::infinity()
                                     : float(distance - 1e-6 * (glm::length(pos) + distance));
  shadow.mask = 0xffffffffu;
  return shadow;
}

}  // namespace

bool triangle_nearer_within(const glm::dvec3 (&c)[3], double x, double y, double distance,
                            const std::function<glm::dvec3(const glm::dvec3&)>& to_window,
                            const std::function<glm::dvec3(double, double)>& ray) {
  const glm::dvec3 n = glm::cross(c[1] - c[0], c[2] - c[0]);
  if (!(glm::dot(n, n) > 0.0)) return false;
  // Where the ray through window point (wx, wy) meets the triangle's plane: nearer than distance?
  const auto nearer_at = [&](double wx, double wy) {
    const glm::dvec3 dir = ray(wx, wy);
    const double across = glm::dot(n, dir);
    if (across == 0.0) return false;
    const double t = glm::dot(n, c[0]) / across;
    return t > 0.0 && t < distance;
  };
  // The triangle in the window, cut to the square; 1 / depth is affine over a plane's projection,
  // so the nearest point of what is left is one of its corners.
  std::vector<glm::dvec2> poly;
  for (const glm::dvec3& corner : c) {
    const glm::dvec3 w = to_window(corner);
    if (!(w.z > 0.0)) return false;  // reaches behind the eye: taken as not in the pixel
    poly.emplace_back(w.x, w.y);
  }
  const double bounds[4] = {x - 1.0, x + 1.0, y - 1.0, y + 1.0};
  for (int side = 0; side < 4 && !poly.empty(); ++side) {
    const int axis = side / 2;
    const double limit = bounds[side], sign = side % 2 == 0 ? 1.0 : -1.0;  // keep sign*(p-limit)>=0
    std::vector<glm::dvec2> kept;
    for (std::size_t k = 0; k < poly.size(); ++k) {
      const glm::dvec2 a = poly[k], b = poly[(k + 1) % poly.size()];
      const double da = sign * (a[axis] - limit), db = sign * (b[axis] - limit);
      if (da >= 0.0) kept.push_back(a);
      if ((da >= 0.0) != (db >= 0.0)) kept.push_back(a + (b - a) * (da / (da - db)));
    }
    poly = std::move(kept);
  }
  for (const glm::dvec2& p : poly)
    if (nearer_at(p.x, p.y)) return true;
  return false;
}

namespace {

// The eye-relative corners of face `face` (one the scene has) of geometry `object`; false where
// there is no such geometry.
bool face_corners(RTCScene scene, std::int32_t object, std::uint32_t face, glm::dvec3 (&c)[3]) {
  if (object < 0) return false;
  RTCGeometry g = rtcGetGeometry(scene, static_cast<unsigned>(object));
  if (g == nullptr) return false;
  const auto* v = static_cast<const float*>(rtcGetGeometryBufferData(g, RTC_BUFFER_TYPE_VERTEX, 0));
  const auto* i =
      static_cast<const unsigned*>(rtcGetGeometryBufferData(g, RTC_BUFFER_TYPE_INDEX, 0));
  if (v == nullptr || i == nullptr) return false;
  for (int k = 0; k < 3; ++k) {
    const float* p = v + 3 * std::size_t{i[3 * std::size_t{face} + k]};
    c[k] = {p[0], p[1], p[2]};
  }
  return true;
}

// The direction from `pos` to a light and its distance (infinite for a directional light).
std::pair<glm::dvec3, double> toward(const glm::dvec4& light, const glm::dvec3& pos) {
  if (light.w == 0.0)
    return {glm::normalize(glm::dvec3(light)), std::numeric_limits<double>::infinity()};
  const glm::dvec3 to_light = glm::dvec3(light) / light.w - pos;
  return {glm::normalize(to_light), glm::length(to_light)};
}

}  // namespace

bool ReferenceTracer::face_nearer_within(double x, double y, std::int32_t object,
                                         std::uint32_t face, double distance) const {
  const State& s = *state_;
  glm::dvec3 c[3];
  if (!face_corners(s.scene.get(), object, face, c)) return false;
  const glm::dmat4 view_proj = glm::inverse(s.inv_view_proj);
  return triangle_nearer_within(
      c, x, y, distance,
      [&](const glm::dvec3& p) {
        const glm::dvec4 clip = view_proj * glm::dvec4(p, 1.0);
        return glm::dvec3((clip.x / clip.w + 1.0) * 0.5 * s.width,
                          (1.0 - clip.y / clip.w) * 0.5 * s.height, clip.w);
      },
      [&](double wx, double wy) { return ray_direction(s.inv_view_proj, s.width, s.height, wx, wy); });
}

ReferenceSurface ReferenceTracer::on_face_plane(double x, double y, std::int32_t object,
                                                std::uint32_t face) const {
  const State& s = *state_;
  ReferenceSurface out;
  out.distance = std::numeric_limits<double>::infinity();
  glm::dvec3 c[3];
  if (!face_corners(s.scene.get(), object, face, c)) return out;
  const glm::dvec3 dir = ray_direction(s.inv_view_proj, s.width, s.height, x, y);
  glm::dvec3 n = glm::normalize(glm::cross(c[1] - c[0], c[2] - c[0]));
  const double t = glm::dot(n, c[0]) / glm::dot(n, dir);
  if (!(t >= double(s.near) && std::isfinite(t))) return out;
  if (glm::dot(n, dir) > 0.0) n = -n;  // the side the eye sees
  out.object = object, out.face = face, out.distance = t;
  light_surface(dir * t, n, out);
  return out;
}

std::vector<std::uint8_t> ReferenceTracer::near_plane_shadowed(double x, double y) const {
  const State& s = *state_;
  std::vector<std::uint8_t> out(s.lights.size(), 0);
  const glm::dvec4 on_near =
      s.inv_view_proj * glm::dvec4(x / s.width * 2.0 - 1.0, 1.0 - y / s.height * 2.0, 1.0, 1.0);
  const glm::dvec3 pos = glm::dvec3(on_near) / on_near.w;
  for (std::size_t l = 0; l < s.lights.size(); ++l) {
    const auto [d, distance] = toward(s.lights[l], pos);
    RTCRay shadow = shadow_ray(pos, pos, d, distance);
    // Transparent casters shadow here too: any caster's volume counts.
    GlassContext context{{}, &s.none_transparent, &s.not_casting, {}};
    rtcInitIntersectContext(&context.context);
    if (s.filtered) context.context.filter = see_through_glass;
    rtcOccluded1(s.scene.get(), &context.context, &shadow);
    out[l] = shadow.tfar < 0.0f;
  }
  return out;
}

// Light at the point `pos` of a surface with normal n (turned towards the eye), per light:
// whether the surface faces it, whether an opaque surface blocks it, and (with transparent
// casters) the product of the transmittances of the transparent surfaces on the way.
// A surface of an object that receives no shadows gets every light that reaches it; one beyond
// a light's range gets none of it (not compared, as a surface facing away).
void ReferenceTracer::light_surface(const glm::dvec3& pos, const glm::dvec3& n,
                                    ReferenceSurface& out) const {
  const State& s = *state_;
  const bool receives = !s.not_receiving[static_cast<std::size_t>(out.object)];
  const std::size_t lights = s.lights.size();
  out.faces_light.assign(lights, 0);
  out.shadowed.assign(lights, 0);
  out.grazing.assign(lights, 0);
  out.transmitted.assign(s.glass ? lights : 0, glm::vec3(0.0f));
  for (std::size_t l = 0; l < lights; ++l) {
    const auto [d, distance] = toward(s.lights[l], pos);
    const double cosine = glm::dot(n, d);
    out.grazing[l] = std::abs(cosine) < kGrazingCosine;
    if (cosine <= 0.0) continue;  // faces away: not compared
    if (std::isfinite(s.ranges[l]) && !(distance < s.ranges[l])) continue;  // beyond the range
    out.faces_light[l] = 1;
    if (!receives) {
      if (s.glass) out.transmitted[l] = glm::vec3(1.0f);
      continue;
    }
    // Start a hair off the surface, towards the light's side, to leave its own triangle: a
    // hair of its distance from the eye, far above float's steps there and, whatever the
    // scene's scale, far below its features (DESIGN.md "Numerics").
    RTCRay shadow = shadow_ray(pos + n * (1e-5 * glm::length(pos)), pos, d, distance);
    GlassContext context{{}, &s.transparent, &s.not_casting, {}};
    rtcInitIntersectContext(&context.context);
    if (s.glass || s.filtered) context.context.filter = see_through_glass;
    rtcOccluded1(s.scene.get(), &context.context, &shadow);
    out.shadowed[l] = shadow.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
    if (!s.glass || out.shadowed[l]) continue;
    // Each surface once: a filter may see one triangle more than once (spatial splits).
    std::sort(context.hits.begin(), context.hits.end());
    context.hits.erase(std::unique(context.hits.begin(), context.hits.end()), context.hits.end());
    glm::dvec3 passed(1.0);
    for (const GlassContext::Hit& hit : context.hits) passed *= s.transmittance[hit.geometry];
    out.transmitted[l] = glm::vec3(passed);
  }
}

ReferenceSample ReferenceTracer::sample(double x, double y) const {
  const State& s = *state_;
  ReferenceSample out;
  const std::size_t lights = s.lights.size();
  out.distance = std::numeric_limits<double>::infinity();
  out.glass.distance = out.distance;
  out.faces_light.assign(lights, 0);
  out.shadowed.assign(lights, 0);
  out.grazing.assign(lights, 0);
  out.transmitted.assign(s.glass ? lights : 0, glm::vec3(0.0f));
  const glm::dvec3 dir = ray_direction(s.inv_view_proj, s.width, s.height, x, y);
  if (!std::isfinite(dir.x) || !std::isfinite(dir.y) || !std::isfinite(dir.z)) return out;
  GlassContext context{{}, &s.transparent, nullptr, {}};
  rtcInitIntersectContext(&context.context);
  if (s.glass) context.context.filter = see_through_glass;
  RTCRayHit hit{};
  hit.ray.dir_x = float(dir.x), hit.ray.dir_y = float(dir.y), hit.ray.dir_z = float(dir.z);
  hit.ray.tnear = s.near;
  hit.ray.tfar = std::numeric_limits<float>::infinity();
  hit.ray.mask = 0xffffffffu;
  hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(s.scene.get(), &context.context, &hit);
  // A surface at distance t along the ray, with geometric normal ng.
  auto surface = [&](unsigned geometry, unsigned primitive, float t, const glm::vec3& ng,
                     ReferenceSurface& layer) {
    layer.object = static_cast<std::int32_t>(geometry);
    layer.face = primitive;
    layer.distance = double(t);
    const glm::dvec3 pos = dir * double(t);
    glm::dvec3 n = glm::normalize(glm::dvec3(ng));
    if (glm::dot(n, dir) > 0.0) n = -n;  // the side the eye sees
    light_surface(pos, n, layer);
  };
  if (hit.hit.geomID != RTC_INVALID_GEOMETRY_ID)
    surface(hit.hit.geomID, hit.hit.primID, hit.ray.tfar,
            {hit.hit.Ng_x, hit.hit.Ng_y, hit.hit.Ng_z}, out);
  if (s.glass) {
    out.glass.faces_light.assign(lights, 0);
    out.glass.shadowed.assign(lights, 0);
    out.glass.grazing.assign(lights, 0);
    out.glass.transmitted.assign(lights, glm::vec3(0.0f));
    // The nearest transparent hit in front of the opaque one (ties: the lower ids, as the
    // rasterizer's first-drawn-wins depth test keeps the first of equal depths).
    const GlassContext::Hit* nearest = nullptr;
    for (const GlassContext::Hit& h : context.hits)
      if (h.t < hit.ray.tfar &&
          (nearest == nullptr || h.t < nearest->t || (h.t == nearest->t && h < *nearest)))
        nearest = &h;
    if (nearest != nullptr)
      surface(nearest->geometry, nearest->primitive, nearest->t, nearest->normal, out.glass);
  }
  return out;
}

std::string ReferenceTracer::error() const { return device_error(state_->device.get()); }

Expected<ReferenceFrame> trace_reference(const Scene& scene, int width, int height,
                                         const Progress& progress) {
  if (progress) progress("building the reference's BVH (Embree)", 0.0f);
  auto tracer = ReferenceTracer::create(scene, width, height);
  if (!tracer) return tracer.error();
  return trace_frame(std::move(*tracer), width, height, scene.lights.size(),
                     has_transparent_casters(scene), progress);
}

Expected<ReferenceFrame> trace_frame(std::shared_ptr<const ReferenceSampler> sampler, int width,
                                     int height, std::size_t lights, bool glass,
                                     const Progress& progress) {
  ReferenceFrame ref;
  ref.width = width, ref.height = height;
  const std::size_t pixels = static_cast<std::size_t>(width) * height;
  auto size = [&](ReferenceLayer& layer) {
    layer.object.assign(pixels, -1);
    layer.face.assign(pixels, 0);
    layer.faces_light.assign(lights, std::vector<std::uint8_t>(pixels, 0));
    layer.shadowed.assign(lights, std::vector<std::uint8_t>(pixels, 0));
    layer.grazing.assign(lights, std::vector<std::uint8_t>(pixels, 0));
    layer.transmitted.assign(glass ? lights : 0, std::vector<glm::vec3>(pixels));
  };
  auto put = [&](ReferenceLayer& layer, std::size_t p, const ReferenceSurface& s) {
    layer.object[p] = s.object;
    layer.face[p] = s.face;
    for (std::size_t l = 0; l < lights; ++l) {
      layer.faces_light[l][p] = s.faces_light[l];
      layer.shadowed[l][p] = s.shadowed[l];
      layer.grazing[l][p] = s.grazing[l];
      if (glass) layer.transmitted[l][p] = s.transmitted[l];
    }
  };
  size(ref);
  if (glass) size(ref.glass);
  ref.near_plane_shadowed.assign(lights, std::vector<std::uint8_t>(pixels, 0));
  // Rows in parallel, a slice of them at a time so that progress is said between slices.
  const int slice = std::max(1, height / 64);
  for (int y0 = 0; y0 < height; y0 += slice) {
    if (progress) progress("tracing the reference", float(y0) / float(height));
    tbb::parallel_for(tbb::blocked_range<int>(y0, std::min(height, y0 + slice)),
                      [&](const tbb::blocked_range<int>& rows) {
                        for (int y = rows.begin(); y < rows.end(); ++y)
                          for (int x = 0; x < width; ++x) {
                            const std::size_t p = static_cast<std::size_t>(y) * width + x;
                            const ReferenceSample s = sampler->sample(x + 0.5, y + 0.5);
                            put(ref, p, s);
                            if (glass) put(ref.glass, p, s.glass);
                            const std::vector<std::uint8_t> near =
                                sampler->near_plane_shadowed(x + 0.5, y + 0.5);
                            for (std::size_t l = 0; l < lights; ++l)
                              ref.near_plane_shadowed[l][p] = near[l];
                          }
                      });
  }
  if (progress) progress("tracing the reference", 1.0f);
  if (std::string e = sampler->error(); !e.empty()) return make_error(e + " while tracing");
  ref.tracer = std::move(sampler);
  return ref;
}

}  // namespace shadowvol
