// Loading real files through assimp: formats, hierarchy transforms, and every kind of bad file.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include <glm/geometric.hpp>

#include "core/topology.h"
#include "scene/mesh_io.h"

namespace shadowvol {
namespace {

const std::filesystem::path kData = SHADOWVOL_TEST_DATA;

TEST(LoadMesh, ObjQuadsAreTriangulated) {
  auto loaded = load_mesh(kData / "cube_quads.obj");
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  EXPECT_EQ(loaded->mesh.triangle_count(), 12u);
  EXPECT_TRUE(build_topology(loaded->mesh).report.closed_manifold);
  EXPECT_TRUE(loaded->warnings.empty());
}

TEST(LoadMesh, PlyAndStlGiveTheTopologyTheyDescribe) {
  auto box = load_mesh(kData / "open_box.ply");
  ASSERT_TRUE(box.ok()) << box.error().message;
  EXPECT_EQ(build_topology(box->mesh).report.boundary_edges, 4u);
  auto fin = load_mesh(kData / "fin.stl");  // STL repeats vertices; welding joins them
  ASSERT_TRUE(fin.ok()) << fin.error().message;
  const TopologyReport r = build_topology(fin->mesh).report;
  EXPECT_EQ(r.vertices, 5u);
  EXPECT_EQ(r.nonmanifold_edges, 1u);
}

TEST(LoadMesh, GltfNodeTransformsAreAppliedPerInstance) {
  // One triangle (0,0,0) (1,0,0) (0,1,0), placed by two children (translated by (10,0,0) and
  // (0,0,5)) of a parent scaled by 2: world = parent * child.
  auto loaded = load_mesh(kData / "instanced.gltf");
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  ASSERT_EQ(loaded->mesh.triangle_count(), 2u);
  std::vector<glm::vec3> corners;
  for (std::uint32_t i : loaded->mesh.indices) corners.push_back(loaded->mesh.positions[i]);
  auto has = [&](glm::vec3 p) {
    return std::find(corners.begin(), corners.end(), p) != corners.end();
  };
  EXPECT_TRUE(has({20, 0, 0}));
  EXPECT_TRUE(has({22, 0, 0}));
  EXPECT_TRUE(has({20, 2, 0}));
  EXPECT_TRUE(has({0, 0, 10}));
  EXPECT_TRUE(has({2, 0, 10}));
  EXPECT_TRUE(has({0, 2, 10}));
}

TEST(LoadMesh, ColladaNestedTransformsAreApplied) {
  // One triangle under a root scaled by 3: once translated by (1,0,0), once turned 90 degrees
  // about z.
  auto loaded = load_mesh(kData / "nested.dae");
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  ASSERT_EQ(loaded->mesh.triangle_count(), 2u);
  const glm::vec3 expected[6] = {{3, 0, 0}, {6, 0, 0}, {3, 3, 0}, {0, 0, 0}, {0, 3, 0}, {-3, 0, 0}};
  for (int k = 0; k < 6; ++k) {
    const glm::vec3 p = loaded->mesh.positions[loaded->mesh.indices[k]];
    EXPECT_NEAR(glm::distance(p, expected[k]), 0.0f, 1e-5f) << "corner " << k;
  }
}

TEST(LoadMesh, ReportsProgressEndingAtOne) {
  std::vector<float> seen;
  auto loaded = load_mesh(kData / "cube_quads.obj", [&](float f) { seen.push_back(f); });
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  ASSERT_FALSE(seen.empty());
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  EXPECT_GE(seen.front(), 0.0f);
  EXPECT_EQ(seen.back(), 1.0f);
}

TEST(LoadMesh, PointsAndLinesAreLeftOutWithAWarning) {
  auto loaded = load_mesh(kData / "points_and_lines.obj");
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  EXPECT_EQ(loaded->mesh.triangle_count(), 1u);
  EXPECT_EQ(loaded->points_ignored, 1u);
  EXPECT_EQ(loaded->lines_ignored, 1u);
  ASSERT_EQ(loaded->warnings.size(), 2u);
  EXPECT_NE(loaded->warnings[0].find("points_and_lines.obj: ignored 1 point"), std::string::npos);
}

struct BadFile {
  const char* file;
  const char* message;  // what the error must say after "<path>: "
};

void PrintTo(const BadFile& bad, std::ostream* os) { *os << bad.file; }

class LoadMeshRefuses : public ::testing::TestWithParam<BadFile> {};

TEST_P(LoadMeshRefuses, WithAMessageNamingTheFileAndTheProblem) {
  const auto path = kData / GetParam().file;
  auto loaded = load_mesh(path);
  ASSERT_FALSE(loaded.ok());
  const std::string& message = loaded.error().message;
  EXPECT_EQ(message.rfind(path.string() + ": ", 0), 0u) << message;
  EXPECT_NE(message.find(GetParam().message), std::string::npos) << message;
}

INSTANTIATE_TEST_SUITE_P(
    BadFiles, LoadMeshRefuses,
    ::testing::Values(
        BadFile{"missing.obj", "no such file"}, BadFile{"", "is a directory"},
        BadFile{"empty.obj", "the file is empty"},
        BadFile{"garbage.bin", "cannot be read as a mesh"},
        BadFile{"lines_only.obj", "no triangles"},
        BadFile{"nan.obj", "vertex 1 has a coordinate that is NaN or infinite"},
        BadFile{"bad_index.obj", "vertex index out of range"},
        // Refused from the file's size before any allocation (under
        // AddressSanitizer too, whose operator new cannot fail softly).
        BadFile{"absurd_count.ply",
                "declares more data than the file holds (element vertex 4000000000, element face "
                "4000000000: at least"},
        // (Found by fuzzing: a line that cannot be made out hides no count.)
        BadFile{"absurd_count_garbled.ply",
                "declares more data than the file holds (element vertex 4000000000, element fc "
                "0: at least"},
        BadFile{"absurd_count_mangled.ply",  // (and a type it cannot make out: a byte)
                "declares more data than the file holds"},
        BadFile{"absurd_count_binary.ply",
                "(element vertex 3, element face 1000000000: at least 1000000036 bytes, in a "
                "file of 178 bytes)"},
        BadFile{"absurd_count.off",
                "declares more data than the file holds (1000000000 vertices, "
                "1000000000 faces: at least 7999999999 bytes"},
        // assimp's validation, said in the file's own terms first.
        BadFile{"truncated.obj",
                "line 7: a face of 2 vertices ('f 1 2'); a face needs three or "
                "more (is the file cut short?); assimp: Validation failed"},
        BadFile{"one_index_face.obj",
                "line 5: a face of 1 vertex ('f 3'); a face needs three or more"},
        BadFile{"absurd_count.stl", "cannot be read as a mesh"}),
    [](const auto& info) {
      std::string name = info.param.file[0] ? info.param.file : "directory";
      std::replace_if(
          name.begin(), name.end(), [](char c) { return !std::isalnum(c); }, '_');
      return name;
    });

}  // namespace
}  // namespace shadowvol
