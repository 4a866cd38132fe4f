#include "render/soft_renderer.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <optional>
#include <span>
#include <tuple>

#include <tbb/parallel_for.h>
#include <glm/exponential.hpp>
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

// What the passes of one frame share.
struct SoftRenderer::Pass {
  const Scene& scene;
  const RenderOptions& options;
  const FramePlan& plan;
  Frame& frame;
  // RenderOptions::tile_work_per_object: the frame's total (the target's tile work moves into it
  // and into the object's share after each volume).
  std::vector<soft::TileWork>* total_work;
};

void SoftRenderer::Grouped::group(std::span<const glm::vec4> triangles,
                                  std::span<const std::int32_t> triangle_weights,
                                  std::span<const std::uint32_t> keys, std::size_t key_count) {
  offsets.assign(key_count + 1, 0);
  for (const std::uint32_t k : keys) ++offsets[k + 1];
  for (std::size_t k = 0; k < key_count; ++k) offsets[k + 1] += offsets[k];
  if (std::is_sorted(keys.begin(), keys.end())) {
    tris = triangles;
    weights = triangle_weights;
    return;
  }
  sorted_tris.resize(triangles.size());
  sorted_weights.resize(triangle_weights.size());
  cursor.assign(offsets.begin(), offsets.end() - 1);
  for (std::size_t t = 0; t < keys.size(); ++t) {
    const std::size_t at = cursor[keys[t]]++;
    std::copy_n(&triangles[3 * t], 3, &sorted_tris[3 * at]);
    sorted_weights[at] = triangle_weights[t];
  }
  tris = sorted_tris;
  weights = sorted_weights;
}

