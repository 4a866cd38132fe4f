#include "render/cc_shadow_volumes.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>

#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>
#include <glm/vec4.hpp>

#include "accel/slices.h"

namespace shadowvol {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

std::array<glm::dvec3, 8> corners(const glm::dvec3& lo, const glm::dvec3& hi) {
  std::array<glm::dvec3, 8> c;
  for (int i = 0; i < 8; ++i)
    c[i] = {i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z};
  return c;
}

// Whether any part of the box may lie in the view frustum: not when all eight corners lie
// outside one of its planes (core/projection.h: x, y in [-w, w], z <= w; no far plane).
bool in_frustum(const Box& box, const glm::dmat4& view_proj) {
  if (box.empty()) return false;
  std::array<int, 5> outside{};
  for (const glm::dvec3& corner : corners(box.lo, box.hi)) {
    const glm::dvec4 c = view_proj * glm::dvec4(corner, 1.0);
    outside[0] += c.x > c.w;
    outside[1] += c.x < -c.w;
    outside[2] += c.y > c.w;
    outside[3] += c.y < -c.w;
    outside[4] += c.z > c.w;
  }
  return std::none_of(outside.begin(), outside.end(), [](int n) { return n == 8; });
}

// An object-space box's bounds eye-relative (its eight corners through the model, in double).
Box transformed(const glm::vec3& lo, const glm::vec3& hi, const glm::dmat4& model) {
  if (!(lo.x <= hi.x)) return {glm::dvec3(INFINITY), glm::dvec3(-INFINITY)};
  Box box{glm::dvec3(INFINITY), glm::dvec3(-INFINITY)};
  for (const glm::dvec3& c : corners(glm::dvec3(lo), glm::dvec3(hi))) {
    const glm::dvec3 p(model * glm::dvec4(c, 1.0));
    box.lo = glm::min(box.lo, p), box.hi = glm::max(box.hi, p);
  }
  return box;
}

// The float at or below d, and at or above it: an interval stored no narrower than computed.
float round_down(double d) {
  float f = static_cast<float>(d);
  return double(f) > d ? std::nextafter(f, -INFINITY) : f;
}
float round_up(double d) {
  float f = static_cast<float>(d);
  return double(f) < d ? std::nextafter(f, INFINITY) : f;
}

// V's vertices for a sub-object of `faces` faces (§3.2.1: 2C + 2S): about half its faces face
// the light, three cap vertices each (C = 1.5 F), and a silhouette's length grows as the square
// root of a surface's faces (a sphere of F faces shows about sqrt(2 F) edges: S = 2 sqrt(2 F)).
double interval_vertices(std::size_t faces) {
  const double f = static_cast<double>(faces);
  return 2.0 * 1.5 * f + 2.0 * 2.0 * std::sqrt(2.0 * f);
}

}  // namespace

std::array<glm::dvec3, 3> CcShadowVolumes::face(const Scene& scene, std::size_t o,
                                                std::uint32_t f) const {
  const std::uint32_t* v = &scene.objects[o].topology->face_vertices[3 * std::size_t{f}];
  const glm::dvec3* p = world(o);
  return {p[v[0]], p[v[1]], p[v[2]]};
}

