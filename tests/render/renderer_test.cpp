// The renderer gives the same frame, counters included, whatever the thread count.
#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <string>

#include <cmath>

#include <tbb/global_control.h>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>

#include "core/shapes.h"
#include "render/frame_plan.h"
#include "render/heatmap.h"
#include "render/shading.h"
#include "scene/scene.h"
#include "scene/scene_io.h"
#include "scene/stage.h"
#include "soft/soft_backend.h"
#include "test_meshes.h"

namespace shadowvol {
namespace {

TEST(Renderer, FrameDoesNotDependOnTheThreadCount) {
  auto scene = builtin_scene("light-in-view");
  ASSERT_TRUE(scene.ok());
  const RenderOptions options{200, 120, Method::automatic, Generator::automatic};
  std::vector<Frame> frames;
  for (int threads : {1, 2, 4}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    Renderer renderer = soft::soft_renderer();
    frames.push_back(renderer.render(*scene, options));
  }
  for (std::size_t i = 1; i < frames.size(); ++i) {
    EXPECT_EQ(frames[i].image.rgba, frames[0].image.rgba);
    EXPECT_EQ(frames[i].shadowed, frames[0].shadowed);
    EXPECT_EQ(frames[i].stats.counts.count_updates, frames[0].stats.counts.count_updates);
    EXPECT_EQ(frames[i].stats.counts.tiles_skipped, frames[0].stats.counts.tiles_skipped);
    EXPECT_EQ(frames[i].stats.depth.pixels_passed, frames[0].stats.depth.pixels_passed);
  }
  EXPECT_GT(frames[0].stats.counts.count_updates, 1000u);
}

// SplitPlanes::sampled draws samples before each volume of an object left to `auto`, and counts
// their work apart from the count passes' (FrameStats::split_sampling); Laine's planes draw none,
// and neither does an object whose plane the scene fixes. Candidates: the plane Laine's rule
// gives first, then the others.
TEST(Renderer, SampledSplitPlanesCountTheirSamplesApart) {
  auto scene = builtin_scene("knight");
  ASSERT_TRUE(scene.ok());
  RenderOptions options{256, 192, Method::split_plane, Generator::automatic};
  Renderer renderer = soft::soft_renderer();
  const FrameStats sampled = renderer.render(*scene, options).stats;
  EXPECT_GT(sampled.split_sampling.pixels_processed, 0u);
  EXPECT_GT(sampled.split_sampling.triangles_in, 0u);
  FrameStats stats;
  const FramePlan plan = plan_frame(*scene, options, stats);
  for (std::size_t o = 0; o < scene->objects.size(); ++o) {
    ASSERT_FALSE(plan.volume(0, o).split.empty());
    for (const PartSplit& part : plan.volume(0, o).split)
      EXPECT_GE(part.candidates.size(), 2u);  // at least both whole-volume rules
  }
  options.split_planes = SplitPlanes::laine;
  EXPECT_EQ(renderer.render(*scene, options).stats.split_sampling.triangles_in, 0u);
  EXPECT_TRUE(plan_frame(*scene, options, stats).volume(0, 0).split[0].candidates.empty());
  options.split_planes = SplitPlanes::sampled;
  for (SceneObject& object : scene->objects)
    object.split_plane = SplitPlaneChoice::point_camera_light;
  EXPECT_EQ(renderer.render(*scene, options).stats.split_sampling.triangles_in, 0u);
}

// SplitParts::each gives every part of a caster its own split plane (the knight is twelve closed
// shells: legs, torso, head, sword...), the ground one; SplitParts::whole one per object; an
// object of more than kMaxSplitParts parts keeps one. The volume is built with its parts then.
TEST(Renderer, EachPartOfACasterGetsItsOwnSplitPlane) {
  auto scene = builtin_scene("knight");
  ASSERT_TRUE(scene.ok());
  ASSERT_EQ(scene->objects[1].name, "knight");
  ASSERT_EQ(scene->objects[1].topology->part_count(), 12u);
  RenderOptions options{256, 192, Method::split_plane, Generator::automatic};
  FrameStats stats;
  const FramePlan each = plan_frame(*scene, options, stats);
  EXPECT_EQ(each.volume(0, 0).split.size(), 1u);  // the ground
  EXPECT_EQ(each.volume(0, 1).split.size(), 12u);
  EXPECT_TRUE(each.volume(0, 1).by_part());
  options.split_parts = SplitParts::whole;
  const FramePlan whole = plan_frame(*scene, options, stats);
  EXPECT_EQ(whole.volume(0, 1).split.size(), 1u);
  EXPECT_FALSE(whole.volume(0, 1).by_part());

  Mesh many;  // kMaxSplitParts + 1 separate triangles
  for (std::size_t i = 0; i <= kMaxSplitParts; ++i) {
    const auto first = static_cast<std::uint32_t>(many.positions.size());
    const float x = static_cast<float>(i);
    many.positions.insert(many.positions.end(), {{x, 0, 0}, {x + 0.5f, 0, 0}, {x, 0.5f, 0}});
    many.indices.insert(many.indices.end(), {first, first + 1, first + 2});
  }
  scene->objects[1] = make_object("many", many, glm::mat4(1.0f), glm::vec3(0.8f));
  options.split_parts = SplitParts::each;
  EXPECT_EQ(plan_frame(*scene, options, stats).volume(0, 1).split.size(), 1u);
  EXPECT_EQ(parse_split_parts("whole").value(), SplitParts::whole);
  EXPECT_EQ(parse_split_parts("all").error().message,
            "unknown split-plane decomposition 'all': expected each or whole");
}

// Per-tile work adds up to the frame's counters, and the heatmap shows it where it happened.
TEST(Renderer, TileWorkAddsUpToTheCountersAndTheHeatmapShowsIt) {
  auto scene = builtin_scene("demo");
  ASSERT_TRUE(scene.ok());
  for (Method method : {Method::zpass, Method::zfail, Method::split_plane, Method::zpass_prefill}) {
    SCOPED_TRACE(std::string(to_string(method)));
    RenderOptions options{203, 117, method, Generator::automatic};  // partial edge tiles
    Renderer renderer = soft::soft_renderer();
    EXPECT_TRUE(renderer.render(*scene, options).tile_work.empty());  // not asked for
    options.tile_work = true;
    const Frame frame = renderer.render(*scene, options);
    ASSERT_EQ(frame.tile_work.size(), std::size_t{26 * 15});
    std::uint64_t processed = 0, updated = 0;
    for (const raster::TileWork& t : frame.tile_work) {
      processed += t.pixels_processed;
      updated += t.pixels_updated;
      EXPECT_LE(t.pixels_updated, t.pixels_processed);
    }
    EXPECT_EQ(processed, frame.stats.counts.pixels_processed);
    EXPECT_EQ(updated, frame.stats.counts.count_updates);
    EXPECT_GT(updated, 1000u);
    const Heatmap map = tile_work_heatmap(frame);
    ASSERT_EQ(map.image.width, 2 * 203 + 4);
    ASSERT_EQ(map.image.height, 117 + 4 + 12);
    EXPECT_GE(map.passes_at_top, 1.0);
    // A tile without work shows the grey scene; one with work, a colour.
    const auto rgb_at = [&](int x, int y) {
      const std::uint8_t* p =
          &map.image.rgba[4 * (static_cast<std::size_t>(y) * map.image.width + x)];
      return std::array<int, 3>{p[0], p[1], p[2]};
    };
    for (std::size_t t = 0; t < frame.tile_work.size(); ++t) {
      const int x = static_cast<int>(t % 26) * 8, y = static_cast<int>(t / 26) * 8;
      const auto c = rgb_at(x, y);
      if (frame.tile_work[t].pixels_processed == 0) {
        EXPECT_TRUE(c[0] == c[1] && c[1] == c[2]) << "tile " << t;
      } else if (frame.tile_work[t].pixels_processed >= 64) {
        EXPECT_FALSE(c[0] == c[1] && c[1] == c[2]) << "tile " << t;
      }
    }
  }
}

// Laine 2005 §4: a long thin pole gets a Point-Point-Light plane, through the light and both
// ends of its axis; asked for Point-Camera-Light, a plane through the light and its centre.
TEST(Renderer, SplitPlanesRunAlongLongThinObjects) {
  Scene scene;
  const glm::mat4 tilt = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0.5f, 1.0f, -1.0f)),
                                     0.7f, glm::vec3(0.3f, 0.2f, 1.0f));
  scene.objects.push_back(make_object(
      "pole", make_box({-0.05f, -1.5f, -0.05f}, {0.05f, 1.5f, 0.05f}), tilt, glm::vec3(0.8f)));
  scene.lights.push_back({{2.0f, 6.0f, 3.0f, 1.0f}, glm::vec3(1.0f), 1.0f});
  scene.camera = {{0.0f, 2.0f, 6.0f}, {0.0f, 1.0f, 0.0f}};
  const RenderOptions options{320, 200, Method::split_plane, Generator::automatic};
  // The distance from the object-space point p to the split plane, in world units (the plane
  // back in eye-relative space: planes map by the transpose).
  const auto side = [](const FramePlan& plan, const glm::vec4& p) {
    const glm::dvec4 plane =
        glm::transpose(glm::dmat4(plan.view_proj)) * glm::dvec4(plan.volume(0, 0).split[0].plane);
    const glm::dvec4 x = glm::dmat4(plan.objects[0].model) * glm::dvec4(p);
    return std::abs(glm::dot(plane, x)) / glm::length(glm::dvec3(plane));
  };
  FrameStats stats;
  const glm::vec4 end1(0, -1.5f, 0, 1), end2(0, 1.5f, 0, 1), centre(0, 0, 0, 1);
  const FramePlan ppl = plan_frame(scene, options, stats);
  ASSERT_EQ(ppl.volume(0, 0).split.size(), 1u);
  EXPECT_LT(side(ppl, end1), 1e-4);
  EXPECT_LT(side(ppl, end2), 1e-4);
  scene.objects[0].split_plane = SplitPlaneChoice::point_camera_light;
  const FramePlan pcl = plan_frame(scene, options, stats);
  EXPECT_LT(side(pcl, centre), 1e-4);
  EXPECT_GT(side(pcl, end1), 0.05);  // it turns to face the camera instead
  EXPECT_EQ(parse_split_plane_choice("ppl").value(), SplitPlaneChoice::point_point_light);
  EXPECT_EQ(parse_split_plane_choice("pp").error().message,
            "unknown split plane 'pp': expected auto, pcl, ppl or flat");
}

