#include "render/frame_outputs.h"

#include <array>
#include <cmath>
#include <limits>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include "raster/raster.h"
#include "render/shading.h"

namespace shadowvol {
namespace {

// The plane of face `face` of object `object` in eye-relative world space (the eye at the
// origin), in double: geo-referenced scenes sit far from the origin (DESIGN.md "Numerics").
struct FacePlane {
  glm::dvec3 normal;  // not normalised
  double offset;      // dot(normal, any point of the face)
};
FacePlane face_plane(const Scene& scene, std::int32_t object, std::uint32_t face) {
  const SceneObject& o = scene.objects[static_cast<std::size_t>(object)];
  const glm::dmat4 m(o.transform);
  const glm::dvec3 eye(scene.camera.position);
  glm::dvec3 corner[3];
  for (int k = 0; k < 3; ++k) {
    const glm::vec3& p = o.mesh->positions[o.mesh->indices[3 * std::size_t{face} + k]];
    corner[k] = glm::dvec3(m * glm::dvec4(glm::dvec3(p), 1.0)) - eye;
  }
  const glm::dvec3 n = glm::cross(corner[1] - corner[0], corner[2] - corner[0]);
  return {n, glm::dot(n, corner[0])};
}

// The ray from the eye (the origin of eye-relative space) through a pixel's centre, as the
// reference casts it (trace/reference.h); not normalised.
class PixelRays {
 public:
  PixelRays(const Scene& scene, int width, int height)
      : width_(width),
        height_(height),
        inv_view_proj_(
            glm::inverse(glm::dmat4(scene.camera.projection(float(width) / float(height))) *
                         glm::dmat4(scene.camera.view_from_eye()))) {}
  glm::dvec3 through(int x, int y) const {
    const glm::dvec4 on_near =
        inv_view_proj_ *
        glm::dvec4((x + 0.5) / width_ * 2.0 - 1.0, 1.0 - (y + 0.5) / height_ * 2.0, 1.0, 1.0);
    return glm::dvec3(on_near) / on_near.w;
  }

 private:
  int width_, height_;
  glm::dmat4 inv_view_proj_;
};

// Where a ray meets a face's plane, as a multiple of the ray.
double hit_at(const FacePlane& plane, const glm::dvec3& ray) {
  return plane.offset / glm::dot(plane.normal, ray);
}

template <class PerRow>
void for_rows(int height, PerRow&& per_row) {
  tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y) per_row(y);
  });
}

}  // namespace

GreyImage shadow_mask(const Scene& scene, const Frame& frame, std::size_t light) {
  const int w = frame.image.width, h = frame.image.height;
  GreyImage out{w, h, std::vector<std::uint8_t>(std::size_t(w) * std::size_t(h), kMaskNotFacing)};
  const glm::dvec4 l(scene.lights[light].position);
  // The light relative to the eye: a point (w = 1) moves with it, a direction does not.
  const glm::dvec4 to_light(glm::dvec3(l) - l.w * glm::dvec3(scene.camera.position), l.w);
  const std::vector<std::uint8_t>& shadowed = frame.shadowed[light];
  const PixelRays rays(scene, w, h);
  const bool limited = scene.lights[light].limited();
  const double range = scene.lights[light].range;
  for_rows(h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      const std::size_t p = std::size_t(y) * w + x;
      const std::int32_t object = frame.object[p];
      if (object < 0) continue;
      const FacePlane plane = face_plane(scene, object, frame.face[p]);
      // The eye (the origin) and the light on the same side of the face's plane.
      const double eye_side = -plane.offset;
      const double light_side = glm::dot(plane.normal, glm::dvec3(to_light)) - plane.offset * l.w;
      if (!(eye_side * light_side > 0.0)) continue;
      // Beyond the range no light arrives, on a surface that receives no shadows too.
      const glm::dvec3 ray = rays.through(x, y);
      const bool beyond =
          limited && !(glm::length(glm::dvec3(to_light) - hit_at(plane, ray) * ray) < range);
      out.value[p] = beyond || shadowed[p] != 0 ? kMaskShadowed : kMaskLit;
    }
  });
  return out;
}