void SoftRenderer::count_volume(const Pass& pass, std::size_t l, std::size_t o) {
  const FramePlan& plan = pass.plan;
  FrameStats& stats = pass.frame.stats;
  const VolumeBuffer& v = volumes_.volume(l, o);
  const std::vector<FramePlan::PartSplit>& splits = plan.split[l][o];
  const bool by_part = plan.splits_by_part(l, o);
  stats.volume_primitives += v.primitive_count();
  const glm::mat4 mvp = plan.view_proj * plan.model[o];
  const int sign = plan.weight_sign[o];
  tris_.clear();
  weights_.clear();
  keys_.clear();
  // Under a split plane, each triangle's key: 2 * its part (0 for a volume split whole), plus 1
  // for a cap, which counts only where z-fail does (Laine 2005 §3.3).
  auto add = [&](const PrimitiveList& list, int corners, std::uint32_t cap) {
    clip_volume(list, corners, mvp, sign, tris_, weights_);
    if (splits.empty()) return;
    const int per = corners == kQuadCorners ? 2 : 1;
    for (std::size_t p = 0; p < list.size(); ++p)
      keys_.insert(keys_.end(), per, 2 * (by_part ? list.parts[p] : 0) + cap);
  };
  // First what counts in every tile: the sides, and a transparent caster's light caps; then the
  // caps that count only where z-fail does.
  add(v.sides, kQuadCorners, 0);
  const bool glass = plan.counts_light_caps_everywhere(o);
  if (glass) add(v.light_caps, kTriangleCorners, 0);
  if (plan.counts_caps(l, o)) {
    if (!glass) add(v.light_caps, kTriangleCorners, 1);
    add(v.dark_caps, kTriangleCorners, 1);
  }
  // Depth bounds, Laine 2005 §7's (FramePlan::depth_bounds). Pre-filled z-pass starts inside the
  // volume: a pixel beyond all of it must still count its way out, so no far bound.
  soft::DepthBounds bounds = plan.depth_bounds[l][o];
  if (plan.prefill[l][o]) {  // ZP+: where z-pass counts, start from the near plane's count
    bounds.zmin = 0.0f;
    prefill_tris_.clear();
    prefill_weights_.clear();
    prefill_keys_.clear();
    append_near_plane_prefill(v.light_caps, plan.model[o], sign, plan.lights[l], plan.view_proj,
                              prefill_tris_, prefill_weights_, by_part ? &prefill_keys_ : nullptr);
  }
  if (splits.empty()) {
    if (plan.prefill[l][o])
      soft::draw_counts(target_, prefill_tris_, prefill_weights_, soft::CountRule::prefill,
                        stats.counts);
    soft::draw_counts(target_, tris_, weights_,
                      plan.zfail[l][o] ? soft::CountRule::zfail : soft::CountRule::zpass,
                      stats.counts, bounds);
  } else {
    volume_groups_.group(tris_, weights_, keys_, 2 * splits.size());
    if (plan.prefill[l][o]) {
      if (!by_part) prefill_keys_.assign(prefill_weights_.size(), 0);
      prefill_groups_.group(prefill_tris_, prefill_weights_, prefill_keys_, splits.size());
    }
    for (std::size_t p = 0; p < splits.size(); ++p) {
      const auto everywhere = volume_groups_.triangles_of(2 * p, 2 * p + 1);
      const auto caps = volume_groups_.triangles_of(2 * p + 1, 2 * p + 2);
      if (everywhere.empty() && caps.empty()) continue;  // a part that casts nothing
      glm::vec4 plane = splits[p].plane;
      if (const std::vector<glm::vec4>& candidates = splits[p].candidates; !candidates.empty())
        plane = candidates[split_sampler_.cheapest(target_, everywhere, caps, bounds, candidates,
                                                   stats.split_sampling)];
      if (plan.prefill[l][o])
        soft::draw_counts(target_, prefill_groups_.triangles_of(p, p + 1),
                          prefill_groups_.weights_of(p, p + 1), soft::CountRule::prefill,
                          stats.counts, {}, {plane, soft::SplitTiles::zpass_only});
      // Laine 2005 §3.3: the sides in every tile, the caps only where z-fail counts.
      soft::draw_counts(target_, everywhere, volume_groups_.weights_of(2 * p, 2 * p + 1),
                        soft::CountRule::split, stats.counts, bounds, {plane});
      soft::draw_counts(target_, caps, volume_groups_.weights_of(2 * p + 1, 2 * p + 2),
                        soft::CountRule::split, stats.counts, bounds,
                        {plane, soft::SplitTiles::zfail_only});
    }
  }
  if (pass.total_work != nullptr) {  // bookkeeping, left out of the count passes' time
    const auto bookkeeping = Clock::now();
    for (std::size_t t = 0; t < pass.total_work->size(); ++t) {
      soft::TileWork& work = target_.tile_work[t];
      for (soft::TileWork* sum : {&pass.frame.object_tile_work[o][t], &(*pass.total_work)[t]}) {
        sum->pixels_processed += work.pixels_processed;
        sum->pixels_updated += work.pixels_updated;
      }
      work = {};
    }
    stats.ms_counts -= ms_since(bookkeeping);
  }
}

void SoftRenderer::light_layer(const Pass& pass, std::size_t l, SurfaceLayer& layer) {
  const FramePlan& plan = pass.plan;
  const std::size_t objects = pass.scene.objects.size();
  auto start = Clock::now();
  for (std::size_t o = 0; o < objects; ++o)
    if (plan.glass_group[o] < 0) count_volume(pass, l, o);
  target_.take_nonzero_counts(layer.shadowed[l]);
  if (!plan.glass_log_transmittance.empty()) {
    log_light_.assign(target_.count.size(), glm::vec3(0.0f));
    for (std::size_t g = 0; g < plan.glass_members.size(); ++g) {
      for (const std::size_t o : plan.glass_members[g]) count_volume(pass, l, o);
      target_.take_counts_into(log_light_, plan.glass_log_transmittance[g]);
    }
    std::vector<glm::vec3>& light = layer.transmitted[l];
    tbb::parallel_for(std::size_t{0}, light.size(), [&](std::size_t p) {
      light[p] = layer.shadowed[l][p] ? glm::vec3(0.0f) : glm::exp(log_light_[p]);
    });
  }
  pass.frame.stats.ms_counts += ms_since(start);
}