// Point-Camera-Light's line runs through the mean of the object's vertices, not the centre of its
// box: a plain box with a finely tessellated ball beside it puts the line near the ball.
TEST(Renderer, PointCameraLightRunsThroughTheObjectsCentroid) {
  Mesh mesh = make_box({-2.0f, -0.5f, -0.5f}, {-1.0f, 0.5f, 0.5f});
  const Mesh ball = make_sphere({2.0f, 0.0f, 0.0f}, 0.5f, 16, 32);
  const auto base = static_cast<std::uint32_t>(mesh.positions.size());
  mesh.positions.insert(mesh.positions.end(), ball.positions.begin(), ball.positions.end());
  for (const std::uint32_t i : ball.indices) mesh.indices.push_back(base + i);
  Scene scene;
  scene.objects.push_back(make_object(
      "box_and_ball", mesh, glm::translate(glm::mat4(1.0f), {0.0f, 1.0f, 0.0f}), glm::vec3(0.8f)));
  scene.objects[0].split_plane = SplitPlaneChoice::point_camera_light;
  scene.lights.push_back({{1.0f, 6.0f, -3.0f, 1.0f}, glm::vec3(1.0f), 1.0f});
  scene.camera = {{0.0f, 2.0f, 6.0f}, {0.0f, 1.0f, 0.0f}};
  FrameStats stats;
  RenderOptions options{320, 200, Method::split_plane, Generator::automatic};
  options.split_parts = SplitParts::whole;  // box and ball are two parts: one plane for both
  const FramePlan plan = plan_frame(scene, options, stats);
  ASSERT_EQ(plan.volume(0, 0).split.size(), 1u);
  const glm::dvec4 plane =
      glm::transpose(glm::dmat4(plan.view_proj)) * glm::dvec4(plan.volume(0, 0).split[0].plane);
  const auto distance = [&](const glm::dvec3& object_point) {  // world units
    const glm::dvec4 x = glm::dmat4(plan.objects[0].model) * glm::dvec4(object_point, 1.0);
    return std::abs(glm::dot(plane, x)) / glm::length(glm::dvec3(plane));
  };
  const Topology& topology = *scene.objects[0].topology;
  glm::dvec3 mean(0.0);
  for (const glm::vec3& p : topology.positions) mean += glm::dvec3(p);
  mean /= double(topology.positions.size());
  EXPECT_GT(mean.x, 1.5);  // the ball's many vertices pull it over
  EXPECT_LT(distance(mean), 1e-4);
  EXPECT_GT(distance({0.25, 0.0, 0.0}), 0.1);  // the box's centre lies off the plane
}

