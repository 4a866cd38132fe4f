// Textures: image files decoded, bad ones refused by name, and the sampling both backends share.
#include <gtest/gtest.h>

#include <filesystem>

#include <glm/geometric.hpp>

#include "render/shading.h"
#include "scene/mesh_io.h"
#include "scene/scene_io.h"
#include "scene/texture_io.h"

namespace shadowvol {
namespace {

const std::filesystem::path kData = SHADOWVOL_TEST_DATA;

// checker.png: 64 x 64, squares of 16 pixels, orange (235, 150, 50) and blue (60, 110, 210),
// the top-left square red (200, 30, 40).
TEST(LoadTexture, DecodesAnImageFile) {
  auto texture = load_texture(kData / "checker.png");
  ASSERT_TRUE(texture.ok()) << texture.error().message;
  EXPECT_EQ(texture->width, 64);
  EXPECT_EQ(texture->height, 64);
  ASSERT_EQ(texture->rgba.size(), 64u * 64u * 4u);
  EXPECT_EQ(texture->rgba[0], 200);  // the top row comes first
  EXPECT_EQ(texture->rgba[1], 30);
  EXPECT_EQ(texture->rgba[3], 255);
  EXPECT_EQ(texture->rgba[(16 * 64 + 0) * 4 + 2], 210);  // the square below: blue
}

TEST(LoadTexture, RefusesWhatItCannotUse) {
  struct Bad {
    const char* file;
    const char* says;
  };
  for (const Bad& bad : {Bad{"missing.png", "missing.png: no such file"},
                         Bad{"garbage.bin", "garbage.bin: not an image stb_image can read"},
                         Bad{"huge_texture.png",
                             "huge_texture.png: 20000x8 pixels; a texture may be at most 16384 a "
                             "side"}}) {
    auto texture = load_texture(kData / bad.file);
    ASSERT_FALSE(texture.ok()) << bad.file;
    EXPECT_NE(texture.error().message.find(bad.says), std::string::npos) << texture.error().message;
  }
}

TEST(SampleTexture, BilinearInLinearLightRepeatingVUp) {
  auto texture = load_texture(kData / "checker.png");
  ASSERT_TRUE(texture.ok()) << texture.error().message;
  const auto linear = [](float srgb8) {
    const float c = srgb8 / 255.0f;
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
  };
  const glm::vec3 red(linear(200), linear(30), linear(40));
  const glm::vec3 blue(linear(60), linear(110), linear(210));
  // Inside the red square (the image's top left: v near 1), and one repeat away.
  for (const glm::vec2 uv : {glm::vec2(0.125f, 0.875f), glm::vec2(1.125f, -1.125f)})
    EXPECT_NEAR(glm::distance(shading::sample_texture(*texture, uv), red), 0.0f, 1e-6f);
  // On the boundary between the red square and the blue one below it: their mean, in linear
  // light (bilinear between the texel centres either side).
  EXPECT_NEAR(
      glm::distance(shading::sample_texture(*texture, {0.125f, 0.75f}), (red + blue) * 0.5f), 0.0f,
      1e-6f);
  // Across the seam of the repeat: the first column's texel and the last's, halved.
  const glm::vec3 last_column = shading::sample_texture(*texture, {63.5f / 64.0f, 0.875f});
  EXPECT_NEAR(
      glm::distance(shading::sample_texture(*texture, {0.0f, 0.875f}), (red + last_column) * 0.5f),
      0.0f, 1e-6f);
  EXPECT_EQ(shading::sample_texture(Texture{}, {0.5f, 0.5f}), glm::vec3(1.0f));  // no pixels
}

TEST(MeshTextures, AMaterialsMapAndTheCornersCoordinates) {
  auto loaded = load_mesh(kData / "textured.obj");
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  ASSERT_EQ(loaded->materials.size(), 1u);
  const auto& map = loaded->materials[0].material.base_color_map;
  ASSERT_NE(map, nullptr);
  EXPECT_EQ(map->width, 64);
  ASSERT_EQ(loaded->corner_uvs.size(), loaded->mesh.indices.size());
  EXPECT_EQ(loaded->corner_uvs[0], glm::vec2(0, 0));
  EXPECT_EQ(loaded->corner_uvs[2], glm::vec2(1, 1));
  auto scene = load_scene((kData / "textured.obj").string());
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  EXPECT_NE(texture_coordinates(scene->scene.objects[0]), nullptr);
}

// The same cube as a glTF (v down from the image's top, as glTF has it): the same texture at
// the same places, and the file's camera.
TEST(MeshTextures, GltfAndObjAgree) {
  auto gltf = load_mesh(kData / "textured.gltf");
  auto obj = load_mesh(kData / "textured.obj");
  ASSERT_TRUE(gltf.ok()) << gltf.error().message;
  ASSERT_TRUE(obj.ok()) << obj.error().message;
  ASSERT_EQ(gltf->materials.size(), 2u);  // Checker, Floor
  ASSERT_NE(gltf->materials[0].material.base_color_map, nullptr);
  EXPECT_EQ(gltf->materials[0].material.base_color_map->rgba,
            obj->materials[0].material.base_color_map->rgba);
  EXPECT_EQ(gltf->materials[1].material.base_color_map, nullptr);
  // The cube's 36 corners first in both, in the same order.
  for (std::size_t c = 0; c < 36; ++c) {
    EXPECT_EQ(gltf->mesh.positions[gltf->mesh.indices[c]],
              obj->mesh.positions[obj->mesh.indices[c]]);
    EXPECT_NEAR(glm::distance(gltf->corner_uvs[c], obj->corner_uvs[c]), 0.0f, 1e-6f) << c;
  }
  ASSERT_EQ(gltf->cameras.size(), 1u);
  EXPECT_EQ(gltf->cameras[0].name, "Overview");
}

TEST(MeshTextures, AMissingTextureIsLeftOutWithAWarning) {
  auto loaded = load_mesh(kData / "missing_texture.obj");
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  ASSERT_EQ(loaded->materials.size(), 1u);
  EXPECT_EQ(loaded->materials[0].material.base_color_map, nullptr);
  EXPECT_NEAR(loaded->materials[0].material.color.g, 0.6f, 1e-6f);
  ASSERT_EQ(loaded->warnings.size(), 1u);
  EXPECT_NE(loaded->warnings[0].find("material 'lost': its texture is left out ("),
            std::string::npos)
      << loaded->warnings[0];
  EXPECT_NE(
      loaded->warnings[0].find("no_such_texture.png: no such file); drawn in its base colour"),
      std::string::npos)
      << loaded->warnings[0];
  EXPECT_TRUE(loaded->corner_uvs.empty());
}

TEST(MeshTextures, AMapWithoutCoordinatesIsLeftOutWithAWarning) {
  auto loaded = load_mesh(kData / "texture_no_uvs.obj");
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  ASSERT_EQ(loaded->materials.size(), 1u);
  EXPECT_EQ(loaded->materials[0].material.base_color_map, nullptr);
  ASSERT_EQ(loaded->warnings.size(), 1u);
  EXPECT_NE(loaded->warnings[0].find("material 'checker': its texture is left out (its triangles "
                                     "have no texture coordinates)"),
            std::string::npos)
      << loaded->warnings[0];
}

}  // namespace
}  // namespace shadowvol
