#include "soft/soft_backend.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <span>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <glm/exponential.hpp>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "accel/light_reach.h"
#include "accel/near_plane.h"
#include "render/shading.h"
#include "render/volume_costs.h"

namespace shadowvol::soft {
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

// Clip-space triangles of primitive p of a list (a quad split by kQuadTriangles) and their
// weights.
void clip_primitive(const PrimitiveList& list, int corners, std::size_t p, const glm::mat4& mvp,
                    int sign, std::vector<glm::vec4>& tris, std::vector<std::int32_t>& weights) {
  const glm::vec4* v = &list.vertices[p * static_cast<std::size_t>(corners)];
  for (int t = 0; t < (corners == kQuadCorners ? 2 : 1); ++t) {
    for (int k = 0; k < 3; ++k) tris.push_back(mvp * v[kQuadTriangles[3 * t + k]]);
    weights.push_back(sign * list.weights[p]);
  }
}

// The same for every primitive of the list.
void clip_volume(const PrimitiveList& list, int corners, const glm::mat4& mvp, int sign,
                 std::vector<glm::vec4>& tris, std::vector<std::int32_t>& weights) {
  for (std::size_t p = 0; p < list.size(); ++p)
    clip_primitive(list, corners, p, mvp, sign, tris, weights);
}

// Calls add(list, corners, cap) for each primitive list of a volume its plan counts: first what
// counts in every tile (the sides, a transparent caster's light caps, a clamped volume's dark caps,
// which lie among the receivers), then the caps that count only where z-fail does (cap = 1).
template <class Add>
void for_each_counted_list(const VolumeBuffer& v, const VolumePlan& vp, Add&& add) {
  add(v.sides, kQuadCorners, 0u);
  if (vp.light_caps_everywhere) add(v.light_caps, kTriangleCorners, 0u);
  if (vp.dark_caps_everywhere()) add(v.dark_caps, kTriangleCorners, 0u);
  if (vp.counts_caps) {
    if (!vp.light_caps_everywhere) add(v.light_caps, kTriangleCorners, 1u);
    if (!vp.dark_caps_everywhere()) add(v.dark_caps, kTriangleCorners, 1u);
  }
}

// Laine 2005 §7's depth bounds (VolumePlan::depth_bounds), within the depths the volume's own
// clip-space triangles reach: a clamped or bounded volume's segments often lie in a narrow range
// of them.
raster::DepthBounds counted_bounds(const VolumePlan& vp, std::span<const glm::vec4> triangles) {
  const raster::DepthBounds reached = raster::reached_depths(triangles);
  return {std::max(vp.depth_bounds.zmin, reached.zmin),
          std::min(vp.depth_bounds.zmax, reached.zmax)};
}

}  // namespace

Renderer soft_renderer() { return Renderer(std::make_unique<SoftBackend>()); }