DepthImage view_depth(const Scene& scene, const Frame& frame) {
  const int w = frame.image.width, h = frame.image.height;
  DepthImage out{
      w, h,
      std::vector<float>(std::size_t(w) * std::size_t(h), std::numeric_limits<float>::infinity())};
  const PixelRays rays(scene, w, h);
  const glm::dvec3 forward =
      glm::normalize(glm::dvec3(scene.camera.target) - glm::dvec3(scene.camera.position));
  for_rows(h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      const std::size_t p = std::size_t(y) * w + x;
      if (frame.object[p] < 0) continue;
      const glm::dvec3 ray = rays.through(x, y);
      const FacePlane plane = face_plane(scene, frame.object[p], frame.face[p]);
      const double depth = hit_at(plane, ray) * glm::dot(ray, forward);
      if (std::isfinite(depth) && depth > 0.0) out.depth[p] = static_cast<float>(depth);
    }
  });
  return out;
}

Image object_ids(const Frame& frame) {
  Image out{frame.image.width, frame.image.height, {}};
  out.rgba.resize(frame.object.size() * 4);
  for (std::size_t p = 0; p < frame.object.size(); ++p) {
    const std::uint32_t id = static_cast<std::uint32_t>(frame.object[p] + 1);
    out.rgba[4 * p + 0] = static_cast<std::uint8_t>(id);
    out.rgba[4 * p + 1] = static_cast<std::uint8_t>(id >> 8);
    out.rgba[4 * p + 2] = static_cast<std::uint8_t>(id >> 16);
    out.rgba[4 * p + 3] = 255;
  }
  return out;
}

Expected<int> samples_side(int samples, int width, int height) {
  int side = 1;
  while (side * side < samples && side * side < kMaxSamples) ++side;
  if (samples < 1 || samples > kMaxSamples || side * side != samples)
    return make_error(std::to_string(samples) +
                      " samples per pixel: give a square number from 1 to 64 (1, 4, 9, 16, "
                      "25, 36, 49 or 64: a k x k grid in each pixel)");
  if (std::max(width, height) * side > raster::kMaxViewport)
    return make_error(std::to_string(samples) + " samples per pixel of a " + std::to_string(width) +
                      "x" + std::to_string(height) + " picture are drawn at " +
                      std::to_string(width * side) + "x" + std::to_string(height * side) +
                      ", past the " + std::to_string(raster::kMaxViewport) +
                      " pixels a side the renderer draws");
  return side;
}

Image resolve_samples(const Image& samples, int side) {
  static const std::array<float, 256> linear = [] {
    std::array<float, 256> table{};
    for (int i = 0; i < 256; ++i) {
      const float c = float(i) / 255.0f;
      table[i] = c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
    }
    return table;
  }();
  Image out{samples.width / side, samples.height / side, {}};
  out.rgba.resize(std::size_t(out.width) * std::size_t(out.height) * 4);
  const float weight = 1.0f / float(side * side);
  const shading::SrgbTable& srgb = shading::srgb_table();
  for_rows(out.height, [&](int y) {
    for (int x = 0; x < out.width; ++x) {
      float sum[4] = {0, 0, 0, 0};
      for (int j = 0; j < side; ++j)
        for (int i = 0; i < side; ++i) {
          const std::uint8_t* s =
              &samples.rgba[(std::size_t(y * side + j) * samples.width + x * side + i) * 4];
          for (int c = 0; c < 3; ++c) sum[c] += linear[s[c]];
          sum[3] += s[3];
        }
      std::uint8_t* d = &out.rgba[(std::size_t(y) * out.width + x) * 4];
      for (int c = 0; c < 3; ++c) d[c] = shading::to_srgb8(sum[c] * weight, srgb);
      d[3] = static_cast<std::uint8_t>(std::lround(sum[3] * weight));
    }
  });
  return out;
}

}  // namespace shadowvol