// A floor gets its own plane, moved just past it away from the light: every point of the floor
// on the light's side, and its volume (below it) on the other. A rod a thousand times thinner
// than long is elongated, not flat: it still gets Point-Point-Light.
TEST(Renderer, FlatCastersGetTheirOwnPlaneAndRodsStayPointPointLight) {
  Scene scene;
  const glm::mat4 lift = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.5f, 0.0f));
  scene.objects.push_back(make_object("floor", make_ground(4.0f), lift, glm::vec3(0.8f)));
  scene.lights.push_back({{1.0f, 6.0f, 2.0f, 1.0f}, glm::vec3(1.0f), 1.0f});
  scene.camera = {{0.0f, 3.0f, 6.0f}, {0.0f, 0.0f, 0.0f}};
  const RenderOptions options{320, 200, Method::split_plane, Generator::automatic};
  FrameStats stats;
  const auto world_plane = [](const FramePlan& plan) {  // eye-relative, unit normal
    glm::dvec4 plane =
        glm::transpose(glm::dmat4(plan.view_proj)) * glm::dvec4(plan.volume(0, 0).split[0].plane);
    return plane / glm::length(glm::dvec3(plane));
  };
  const FramePlan flat = plan_frame(scene, options, stats);
  ASSERT_EQ(flat.volume(0, 0).split.size(), 1u);
  const glm::dvec4 plane = world_plane(flat);
  EXPECT_NEAR(std::abs(plane.y), 1.0, 1e-6);  // the floor's own orientation
  const auto at = [&](const glm::vec3& world) {
    return glm::dot(plane, glm::dvec4(glm::dvec3(world) - glm::dvec3(scene.camera.position), 1.0));
  };
  const double floor_side = at({0.0f, 0.5f, 0.0f}), light_side = at({1.0f, 6.0f, 2.0f});
  const double below = at({0.0f, 0.3f, 0.0f});
  EXPECT_GT(floor_side * light_side, 0.0);  // the floor with the light
  EXPECT_LT(floor_side * below, 0.0);       // its volume beyond: the plane lies just under it
  // A hundredth of its length along its long axis: between its side, 8, and its diagonal.
  EXPECT_GE(std::abs(floor_side), 0.08 - 1e-6);
  EXPECT_LE(std::abs(floor_side), 0.08 * std::sqrt(2.0) + 1e-6);

  scene.objects[0] = make_object("rod", make_box({-5.0f, -0.005f, -0.005f}, {5.0f, 0.005f, 0.005f}),
                                 lift, glm::vec3(0.8f));
  const FramePlan rod = plan_frame(scene, options, stats);
  ASSERT_EQ(rod.volume(0, 0).split.size(), 1u);
  const glm::dvec4 rod_plane = world_plane(rod);
  const auto rod_at = [&](const glm::vec3& world) {
    return glm::dot(rod_plane,
                    glm::dvec4(glm::dvec3(world) - glm::dvec3(scene.camera.position), 1.0));
  };
  EXPECT_NEAR(rod_at({1.0f, 6.0f, 2.0f}), 0.0, 1e-3);  // through the light (Point-Point-Light)
  EXPECT_NEAR(rod_at({-5.0f, 0.5f, 0.0f}), 0.0, 1e-2);
  EXPECT_NEAR(rod_at({5.0f, 0.5f, 0.0f}), 0.0, 1e-2);
}