void SoftBackend::Grouped::group(std::span<const glm::vec4> triangles,
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

void SoftBackend::begin_frame(const FrameInputs& inputs) {
  in_ = &inputs;
  answers_.clear();
  const RenderOptions& options = inputs.options;
  const int w = options.width, h = options.height;
  if (target_.width != w || target_.height != h) target_ = raster::Target(w, h);
  // Per object, the tile work moves out of the target after each volume, into the object's
  // share and the frame's total.
  target_.tile_work.assign(options.tile_work ? target_.tile_depth.size() : 0, raster::TileWork{});
  const bool per_object = options.tile_work && options.tile_work_per_object;
  total_work_.assign(per_object ? target_.tile_work.size() : 0, raster::TileWork{});
  std::vector<std::vector<raster::TileWork>>& shares = inputs.frame.object_tile_work;
  shares.resize(per_object ? inputs.scene.objects.size() : 0);
  for (std::vector<raster::TileWork>& share : shares)
    share.assign(target_.tile_work.size(), raster::TileWork{});
}

void SoftBackend::begin_depth(Layer layer) {
  layer_ = layer;
  if (layer == Layer::opaque) target_.clear_depth();
  std::fill(target_.id.begin(), target_.id.end(), raster::Target::kNoId);
}

void SoftBackend::draw_depth(std::span<const std::uint32_t> objects) {
  const Scene& scene = in_->scene;
  const FramePlan& plan = in_->plan;
  std::size_t vertices = 0, triangles = 0;
  bool culls = false;
  for (const std::uint32_t o : objects) {
    assert(plan.transparent(o) == (layer_ == Layer::glass));
    vertices += scene.objects[o].mesh->positions.size();
    triangles += scene.objects[o].mesh->triangle_count();
    culls = culls || plan.objects[o].back_faces_hidden;
  }
  clip_vertices_.resize(vertices);
  indices_.resize(3 * triangles);
  ids_.resize(triangles);
  face_cull_.assign(culls ? triangles : 0, raster::FaceCull::none);
  std::size_t first_vertex = 0, first_triangle = 0;  // the object's in the draw
  for (const std::uint32_t o : objects) {
    const Mesh& mesh = *scene.objects[o].mesh;
    const Topology& topology = *scene.objects[o].topology;
    const ObjectPlan& op = plan.objects[o];
    const glm::mat4 mvp = plan.view_proj * op.model;
    // Each vertex once, then each triangle's indices into the draw's vertices, in parallel for
    // large meshes.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.positions.size(), 4096),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t v = r.begin(); v < r.end(); ++v)
                          clip_vertices_[first_vertex + v] =
                              mvp * glm::vec4(mesh.positions[v], 1.0f);
                      });
    // A mirroring transform shows the outward faces clockwise: its back faces look front.
    const raster::FaceCull cull = !op.back_faces_hidden ? raster::FaceCull::none
                                  : op.weight_sign > 0  ? raster::FaceCull::back
                                                        : raster::FaceCull::front;
    const auto base = static_cast<std::uint32_t>(first_vertex);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.triangle_count(), 4096),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t f = r.begin(); f < r.end(); ++f) {
                          const std::size_t t = first_triangle + f;
                          for (std::size_t k = 0; k < 3; ++k)
                            indices_[3 * t + k] = base + mesh.indices[3 * f + k];
                          ids_[t] = op.first_id + static_cast<std::uint32_t>(f);
                          if (culls && topology.part_wound_outwards[topology.part_of_face(f)])
                            face_cull_[t] = cull;
                        }
                      });
    first_vertex += mesh.positions.size();
    first_triangle += mesh.triangle_count();
  }
  raster::draw_depth(target_, clip_vertices_, indices_, ids_, in_->frame.stats.depth, face_cull_);
}

void SoftBackend::end_depth() { target_.update_tile_depth(); }

FrameBackend::QueryId SoftBackend::issue_query(std::span<const glm::vec4> triangles,
                                               bool surfaces_only) {
  tris_.clear();
  for (const glm::vec4& v : triangles) tris_.push_back(in_->plan.view_proj * v);
  // A stored depth of exactly 0 is the background (infinity): no surface.
  const raster::DepthBounds bounds{surfaces_only ? std::numeric_limits<float>::denorm_min() : 0.0f,
                                   1.0f};
  raster::Counters counters;
  answers_.push_back(raster::query(target_, tris_, bounds, counters, true) > 0);
  return static_cast<QueryId>(answers_.size() - 1);
}

void SoftBackend::read_ids(Layer, SurfaceLayer& out) {
  const std::size_t pixels = target_.id.size();
  out.object.resize(pixels);
  out.face.resize(pixels);
  const FramePlan& plan = in_->plan;
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, pixels, 4096),
      [&](const tbb::blocked_range<std::size_t>& r) {
        // Neighbouring pixels mostly show one object: its id range is tried first.
        std::uint32_t first = 1, end = 0;
        std::int32_t object = -1;
        for (std::size_t p = r.begin(); p < r.end(); ++p) {
          const std::uint32_t id = target_.id[p];
          if (id >= plan.id_count) {  // kNoId: no surface
            out.object[p] = -1, out.face[p] = 0;
            continue;
          }
          if (id < first || id >= end) {  // the object's ids: up to the next one's first
            object = plan.object_of(id).first;
            const auto o = static_cast<std::size_t>(object);
            first = plan.objects[o].first_id;
            end = o + 1 < plan.objects.size() ? plan.objects[o + 1].first_id : plan.id_count;
          }
          out.object[p] = object, out.face[p] = id - first;
        }
      });
}

void SoftBackend::begin_mask(std::size_t l) { target_.scissor = in_->plan.reach[l].scissor; }

void SoftBackend::begin_light_map(std::size_t l) {
  log_light_.assign(target_.count.size(), glm::vec3(0.0f));
  target_.scissor = in_->plan.reach[l].scissor;
}

void SoftBackend::end_counts() { target_.scissor = {0, 0, target_.width, target_.height}; }

void SoftBackend::end_group(std::size_t g) {
  target_.take_counts_into(log_light_, in_->plan.glass[g].log_transmittance);
}