void CcShadowVolumes::split_objects(const Scene& scene, const FramePlan& plan, bool sub_objects) {
  const std::size_t objects = plan.objects.size();
  Box scene_box{glm::dvec3(INFINITY), glm::dvec3(-INFINITY)};
  for (const Box& b : boxes_)
    if (!b.empty())
      scene_box.lo = glm::min(scene_box.lo, b.lo), scene_box.hi = glm::max(scene_box.hi, b.hi);
  const glm::dvec3 extent = scene_box.hi - scene_box.lo;
  const double longest = scene_box.empty() ? 0.0 : std::max({extent.x, extent.y, extent.z});
  // A power of two, so that the cells (and the cached splits) hold still while the scene's
  // bounds move a little from frame to frame.
  const double cell =
      longest > 0.0 ? std::exp2(std::floor(std::log2(longest / kCellsAcross))) : 0.0;
  split_cache_.resize(objects);
  leaves_.resize(objects);
  leaf_caster_.clear();
  leaf_receiver_.clear();
  leaf_object_.clear();
  leaf_faces_.clear();
  for (std::size_t o = 0; o < objects; ++o) {
    const Box& box = boxes_[o];
    const glm::dvec3 size = box.empty() ? glm::dvec3(0.0) : box.hi - box.lo;
    Leaves& leaves = leaves_[o];
    leaves = {leaf_caster_.size(), 1, nullptr};
    if (sub_objects && cell > 0.0 && std::max({size.x, size.y, size.z}) > longest / kLargeAcross) {
      const glm::dmat4 model(plan.objects[o].model);
      const double scale =
          std::max({glm::length(glm::dvec3(model[0])), glm::length(glm::dvec3(model[1])),
                    glm::length(glm::dvec3(model[2]))});
      const Topology& topology = *scene.objects[o].topology;
      const auto object_cell = static_cast<float>(cell / scale);
      Cached& cached = split_cache_[o];
      if (!cached.split || cached.topology != &topology || cached.split->cell != object_cell) {
        cached.topology = &topology;
        cached.split =
            std::make_unique<SubObjects>(split_sub_objects(topology, object_cell, kMaxSubObjects));
      }
      if (cached.split->leaves.size() > 1) {
        leaves.count = cached.split->leaves.size();
        leaves.split = cached.split.get();
        for (const SubObjects::Leaf& leaf : cached.split->leaves) {
          leaf_caster_.push_back(transformed(leaf.caster_lo, leaf.caster_hi, model));
          leaf_receiver_.push_back(transformed(leaf.receiver_lo, leaf.receiver_hi, model));
          leaf_object_.push_back(o);
          leaf_faces_.push_back(leaf.faces);
        }
        continue;
      }
    }
    leaf_caster_.push_back(box);
    leaf_receiver_.push_back(box);
    leaf_object_.push_back(o);
    leaf_faces_.push_back(scene.objects[o].topology->face_count());
  }
}

