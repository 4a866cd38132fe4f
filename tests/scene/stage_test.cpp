// The benchmark stage (scene/stage.h): laid out from the mesh's bounds as specified, its
// spheres of 2 N^2 triangles, the CAD-like assembly's size and openness, and its names.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "core/topology.h"
#include "scene/scene_io.h"
#include "scene/stage.h"

namespace shadowvol {
namespace {

TEST(Stage, IsLaidOutFromTheMeshBounds) {
  Mesh box;
  box.positions = {{1, 2, 3}, {5, 2, 3}, {1, 6, 3}, {1, 2, 7}};
  box.indices = {0, 1, 2, 0, 2, 3};
  const Scene s = stage_scene("m", box);
  const glm::vec3 c(3, 4, 5);
  const float r = 0.5f * glm::length(glm::vec3(4, 4, 4));
  ASSERT_EQ(s.objects.size(), 2u);
  EXPECT_EQ(s.objects[0].name, "m");
  const glm::mat4& ground = s.objects[1].transform;
  EXPECT_NEAR(ground[3].y, 2.0f - 0.001f * r, 1e-6f);
  EXPECT_EQ(glm::vec2(ground[3].x, ground[3].z), glm::vec2(c.x, c.z));
  float half = 0.0f;
  for (const glm::vec3& p : s.objects[1].mesh->positions) half = std::max(half, std::abs(p.x));
  EXPECT_NEAR(half, 4.0f * r, 1e-5f);
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_LT(glm::length(glm::vec3(s.lights[0].position) - (c + r * glm::vec3(1.5f, 3.0f, 1.0f))),
            1e-5f);
  EXPECT_EQ(s.lights[0].position.w, 1.0f);
  EXPECT_LT(glm::length(s.camera.position - (c + r * glm::vec3(0.0f, 1.2f, 3.0f))), 1e-5f);
  EXPECT_EQ(s.camera.target, c);
  EXPECT_EQ(s.camera.fov_y_degrees, 50.0f);
  EXPECT_NEAR(s.camera.near, 0.05f * r, 1e-6f);
}

TEST(Stage, AnimatedTheMeshSlidesOverTheStillGround) {
  const Scene s = stage_scene("sphere", stage_sphere(8));
  const float r = 0.5f * glm::length(glm::vec3(2.0f));  // the unit sphere's bounds
  const Scene later = scene_at_frame(s, 3);
  const glm::vec3 moved(later.objects[0].transform[3]);
  EXPECT_NEAR(moved.x, 3.0f * kStageStepPerFrame * r, 1e-3f * r);
  EXPECT_EQ(moved.y, 0.0f);
  EXPECT_EQ(moved.z, 0.0f);
  EXPECT_EQ(later.objects[1].transform, s.objects[1].transform);
  EXPECT_EQ(later.lights[0].position, s.lights[0].position);
  EXPECT_EQ(later.camera.position, s.camera.position);
}

TEST(Stage, SpheresHaveTwoNSquaredTriangles) {
  for (const int n : {3, 128, 512}) {
    const Mesh m = stage_sphere(n);
    EXPECT_EQ(m.triangle_count(), std::size_t(2 * n * n)) << n;
    const Topology t = build_topology(m);
    EXPECT_TRUE(t.report.closed_manifold) << n;
  }
}

TEST(Stage, TheCadAssemblyIsLargeOpenAndInHundredsOfParts) {
  const Mesh m = make_cad_assembly();
  EXPECT_GE(m.triangle_count(), 100000u);
  const Topology t = build_topology(m);
  EXPECT_GE(t.report.components, 300u);
  EXPECT_GT(t.report.boundary_edges, 1000u);  // open pipes, domes, the base's open box
  EXPECT_FALSE(t.report.closed_manifold);
  EXPECT_EQ(make_cad_assembly().positions, m.positions);  // deterministic
}

TEST(Stage, NamesAreReadOrRefused) {
  EXPECT_TRUE(load_stage("sphere:16").ok());
  EXPECT_TRUE(load_scene("stage:sphere:16").ok());
  for (const char* bad : {"sphere:2", "sphere:x", "sphere:", "nonexistent.obj"}) {
    auto s = load_stage(bad);
    EXPECT_FALSE(s.ok()) << bad;
  }
  EXPECT_NE(load_stage("sphere:2").error().message.find("3 to 4096"), std::string::npos);
}

}  // namespace
}  // namespace shadowvol
