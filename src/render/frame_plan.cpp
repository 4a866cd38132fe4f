#include "render/frame_plan.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "accel/depth_bounds.h"
#include "accel/near_plane.h"
#include "accel/split_planes.h"

namespace shadowvol {

namespace {

// Laine 2005 §4: the split plane of one caster (or part), eye-relative, as its SplitPlaneChoice
// says: ours for a flat shape (none edge-on: then as for any other), Point-Point-Light for an
// elongated one, else Point-Camera-Light.
glm::vec4 split_plane(const Shape& shape, SplitPlaneChoice choice, const glm::vec4& light) {
  const bool automatic = choice == SplitPlaneChoice::automatic;
  if (choice == SplitPlaneChoice::flat || (automatic && shape.flat))
    if (const std::optional<glm::vec4> plane = flat_plane(shape, light)) return *plane;
  const bool ppl = choice == SplitPlaneChoice::point_point_light || (automatic && shape.elongated);
  return ppl ? point_point_light(shape.p1, shape.p2, light)
             : point_camera_light(shape.centroid, light);
}

// Under Method::split_plane, the shapes of the object's casters: the whole object, or each part
// (Laine 2005 §6) where it has 2 to kMaxSplitParts of them and SplitParts::each asks.
std::vector<Shape> caster_shapes(const Topology& topo, const glm::mat4& model,
                                 SplitParts split_parts) {
  const bool by_part = split_parts == SplitParts::each && topo.part_count() >= 2 &&
                       topo.part_count() <= kMaxSplitParts;
  std::vector<std::vector<glm::vec3>> points(by_part ? topo.part_count() : 1);
  for (std::size_t v = 0; v < topo.positions.size(); ++v) {
    const glm::vec3 q = glm::vec3(model * glm::vec4(topo.positions[v], 1.0f));
    if (!by_part)
      points[0].push_back(q);
    else if (topo.vertex_part[v] != Topology::kNoPart)
      points[topo.vertex_part[v]].push_back(q);
  }
  std::vector<Shape> shapes;
  for (const std::vector<glm::vec3>& part : points) shapes.push_back(shape_of(part));
  return shapes;
}

// Under Method::automatic, for an object whose volume may reach the near plane: per part, 1
// where the part's own bounding sphere may shadow the near-plane rectangle; empty where every
// part may (or the object is one part).
std::vector<std::uint8_t> parts_reaching_near(const Topology& topo, const glm::mat4& model,
                                              const std::array<glm::vec3, 4>& near_rect,
                                              const glm::vec4& light) {
  const std::size_t parts = topo.part_count();
  if (parts < 2) return {};
  std::vector<glm::vec3> lo(parts, glm::vec3(INFINITY)), hi(parts, glm::vec3(-INFINITY));
  for (std::size_t v = 0; v < topo.positions.size(); ++v) {
    const std::uint32_t part = topo.vertex_part[v];
    if (part == Topology::kNoPart) continue;
    const glm::vec3 q = glm::vec3(model * glm::vec4(topo.positions[v], 1.0f));
    lo[part] = glm::min(lo[part], q);
    hi[part] = glm::max(hi[part], q);
  }
  std::vector<std::uint8_t> zfail(parts, 0);
  bool any_zpass = false;
  for (std::size_t p = 0; p < parts; ++p) {
    zfail[p] = lo[p].x <= hi[p].x &&
               may_shadow_near_plane((lo[p] + hi[p]) * 0.5f, glm::length(hi[p] - lo[p]) * 0.5f,
                                     near_rect, light);
    any_zpass = any_zpass || !zfail[p];
  }
  return any_zpass ? zfail : std::vector<std::uint8_t>{};
}

}  // namespace

std::pair<std::int32_t, std::uint32_t> FramePlan::object_of(std::uint32_t id) const {
  if (id >= id_count) return {-1, 0};
  const auto o =
      std::upper_bound(objects.begin(), objects.end(), id,
                       [](std::uint32_t i, const ObjectPlan& p) { return i < p.first_id; }) -
      objects.begin() - 1;
  return {static_cast<std::int32_t>(o), id - objects[static_cast<std::size_t>(o)].first_id};
}

namespace {

// Whether every corner of the eye-relative box lies beyond the near plane, by a thousandth of
// its distance (float rounding of the corners' depths is far below that).
bool box_beyond_near_plane(const glm::vec3& lo, const glm::vec3& hi, const glm::mat4& view,
                           float near) {
  if (lo.x > hi.x) return false;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 c(corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y, corner & 4 ? hi.z : lo.z);
    if (!(-(view * glm::vec4(c, 1.0f)).z > 1.001f * near)) return false;
  }
  return true;
}

}  // namespace

FramePlan plan_frame(const Scene& scene, const RenderOptions& options, FrameStats& stats) {
  FramePlan plan;
  plan_frame(scene, options, plan, stats);
  return plan;
}

