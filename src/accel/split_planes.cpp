#include "accel/split_planes.h"

#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

namespace shadowvol {
namespace {

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

}  // namespace

glm::vec4 point_camera_light(const glm::vec3& p, const glm::vec4& light, double turn, double tilt) {
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

glm::vec4 point_point_light(const glm::vec3& p1, const glm::vec3& p2, const glm::vec4& light) {
  const glm::dvec3 a(p1), b(p2);
  const glm::dvec3 normal = light.w != 0.0f ? glm::cross(a - glm::dvec3(light) / double(light.w),
                                                         b - glm::dvec3(light) / double(light.w))
                                            : glm::cross(b - a, glm::dvec3(light));
  return glm::vec4(glm::vec3(normal), float(-glm::dot(normal, a)));
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

}  // namespace shadowvol
