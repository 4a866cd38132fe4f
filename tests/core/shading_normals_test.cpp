// Shading normals: smooth across flat edges, creased where a surface folds, whatever the file
// repeats, and the interpolation the lit pass shades with.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "core/shading_normals.h"
#include "core/shapes.h"
#include "render/shading.h"

namespace shadowvol {
namespace {

glm::vec3 face_normal(const Mesh& mesh, std::size_t f) {
  const glm::vec3 a = mesh.positions[mesh.indices[3 * f]];
  return glm::normalize(glm::cross(mesh.positions[mesh.indices[3 * f + 1]] - a,
                                   mesh.positions[mesh.indices[3 * f + 2]] - a));
}

// Every triangle its own three vertices, as OBJ files without normals and STL files come.
Mesh unwelded(const Mesh& mesh) {
  Mesh soup;
  for (const std::uint32_t v : mesh.indices) {
    soup.indices.push_back(static_cast<std::uint32_t>(soup.positions.size()));
    soup.positions.push_back(mesh.positions[v]);
  }
  return soup;
}

TEST(CreaseNormals, ABoxKeepsItsEdges) {
  const Mesh box = make_box({-1, -1, -1}, {1, 2, 3});
  const std::vector<glm::vec3> normals = crease_normals(box, kDefaultCreaseDegrees);
  ASSERT_EQ(normals.size(), box.indices.size());
  for (std::size_t c = 0; c < normals.size(); ++c)
    EXPECT_NEAR(glm::distance(normals[c], face_normal(box, c / 3)), 0.0f, 1e-6f) << c;
}

TEST(CreaseNormals, AboveTheFoldABoxCornerAveragesItsFaces) {
  const Mesh box = make_box({-1, -1, -1}, {1, 1, 1});
  const std::vector<glm::vec3> normals = crease_normals(box, 100.0f);
  // Every corner of a cube, its three faces around it, each at a right angle there, whether one
  // triangle of the face meets the corner or two: the diagonal.
  for (std::size_t c = 0; c < normals.size(); ++c) {
    const glm::vec3 p = box.positions[box.indices[c]];
    EXPECT_NEAR(glm::distance(normals[c], glm::normalize(p)), 0.0f, 1e-5f) << c;
  }
}

TEST(CreaseNormals, ASphereIsSmoothWhetherWeldedOrNot) {
  const Mesh sphere = make_sphere({1, 2, 3}, 2.0f, 16, 32);
  const std::vector<glm::vec3> welded = crease_normals(sphere, kDefaultCreaseDegrees);
  const std::vector<glm::vec3> soup = crease_normals(unwelded(sphere), kDefaultCreaseDegrees);
  ASSERT_EQ(welded.size(), soup.size());
  for (std::size_t c = 0; c < welded.size(); ++c) {
    EXPECT_NEAR(glm::distance(welded[c], soup[c]), 0.0f, 1e-6f) << c;
    // Near the radial direction: closer than any face's own normal can be at a vertex.
    const glm::vec3 radial =
        glm::normalize(sphere.positions[sphere.indices[c]] - glm::vec3(1, 2, 3));
    EXPECT_GT(glm::dot(welded[c], radial), 0.995f) << c;
  }
}

TEST(CreaseNormals, AFaceWoundAgainstItsNeighboursKeepsItsOwnSide) {
  // Two triangles of one plane (y = 0), the second wound the other way.
  Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {1, 0, 1}};
  mesh.indices = {0, 2, 1, 1, 3, 2};
  const std::vector<glm::vec3> normals = crease_normals(mesh, kDefaultCreaseDegrees);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(normals[c], glm::vec3(0, 1, 0));
  for (int c = 3; c < 6; ++c) EXPECT_EQ(normals[c], glm::vec3(0, -1, 0));
}

TEST(CreaseNormals, AFaceOfNoAreaHasNoDirection) {
  Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {2, 0, 0}};
  mesh.indices = {0, 2, 1, 0, 1, 3};  // the second: three points on a line
  const std::vector<glm::vec3> normals = crease_normals(mesh, kDefaultCreaseDegrees);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(normals[c], glm::vec3(0, 1, 0));
  for (int c = 3; c < 6; ++c) EXPECT_EQ(normals[c], glm::vec3(0.0f));
}