void plan_frame(const Scene& scene, const RenderOptions& options, FramePlan& plan,
                FrameStats& stats) {
  const glm::mat4 view = scene.camera.view_from_eye();
  const glm::mat4 proj = scene.camera.projection(static_cast<float>(options.width) /
                                                 static_cast<float>(options.height));
  plan.view_proj = proj * view;
  plan.inv_view_proj = glm::inverse(plan.view_proj);
  const std::size_t objects = scene.objects.size();
  const std::size_t lights = scene.lights.size();
  plan.objects.resize(objects);
  plan.id_count = 0;
  plan.lights.resize(lights);
  plan.reach.resize(lights);
  for (std::size_t l = 0; l < lights; ++l) {
    plan.lights[l] = eye_relative(scene.lights[l].position, scene.camera.position);
    plan.reach[l] = light_reach(plan.lights[l], scene.lights[l].range, view, proj,
                                scene.camera.near, options.width, options.height);
    stats.scissor_pixels_saved +=
        static_cast<std::uint64_t>(options.width) * options.height - plan.reach[l].scissor.area();
  }

  // Each object's transform, ids and bounding box (eye-relative), and the scene's reach: its
  // box and the near plane's, which a bounded volume's far plane must lie beyond.
  const std::array<glm::vec3, 4> near_rect = near_rectangle(plan.inv_view_proj);
  glm::vec3 reach_lo(INFINITY), reach_hi(-INFINITY);
  for (const glm::vec3& c : near_rect)
    reach_lo = glm::min(reach_lo, c), reach_hi = glm::max(reach_hi, c);
  std::size_t glass_groups = 0;
  plan.any_non_receiver = false;
  for (std::size_t o = 0; o < objects; ++o) {
    const SceneObject& object = scene.objects[o];
    ObjectPlan& op = plan.objects[o];
    op.model = eye_relative(object.transform, scene.camera.position);
    op.weight_sign = glm::determinant(glm::mat3(object.transform)) < 0.0f ? -1 : 1;
    op.first_id = plan.id_count;
    plan.id_count += static_cast<std::uint32_t>(object.mesh->triangle_count());
    op.lo = glm::vec3(INFINITY), op.hi = glm::vec3(-INFINITY);
    for (const glm::vec3& p : object.topology->positions) {
      const glm::vec3 q = glm::vec3(op.model * glm::vec4(p, 1.0f));
      op.lo = glm::min(op.lo, q);
      op.hi = glm::max(op.hi, q);
    }
    reach_lo = glm::min(reach_lo, op.lo);
    reach_hi = glm::max(reach_hi, op.hi);
    op.back_faces_hidden = object.topology->report.parts_wound_outwards > 0 &&
                           box_beyond_near_plane(op.lo, op.hi, view, scene.camera.near);
    op.receives = object.receives_shadows;
    plan.any_non_receiver = plan.any_non_receiver || !op.receives;
    // Transparent casters, grouped by material in order of first use.
    op.glass_group = -1;
    if (!object.material.transparent()) continue;
    std::size_t g = 0;
    while (g < glass_groups && !(plan.glass[g].material == object.material)) ++g;
    if (g == glass_groups) {
      if (plan.glass.size() <= g) plan.glass.emplace_back();
      plan.glass[g].material = object.material;
      plan.glass[g].log_transmittance = log_transmittance(object.material);
      plan.glass[g].members.clear();
      ++glass_groups;
    }
    plan.glass[g].members.push_back(o);
    op.glass_group = static_cast<int>(g);
  }
  plan.glass.resize(glass_groups);

  plan.volumes.resize(lights * objects);
  stats.zfail_lights.assign(objects, 0);
  stats.culled_lights.assign(objects, 0);
  const glm::mat4 plane_to_clip = glm::transpose(plan.inv_view_proj);  // planes map by M^-T
  const bool prefills =
      options.method == Method::split_plane || options.method == Method::zpass_prefill;
  const bool per_object = options.method != Method::zpass && options.method != Method::zfail;
  std::vector<std::vector<Shape>> shapes(options.method == Method::split_plane ? objects : 0);
  for (std::size_t o = 0; o < shapes.size(); ++o)
    shapes[o] =
        caster_shapes(*scene.objects[o].topology, plan.objects[o].model, options.split_parts);
  for (std::size_t l = 0; l < lights; ++l) {
    const glm::vec4 light = plan.lights[l];
    for (std::size_t o = 0; o < objects; ++o) {
      const SceneObject& object = scene.objects[o];
      const ObjectPlan& op = plan.objects[o];
      VolumePlan& v = plan.volume(l, o);
      const bool has_box = op.lo.x <= op.hi.x;  // an object with vertices
      v.far_plane = options.extrusion == Extrusion::bounded && has_box
                        ? bounded_far_plane(op.lo, op.hi, reach_lo, reach_hi, light)
                        : kPlaneAtInfinity;
      const glm::vec3 centre = (op.lo + op.hi) * 0.5f;
      const bool reaches_near =
          per_object &&
          may_shadow_near_plane(centre, glm::length(op.hi - op.lo) * 0.5f, near_rect, light);
      const bool zfail = options.method == Method::zfail || (reaches_near && !prefills);
      v.prefill = reaches_near && prefills;
      v.part_zfail = zfail && options.method == Method::automatic
                         ? parts_reaching_near(*object.topology, op.model, near_rect, light)
                         : std::vector<std::uint8_t>{};
      for (const std::uint8_t z : v.part_zfail) stats.parts_zpass += !z;
      // Under split_plane, a split plane per caster shape.
      v.split.resize(zfail || shapes.empty() ? 0 : shapes[o].size());
      for (std::size_t p = 0; p < v.split.size(); ++p) {
        const Shape& shape = shapes[o][p];
        PartSplit& split = v.split[p];
        split.plane = plane_to_clip * split_plane(shape, object.split_plane, light);
        split.candidates.clear();
        if (object.split_plane == SplitPlaneChoice::automatic &&
            options.split_planes == SplitPlanes::sampled) {
          split.candidates.push_back(split.plane);
          for (const glm::vec4& candidate : split_plane_candidates(shape, light))
            split.candidates.push_back(plane_to_clip * candidate);
        }
      }
      v.rule = zfail ? VolumeRule::zfail : v.split.empty() ? VolumeRule::zpass : VolumeRule::split;
      v.counts_caps = v.rule != VolumeRule::zpass;
      v.light_caps_everywhere = op.glass_group >= 0;
      // Until the culling and clamping, after the depth pass, but for casters that cast nothing
      // of this light.
      const bool out_of_range =
          scene.lights[l].limited() &&
          !box_meets_sphere(op.lo, op.hi, glm::vec3(light), scene.lights[l].range);
      stats.volumes_out_of_range += out_of_range && object.casts_shadows;
      v.culled = !object.casts_shadows || out_of_range;
      v.clamp.face_leaf = v.clamp.vertex_leaf_offsets = v.clamp.vertex_leaves = {};
      v.clamp.offsets.clear();
      v.clamp.intervals.clear();
      v.strips.clear();
      v.object_light = object_space_point(object, scene.lights[l].position);
      // Planes map from the eye-relative world to the object by the transpose of its model.
      const glm::vec4 object_far_plane =
          v.far_plane == kPlaneAtInfinity
              ? kPlaneAtInfinity
              : glm::vec4(glm::transpose(glm::dmat4(op.model)) * glm::dvec4(v.far_plane));
      v.build = {
          resolve_generator(object_generator(object, options.generator), object.topology->report),
          v.counts_caps || v.prefill || v.light_caps_everywhere, object_far_plane,
          v.by_part() || v.by_part_rule()};
      (zfail             ? stats.objects_zfail
       : v.split.empty() ? stats.objects_zpass
                         : stats.objects_split) += 1;
      stats.zfail_lights[o] += zfail;
    }
  }
}