void SoftRenderer::filter_through_glass(const Pass& pass) {
  const FramePlan& plan = pass.plan;
  eye_log_.assign(target_.depth.size(), glm::vec3(0.0f));
  std::vector<soft::TileWork> shadow_work;  // not a shadow pass: leave the tile work alone
  std::swap(shadow_work, target_.tile_work);
  for (std::size_t g = 0; g < plan.glass_members.size(); ++g) {
    for (const std::size_t o : plan.glass_members[g]) {
      clip_triangles(pass.scene.objects[o], plan.view_proj * plan.model[o], tris_);
      weights_.assign(tris_.size() / 3, 1);
      soft::draw_counts(target_, tris_, weights_, soft::CountRule::cover, pass.frame.stats.depth);
    }
    target_.take_counts_into(eye_log_, plan.glass_log_transmittance[g]);
  }
  std::swap(shadow_work, target_.tile_work);
}

Frame SoftRenderer::render(const Scene& scene, const RenderOptions& options) {
  assert(check_options(options).ok());
  const int w = options.width, h = options.height;
  const std::size_t pixels = static_cast<std::size_t>(w) * h;
  if (target_.width != w || target_.height != h) target_ = soft::Target(w, h);
  Frame frame;
  FrameStats& stats = frame.stats;
  const FramePlan plan = plan_frame(scene, options, stats);
  const bool glass = !plan.glass_log_transmittance.empty();
  const std::size_t lights = scene.lights.size();

  // Per object, the tile work moves out of the target after each volume, into the object's
  // share and the frame's total.
  target_.tile_work.assign(options.tile_work ? target_.tile_depth.size() : 0, soft::TileWork{});
  const bool per_object = options.tile_work && options.tile_work_per_object;
  std::vector<soft::TileWork> total_work(per_object ? target_.tile_work.size() : 0);
  if (per_object)
    frame.object_tile_work.assign(scene.objects.size(),
                                  std::vector<soft::TileWork>(target_.tile_work.size()));
  const Pass pass{scene, options, plan, frame, per_object ? &total_work : nullptr};

  // A layer: the depth pass of the objects `in_layer` takes, over the depth buffer as it stands
  // (ids are (first face id of the object) + face), then per light its shadows.
  std::vector<glm::vec4> tris;
  auto draw_layer = [&](SurfaceLayer& layer, bool clear, auto in_layer) {
    auto start = Clock::now();
    if (clear) target_.clear_depth();
    std::fill(target_.id.begin(), target_.id.end(), soft::Target::kNoId);
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
      if (!in_layer(scene.objects[o])) continue;
      const SceneObject& object = scene.objects[o];
      clip_triangles(object, plan.view_proj * plan.model[o], tris);
      soft::draw_depth(target_, tris, plan.first_id[o], stats.depth);
      stats.triangles += object.mesh->triangle_count();
    }
    target_.update_tile_depth();
    layer.object.assign(pixels, -1);
    layer.face.assign(pixels, 0);
    for (std::size_t p = 0; p < pixels; ++p)
      if (target_.id[p] != soft::Target::kNoId)
        std::tie(layer.object[p], layer.face[p]) = plan.object_of(target_.id[p]);
    stats.ms_depth += ms_since(start);
    layer.shadowed.resize(lights);  // each sized in place: a copy would touch its pages twice
    for (std::vector<std::uint8_t>& mask : layer.shadowed) mask.resize(pixels);
    layer.transmitted.resize(glass ? lights : 0);
    for (std::vector<glm::vec3>& light : layer.transmitted) light.resize(pixels);
    for (std::size_t l = 0; l < lights; ++l) {
      start = Clock::now();
      volumes_.update(scene, plan, l, options.generator, stats);
      stats.ms_volumes += ms_since(start);
      light_layer(pass, l, layer);
    }
  };
  draw_layer(frame, true, [](const SceneObject& o) { return !o.material.transparent(); });
  if (glass) {
    opaque_depth_ = target_.depth;  // into storage kept between frames
    auto start = Clock::now();
    filter_through_glass(pass);
    stats.ms_depth += ms_since(start);
    draw_layer(frame.glass, false, [](const SceneObject& o) { return o.material.transparent(); });
  }
  frame.tile_work = std::move(per_object ? total_work : target_.tile_work);  // sized afresh

  // --- shading: ambient everywhere, each light as much as reaches the surface; the opaque
  // layer seen through every transparent surface in front, plus the nearest one's reflection ---
  auto start = Clock::now();
  frame.image = {w, h, std::vector<std::uint8_t>(pixels * 4)};
  std::vector<std::vector<glm::vec3>> world(scene.objects.size());  // vertices, once per frame
  for (std::size_t o = 0; o < scene.objects.size(); ++o) {
    const SceneObject& object = scene.objects[o];
    world[o].reserve(object.mesh->positions.size());
    for (const glm::vec3& p : object.mesh->positions)
      world[o].push_back(glm::vec3(plan.model[o] * glm::vec4(p, 1.0f)));
  }
  const glm::dmat4 inv_vp(plan.inv_view_proj);
  auto shade = [&](const SurfaceLayer& layer, std::span<const float> depth, int x, int y,
                   std::size_t p) {
    const auto o = static_cast<std::size_t>(layer.object[p]);
    const SceneObject& object = scene.objects[o];
    const std::uint32_t* f = &object.mesh->indices[3 * static_cast<std::size_t>(layer.face[p])];
    const glm::vec3& a = world[o][f[0]];
    glm::vec3 n = glm::cross(world[o][f[1]] - a, world[o][f[2]] - a);
    const float len = glm::length(n);
    n = len > 0.0f ? n / len : glm::vec3(0, 1, 0);
    const glm::dvec4 ndc((x + 0.5) / w * 2.0 - 1.0, 1.0 - (y + 0.5) / h * 2.0, double(depth[p]),
                         1.0);
    const glm::dvec4 at = inv_vp * ndc;
    const glm::vec3 pos = glm::vec3(glm::dvec3(at) / at.w);
    const glm::vec3 to_eye = glm::normalize(-pos);  // the eye is the origin
    if (glm::dot(n, to_eye) < 0.0f) n = -n;         // two-sided: light the side we see
    const glm::vec3 albedo = object.material.color;
    glm::vec3 color = scene.ambient * albedo;
    for (std::size_t l = 0; l < lights; ++l) {
      if (layer.shadowed[l][p]) continue;
      const SceneLight& light = scene.lights[l];
      const glm::vec4 lp = plan.lights[l];
      const glm::vec3 to_light =
          glm::normalize(lp.w != 0.0f ? glm::vec3(lp) / lp.w - pos : glm::vec3(lp));
      const float lambert = glm::dot(n, to_light);
      if (lambert <= 0.0f) continue;
      const float spec = std::pow(std::max(0.0f, glm::dot(n, glm::normalize(to_light + to_eye))),
                                  shading::kShininess);
      const glm::vec3 arriving =
          layer.transmitted.empty() ? glm::vec3(1.0f) : layer.transmitted[l][p];
      color += light.color * light.intensity * arriving *
               (albedo * lambert + glm::vec3(shading::kSpecular * spec));
    }
    return color;
  };
  const std::span<const float> glass_depth(target_.depth);
  const std::span<const float> surface_depth =
      glass ? std::span<const float>(opaque_depth_) : glass_depth;
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      const std::size_t p = static_cast<std::size_t>(y) * w + x;
      glm::vec3 color =
          frame.object[p] >= 0 ? shade(frame, surface_depth, x, y, p) : shading::background(y, h);
      if (glass) color *= glm::exp(eye_log_[p]);  // through every transparent surface in front
      if (glass && frame.glass.object[p] >= 0) {
        const Material& m = scene.objects[static_cast<std::size_t>(frame.glass.object[p])].material;
        color += m.opacity * shade(frame.glass, glass_depth, x, y, p);
      }
      for (int k = 0; k < 3; ++k) frame.image.rgba[4 * p + k] = shading::to_srgb8(color[k]);
      frame.image.rgba[4 * p + 3] = 255;
    }
  });
  stats.ms_shade = ms_since(start);

  if (options.show_volumes) overlay_volumes(frame.image, scene, plan, volumes_);
  return frame;
}

}  // namespace shadowvol