TEST(TerminatorOffsets, FlatIsZeroSmoothIsTheSineOfTheLean) {
  // A box's crease normals are its faces': nothing to take off.
  const Mesh box = make_box({-1, -1, -1}, {1, 1, 1});
  const ShadingNormals flat = make_shading_normals(box, crease_normals(box, kDefaultCreaseDegrees));
  for (const float t : flat.offsets) EXPECT_EQ(t, 0.0f);
  // A roof of two faces meeting at 90 degrees, smoothed (crease above 90): the ridge's normals
  // point straight up, 45 degrees from each face, so the ridge's offset is sin 45; an eave
  // touches one face only, its normal is the face's: offset 0.
  Mesh roof;
  roof.positions = {{-1, 0, -1}, {-1, 0, 1}, {0, 1, -1}, {0, 1, 1}, {1, 0, -1}, {1, 0, 1}};
  roof.indices = {0, 1, 3, 0, 3, 2, 2, 3, 5, 2, 5, 4};
  const ShadingNormals smooth = make_shading_normals(roof, crease_normals(roof, 100.0f));
  for (std::size_t c = 0; c < roof.indices.size(); ++c) {
    const bool ridge = roof.positions[roof.indices[c]].y == 1.0f;
    EXPECT_NEAR(smooth.offsets[c], ridge ? std::sqrt(0.5f) : 0.0f, 1e-6f) << c;
  }
  // Normals of another count than the corners': no offsets to find (the backends shade flat).
  const ShadingNormals wrong = make_shading_normals(roof, {glm::vec3(0, 1, 0)});
  EXPECT_EQ(wrong.offsets, std::vector<float>{0.0f});
}

TEST(InterpolateSmooth, BarycentricInTheFaceClampedOutside) {
  const glm::vec3 corners[3] = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}};
  const glm::vec3 normals[3] = {{0, 0, 1}, {1, 0, 0}, {0, 2, 0}};  // any length
  const float offsets[3] = {0.0f, 0.2f, 0.4f};
  const glm::vec3 face(0, 0, 1);
  const auto at = [&](glm::vec3 p) {
    glm::vec3 w(0.0f);
    EXPECT_TRUE(shading::barycentric(corners, p, w));
    return shading::interpolate_smooth(w, normals, offsets, face);
  };
  for (int k = 0; k < 3; ++k) {  // at a corner, its own
    EXPECT_NEAR(glm::distance(at(corners[k]).normal, glm::normalize(normals[k])), 0.0f, 1e-6f);
    EXPECT_NEAR(at(corners[k]).offset, offsets[k], 1e-6f);
  }
  // Halfway along the first edge: the mean of its ends' (the third's weight is 0).
  EXPECT_NEAR(glm::distance(at({1, 0, 0}).normal, glm::normalize(glm::vec3(1, 0, 1))), 0.0f, 1e-6f);
  EXPECT_NEAR(at({1, 0, 0}).offset, 0.1f, 1e-6f);
  // Beyond that edge (y < 0): the coordinate below 0 taken as 0, (0.75, 0.5, -0.25) -> (0.75,
  // 0.5, 0), so nothing outside the corners' span.
  EXPECT_NEAR(glm::distance(at({1, -0.5f, 0}).normal,
                            glm::normalize(0.75f * normals[0] + 0.5f * normals[1])),
              0.0f, 1e-6f);
  EXPECT_NEAR(at({1, -0.5f, 0}).offset, 0.5f * 0.2f / 1.25f, 1e-6f);
  // Normals that cancel: the face's own, nothing taken off. A face of no area has no
  // coordinates.
  glm::vec3 w(0.0f);
  ASSERT_TRUE(shading::barycentric(corners, {1, 0, 0}, w));
  const glm::vec3 opposed[3] = {{1, 0, 0}, {-1, 0, 0}, {0, 0, 0}};
  EXPECT_EQ(shading::interpolate_smooth(w, opposed, offsets, face).normal, face);
  EXPECT_EQ(shading::interpolate_smooth(w, opposed, offsets, face).offset, 0.0f);
  const glm::vec3 line[3] = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  EXPECT_FALSE(shading::barycentric(line, {1, 0, 0}, w));
  // The Lambert term: the offset taken off, 1 kept at 1; with no offset, the cosine itself.
  EXPECT_FLOAT_EQ(shading::smooth_lambert(1.0f, 0.4f), 1.0f);
  EXPECT_FLOAT_EQ(shading::smooth_lambert(0.4f, 0.4f), 0.0f);
  EXPECT_EQ(shading::smooth_lambert(0.3f, 0.0f), 0.3f);
}

}  // namespace
}  // namespace shadowvol
