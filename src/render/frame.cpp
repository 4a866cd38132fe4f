#include "render/frame.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <limits>

#include <string>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include "core/names.h"
#include "raster/raster.h"

namespace shadowvol {
std::string_view to_string(Method method) {
  switch (method) {
    case Method::zpass:
      return "zpass";
    case Method::zfail:
      return "zfail";
    case Method::automatic:
      return "auto";
    case Method::split_plane:
      return "spsv";
    case Method::zpass_prefill:
      return "zp+db";
  }
  return "unknown";
}

Expected<Method> parse_method(std::string_view name) {
  return parse_name(
      name,
      {Method::zpass, Method::zfail, Method::automatic, Method::split_plane, Method::zpass_prefill},
      "method");
}

std::string_view to_string(Extrusion extrusion) {
  return extrusion == Extrusion::infinite ? "infinite" : "bounded";
}

Expected<Extrusion> parse_extrusion(std::string_view name) {
  return parse_name(name, {Extrusion::infinite, Extrusion::bounded}, "extrusion");
}

std::string_view to_string(Cull cull) {
  return cull == Cull::none ? "none" : cull == Cull::frustum ? "frustum" : "occlusion";
}

Expected<Cull> parse_cull(std::string_view name) {
  return parse_name(name, {Cull::none, Cull::frustum, Cull::occlusion}, "culling");
}

std::string_view to_string(Occlusion occlusion) {
  switch (occlusion) {
    case Occlusion::none:
      return "none";
    case Occlusion::eye:
      return "eye";
    case Occlusion::shadows:
      return "shadows";
    case Occlusion::both:
      return "both";
  }
  return "unknown";
}

Expected<Occlusion> parse_occlusion(std::string_view name) {
  return parse_name(name, {Occlusion::none, Occlusion::eye, Occlusion::shadows, Occlusion::both},
                    "occlusion culling");
}

std::string_view to_string(Clamp clamp) {
  switch (clamp) {
    case Clamp::none:
      return "none";
    case Clamp::continuous:
      return "continuous";
    case Clamp::discrete:
      return "discrete";
    case Clamp::both:
      return "both";
  }
  return "unknown";
}

Expected<Clamp> parse_clamp(std::string_view name) {
  return parse_name(name, {Clamp::none, Clamp::continuous, Clamp::discrete, Clamp::both},
                    "clamping");
}

Expected<void> check_slices(int slices) {
  if (slices < 1 || slices > kMaxSlices)
    return make_error(std::to_string(slices) + " is outside 1 .. " + std::to_string(kMaxSlices));
  return {};
}

std::string_view to_string(SplitPlanes planes) {
  return planes == SplitPlanes::laine ? "laine" : "sampled";
}

Expected<SplitPlanes> parse_split_planes(std::string_view name) {
  return parse_name(name, {SplitPlanes::laine, SplitPlanes::sampled}, "split-plane construction");
}

std::string_view to_string(SplitParts parts) {
  return parts == SplitParts::each ? "each" : "whole";
}

Expected<SplitParts> parse_split_parts(std::string_view name) {
  return parse_name(name, {SplitParts::each, SplitParts::whole}, "split-plane decomposition");
}

Expected<void> check_options(const RenderOptions& options) {
  if (options.width < 1 || options.height < 1 || options.width > raster::kMaxViewport ||
      options.height > raster::kMaxViewport)
    return make_error("image size " + std::to_string(options.width) + "x" +
                      std::to_string(options.height) + " is outside 1x1 .. " +
                      std::to_string(raster::kMaxViewport) + "x" +
                      std::to_string(raster::kMaxViewport));
  if (auto ok = check_light_view_size(options.light_view_size); !ok)
    return make_error("light view size " + ok.error().message);
  if (auto ok = check_slices(options.slices); !ok)
    return make_error("slices: " + ok.error().message);
  return {};
}

Expected<void> check_light_view_size(int size) {
  if (size < kMinLightView || size > kMaxLightView)
    return make_error(std::to_string(size) + " is outside " + std::to_string(kMinLightView) +
                      " .. " + std::to_string(kMaxLightView));
  return {};
}

namespace {

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", x);
  return text;
}

// A view the camera can be made into: finite, a direction to look in and an up that is not it.
Expected<void> check_camera(const Camera& c) {
  for (const glm::vec3& v : {c.position, c.target, c.up})
    for (int i = 0; i < 3; ++i)
      if (!std::isfinite(v[i])) return make_error("the camera has a coordinate that is not finite");
  const glm::dvec3 forward = glm::dvec3(c.target) - glm::dvec3(c.position), up(c.up);
  if (glm::length(forward) == 0.0)
    return make_error("the camera's target is its position: it looks nowhere");
  if (glm::length(up) == 0.0) return make_error("the camera's up is [0, 0, 0]: no direction");
  if (glm::length(glm::cross(glm::normalize(forward), glm::normalize(up))) < 1e-6)
    return make_error(
        "the camera's up lies along its view direction, so it says nothing of "
        "which way is up");
  if (!(c.fov_y_degrees > 0.0f && c.fov_y_degrees < 180.0f))
    return make_error("the camera's fov " + number(c.fov_y_degrees) +
                      " degrees is outside (0, 180)");
  if (!(c.near > 0.0f) || !std::isfinite(c.near))
    return make_error("the camera's near distance " + number(c.near) + " is not positive");
  return {};
}

// What every stage can draw exactly (float rasterizers, Embree's float rays), docs/verification.md
// "The range drawn exactly": world coordinates within kMaxWorldCoordinate, and every object within
// kMaxDepthRange near distances of the eye.
Expected<void> check_extent(const Scene& scene) {
  const glm::dvec3 eye(scene.camera.position);
  for (const glm::vec3& p : {scene.camera.position, scene.camera.target})
    if (glm::length(glm::dvec3(p)) > kMaxWorldCoordinate)
      return make_error("the camera lies " + number(glm::length(glm::dvec3(p))) +
                        " from the origin, beyond the " + number(kMaxWorldCoordinate) +
                        " drawn exactly");
  for (const SceneLight& light : scene.lights)
    if (light.position.w != 0.0f && glm::length(glm::dvec3(light.position)) > kMaxWorldCoordinate)
      return make_error("a light lies " + number(glm::length(glm::dvec3(light.position))) +
                        " from the origin, beyond the " + number(kMaxWorldCoordinate) +
                        " drawn exactly");
  const double most = kMaxDepthRange * double(scene.camera.near);
  for (const SceneObject& object : scene.objects) {
    if (!object.mesh || object.mesh->positions.empty()) continue;
    glm::vec3 lo(std::numeric_limits<float>::infinity()), hi(-lo);
    for (const glm::vec3& p : object.mesh->positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    double origin = 0.0, from_eye = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
      const glm::dvec3 q(glm::dmat4(object.transform) * glm::dvec4(corner & 1 ? hi.x : lo.x,
                                                                   corner & 2 ? hi.y : lo.y,
                                                                   corner & 4 ? hi.z : lo.z, 1.0));
      origin = std::max(origin, glm::length(q));
      from_eye = std::max(from_eye, glm::length(q - eye));
    }
    if (!std::isfinite(origin) || origin > kMaxWorldCoordinate)
      return make_error("object '" + object.name + "' reaches " + number(origin) +
                        " from the origin, beyond the " + number(kMaxWorldCoordinate) +
                        " drawn exactly (Embree's rays and float vertices lose it)");
    if (from_eye > most)
      return make_error("object '" + object.name + "' reaches " + number(from_eye) +
                        " from the eye, " + number(from_eye / scene.camera.near) +
                        " times the camera's near distance (" + number(scene.camera.near) +
                        "); shadows are exact within " + number(kMaxDepthRange) +
                        " near distances: move the near plane out or make the object smaller");
  }
  return {};
}

}  // namespace