// Laine 2005 §7's depth bounds (FramePlan::depth_bounds) hold every point of each volume that the
// frustum keeps: points along the rays from each vertex away from the light, up to the far
// plane, every one in view within its object's bounds. They reach depth 1 when the eye is in
// the volume, and are empty for a volume out of view.
TEST(FramePlan, DepthBoundsHoldEveryVisiblePointOfTheVolume) {
  for (const char* name : {"demo", "light-in-view", "camera-in-shadow", "directional", "knight"})
    for (const Extrusion extrusion : {Extrusion::infinite, Extrusion::bounded}) {
      auto scene = builtin_scene(name);
      ASSERT_TRUE(scene.ok());
      FrameStats stats;
      FramePlan plan =
          plan_frame(*scene, {320, 180, Method::automatic, Generator::automatic, extrusion}, stats);
      for (std::size_t l = 0; l < scene->lights.size(); ++l) plan_depth_bounds(plan, l);
      std::size_t inside = 0;
      for (std::size_t l = 0; l < scene->lights.size(); ++l)
        for (std::size_t o = 0; o < scene->objects.size(); ++o) {
          const raster::DepthBounds b = plan.volume(l, o).depth_bounds;
          const glm::vec4 light = plan.lights[l];
          const glm::vec4 far = plan.volume(l, o).far_plane;
          for (const glm::vec3& p : scene->objects[o].mesh->positions) {
            const glm::vec3 q = glm::vec3(plan.objects[o].model * glm::vec4(p, 1.0f));
            const glm::vec3 away =
                light.w != 0.0f ? q - glm::vec3(light) / light.w : -glm::vec3(light);
            for (float t = 0.0f; t <= 64.0f; t = t * 1.5f + 0.05f) {
              const glm::vec3 x = q + away * t;
              if (glm::dot(glm::vec3(far), x) + far.w > 0.0f) break;  // past the far plane
              const glm::vec4 c = plan.view_proj * glm::vec4(x, 1.0f);
              if (c.w <= 0.0f || c.z > c.w || std::abs(c.x) > c.w || std::abs(c.y) > c.w)
                continue;  // out of view
              const float depth = c.z / c.w;
              ++inside;
              ASSERT_GE(depth, b.zmin) << name << " " << scene->objects[o].name;
              ASSERT_LE(depth, b.zmax) << name << " " << scene->objects[o].name;
            }
          }
        }
      EXPECT_GT(inside, 1000u) << name;
    }
  // The eye inside the slab's volume: the bounds reach the near plane.
  auto shadowed_eye = builtin_scene("camera-in-shadow");
  ASSERT_TRUE(shadowed_eye.ok());
  FrameStats stats;
  FramePlan plan = plan_frame(*shadowed_eye, {320, 180}, stats);
  plan_depth_bounds(plan, 0);
  EXPECT_EQ(plan.volume(0, 1).depth_bounds.zmax, 1.0f);  // objects[1]: the slab
  // A box behind the camera, lit from behind it too: its volume runs away out of view.
  Scene behind;
  behind.objects.push_back(make_object("box", make_box(glm::vec3(-0.5f), glm::vec3(0.5f)),
                                       glm::translate(glm::mat4(1.0f), {0.0f, 2.0f, 12.0f}),
                                       glm::vec3(0.8f)));
  behind.lights.push_back({{0.0f, 2.0f, 6.0f, 1.0f}});
  FramePlan away = plan_frame(behind, {320, 180}, stats);
  plan_depth_bounds(away, 0);
  EXPECT_GT(away.volume(0, 0).depth_bounds.zmin, away.volume(0, 0).depth_bounds.zmax);
}