// A light of limited range counted only within its scissor: the rest of its mask is beyond it.
void SoftBackend::read_mask(std::size_t l, SurfaceLayer& layer) {
  const FramePlan& plan = in_->plan;
  target_.take_nonzero_counts(layer.shadowed[l], plan.reach[l].scissor);
  mark_beyond_reach(layer.shadowed[l], target_.depth, plan.inv_view_proj, plan.lights[l],
                    in_->scene.lights[l].range, plan.reach[l], target_.width, target_.height);
}

void SoftBackend::read_light_map(std::size_t l, SurfaceLayer& layer) {
  std::vector<glm::vec3>& light = layer.transmitted[l];
  const std::vector<std::uint8_t>& shadowed = layer.shadowed[l];
  tbb::parallel_for(std::size_t{0}, light.size(), [&](std::size_t p) {
    light[p] = shadowed[p] ? glm::vec3(0.0f) : glm::exp(log_light_[p]);
  });
}

void SoftBackend::count_volume(std::size_t l, std::size_t o) {
  const FramePlan& plan = in_->plan;
  const VolumePlan& vp = plan.volume(l, o);
  const ObjectPlan& op = plan.objects[o];
  FrameStats& stats = in_->frame.stats;
  const VolumeBuffer& v = in_->volumes.volume(l, o);
  const std::vector<PartSplit>& splits = vp.split;
  const bool by_part = vp.by_part();
  const glm::mat4 mvp = plan.view_proj * op.model;
  const int sign = op.weight_sign;
  tris_.clear();
  weights_.clear();
  keys_.clear();
  // Under a split plane, each triangle's key: 2 * its part (0 for a volume split whole), plus 1
  // for a cap, which counts only where z-fail does (Laine 2005 §3.3). Under rules per part, its
  // part's rule (1 for z-fail), a z-pass part's caps left out.
  const bool part_rules = vp.by_part_rule();
  auto add = [&](const PrimitiveList& list, int corners, std::uint32_t cap) {
    const int per = corners == kQuadCorners ? 2 : 1;
    if (part_rules) {
      for (std::size_t p = 0; p < list.size(); ++p) {
        const std::uint8_t zfail = vp.part_zfail[list.parts[p]];
        if (cap && !zfail) continue;
        clip_primitive(list, corners, p, mvp, sign, tris_, weights_);
        keys_.insert(keys_.end(), per, zfail);
      }
      return;
    }
    clip_volume(list, corners, mvp, sign, tris_, weights_);
    if (splits.empty()) return;
    for (std::size_t p = 0; p < list.size(); ++p)
      keys_.insert(keys_.end(), per, 2 * (by_part ? list.parts[p] : 0) + cap);
  };
  for_each_counted_list(v, vp, add);
  // Pre-filled z-pass starts inside the volume: a pixel beyond all of it must still count its way
  // out, so no far bound.
  raster::DepthBounds bounds = counted_bounds(vp, tris_);
  if (vp.prefill) {  // ZP+: where z-pass counts, start from the near plane's count
    bounds.zmin = 0.0f;
    prefill_tris_.clear();
    prefill_weights_.clear();
    prefill_keys_.clear();
    // From the whole volume: what the count pass draws, and for a while the caps it leaves out.
    const std::size_t counted = weights_.size();
    if (!vp.counts_caps) {
      if (!vp.light_caps_everywhere)
        clip_volume(v.light_caps, kTriangleCorners, mvp, sign, tris_, weights_);
      if (!vp.dark_caps_everywhere())
        clip_volume(v.dark_caps, kTriangleCorners, mvp, sign, tris_, weights_);
    }
    prefill_parts_.clear();
    for (const std::uint32_t key : keys_) prefill_parts_.push_back(key / 2);  // keys: 2 part + cap
    append_near_plane_prefill(tris_, weights_, prefill_parts_, prefill_tris_, prefill_weights_,
                              splits.empty() ? nullptr : &prefill_keys_, prefill_apexes_);
    tris_.resize(3 * counted);
    weights_.resize(counted);
  }
  // Each draw once per strip of discrete clamping (or once), and measured for its fill where
  // asked (CountRule::fill: the pixels it touches with the depth test off).
  static const std::vector<raster::ScreenStrip> kWhole(1);
  const std::vector<raster::ScreenStrip>& strips = vp.strips.empty() ? kWhole : vp.strips;
  auto draw = [&](std::span<const glm::vec4> triangles, std::span<const std::int32_t> weights,
                  raster::CountRule rule, raster::DepthBounds bounds,
                  const raster::SplitPlane& split) {
    for (const raster::ScreenStrip& strip : strips) {
      const std::uint64_t writes = stats.counts.count_updates;
      raster::draw_counts(target_, triangles, weights, rule, stats.counts, bounds, split, strip);
      if (rule == raster::CountRule::prefill) continue;
      stats.stencil_writes += stats.counts.count_updates - writes;
      if (!in_->options.count_fill) continue;
      raster::Counters fill;
      const auto measuring = Clock::now();
      raster::draw_counts(target_, triangles, weights, raster::CountRule::fill, fill, {},
                          {split.plane, split.tiles}, strip);
      stats.fill += fill.pixels_processed;
      const double ms = ms_since(measuring);  // not the frame's work
      stats.ms_counts -= ms;
      stats.ms_measuring += ms;
    }
  };
  if (part_rules) {  // never pre-filled: only Method::automatic gives rules per part
    volume_groups_.group(tris_, weights_, keys_, 2);
    for (std::size_t zfail = 0; zfail < 2; ++zfail)
      draw(volume_groups_.triangles_of(zfail, zfail + 1),
           volume_groups_.weights_of(zfail, zfail + 1),
           zfail ? raster::CountRule::zfail : raster::CountRule::zpass, bounds, {});
  } else if (splits.empty()) {
    if (vp.prefill) draw(prefill_tris_, prefill_weights_, raster::CountRule::prefill, {}, {});
    draw(tris_, weights_,
         vp.rule == VolumeRule::zfail ? raster::CountRule::zfail : raster::CountRule::zpass, bounds,
         {});
  } else {
    volume_groups_.group(tris_, weights_, keys_, 2 * splits.size());
    if (vp.prefill) {
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
      if (vp.prefill)
        draw(prefill_groups_.triangles_of(p, p + 1), prefill_groups_.weights_of(p, p + 1),
             raster::CountRule::prefill, {}, {plane, raster::SplitTiles::zpass_only});
      // Laine 2005 §3.3: the sides in every tile, the caps only where z-fail counts.
      draw(everywhere, volume_groups_.weights_of(2 * p, 2 * p + 1), raster::CountRule::split,
           bounds, {plane});
      draw(caps, volume_groups_.weights_of(2 * p + 1, 2 * p + 2), raster::CountRule::split, bounds,
           {plane, raster::SplitTiles::zfail_only});
    }
  }
  if (!total_work_.empty()) {  // bookkeeping, left out of the count passes' time
    const auto bookkeeping = Clock::now();
    for (std::size_t t = 0; t < total_work_.size(); ++t) {
      raster::TileWork& work = target_.tile_work[t];
      for (raster::TileWork* sum : {&in_->frame.object_tile_work[o][t], &total_work_[t]}) {
        sum->pixels_processed += work.pixels_processed;
        sum->pixels_updated += work.pixels_updated;
      }
      work = {};
    }
    const double ms = ms_since(bookkeeping);
    stats.ms_counts -= ms;
    stats.ms_measuring += ms;
  }
}