void CcShadowVolumes::find_receivers(const Scene& scene, const RenderOptions& options,
                                     const FramePlan& plan, const SurfaceLayer* opaque) {
  const std::size_t objects = plan.objects.size();
  const glm::dmat4 view_proj(plan.view_proj);
  receiver_.assign(objects, 0);
  for (std::size_t o = 0; o < objects; ++o) {
    const bool visible = in_frustum(boxes_[o], view_proj);
    receiver_[o] = visible && (options.cull != Cull::occlusion || plan.transparent(o));
  }
  edge_on_.clear();
  if (!opaque) {
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

void CcShadowVolumes::apply(const Scene& scene, const RenderOptions& options, FramePlan& plan,
                            const SurfaceLayer* opaque, const VolumeCosts& costs, bool sub_objects,
                            FrameStats& stats) {
  if (options.cull == Cull::none && options.clamp == Clamp::none) return;
  const auto start = Clock::now();
  const std::size_t objects = plan.objects.size();
  boxes_.resize(objects);
  for (std::size_t o = 0; o < objects; ++o)
    boxes_[o] = {glm::dvec3(plan.objects[o].lo), glm::dvec3(plan.objects[o].hi)};
  // The vertices, which only the occlusion tests and the receiver triangles draw.
  const bool vertices = needs_ids(options);
  world_first_.assign(objects + 1, 0);
  for (std::size_t o = 0; vertices && o < objects; ++o)
    world_first_[o + 1] = world_first_[o] + scene.objects[o].topology->positions.size();
  world_.resize(world_first_[objects]);
  for (std::size_t o = 0; vertices && o < objects; ++o) {
    const glm::dmat4 model(plan.objects[o].model);
    const std::vector<glm::vec3>& positions = scene.objects[o].topology->positions;
    for (std::size_t v = 0; v < positions.size(); ++v)
      world_[world_first_[o] + v] = glm::dvec3(model * glm::dvec4(glm::dvec3(positions[v]), 1.0));
  }
  find_receivers(scene, options, plan, needs_ids(options) ? opaque : nullptr);
  split_objects(scene, plan, sub_objects);
  receiver_boxes_.clear();
  for (std::size_t o = 0; o < objects; ++o)
    if (receiver_[o]) receiver_boxes_.push_back(boxes_[o]);
  clampers_.resize(plan.lights.size());
  // The light views and their depths are the culling's where culling by occlusion draws them,
  // or culling by the frustum needs the views alone; else discrete clamping's, which needs them.
  const bool culling_owns = options.cull == Cull::occlusion ||
                            (options.cull == Cull::frustum && !clamps_discrete(options.clamp));
  double& shared_ms = culling_owns ? stats.ms_cull : stats.ms_clamp;
  shared_ms += ms_since(start);
  for (std::size_t l = 0; l < plan.lights.size(); ++l) {
    const auto light_start = Clock::now();
    cull_light(scene, options, plan, l, stats);
    shared_ms += ms_since(light_start);
    const auto clamp_start = Clock::now();
    for (std::size_t o = 0; o < objects; ++o) {
      const Leaves& leaves = leaves_[o];
      bool any = false;
      for (std::size_t k = leaves.first; k < leaves.first + leaves.count; ++k)
        any = any || leaf_kept_[k];
      VolumePlan& v = plan.volume(l, o);
      v.culled = !any;
    }
    if (clamps_continuous(options.clamp)) clamp_continuously(options, plan, l, costs, stats);
    write_plan(options, plan, l, stats);
    if (clamps_discrete(options.clamp)) clamp_discretely(options, plan, l, stats);
    if (options.clamp != Clamp::none)
      stats.ms_clamp += ms_since(clamp_start);
    else
      stats.ms_cull += ms_since(clamp_start);
  }
}

void CcShadowVolumes::cull_light(const Scene& scene, const RenderOptions& options,
                                 const FramePlan& plan, std::size_t l, FrameStats& stats) {
  const std::size_t objects = plan.objects.size();
  const bool occlusion = options.cull == Cull::occlusion;
  const bool discrete = clamps_discrete(options.clamp);
  const bool depths = occlusion || discrete;
  const Slices slices = discrete ? make_slices(plan.view_proj, plan.lights[l], options.width,
                                               options.height, options.slices)
                                 : Slices{};
  views_.fit(glm::dvec4(plan.lights[l]), receiver_boxes_, options.light_view_size, depths,
             discrete ? options.slices : 0);
  stats.light_views += static_cast<int>(views_.view_count());
  if (depths) {
    if (occlusion) {
      occluders_.clear();
      for (std::size_t o = 0; o < objects; ++o)
        if (!plan.transparent(o) && views_.touches(boxes_[o])) {
          const Topology& topology = *scene.objects[o].topology;
          occluders_.push_back({&topology, {world(o), topology.positions.size()}, boxes_[o]});
        }
      views_.add_occluders(occluders_);
    }
    // Each sample into the strips of the image its pixel lies in (discrete clamping).
    const int width = options.width;
    sample_strips_.resize(discrete ? samples_.size() : 0);
    tbb::parallel_for(std::size_t{0}, sample_strips_.size(), [&](std::size_t p) {
      const double x = (static_cast<double>(p % width) + 0.5) / width * 2.0 - 1.0;
      const double y = 1.0 - (static_cast<double>(p / width) + 0.5) / options.height * 2.0;
      sample_strips_[p] = slices.of(slices.across.x * x + slices.across.y * y);
    });
    views_.add_receiver_points(samples_, sample_strips_);
    const glm::dmat4 view_proj(plan.view_proj);
    auto add_face = [&](std::size_t o, std::uint32_t f) {
      const std::array<glm::dvec3, 3> v = face(scene, o, f);
      LayerRange strips{};
      if (discrete) {  // the strips its image may touch: all where it reaches behind the eye
        double lo = INFINITY, hi = -INFINITY;
        for (const glm::dvec3& p : v) {
          const glm::dvec4 c = view_proj * glm::dvec4(p, 1.0);
          const double s = c.w > 0.0 ? (slices.across.x * c.x + slices.across.y * c.y) / c.w
                                     : (c.w == 0.0 ? 0.0 : NAN);
          if (!(c.w > 0.0))
            lo = -INFINITY, hi = INFINITY;
          else
            lo = std::min(lo, s), hi = std::max(hi, s);
        }
        strips = slices.of(std::max(lo, -1e9), std::min(hi, 1e9));
      }
      views_.add_receiver_triangle(v[0], v[1], v[2], strips);
    };
    for (const auto& [o, f] : edge_on_) add_face(o, f);
    for (std::size_t o = 0; o < objects; ++o)
      if (plan.transparent(o) && receiver_[o])
        for (std::uint32_t f = 0; f < scene.objects[o].topology->face_count(); ++f) add_face(o, f);
  }
  views_.finish(occlusion, depths);
  // Each sub-object's verdict; an object is culled where all of its are.
  const std::size_t leaves = leaf_caster_.size();
  leaf_kept_.assign(leaves, 0);
  for (std::size_t o = 0; o < objects; ++o) {
    if (plan.volume(l, o).culled) continue;  // casts nothing of this light: none of it is kept
    const Leaves& range = leaves_[o];
    int kept = 0, unseen = 0;
    for (std::size_t k = range.first; k < range.first + range.count; ++k) {
      const Box& box = leaf_caster_[k];
      BoxVisibility seen = BoxVisibility::kept;
      if (box.empty())
        seen = BoxVisibility::unseen;  // casts nothing
      else if (options.cull == Cull::frustum)
        seen = views_.touches(box) ? BoxVisibility::kept : BoxVisibility::unseen;
      else if (occlusion)
        seen = views_.test(box, stats.cull_queries);
      leaf_kept_[k] = seen == BoxVisibility::kept;
      kept += leaf_kept_[k];
      unseen += seen == BoxVisibility::unseen && !box.empty();
    }
    if (options.cull == Cull::none) continue;
    if (kept == 0) {
      ++stats.culled_lights[o];
      (unseen > 0 ? stats.casters_culled_unseen : stats.casters_culled_in_shadow) += 1;
    } else if (range.split) {
      for (std::size_t k = range.first; k < range.first + range.count; ++k)
        stats.sub_objects_culled += !leaf_kept_[k] && !leaf_caster_[k].empty();
    }
  }
}

void CcShadowVolumes::clamp_continuously(const RenderOptions& options, const FramePlan& plan,
                                         std::size_t l, const VolumeCosts& costs,
                                         FrameStats& stats) {
  const std::size_t objects = plan.objects.size(), leaves = leaf_caster_.size();
  leaf_clamped_.assign(leaves, 0);
  leaf_offsets_.assign(2 * leaves, 0);
  leaf_intervals_.clear();
  const std::size_t views = views_.view_count();
  if (views == 0) return;  // no receivers: every volume is culled or drawn whole
  std::vector<ContinuousClamping>& clampers = clampers_[l];
  if (clampers.size() != views) clampers.assign(views, {});
  object_view_.resize(objects);
  for (std::size_t o = 0; o < objects; ++o)
    object_view_[o] = boxes_[o].empty() ? 0 : views_.view_of((boxes_[o].lo + boxes_[o].hi) * 0.5);
  const glm::dmat4 view_proj(plan.view_proj);
  const double width = options.width, height = options.height;
  // The largest coordinate of the volumes' float arithmetic: an object's own coordinates reach
  // about its eye-relative box plus its translation, and the model adds the translation again.
  double float_magnitude = 0.0;
  for (std::size_t o = 0; o < objects; ++o) {
    if (boxes_[o].empty()) continue;
    const double box = std::max(glm::length(boxes_[o].lo), glm::length(boxes_[o].hi));
    float_magnitude = std::max(
        float_magnitude, box + 2.0 * glm::length(glm::dvec3(plan.objects[o].model[3])));
  }
  ContinuousClamping::Stats clamp_stats;
  for (std::size_t view = 0; view < views; ++view) {
    items_.resize(leaves);
    double nearest = INFINITY, farthest = -INFINITY;
    for (std::size_t k = 0; k < leaves; ++k) {
      const std::size_t o = leaf_object_[k];
      ContinuousClamping::Item& item = items_[k];
      item.casts = leaf_kept_[k] && object_view_[o] == view &&
                   views_.light_box(view, leaf_caster_[k], true, item.caster);
      item.receives =
          receiver_[o] && views_.light_box(view, leaf_receiver_[k], false, item.receiver);
      item.interval_vertices = interval_vertices(leaf_faces_[k]);
      if (item.casts)
        nearest = std::min(nearest, item.caster.z0), farthest = std::max(farthest, item.caster.z1);
      if (item.receives)
        nearest = std::min(nearest, item.receiver.z0),
        farthest = std::max(farthest, item.receiver.z1);
    }
    if (!(nearest <= farthest)) continue;
    const double margin =
        std::max(kDepthMargin * std::max(farthest - nearest, 1e-30),
                 kFloatSlack * (float_magnitude + std::abs(views_.depth_plane(view).w) +
                                std::max(std::abs(nearest), std::abs(farthest))));
    // R: the gap's area on the image, from its box in light space (the caster's rectangle swept
    // over the gap's depths), times r. The whole image where it reaches behind the eye.
    auto gap_cost = [&](std::size_t k, double from, double to) {
      const LightViews::LightBox& b = items_[k].caster;
      double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
      bool behind = false;
      for (int i = 0; i < 8; ++i) {
        const glm::dvec3 p =
            views_.point(view, i & 1 ? b.u1 : b.u0, i & 2 ? b.v1 : b.v0, i & 4 ? to : from);
        const glm::dvec4 c = view_proj * glm::dvec4(p, 1.0);
        if (!(c.w > 0.0)) behind = true;
        x0 = std::min(x0, c.x / c.w), x1 = std::max(x1, c.x / c.w);
        y0 = std::min(y0, c.y / c.w), y1 = std::max(y1, c.y / c.w);
      }
      const double area =
          behind ? width * height
                 : std::max(0.0, std::min(x1, 1.0) - std::max(x0, -1.0)) * 0.5 * width *
                       std::max(0.0, std::min(y1, 1.0) - std::max(y0, -1.0)) * 0.5 * height;
      return area * costs.ms_per_pixel;
    };
    clampers[view].clamp(items_, margin, costs.ms_per_vertex, gap_cost, item_offsets_,
                         item_intervals_, clamp_stats);
    for (std::size_t k = 0; k < leaves; ++k) {
      if (!items_[k].casts) continue;
      leaf_clamped_[k] = 1;
      leaf_offsets_[2 * k] = static_cast<std::uint32_t>(leaf_intervals_.size());
      leaf_intervals_.insert(leaf_intervals_.end(), item_intervals_.begin() + item_offsets_[k],
                             item_intervals_.begin() + item_offsets_[k + 1]);
      leaf_offsets_[2 * k + 1] = static_cast<std::uint32_t>(leaf_intervals_.size());
    }
  }
  stats.clamp_pairs += clamp_stats.pairs;
  stats.clamp_swaps += clamp_stats.swaps;
  stats.intervals_merged_by_cost += clamp_stats.merged_by_cost;
}

void CcShadowVolumes::write_plan(const RenderOptions& options, FramePlan& plan, std::size_t l,
                                 FrameStats& stats) {
  const bool continuous = clamps_continuous(options.clamp);
  for (std::size_t o = 0; o < plan.objects.size(); ++o) {
    VolumePlan& v = plan.volume(l, o);
    if (v.culled) continue;
    const Leaves& range = leaves_[o];
    bool partial = false, clamped = false;
    for (std::size_t k = range.first; k < range.first + range.count; ++k) {
      partial = partial || (!leaf_kept_[k] && !leaf_caster_[k].empty());
      clamped = clamped || (continuous && leaf_clamped_[k]);
    }
    if (!partial && !clamped) continue;  // drawn whole
    VolumeClamp& clamp = v.clamp;
    v.part_zfail.clear();  // a clamped volume is counted by its rule whole
    clamp.depth = glm::vec4(0.0f);
    if (clamped) {  // depth along its view's axis, in the object's own space
      const glm::dvec4 plane = views_.depth_plane(object_view_[o]);
      clamp.depth = glm::vec4(glm::transpose(glm::dmat4(plan.objects[o].model)) * plane);
    }
    using Span = std::span<const std::uint32_t>;
    clamp.face_leaf = range.split ? Span(range.split->face_leaf) : Span{};
    clamp.vertex_leaf_offsets = range.split ? Span(range.split->vertex_leaf_offsets) : Span{};
    clamp.vertex_leaves = range.split ? Span(range.split->vertex_leaves) : Span{};
    clamp.offsets.assign(1, 0);
    clamp.intervals.clear();
    for (std::size_t k = range.first; k < range.first + range.count; ++k) {
      if (!leaf_kept_[k]) {
      } else if (continuous && leaf_clamped_[k]) {
        for (std::uint32_t i = leaf_offsets_[2 * k]; i < leaf_offsets_[2 * k + 1]; ++i) {
          const Interval& interval = leaf_intervals_[i];
          clamp.intervals.push_back(
              {interval.begin == -INFINITY ? -INFINITY : round_down(interval.begin),
               round_up(interval.end)});
        }
      } else {
        clamp.intervals.push_back({-INFINITY, INFINITY});
      }
      clamp.offsets.push_back(static_cast<std::uint32_t>(clamp.intervals.size()));
    }
    v.build.caps = true;  // its segments' caps
    stats.volumes_clamped += clamped;
  }
}

void CcShadowVolumes::clamp_discretely(const RenderOptions& options, FramePlan& plan, std::size_t l,
                                       FrameStats& stats) {
  const int count = options.slices;
  const Slices slices =
      make_slices(plan.view_proj, plan.lights[l], options.width, options.height, count);
  for (std::size_t o = 0; o < plan.objects.size(); ++o) {
    VolumePlan& v = plan.volume(l, o);
    if (v.culled) continue;
    const Leaves& range = leaves_[o];
    strips_.assign(static_cast<std::size_t>(count), 0);
    for (std::size_t k = range.first; k < range.first + range.count; ++k) {
      if (!leaf_kept_[k]) continue;
      for (int s = 0; s < count; ++s)
        if (!strips_[s]) strips_[s] = views_.kept_in_layer(leaf_caster_[k], s, stats.slice_queries);
    }
    // Runs of occupied strips: the caps between them would cover no pixel (§3.3).
    v.strips.clear();
    for (int s = 0; s < count;) {
      if (!strips_[s]) {
        ++s;
        continue;
      }
      int last = s;
      while (last + 1 < count && strips_[last + 1]) ++last;
      v.strips.push_back(slices.strip(s, last));
      s = last + 1;
    }
    if (v.strips.empty()) {
      v.culled = true;
      ++stats.volumes_clamped_away;
    } else if (v.strips.size() == 1 && v.strips[0].whole()) {
      v.strips.clear();  // every strip: the whole image
    }
  }
}

}  // namespace shadowvol