Expected<void> check_frame(const Scene& scene, const RenderOptions& options) {
  if (auto ok = check_options(options); !ok) return ok;
  for (const SceneLight& light : scene.lights)
    if (auto ok = check_light(light.position); !ok)
      return make_error("scene " + scene.name + ": " + ok.error().message);
  if (auto ok = check_camera(scene.camera); !ok)
    return make_error("scene " + scene.name + ": " + ok.error().message);
  if (auto ok = check_extent(scene); !ok)
    return make_error("scene " + scene.name + ": " + ok.error().message);
  if (options.generator != Generator::standard) return {};
  if (has_transparent_casters(scene))
    return make_error(
        "generator standard counts only the surfaces that face the light, but scene " + scene.name +
        " has transparent casters, whose every surface filters the light: use robust, "
        "multiplicity or auto");
  for (const SceneObject& object : scene.objects)
    if (!object.topology->report.closed_manifold)
      return check_generator(options.generator, object.topology->report,
                             "scene " + scene.name + ", object '" + object.name + "'");
  return {};
}

FrameStats& FrameStats::operator+=(const FrameStats& other) {
  using S = FrameStats;
  for (double S::*ms : {&S::ms_depth, &S::ms_volumes, &S::ms_counts, &S::ms_shade, &S::ms_readback,
                        &S::ms_cull, &S::ms_clamp, &S::ms_bvh, &S::ms_occlusion, &S::ms_measuring,
                        &S::ms_volume_builds, &S::ms_volumes_hidden})
    this->*ms += other.*ms;
  for (std::uint64_t S::*n :
       {&S::cull_queries, &S::volume_segments, &S::slice_queries, &S::clamp_pairs, &S::clamp_swaps,
        &S::intervals_merged_by_cost, &S::fill, &S::stencil_writes, &S::nodes_visited, &S::queries,
        &S::queries_waited, &S::scissor_pixels_saved})
    this->*n += other.*n;
  for (std::size_t S::*n : {&S::triangles, &S::volume_primitives}) this->*n += other.*n;
  for (int S::*n :
       {&S::objects_zpass, &S::objects_zfail, &S::objects_split, &S::parts_zpass, &S::volumes_built,
        &S::volumes_reused, &S::casters_culled_in_shadow, &S::casters_culled_unseen,
        &S::light_views, &S::sub_objects_culled, &S::volumes_clamped, &S::volumes_clamped_away,
        &S::bvh_rebuilt, &S::objects_culled, &S::volumes_culled, &S::objects_drawn,
        &S::volumes_drawn, &S::volumes_out_of_range})
    this->*n += other.*n;
  for (raster::Counters S::*c : {&S::depth, &S::counts, &S::split_sampling}) this->*c += other.*c;
  for (std::vector<int> S::*per_object : {&S::zfail_lights, &S::culled_lights}) {
    std::vector<int>& mine = this->*per_object;
    const std::vector<int>& theirs = other.*per_object;
    if (mine.size() < theirs.size()) mine.resize(theirs.size());
    for (std::size_t o = 0; o < theirs.size(); ++o) mine[o] += theirs[o];
  }
  return *this;
}

}  // namespace shadowvol