// The 8-bit sRGB encoding by table search gives exactly the rounded formula: on every float
// from 0 to 1 a step of 2^-20 apart, at and around every step of the table, and outside [0, 1].
TEST(Shading, EightBitSrgbIsTheRoundedFormulaExactly) {
  const auto formula = [](float v) {
    return static_cast<int>(std::lround(shading::to_srgb(v) * 255.0f));
  };
  for (int i = 0; i <= (1 << 20); ++i) {
    const float v = static_cast<float>(i) / static_cast<float>(1 << 20);
    ASSERT_EQ(shading::to_srgb8(v), formula(v)) << v;
    for (const float w : {std::nextafter(v, 0.0f), std::nextafter(v, 1.0f)})
      ASSERT_EQ(shading::to_srgb8(w), formula(w)) << w;
  }
  for (int code = 1; code <= 255; ++code) {  // where each code begins, found by the formula
    float lo = 0.0f, hi = 1.0f;
    for (int i = 0; i < 64; ++i) {
      const float mid = lo + (hi - lo) * 0.5f;
      (formula(mid) >= code ? hi : lo) = mid;
    }
    for (float v = std::nextafter(lo, 0.0f), n = 0; n < 4; v = std::nextafter(v, 2.0f), ++n)
      ASSERT_EQ(shading::to_srgb8(v), formula(v)) << v;
  }
  EXPECT_EQ(shading::to_srgb8(-1.0f), 0);
  EXPECT_EQ(shading::to_srgb8(7.0f), 255);
}

