#include "render/soft_renderer.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <optional>
#include <span>
#include <tuple>

#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "render/near_plane_prefill.h"

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

}  // namespace

Frame SoftRenderer::render(const Scene& scene, const RenderOptions& options) {
  assert(check_options(options).ok());
  const int w = options.width, h = options.height;
  const std::size_t pixels = static_cast<std::size_t>(w) * h;
  if (target_.width != w || target_.height != h) target_ = soft::Target(w, h);
  Frame frame;
  FrameStats& stats = frame.stats;
  const FramePlan plan = plan_frame(scene, options, stats);

  // --- depth pass: ids are (first face id of the object) + face ---
  auto start = Clock::now();
  target_.clear_depth();
  target_.tile_work.assign(options.tile_work ? target_.tile_depth.size() : 0, soft::TileWork{});
  std::vector<glm::vec4> tris;
  for (std::size_t o = 0; o < scene.objects.size(); ++o) {
    const SceneObject& object = scene.objects[o];
    clip_triangles(object, plan.view_proj * plan.model[o], tris);
    soft::draw_depth(target_, tris, plan.first_id[o], stats.depth);
    stats.triangles += object.mesh->triangle_count();
  }
  target_.update_tile_depth();
  frame.object.assign(pixels, -1);
  frame.face.assign(pixels, 0);
  for (std::size_t p = 0; p < pixels; ++p)
    if (target_.id[p] != soft::Target::kNoId)
      std::tie(frame.object[p], frame.face[p]) = plan.object_of(target_.id[p]);
  stats.ms_depth = ms_since(start);

  // --- per light: volumes, counts ---
  frame.shadowed.assign(scene.lights.size(), std::vector<std::uint8_t>(pixels, 0));
  // Per object, the tile work moves out of the target after each volume, into the object's
  // share and the frame's total; that bookkeeping is left out of the count passes' time.
  const bool per_object = options.tile_work && options.tile_work_per_object;
  std::vector<soft::TileWork> total_work(per_object ? target_.tile_work.size() : 0);
  if (per_object)
    frame.object_tile_work.assign(scene.objects.size(),
                                  std::vector<soft::TileWork>(target_.tile_work.size()));
  for (std::size_t l = 0; l < scene.lights.size(); ++l) {
    start = Clock::now();
    volumes_.update(scene, plan, l, options.generator, stats);
    stats.ms_volumes += ms_since(start);

    start = Clock::now();
    std::vector<std::int32_t> weights, prefill_weights;
    std::vector<glm::vec4> prefill_tris;
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
      const VolumeBuffer& v = volumes_.volume(l, o);
      const std::optional<glm::vec4>& split = plan.split[l][o];
      stats.volume_primitives += v.primitive_count();
      const glm::mat4 mvp = plan.view_proj * plan.model[o];
      tris.clear();
      weights.clear();
      clip_volume(v.sides, kQuadCorners, mvp, plan.weight_sign[o], tris, weights);
      const std::size_t sides = weights.size();
      if (plan.counts_caps(l, o)) {
        clip_volume(v.light_caps, kTriangleCorners, mvp, plan.weight_sign[o], tris, weights);
        clip_volume(v.dark_caps, kTriangleCorners, mvp, plan.weight_sign[o], tris, weights);
      }
      // Depth bounds: the volume's range of window depths (a triangle's depth is affine on the
      // screen, so its range is its vertices'; one before the near plane stands for the point
      // where the triangle crosses it, at depth 1). Bounded volumes end short of depth 0.
      soft::DepthBounds bounds{1.0f, 0.0f};
      for (const glm::vec4& c : tris) {
        const float depth = c.w <= 0.0f || c.z > c.w ? 1.0f : c.z / c.w;
        bounds.zmin = std::min(bounds.zmin, depth);
        bounds.zmax = std::max(bounds.zmax, depth);
      }
      // Pre-filled z-pass starts inside the volume: a pixel beyond all of it must still count
      // its way out, so no far bound.
      if (plan.prefill[l][o]) bounds.zmin = 0.0f;
      const std::span<const glm::vec4> all_tris(tris);
      const std::span<const std::int32_t> all_weights(weights);
      if (plan.prefill[l][o]) {  // ZP+: where z-pass counts, start from the near plane's count
        prefill_tris.clear();
        prefill_weights.clear();
        append_near_plane_prefill(v.light_caps, plan.model[o], plan.weight_sign[o], plan.lights[l],
                                  plan.view_proj, prefill_tris, prefill_weights);
        soft::draw_counts(target_, prefill_tris, prefill_weights, soft::CountRule::prefill,
                          stats.counts, {},
                          {split.value_or(glm::vec4(0.0f)),
                           split ? soft::SplitTiles::zpass_only : soft::SplitTiles::all});
      }
      if (split) {
        // Laine 2005 §3.3: the sides in every tile, the caps only where z-fail counts.
        soft::draw_counts(target_, all_tris.first(3 * sides), all_weights.first(sides),
                          soft::CountRule::split, stats.counts, bounds, {*split});
        soft::draw_counts(target_, all_tris.subspan(3 * sides), all_weights.subspan(sides),
                          soft::CountRule::split, stats.counts, bounds,
                          {*split, soft::SplitTiles::zfail_only});
      } else {
        soft::draw_counts(target_, all_tris, all_weights,
                          plan.zfail[l][o] ? soft::CountRule::zfail : soft::CountRule::zpass,
                          stats.counts, bounds);
      }
      if (per_object) {
        const auto bookkeeping = Clock::now();
        for (std::size_t t = 0; t < total_work.size(); ++t) {
          soft::TileWork& work = target_.tile_work[t];
          for (soft::TileWork* sum : {&frame.object_tile_work[o][t], &total_work[t]}) {
            sum->pixels_processed += work.pixels_processed;
            sum->pixels_updated += work.pixels_updated;
          }
          work = {};
        }
        start += Clock::now() - bookkeeping;
      }
    }
    target_.take_nonzero_counts(frame.shadowed[l]);
    stats.ms_counts += ms_since(start);
  }
  frame.tile_work = std::move(per_object ? total_work : target_.tile_work);  // sized afresh

  // --- shading: ambient everywhere, each light where it is not shadowed ---
  start = Clock::now();
  frame.image = {w, h, std::vector<std::uint8_t>(pixels * 4)};
  std::vector<std::vector<glm::vec3>> world(scene.objects.size());  // vertices, once per frame
  for (std::size_t o = 0; o < scene.objects.size(); ++o) {
    const SceneObject& object = scene.objects[o];
    world[o].reserve(object.mesh->positions.size());
    for (const glm::vec3& p : object.mesh->positions)
      world[o].push_back(glm::vec3(plan.model[o] * glm::vec4(p, 1.0f)));
  }
  const glm::dmat4 inv_vp(plan.inv_view_proj);
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      const std::size_t p = static_cast<std::size_t>(y) * w + x;
      glm::vec3 color = shading::background(y, h);
      if (frame.object[p] >= 0) {
        const auto o = static_cast<std::size_t>(frame.object[p]);
        const SceneObject& object = scene.objects[o];
        const std::uint32_t* f = &object.mesh->indices[3 * static_cast<std::size_t>(frame.face[p])];
        const glm::vec3& a = world[o][f[0]];
        glm::vec3 n = glm::cross(world[o][f[1]] - a, world[o][f[2]] - a);
        const float len = glm::length(n);
        n = len > 0.0f ? n / len : glm::vec3(0, 1, 0);
        const glm::dvec4 ndc((x + 0.5) / w * 2.0 - 1.0, 1.0 - (y + 0.5) / h * 2.0,
                             double(target_.depth[p]), 1.0);
        const glm::dvec4 at = inv_vp * ndc;
        const glm::vec3 pos = glm::vec3(glm::dvec3(at) / at.w);
        const glm::vec3 to_eye = glm::normalize(-pos);  // the eye is the origin
        if (glm::dot(n, to_eye) < 0.0f) n = -n;         // two-sided: light the side we see
        const glm::vec3 albedo = object.material.color;
        color = scene.ambient * albedo;
        for (std::size_t l = 0; l < scene.lights.size(); ++l) {
          if (frame.shadowed[l][p]) continue;
          const SceneLight& light = scene.lights[l];
          const glm::vec4 lp = plan.lights[l];
          const glm::vec3 to_light =
              glm::normalize(lp.w != 0.0f ? glm::vec3(lp) / lp.w - pos : glm::vec3(lp));
          const float lambert = glm::dot(n, to_light);
          if (lambert <= 0.0f) continue;
          const float spec = std::pow(
              std::max(0.0f, glm::dot(n, glm::normalize(to_light + to_eye))), shading::kShininess);
          color += light.color * light.intensity *
                   (albedo * lambert + glm::vec3(shading::kSpecular * spec));
        }
      }
      for (int k = 0; k < 3; ++k)
        frame.image.rgba[4 * p + k] =
            static_cast<std::uint8_t>(std::lround(shading::to_srgb(color[k]) * 255.0f));
      frame.image.rgba[4 * p + 3] = 255;
    }
  });
  stats.ms_shade = ms_since(start);

  if (options.show_volumes) overlay_volumes(frame.image, scene, plan, volumes_);
  return frame;
}

}  // namespace shadowvol