void plan_depth_bounds(FramePlan& plan, std::size_t light) {
  const std::array<glm::vec3, 4> near_rect = near_rectangle(plan.inv_view_proj);
  for (std::size_t o = 0; o < plan.objects.size(); ++o) {
    VolumePlan& v = plan.volume(light, o);
    const ObjectPlan& op = plan.objects[o];
    if (v.culled) continue;
    // Recomputed only where what it depends on changed since it was last computed.
    const raster::DepthBounds reach = plan.reach[light].depth;
    const DepthBoundsInputs inputs{op.lo,       op.hi,          plan.lights[light],
                                   v.far_plane, plan.view_proj, reach};
    if (v.depth_bounds_of == inputs) continue;
    v.depth_bounds = op.lo.x <= op.hi.x
                         ? box_volume_depth_bounds(op.lo, op.hi, plan.lights[light], v.far_plane,
                                                   plan.view_proj, near_rect)
                         : raster::DepthBounds{};
    v.depth_bounds.zmin = std::max(v.depth_bounds.zmin, reach.zmin);
    v.depth_bounds.zmax = std::min(v.depth_bounds.zmax, reach.zmax);
    v.depth_bounds_of = inputs;
  }
}

Generator object_generator(const SceneObject& object, Generator requested) {
  return requested == Generator::automatic && object.material.transparent()
             ? Generator::multiplicity
             : requested;
}

glm::vec3 log_transmittance(const Material& material) {
  glm::vec3 out;
  for (int c = 0; c < 3; ++c) {
    const float t = material.transmittance()[c];
    out[c] = t > 0.0f ? std::max(std::log(t), kLogOfZero) : kLogOfZero;
  }
  return out;
}

glm::vec4 object_space_point(const SceneObject& object, const glm::vec4& point) {
  return glm::vec4(glm::inverse(glm::dmat4(object.transform)) * glm::dvec4(point));
}

}  // namespace shadowvol