TEST(Renderer, ReusesTheVolumesOfObjectsWhoseLightDidNotMove) {
  auto scene = builtin_scene("demo");
  ASSERT_TRUE(scene.ok());
  const RenderOptions options{160, 90, Method::automatic, Generator::automatic};
  Renderer renderer = soft::soft_renderer();
  const Frame first = renderer.render(*scene, options);
  EXPECT_EQ(first.stats.volumes_built, 4);
  EXPECT_EQ(first.stats.volumes_reused, 0);
  const Frame second = renderer.render(*scene, options);
  EXPECT_EQ(second.stats.volumes_built, 0);
  EXPECT_EQ(second.stats.volumes_reused, 4);
  EXPECT_EQ(second.image.rgba, first.image.rgba);
  // Move the box: only its volume is rebuilt, and the frame equals a fresh renderer's.
  scene->objects[2].transform[3] += glm::vec4(0.3f, 0.0f, 0.2f, 0.0f);
  const Frame third = renderer.render(*scene, options);
  EXPECT_EQ(third.stats.volumes_built, 1);
  EXPECT_EQ(third.stats.volumes_reused, 3);
  Renderer fresh = soft::soft_renderer();
  EXPECT_EQ(third.image.rgba, fresh.render(*scene, options).image.rgba);
  EXPECT_NE(third.image.rgba, first.image.rgba);
  // Moving the light rebuilds them all.
  scene->lights[0].position.x += 0.5f;
  EXPECT_EQ(renderer.render(*scene, options).stats.volumes_built, 4);
}

TEST(Renderer, OptionsOutsideTheRasterizersLimitsAreRefused) {
  EXPECT_TRUE(check_options({640, 480}).ok());
  EXPECT_FALSE(check_options({0, 480}).ok());
  EXPECT_TRUE(check_options({640, raster::kMaxViewport}).ok());
  EXPECT_FALSE(check_options({640, raster::kMaxViewport + 1}).ok());
  auto method = parse_method("zfast");
  ASSERT_FALSE(method.ok());
  EXPECT_EQ(method.error().message,
            "unknown method 'zfast': expected zpass, zfail, auto, spsv or zp+db");
}

}  // namespace
}  // namespace shadowvol