// Volumes counted whole by z-pass or z-fail over the whole image go into one draw per rule, each
// triangle within its own volume's depth bounds; the rest (split planes, pre-fills, strips, and
// every volume where its tile work is kept apart) are counted one by one.
void SoftBackend::count_volumes(std::size_t l, std::span<const std::uint32_t> objects) {
  const FramePlan& plan = in_->plan;
  FrameStats& stats = in_->frame.stats;
  for (Batch& batch : batches_) batch.clear();
  for (const std::uint32_t o : objects) {
    const VolumePlan& vp = plan.volume(l, o);
    if (!batching_ || vp.rule == VolumeRule::split || vp.prefill || !vp.strips.empty() ||
        in_->options.tile_work_per_object) {
      count_volume(l, o);
      continue;
    }
    // Each primitive into its rule's batch: the volume's, or under rules per part its part's (a
    // z-pass part's caps left out); both parts' triangles within the bounds of all of them.
    const std::size_t first[2] = {batches_[0].weights.size(), batches_[1].weights.size()};
    const glm::mat4 mvp = plan.view_proj * plan.objects[o].model;
    const int sign = plan.objects[o].weight_sign;
    for_each_counted_list(in_->volumes.volume(l, o), vp,
                          [&](const PrimitiveList& list, int corners, std::uint32_t cap) {
                            if (!vp.by_part_rule()) {
                              Batch& batch = batches_[vp.rule == VolumeRule::zfail];
                              return clip_volume(list, corners, mvp, sign, batch.tris,
                                                 batch.weights);
                            }
                            for (std::size_t p = 0; p < list.size(); ++p) {
                              const std::uint8_t zfail = vp.part_zfail[list.parts[p]];
                              if (cap && !zfail) continue;
                              clip_primitive(list, corners, p, mvp, sign, batches_[zfail].tris,
                                             batches_[zfail].weights);
                            }
                          });
    raster::DepthBounds bounds{1.0f, 0.0f};
    for (int k = 0; k < 2; ++k) {
      const raster::DepthBounds b =
          counted_bounds(vp, std::span(batches_[k].tris).subspan(3 * first[k]));
      if (b.zmin <= b.zmax) bounds = {std::min(bounds.zmin, b.zmin), std::max(bounds.zmax, b.zmax)};
    }
    for (Batch& batch : batches_) batch.bounds.resize(batch.weights.size(), bounds);
  }
  for (int zfail = 0; zfail < 2; ++zfail) {
    const Batch& batch = batches_[zfail];
    if (batch.weights.empty()) continue;
    const std::uint64_t writes = stats.counts.count_updates;
    raster::draw_counts(target_, batch.tris, batch.weights, batch.bounds,
                        zfail ? raster::CountRule::zfail : raster::CountRule::zpass, stats.counts);
    stats.stencil_writes += stats.counts.count_updates - writes;
    if (!in_->options.count_fill) continue;
    raster::Counters fill;
    const auto measuring = Clock::now();
    raster::draw_counts(target_, batch.tris, batch.weights, raster::CountRule::fill, fill);
    stats.fill += fill.pixels_processed;
    const double ms = ms_since(measuring);  // not the frame's work
    stats.ms_counts -= ms;
    stats.ms_measuring += ms;
  }
}

