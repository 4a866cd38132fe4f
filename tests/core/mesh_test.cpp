#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/mesh.h"

namespace shadowvol {
namespace {

Mesh triangle() {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.indices = {0, 1, 2};
  return m;
}

std::string error_of(const Mesh& m) {
  auto r = validate_mesh(m, "thing.obj");
  return r ? std::string() : r.error().message;
}

TEST(ValidateMesh, AcceptsAGoodTriangle) { EXPECT_TRUE(validate_mesh(triangle(), "t").ok()); }

TEST(ValidateMesh, NamesEachProblem) {
  EXPECT_EQ(error_of(Mesh{}), "thing.obj: the mesh has no triangles");

  Mesh partial = triangle();
  partial.indices.push_back(0);
  EXPECT_NE(error_of(partial).find("not a multiple of 3"), std::string::npos);

  Mesh out_of_range = triangle();
  out_of_range.indices[2] = 7;
  EXPECT_EQ(error_of(out_of_range),
            "thing.obj: triangle 0 uses vertex 7, but the mesh has only 3 vertices");

  Mesh nan = triangle();
  nan.positions[1].y = std::nanf("");
  EXPECT_EQ(error_of(nan), "thing.obj: vertex 1 has a coordinate that is NaN or infinite");

  Mesh far = triangle();
  far.positions[0].x = 3e18f;
  EXPECT_NE(error_of(far).find("vertex 0 lies more than 1e18 from the origin"), std::string::npos);

  Mesh inf = triangle();
  inf.positions[2].z = std::numeric_limits<float>::infinity();
  EXPECT_NE(error_of(inf).find("vertex 2"), std::string::npos);
}

TEST(ValidateMesh, DegenerateTrianglesAreNotErrors) {
  Mesh m;
  m.positions = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  m.indices = {0, 1, 2};
  EXPECT_TRUE(validate_mesh(m, "t").ok());
}

}  // namespace
}  // namespace shadowvol