namespace shadowvol {
namespace {

// Batching (SoftBackend::count_volumes: one draw per rule, each triangle within its own volume's
// depth bounds) gives the image, the masks and every counter of counting volume by volume, on
// scenes with z-pass and z-fail volumes side by side, transparent casters, and the city.
// The depth pass leaves out the back faces of the parts wound outwards of objects whose boxes lie
// beyond the near plane: the frame is the same as with every face drawn (the same scene with no
// part marked wound outwards), with fewer triangles drawn; a box the near plane cuts keeps its
// back faces (seen through the cut).
TEST(Renderer, BackFacesLeftOutOfTheDepthPassChangeNoPixel) {
  for (const char* name : {"demo", "knight", "robots", "glass", "stage:cad"}) {
    const Scene scene =
        std::string_view(name) == "stage:cad" ? *load_stage("cad") : *builtin_scene(name);
    Scene all_faces = scene;
    for (SceneObject& object : all_faces.objects) {
      auto topology = std::make_shared<Topology>(*object.topology);
      topology->report.parts_wound_outwards = 0;
      std::fill(topology->part_wound_outwards.begin(), topology->part_wound_outwards.end(), 0);
      object.topology = topology;
    }
    const RenderOptions options{320, 180, Method::automatic, Generator::automatic};
    Renderer renderer = soft::soft_renderer();
    const Frame culled = renderer.render(scene, options),
                drawn = renderer.render(all_faces, options);
    EXPECT_EQ(culled.object, drawn.object) << name;
    EXPECT_EQ(culled.face, drawn.face) << name;
    EXPECT_EQ(culled.shadowed, drawn.shadowed) << name;
    EXPECT_EQ(culled.glass.object, drawn.glass.object) << name;
    EXPECT_EQ(culled.image.rgba, drawn.image.rgba) << name;
    EXPECT_GT(culled.stats.depth.triangles_culled, drawn.stats.depth.triangles_culled) << name;
  }
  Scene cut;
  cut.objects.push_back(make_object("box", make_box({-1, -1, -1}, {1, 1, 1}, true), glm::mat4(1.0f),
                                    glm::vec3(0.8f)));
  cut.lights.push_back({glm::vec4(0, 5, 0, 1), glm::vec3(1), 1.0f});
  cut.camera = {{0, 0, 1.05f}, {0, 0, -1}, {0, 1, 0}, 60.0f, 0.1f};  // near plane past z = 1
  FrameStats stats;
  const FramePlan plan = plan_frame(cut, {64, 48}, stats);
  EXPECT_FALSE(plan.objects[0].back_faces_hidden);
  cut.camera.position.z = 3.0f;
  EXPECT_TRUE(plan_frame(cut, {64, 48}, stats).objects[0].back_faces_hidden);
}

TEST(Renderer, BatchedVolumesCountAsVolumeByVolume) {
  for (const char* name : {"demo", "camera-in-shadow", "light-in-view", "glass", "city:48"}) {
    const Scene scene = *builtin_scene(name);
    RenderOptions options{200, 120, Method::automatic, Generator::automatic};
    options.count_fill = true;
    Renderer batched = soft::soft_renderer(), apart = soft::soft_renderer();
    dynamic_cast<soft::SoftBackend&>(apart.backend()).set_batching(false);
    const Frame a = batched.render(scene, options), b = apart.render(scene, options);
    EXPECT_EQ(a.image.rgba, b.image.rgba) << name;
    EXPECT_EQ(a.shadowed, b.shadowed) << name;
    EXPECT_EQ(a.glass.transmitted, b.glass.transmitted) << name;
    EXPECT_EQ(a.stats.counts.triangles_in, b.stats.counts.triangles_in) << name;
    EXPECT_EQ(a.stats.counts.tiles_touched, b.stats.counts.tiles_touched) << name;
    EXPECT_EQ(a.stats.counts.tiles_skipped, b.stats.counts.tiles_skipped) << name;
    EXPECT_EQ(a.stats.counts.pixels_processed, b.stats.counts.pixels_processed) << name;
    EXPECT_EQ(a.stats.counts.count_updates, b.stats.counts.count_updates) << name;
    EXPECT_EQ(a.stats.fill, b.stats.fill) << name;
    EXPECT_EQ(a.stats.stencil_writes, b.stats.stencil_writes) << name;
    EXPECT_EQ(a.stats.volumes_drawn, b.stats.volumes_drawn) << name;
  }
}

// A light's falloff (render/shading.h): the inverse square near the light, exactly 0 from the
// range on, never rising with distance; none without a range.
TEST(Shading, RangeFalloffEndsAtTheRange) {
  const shading::Falloff f = shading::falloff_of(10.0f, true);
  EXPECT_FLOAT_EQ(shading::falloff(0.0f, f), 1.0f);
  EXPECT_NEAR(shading::falloff(4.0f, f), (1.0f - 0.0016f) * (1.0f - 0.0016f) / 5.0f, 1e-6f);
  EXPECT_EQ(shading::falloff(100.0f, f), 0.0f);
  EXPECT_EQ(shading::falloff(1e6f, f), 0.0f);
  float last = 2.0f;
  for (float d = 0.0f; d < 10.0f; d += 0.05f) {
    const float v = shading::falloff(d * d, f);
    EXPECT_LE(v, last);
    last = v;
  }
  EXPECT_EQ(shading::falloff(1e6f, shading::falloff_of(10.0f, false)), 1.0f);
}

}  // namespace
}  // namespace shadowvol