VolumeCosts SoftBackend::measure_volume_costs() {
  const TypicalVolumes& volumes = typical_volumes();
  // Over an empty depth buffer every fragment passes z-pass: the volumes over open space.
  auto best_of_runs = [&](int side, std::uint64_t& fill) {
    raster::Target target(side, side);
    double best = INFINITY;
    for (int run = 0; run < 5; ++run) {
      raster::Counters counters;
      const auto start = Clock::now();
      raster::draw_counts(target, volumes.triangles, volumes.weights, raster::CountRule::zpass,
                          counters);
      best = std::min(best, ms_since(start));
      fill = counters.pixels_processed;
      std::fill(target.count.begin(), target.count.end(), 0);
    }
    return best;
  };
  std::uint64_t small_fill = 0, large_fill = 0;
  const double small = best_of_runs(kSmallSide, small_fill);
  const double large = best_of_runs(kLargeSide, large_fill);
  return volume_costs(small, large, volumes.vertices(), large_fill);
}

void SoftBackend::see_through() {
  const FramePlan& plan = in_->plan;
  opaque_depth_ = target_.depth;  // into storage kept between frames
  eye_log_.assign(target_.depth.size(), glm::vec3(0.0f));
  std::swap(shadow_work_, target_.tile_work);  // not a shadow pass: leave the tile work alone
  for (const GlassGroup& group : plan.glass) {
    for (const std::size_t o : group.members) {
      clip_triangles(in_->scene.objects[o], plan.view_proj * plan.objects[o].model, tris_);
      weights_.assign(tris_.size() / 3, 1);
      raster::draw_counts(target_, tris_, weights_, raster::CountRule::cover,
                          in_->frame.stats.depth);
    }
    target_.take_counts_into(eye_log_, group.log_transmittance);
  }
  std::swap(shadow_work_, target_.tile_work);
}

