#include "render/caster_culling.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>

#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

namespace shadowvol {
namespace {

// Whether any part of the box may lie in the view frustum: not when all eight corners lie
// outside one of its planes (core/projection.h: x, y in [-w, w], z <= w; no far plane).
bool in_frustum(const Box& box, const glm::dmat4& view_proj) {
  if (box.empty()) return false;
  std::array<int, 5> outside{};
  for (int i = 0; i < 8; ++i) {
    const glm::dvec4 c =
        view_proj * glm::dvec4(i & 1 ? box.hi.x : box.lo.x, i & 2 ? box.hi.y : box.lo.y,
                               i & 4 ? box.hi.z : box.lo.z, 1.0);
    outside[0] += c.x > c.w;
    outside[1] += c.x < -c.w;
    outside[2] += c.y > c.w;
    outside[3] += c.y < -c.w;
    outside[4] += c.z > c.w;
  }
  return std::none_of(outside.begin(), outside.end(), [](int n) { return n == 8; });
}

}  // namespace

std::array<glm::dvec3, 3> CasterCulling::face(const Scene& scene, std::size_t o,
                                              std::uint32_t f) const {
  const std::uint32_t* v = &scene.objects[o].topology->face_vertices[3 * std::size_t{f}];
  const glm::dvec3* p = world(o);
  return {p[v[0]], p[v[1]], p[v[2]]};
}

void CasterCulling::find_receivers(const Scene& scene, const RenderOptions& options,
                                   const FramePlan& plan, const SurfaceLayer* opaque) {
  const std::size_t objects = plan.objects.size();
  const glm::dmat4 view_proj(plan.view_proj);
  receiver_.assign(objects, 0);
  for (std::size_t o = 0; o < objects; ++o) {
    const bool visible = in_frustum(boxes_[o], view_proj);
    receiver_[o] = visible && (options.cull == Cull::frustum || plan.transparent(o));
  }
  edge_on_.clear();
  if (options.cull != Cull::occlusion || !opaque) {
    samples_.clear();
    return;
  }
  // Each pixel's point: where the ray through its centre meets its face's plane; NaN where it
  // shows nothing, (inf, NaN, NaN) where its face is edge-on to the eye.
  const glm::dmat4 inv_view_proj(plan.inv_view_proj);
  const int width = options.width, height = options.height;
  samples_.resize(static_cast<std::size_t>(width) * height);
  // The near-plane point of a pixel is affine in its centre (x, y) before the division by w.
  const glm::dvec4 origin = inv_view_proj * glm::dvec4(-1.0, 1.0, 1.0, 1.0);
  const glm::dvec4 step_x = inv_view_proj * glm::dvec4(2.0 / width, 0.0, 0.0, 0.0);
  const glm::dvec4 step_y = inv_view_proj * glm::dvec4(0.0, -2.0 / height, 0.0, 0.0);
  tbb::parallel_for(0, height, [&](int y) {
    std::int32_t last_object = -1;
    std::uint32_t last_face = 0;
    glm::dvec3 normal(0.0), a(0.0);
    for (int x = 0; x < width; ++x) {
      const std::size_t p = static_cast<std::size_t>(y) * width + x;
      const std::int32_t o = opaque->object[p];
      glm::dvec3& sample = samples_[p];
      sample = glm::dvec3(NAN);
      if (o < 0) continue;
      const std::uint32_t f = opaque->face[p];
      std::atomic_ref<std::uint8_t>(receiver_[static_cast<std::size_t>(o)])
          .store(1, std::memory_order_relaxed);
      if (o != last_object || f != last_face) {
        last_object = o, last_face = f;
        const std::array<glm::dvec3, 3> v = face(scene, static_cast<std::size_t>(o), f);
        a = v[0];
        normal = glm::cross(v[1] - a, v[2] - a);
      }
      // The ray from the eye (the origin) through the pixel's centre on the near plane.
      const glm::dvec4 n = origin + step_x * (x + 0.5) + step_y * (y + 0.5);
      const glm::dvec3 dir = glm::dvec3(n) / n.w;
      const double along = glm::dot(normal, dir);
      if (!(std::abs(along) > 1e-9 * glm::length(normal) * glm::length(dir)))
        sample = glm::dvec3(INFINITY, NAN, NAN);
      else
        sample = dir * (glm::dot(normal, a) / along);
    }
  });
  for (std::size_t p = 0; p < samples_.size(); ++p)
    if (std::isinf(samples_[p].x)) {
      const std::pair<std::size_t, std::uint32_t> face{opaque->object[p], opaque->face[p]};
      if (edge_on_.empty() || edge_on_.back() != face) edge_on_.push_back(face);
    }
}

void CasterCulling::cull(const Scene& scene, const RenderOptions& options, FramePlan& plan,
                         const SurfaceLayer* opaque, FrameStats& stats) {
  if (options.cull == Cull::none) return;
  const std::size_t objects = plan.objects.size();
  boxes_.resize(objects);
  for (std::size_t o = 0; o < objects; ++o)
    boxes_[o] = {glm::dvec3(plan.objects[o].lo), glm::dvec3(plan.objects[o].hi)};
  const bool occlusion = options.cull == Cull::occlusion;
  // The vertices, which only the occlusion tests draw.
  world_first_.assign(objects + 1, 0);
  for (std::size_t o = 0; occlusion && o < objects; ++o)
    world_first_[o + 1] = world_first_[o] + scene.objects[o].topology->positions.size();
  world_.resize(world_first_[objects]);
  for (std::size_t o = 0; occlusion && o < objects; ++o) {
    const glm::dmat4 model(plan.objects[o].model);
    const std::vector<glm::vec3>& positions = scene.objects[o].topology->positions;
    for (std::size_t v = 0; v < positions.size(); ++v)
      world_[world_first_[o] + v] = glm::dvec3(model * glm::dvec4(glm::dvec3(positions[v]), 1.0));
  }
  find_receivers(scene, options, plan, opaque);
  receiver_boxes_.clear();
  for (std::size_t o = 0; o < objects; ++o)
    if (receiver_[o]) receiver_boxes_.push_back(boxes_[o]);

  for (std::size_t l = 0; l < plan.lights.size(); ++l) {
    views_.fit(glm::dvec4(plan.lights[l]), receiver_boxes_, options.light_view_size, occlusion);
    stats.light_views += static_cast<int>(views_.view_count());
    if (occlusion) {
      occluders_.clear();
      for (std::size_t o = 0; o < objects; ++o)
        if (!plan.transparent(o) && views_.touches(boxes_[o])) {
          const Topology& topology = *scene.objects[o].topology;
          occluders_.push_back({&topology, {world(o), topology.positions.size()}, boxes_[o]});
        }
      views_.add_occluders(occluders_);
      views_.add_receiver_points(samples_);
      auto add_face = [&](std::size_t o, std::uint32_t f) {
        const std::array<glm::dvec3, 3> v = face(scene, o, f);
        views_.add_receiver_triangle(v[0], v[1], v[2]);
      };
      for (const auto& [o, f] : edge_on_) add_face(o, f);
      for (std::size_t o = 0; o < objects; ++o)
        if (plan.transparent(o) && receiver_[o])
          for (std::uint32_t f = 0; f < scene.objects[o].topology->face_count(); ++f)
            add_face(o, f);
    }
    views_.finish(occlusion, occlusion);
    for (std::size_t o = 0; o < objects; ++o) {
      const BoxVisibility seen = views_.test(boxes_[o], stats.cull_queries);
      plan.volume(l, o).culled = seen != BoxVisibility::kept;
      stats.culled_lights[o] += seen != BoxVisibility::kept;
      stats.casters_culled_in_shadow += seen == BoxVisibility::in_shadow;
      stats.casters_culled_unseen += seen == BoxVisibility::unseen;
    }
  }
}

}  // namespace shadowvol