namespace shadowvol {
namespace {

using testing::scaled;

// Shading is scale-free: faces a billion units across (whose float normals overflowed, leaving
// them lit by the ambient light alone) shade as the same faces a unit across.
TEST(Renderer, AHugeSceneShadesAsTheSameSceneAtUnitScale) {
  // Flat faces, transparent ones, and a file's smooth normals and texture (barycentric weights).
  for (const std::string name :
       {"demo", "knight", "glass", "robots", "normals.obj", "textured.obj"}) {
    auto loaded = load_scene(name.ends_with(".obj") ? SHADOWVOL_TEST_DATA "/" + name : name);
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    const Scene& unit = loaded->scene;
    const Scene huge = scaled(unit, 2e9f);
    ASSERT_TRUE(check_frame(huge, {96, 54}).ok()) << check_frame(huge, {96, 54}).error().message;
    Renderer renderer = soft::soft_renderer();
    const Frame a = renderer.render(unit, {96, 54}), b = renderer.render(huge, {96, 54});
    std::size_t differ = 0;
    for (std::size_t i = 0; i < a.image.rgba.size(); ++i)
      differ += std::abs(int(a.image.rgba[i]) - int(b.image.rgba[i])) > 3;
    EXPECT_LT(differ, a.image.rgba.size() / 100)
        << name << ": " << differ << " channels differ by more than 3";
  }
}

// Beyond what float stages draw exactly, a frame is refused with the reason, never drawn wrong.
TEST(CheckFrame, RefusesWhatCannotBeDrawnExactly) {
  const Scene demo = *builtin_scene("demo");
  auto message = [](const Scene& s) {
    auto ok = check_frame(s, {96, 54});
    return ok.ok() ? std::string("accepted") : ok.error().message;
  };
  Scene no_up = demo;
  no_up.camera.up = glm::vec3(0.0f);
  EXPECT_NE(message(no_up).find("the camera's up is [0, 0, 0]"), std::string::npos);
  Scene up_along_view = demo;
  up_along_view.camera.up = demo.camera.target - demo.camera.position;
  EXPECT_NE(message(up_along_view).find("up lies along its view direction"), std::string::npos);
  Scene far_out = demo;
  far_out.objects[0].transform =
      glm::translate(glm::mat4(1.0f), glm::vec3(2e12f, 0.0f, 0.0f)) * far_out.objects[0].transform;
  EXPECT_NE(message(far_out).find("reaches 2e+12 from the origin, beyond the 1e+11"),
            std::string::npos)
      << message(far_out);
  Scene wide_ground = demo;  // a ground 1e8 across seen from near 0.1
  wide_ground.objects[0].transform =
      glm::scale(glm::mat4(1.0f), glm::vec3(1e8f)) * wide_ground.objects[0].transform;
  EXPECT_NE(message(wide_ground).find("near distances: move the near plane out"), std::string::npos)
      << message(wide_ground);
  EXPECT_EQ(message(scaled(demo, 1e-6f)), "accepted");  // the range is relative, not absolute
}

// The standard generator counts only light-facing faces, which is exact on closed 2-manifolds
// alone: any other mesh in the scene (here the ground, a single sheet) refuses the frame.
TEST(CheckFrame, RefusesTheStandardGeneratorOnAMeshThatIsNotClosed) {
  Scene demo = *builtin_scene("demo");
  RenderOptions standard{96, 54};
  standard.generator = Generator::standard;
  auto refused = check_frame(demo, standard);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find("scene demo, object 'ground': the standard generator "
                                         "needs a closed 2-manifold, but this mesh has "),
            std::string::npos)
      << refused.error().message;
  std::erase_if(demo.objects,
                [](const SceneObject& o) { return !o.topology->report.closed_manifold; });
  ASSERT_FALSE(demo.objects.empty());
  EXPECT_TRUE(check_frame(demo, standard).ok());
}

}  // namespace
}  // namespace shadowvol