// Ambient everywhere, each light as much as reaches the surface; the opaque layer seen through
// every transparent surface in front, plus the nearest one's reflection.
void SoftBackend::shade() {
  const Scene& scene = in_->scene;
  const FramePlan& plan = in_->plan;
  Frame& frame = in_->frame;
  const int w = in_->options.width, h = in_->options.height;
  const std::size_t pixels = static_cast<std::size_t>(w) * h;
  const std::size_t lights = scene.lights.size();
  const bool glass = plan.has_glass();
  // The tile work of the frame: the total where it was shared out by object. Swapped, not
  // moved, so that the next frame reuses this one's storage.
  frame.tile_work.swap(total_work_.empty() ? target_.tile_work : total_work_);
  frame.image.width = w;
  frame.image.height = h;
  frame.image.rgba.resize(pixels * 4);
  // The unit normals of the faces of every object the frame shows, eye-relative, once per frame:
  // per pixel, a lookup.
  seen_.assign(scene.objects.size(), 0);
  for (const SurfaceLayer* layer :
       {static_cast<const SurfaceLayer*>(&frame), static_cast<const SurfaceLayer*>(&frame.glass)})
    for (const std::int32_t o : layer->object)
      if (o >= 0) seen_[static_cast<std::size_t>(o)] = 1;
  normals_.resize(scene.objects.size());
  face_corners_.resize(scene.objects.size());
  for (std::size_t o = 0; o < scene.objects.size(); ++o) {
    if (!seen_[o]) continue;
    const SceneObject& object = scene.objects[o];
    const Mesh& mesh = *object.mesh;
    const glm::mat4& model = plan.objects[o].model;
    std::vector<glm::vec3>& normals = normals_[o];
    normals.resize(mesh.triangle_count());
    const ShadingNormals* given = smooth_shading(object);
    const std::vector<glm::vec2>* uvs = texture_coordinates(object);
    FaceCorners& smooth = face_corners_[o];
    smooth.corners.resize(given || uvs ? mesh.indices.size() : 0);
    smooth.normals.resize(given ? mesh.indices.size() : 0);
    smooth.offsets = given ? given->offsets.data() : nullptr;
    smooth.uvs = uvs ? uvs->data() : nullptr;
    const glm::mat3 normal_matrix(glm::transpose(glm::inverse(glm::dmat3(model))));
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, normals.size(), 4096),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t f = r.begin(); f < r.end(); ++f) {
                          const std::uint32_t* v = &mesh.indices[3 * f];
                          const glm::vec3 a(model * glm::vec4(mesh.positions[v[0]], 1.0f));
                          const glm::vec3 b(model * glm::vec4(mesh.positions[v[1]], 1.0f));
                          const glm::vec3 c(model * glm::vec4(mesh.positions[v[2]], 1.0f));
                          // In double: the cross product of edges past ~1e9 overflows float.
                          const glm::dvec3 n = glm::cross(glm::dvec3(b - a), glm::dvec3(c - a));
                          const double len = glm::length(n);
                          normals[f] = len > 0.0 ? glm::vec3(n / len) : glm::vec3(0, 1, 0);
                          if (smooth.corners.empty()) continue;
                          const glm::vec3 corners[3] = {a, b, c};
                          for (std::size_t k = 0; k < 3; ++k) {
                            smooth.corners[3 * f + k] = corners[k];
                            if (given)
                              smooth.normals[3 * f + k] = normal_matrix * given->normals[3 * f + k];
                          }
                        }
                      });
  }
  const glm::mat4 inv_vp(plan.inv_view_proj);
  lights_at_.resize(lights);
  for (std::size_t l = 0; l < lights; ++l) {
    const glm::vec4 lp = plan.lights[l];
    lights_at_[l] =
        lp.w != 0.0f ? glm::vec4(glm::vec3(lp) / lp.w, 1.0f) : glm::vec4(glm::vec3(lp), 0.0f);
  }
  const std::span<const float> glass_depth(target_.depth);
  const std::span<const float> surface_depth =
      glass ? std::span<const float>(opaque_depth_) : glass_depth;
  tbb::parallel_for(tbb::blocked_range<int>(0, h, 8), [&](const tbb::blocked_range<int>& rows) {
    ShadeRows& mine = shade_rows_.local();
    const shading::SrgbTable& srgb = shading::srgb_table();
    ShadeRow &surface = mine.surface, &through = mine.through;
    surface.resize(static_cast<std::size_t>(w));
    if (glass) through.resize(static_cast<std::size_t>(w));
    for (int y = rows.begin(); y < rows.end(); ++y) {
      const std::size_t row = static_cast<std::size_t>(y) * w;
      shade_row(scene, inv_vp, lights_at_, frame, surface_depth, y, surface);
      if (glass) shade_row(scene, inv_vp, lights_at_, frame.glass, glass_depth, y, through);
      const glm::vec3 background = shading::background(y, h);
      for (int x = 0; x < w; ++x) {
        const std::size_t p = row + static_cast<std::size_t>(x);
        glm::vec3 color = frame.object[p] >= 0 ? surface.color(x) : background;
        if (glass) color *= glm::exp(eye_log_[p]);  // through every transparent surface in front
        if (glass && frame.glass.object[p] >= 0)
          color += scene.objects[static_cast<std::size_t>(frame.glass.object[p])].material.opacity *
                   through.color(x);
        for (int k = 0; k < 3; ++k) frame.image.rgba[4 * p + k] = shading::to_srgb8(color[k], srgb);
        frame.image.rgba[4 * p + 3] = 255;
      }
    }
  });
}

