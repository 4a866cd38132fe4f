// Loading real files through assimp: formats, hierarchy transforms, and every kind of bad file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

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

const FileMaterial* material_named(const LoadedMesh& loaded, const std::string& name) {
  for (const FileMaterial& m : loaded.materials)
    if (m.name == name) return &m;
  return nullptr;
}

TEST(LoadMesh, GltfMaterialsCamerasAndLightsAreRead) {
  // A red box, a thin blue panel blended at alpha 0.4, a floor; two cameras placed by their nodes
  // (ShotNode at (0, 2.5, 5) pitched down by 2 asin(0.1891) = 21.8 degrees, yfov 0.8 radians);
  // a KHR_lights_punctual point light of colour (1, 0.8, 0.6) at (2, 4, 3).
  auto loaded = load_mesh(kData / "materials.gltf");
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  ASSERT_EQ(loaded->triangle_material.size(), loaded->mesh.triangle_count());
  ASSERT_EQ(loaded->materials.size(), 3u);
  const FileMaterial* red = material_named(*loaded, "Red");
  const FileMaterial* glass = material_named(*loaded, "BlueGlass");
  ASSERT_TRUE(red && glass && material_named(*loaded, "Floor"));
  EXPECT_NEAR(glm::distance(red->material.color, glm::vec3(0.8f, 0.1f, 0.1f)), 0.0f, 1e-6f);
  EXPECT_EQ(red->material.opacity, 1.0f);
  EXPECT_NEAR(glm::distance(glass->material.color, glm::vec3(0.2f, 0.4f, 0.9f)), 0.0f, 1e-6f);
  EXPECT_NEAR(glass->material.opacity, 0.4f, 1e-6f);
  const auto uses = [&](const FileMaterial* m) {
    return std::count(loaded->triangle_material.begin(), loaded->triangle_material.end(),
                      static_cast<std::uint32_t>(m - loaded->materials.data()));
  };
  EXPECT_EQ(uses(red), 12);    // the box
  EXPECT_EQ(uses(glass), 12);  // the panel, a thin box
  EXPECT_EQ(uses(material_named(*loaded, "Floor")), 2);

  ASSERT_EQ(loaded->cameras.size(), 2u);
  EXPECT_EQ(loaded->cameras[0].name, "ShotNode");
  EXPECT_EQ(loaded->cameras[1].name, "SideNode");
  const Camera& shot = loaded->cameras[0].camera;
  EXPECT_NEAR(glm::distance(shot.position, glm::vec3(0.0f, 2.5f, 5.0f)), 0.0f, 1e-5f);
  const float pitch = 2.0f * std::asin(0.18910752f);
  const glm::vec3 ahead = glm::normalize(shot.target - shot.position);
  EXPECT_NEAR(glm::distance(ahead, glm::vec3(0.0f, -std::sin(pitch), -std::cos(pitch))), 0.0f,
              1e-5f);
  EXPECT_NEAR(shot.fov_y_degrees, glm::degrees(0.8f), 1e-3f);
  EXPECT_NEAR(shot.near, 0.05f, 1e-6f);
  const Camera& side = loaded->cameras[1].camera;  // turned 90 degrees about y: looking along -x
  EXPECT_NEAR(glm::distance(glm::normalize(side.target - side.position), glm::vec3(-1, 0, 0)), 0.0f,
              1e-5f);
  EXPECT_NEAR(side.fov_y_degrees, glm::degrees(0.9f), 1e-3f);

  ASSERT_EQ(loaded->lights.size(), 1u);
  EXPECT_EQ(loaded->lights[0].name, "BulbNode");
  const SceneLight& bulb = loaded->lights[0].light;
  EXPECT_NEAR(glm::distance(bulb.position, glm::vec4(2, 4, 3, 1)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::distance(bulb.color, glm::vec3(1.0f, 0.8f, 0.6f)), 0.0f, 1e-6f);
}

TEST(LoadMesh, MtlDiffuseAndDissolveAreRead) {
  auto loaded = load_mesh(kData / "materials.obj");
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  ASSERT_EQ(loaded->materials.size(), 2u);  // assimp's default material is not one of the file's
  const FileMaterial* green = material_named(*loaded, "green");
  const FileMaterial* smoke = material_named(*loaded, "smoke");
  ASSERT_TRUE(green && smoke);
  EXPECT_NEAR(glm::distance(green->material.color, glm::vec3(0.1f, 0.7f, 0.2f)), 0.0f, 1e-6f);
  EXPECT_EQ(green->material.opacity, 1.0f);
  EXPECT_NEAR(smoke->material.opacity, 0.25f, 1e-6f);
  const auto index = [&](const FileMaterial* m) {
    return static_cast<std::uint32_t>(m - loaded->materials.data());
  };
  EXPECT_EQ(loaded->triangle_material,
            (std::vector<std::uint32_t>{index(green), index(green), index(smoke)}));
  EXPECT_TRUE(loaded->cameras.empty());
  EXPECT_TRUE(loaded->lights.empty());
}

// COLLADA's opaque modes as assimp applies them (transparent white, transparency 0.25), and an
// exporter's "transparency 0" for an opaque material, read as opaque and said.
TEST(LoadMesh, ColladaTransparencyFollowsItsOpaqueMode) {
  for (const auto& [file, opacity] : {std::pair{"collada_a_one_quarter.dae", 0.25f},
                                      std::pair{"collada_a_zero_quarter.dae", 0.75f},
                                      std::pair{"collada_rgb_one_quarter.dae", 0.25f},
                                      std::pair{"collada_rgb_zero_quarter.dae", 0.75f},
                                      std::pair{"collada_rgb_zero_0.dae", 1.0f}}) {
    SCOPED_TRACE(file);
    auto loaded = load_mesh(kData / file);
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    ASSERT_EQ(loaded->materials.size(), 1u);
    EXPECT_NEAR(loaded->materials[0].material.opacity, opacity, 1e-6f);
    EXPECT_TRUE(loaded->warnings.empty());
  }
}

TEST(LoadMesh, AnExportersNoTransparencyIsReadAsOpaque) {
  auto dae = load_mesh(kData / "collada_transparency_0.dae");  // <transparency>0, A_ONE
  ASSERT_TRUE(dae.ok()) << dae.error().message;
  ASSERT_EQ(dae->materials.size(), 1u);
  EXPECT_EQ(dae->materials[0].material.opacity, 1.0f);
  ASSERT_EQ(dae->warnings.size(), 1u);
  EXPECT_NE(dae->warnings[0].find("material 'mat' is fully transparent as the file is written"),
            std::string::npos)
      << dae->warnings[0];
  auto obj = load_mesh(kData / "transparency_tr.obj");  // Tr 1 and Tr 0.75
  ASSERT_TRUE(obj.ok()) << obj.error().message;
  const FileMaterial* clear = material_named(*obj, "clear_by_tr");
  const FileMaterial* smoke = material_named(*obj, "smoke_by_tr");
  ASSERT_TRUE(clear && smoke);
  EXPECT_EQ(clear->material.opacity, 1.0f);
  EXPECT_NEAR(smoke->material.opacity, 0.25f, 1e-6f);
  ASSERT_EQ(obj->warnings.size(), 1u);
  EXPECT_NE(obj->warnings[0].find("MTL d 0 or Tr 1"), std::string::npos) << obj->warnings[0];
}

TEST(LoadMesh, AFileWithoutMaterialsGivesNone) {
  auto loaded = load_mesh(kData / "cube_quads.obj");
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  EXPECT_TRUE(loaded->materials.empty());
  EXPECT_TRUE(loaded->triangle_material.empty());
}

TEST(LoadMesh, NormalsAreTheFilesElseACreaseAngles) {
  auto given = load_mesh(kData / "normals.obj");
  ASSERT_TRUE(given.ok()) << given.error().message;
  ASSERT_EQ(given->corner_normals.size(), 6u);
  for (const glm::vec3& n : given->corner_normals)
    EXPECT_NEAR(glm::distance(n, glm::vec3(0.6f, 0.8f, 0.0f)), 0.0f, 1e-6f);
  // Without normals in the file: a cube's corners keep their faces' (its edges are creases).
  auto cube = load_mesh(kData / "cube_quads.obj");
  ASSERT_TRUE(cube.ok()) << cube.error().message;
  ASSERT_EQ(cube->corner_normals.size(), cube->mesh.indices.size());
  const Mesh& m = cube->mesh;
  for (std::size_t c = 0; c < m.indices.size(); ++c) {
    const std::uint32_t* v = &m.indices[3 * (c / 3)];
    const glm::vec3 face = glm::normalize(
        glm::cross(m.positions[v[1]] - m.positions[v[0]], m.positions[v[2]] - m.positions[v[0]]));
    EXPECT_NEAR(glm::distance(cube->corner_normals[c], face), 0.0f, 1e-6f) << c;
  }
  // A node's transform turns them: instanced.gltf's parent scales by 2 (no turn, unit length).
  auto placed = load_mesh(kData / "instanced.gltf");
  ASSERT_TRUE(placed.ok()) << placed.error().message;
  for (const glm::vec3& n : placed->corner_normals) EXPECT_NEAR(glm::length(n), 1.0f, 1e-6f);
}

// The file's animations as clips of its node hierarchy (scripts/make_turntable_gltf.py), in
// seconds; each triangle knows the node that placed it; the mesh stays at rest.
TEST(LoadMesh, AnimationsAreClipsOfTheNodeHierarchy) {
  auto loaded =
      load_mesh(std::filesystem::path(SHADOWVOL_SOURCE_DIR) / "scenes/meshes/turntable.gltf");
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  ASSERT_NE(loaded->hierarchy, nullptr);
  const NodeHierarchy& h = *loaded->hierarchy;
  ASSERT_EQ(h.clips.size(), 2u);
  EXPECT_EQ(h.clips[0].name, "Spin");
  EXPECT_DOUBLE_EQ(h.clips[0].duration, 2.0);
  EXPECT_EQ(h.clips[1].name, "Hop");
  EXPECT_DOUBLE_EQ(h.clips[1].duration, 1.0);
  // Parents before children: the turntable's two boxes name it as their parent.
  std::vector<std::string> names;
  for (const HierarchyNode& n : h.nodes) names.push_back(n.name);
  const auto index = [&](const std::string& name) {
    return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin());
  };
  ASSERT_LT(index("Bob"), static_cast<int>(names.size()));
  EXPECT_EQ(h.nodes[index("Bob")].parent, index("Turntable"));
  EXPECT_EQ(h.nodes[index("Box")].parent, index("Turntable"));
  EXPECT_TRUE(h.moves(index("Box"), 0));   // by its parent's turn
  EXPECT_FALSE(h.moves(index("Bob"), 1));  // "Hop" lifts the box alone
  EXPECT_FALSE(h.moves(index("Pillar"), 0));
  EXPECT_NEAR(h.nodes[index("Bob")].rest_scale.y, 0.6, 1e-6);
  // Halfway through the turn the turntable has turned a quarter: +x to -z.
  const glm::dvec4 x_axis = h.world_at(index("Turntable"), 0, 0.5) * glm::dvec4(1, 0, 0, 0);
  EXPECT_NEAR(x_axis.z, -1.0, 1e-6);
  ASSERT_EQ(loaded->triangle_node.size(), loaded->mesh.triangle_count());
  EXPECT_EQ(loaded->triangle_node[0], static_cast<std::uint32_t>(index("Pillar")));
  // A still file has neither.
  auto still = load_mesh(kData / "materials.gltf");
  ASSERT_TRUE(still.ok()) << still.error().message;
  EXPECT_EQ(still->hierarchy, nullptr);
  EXPECT_TRUE(still->triangle_node.empty());
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
        BadFile{"missing.obj", "no such file"}, BadFile{"", "is a folder, not a mesh file"},
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
        BadFile{"absurd_count.stl", "cannot be read as a mesh"},
        // (Found by fuzzing: assimp reads such a header forever.)
        BadFile{"element_twice.ply", "the PLY header defines the element 'face' twice"},
        BadFile{"no_end_header.ply",
                "the PLY header has no end_header line (is the file cut short?)"},
        BadFile{"nan_key.gltf",
                "animation 'Spin' moves node 'Turntable' by a key that is not a finite number"}),
    [](const auto& info) {
      std::string name = info.param.file[0] ? info.param.file : "directory";
      std::replace_if(
          name.begin(), name.end(), [](char c) { return !std::isalnum(c); }, '_');
      return name;
    });

}  // namespace
}  // namespace shadowvol