namespace {

// The pixels' eye-relative points along a row: inv_vp (ndc_x, ndc_y, z, 1), ndc_x linear in x.
struct RowPoints {
  glm::vec4 base, step, along_z;  // the point (homogeneous) at x: base + step x + along_z z
};

// Adds one light to a row's colours (r, g, b: the ambient term at first): Lambert (less the
// terminator offset of smooth shading: render/shading.h) + Blinn-Phong where the light reaches
// the surface and the side of its face the eye sees faces the light (into faces_light, per
// pixel). Arrays of the row's pixels, distinct (restrict: GCC honours it on parameters), so
// that the loop vectorizes across pixels.
template <bool kThroughGlass>
void add_light(int n, RowPoints row, glm::vec4 light_at, glm::vec3 light, shading::Falloff falloff,
               const float* __restrict z, const float* __restrict nx, const float* __restrict ny,
               const float* __restrict nz, const float* __restrict fx, const float* __restrict fy,
               const float* __restrict fz, const float* __restrict offset,
               const float* __restrict ar, const float* __restrict ag, const float* __restrict ab,
               const std::uint8_t* __restrict shadowed, const glm::vec3* __restrict arriving,
               float* __restrict r, float* __restrict g, float* __restrict b,
               std::uint8_t* __restrict faces_light) {
  for (int x = 0; x < n; ++x) {
    const float column = float(x);
    // The point (float: it only aims the light) and the unit vector to the eye, the origin.
    const float inv_w = 1.0f / (row.base.w + row.step.w * column + row.along_z.w * z[x]);
    const float px = (row.base.x + row.step.x * column + row.along_z.x * z[x]) * inv_w;
    const float py = (row.base.y + row.step.y * column + row.along_z.y * z[x]) * inv_w;
    const float pz = (row.base.z + row.step.z * column + row.along_z.z * z[x]) * inv_w;
    const float to_eye = -1.0f / std::sqrt(px * px + py * py + pz * pz);
    const float ex = px * to_eye, ey = py * to_eye, ez = pz * to_eye;
    const float sx = nx[x], sy = ny[x], sz = nz[x];  // on the eye's side already (shade_row)
    float lx = light_at.x - px * light_at.w, ly = light_at.y - py * light_at.w,
          lz = light_at.z - pz * light_at.w;
    const float d2 = lx * lx + ly * ly + lz * lz;
    const float reaching = shading::falloff(d2, falloff);
    // The face, not the normal shaded with, decides the side of the light the surface is on.
    const bool faces =
        (fx[x] * lx + fy[x] * ly + fz[x] * lz > 0.0f) & shading::within_range(d2, falloff);
    faces_light[x] = faces;
    const float inv = 1.0f / std::sqrt(d2);
    lx *= inv, ly *= inv, lz *= inv;
    const float lambert = shading::smooth_lambert(sx * lx + sy * ly + sz * lz, offset[x]);
    const float hx = lx + ex, hy = ly + ey, hz = lz + ez;
    const float cos_half = (sx * hx + sy * hy + sz * hz) / std::sqrt(hx * hx + hy * hy + hz * hz);
    const float spec =
        shading::kSpecular * shading::specular_power(cos_half > 0.0f ? cos_half : 0.0f);
    const bool lit = (shadowed[x] == 0) & faces & (lambert > 0.0f);
    float dr = reaching * light.x * (ar[x] * lambert + spec),
          dg = reaching * light.y * (ag[x] * lambert + spec),
          db = reaching * light.z * (ab[x] * lambert + spec);
    if constexpr (kThroughGlass) dr *= arriving[x].x, dg *= arriving[x].y, db *= arriving[x].z;
    r[x] += lit ? dr : 0.0f, g[x] += lit ? dg : 0.0f, b[x] += lit ? db : 0.0f;
  }
}

}  // namespace

// One row of a layer lit, in structure-of-arrays form: the per-pixel gathers (normal, albedo,
// depth) first, then per light a loop over the row's pixels that vectorizes (add_light).
void SoftBackend::shade_row(const Scene& scene, const glm::mat4& inv_vp,
                            std::span<const glm::vec4> lights_at, SurfaceLayer& layer,
                            std::span<const float> depth, int y, ShadeRow& out) const {
  const int w = in_->options.width, h = in_->options.height;
  const std::size_t row = static_cast<std::size_t>(y) * w;
  const glm::vec3 ambient = scene.ambient;
  const float ndc_y = 1.0f - (float(y) + 0.5f) / float(h) * 2.0f;
  const RowPoints points{inv_vp[0] * (1.0f / float(w) - 1.0f) + inv_vp[1] * ndc_y + inv_vp[3],
                         inv_vp[0] * (2.0f / float(w)), inv_vp[2]};
  for (int x = 0; x < w; ++x) {
    const std::int32_t o = layer.object[row + x];
    const bool seen = o >= 0;
    const Material* material =
        seen ? &scene.objects[static_cast<std::size_t>(o)].material : nullptr;
    glm::vec3 albedo = seen ? material->color : glm::vec3(0.0f);
    out.z[x] = seen ? depth[row + x] : 1.0f;  // the near plane: a finite point where none is
    glm::vec3 normal(0.0f), face(0.0f);
    float offset = 0.0f;
    if (seen) {
      // The normal on the side the eye sees: the face's, or the corners' interpolated at the
      // pixel's point, turned to the side the face shows (two-sided, as the face decides); the
      // albedo, times the texture there.
      const std::size_t f = layer.face[row + x];
      face = normals_[static_cast<std::size_t>(o)][f];
      const glm::vec4 h_point = points.base + points.step * float(x) + points.along_z * out.z[x];
      const glm::vec3 point = glm::vec3(h_point) / h_point.w;
      const bool back = glm::dot(face, point) > 0.0f;  // the eye, the origin, behind the face
      const FaceCorners& at = face_corners_[static_cast<std::size_t>(o)];
      normal = face;
      glm::vec3 w(0.0f);
      if (!at.corners.empty() && shading::barycentric(&at.corners[3 * f], point, w)) {
        if (!at.normals.empty()) {
          const shading::SmoothPoint smooth =
              shading::interpolate_smooth(w, &at.normals[3 * f], &at.offsets[3 * f], face);
          normal = smooth.normal, offset = smooth.offset;
        }
        if (at.uvs) {
          const glm::vec2* uv = &at.uvs[3 * f];
          albedo *= shading::sample_texture(*material->base_color_map,
                                            w.x * uv[0] + w.y * uv[1] + w.z * uv[2]);
        }
      }
      if (back) normal = -normal, face = -face;
    }
    out.nx[x] = normal.x, out.ny[x] = normal.y, out.nz[x] = normal.z, out.offset[x] = offset;
    out.fx[x] = face.x, out.fy[x] = face.y, out.fz[x] = face.z;
    out.ar[x] = albedo.x, out.ag[x] = albedo.y, out.ab[x] = albedo.z;
    out.r[x] = ambient.x * albedo.x, out.g[x] = ambient.y * albedo.y,
    out.b[x] = ambient.z * albedo.z;
  }
  for (std::size_t l = 0; l < lights_at.size(); ++l) {
    // Only the pixels of the light's scissor: none beyond it is within the range.
    const raster::PixelRect& rect = in_->plan.reach[l].scissor;
    if (y < rect.y0 || y >= rect.y1 || rect.empty()) continue;
    const SceneLight& scene_light = scene.lights[l];
    const glm::vec3 light = scene_light.color * scene_light.intensity;
    const shading::Falloff falloff = shading::falloff_of(scene_light.range, scene_light.limited());
    const std::size_t x0 = static_cast<std::size_t>(rect.x0), at = row + x0;
    RowPoints from_x0 = points;
    from_x0.base += points.step * float(rect.x0);
    const glm::vec3* arriving = layer.transmitted.empty() ? nullptr : &layer.transmitted[l][at];
    // Which pixels face the light: into the layer where it records them, else thrown away.
    std::uint8_t* faces = layer.faces_light.empty() ? out.faces.data() : &layer.faces_light[l][at];
    (arriving ? add_light<true>
              : add_light<false>)(rect.x1 - rect.x0, from_x0, lights_at[l], light, falloff,
                                  out.z.data() + x0, out.nx.data() + x0, out.ny.data() + x0,
                                  out.nz.data() + x0, out.fx.data() + x0, out.fy.data() + x0,
                                  out.fz.data() + x0, out.offset.data() + x0, out.ar.data() + x0,
                                  out.ag.data() + x0, out.ab.data() + x0, &layer.shadowed[l][at],
                                  arriving, out.r.data() + x0, out.g.data() + x0, out.b.data() + x0,
                                  faces);
  }
}

}  // namespace shadowvol::soft
