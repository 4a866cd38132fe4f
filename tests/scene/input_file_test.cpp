// The files a scene is read from: every kind of path that cannot be read is refused with what it
// is, before a reader opens it; a path is never mistaken for a built-in scene's name.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "scene/scene_io.h"

namespace shadowvol {
namespace {

namespace fs = std::filesystem;

class InputFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("shadowvol_input_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string refusal(const fs::path& path) {
    auto loaded = load_scene(path.string());
    EXPECT_FALSE(loaded.ok()) << path;
    return loaded.ok() ? std::string() : loaded.error().message;
  }

  fs::path dir_;
};

TEST_F(InputFiles, AMissingPathIsNoSuchFileNotAnUnknownScene) {
  for (const fs::path& path : {dir_ / "scene.json", dir_ / "mesh.ply", fs::path("chair.obj")}) {
    const std::string message = refusal(path);
    EXPECT_EQ(message, path.string() + ": no such file") << message;
  }
  EXPECT_NE(refusal("nosuch").find("unknown scene 'nosuch': the built-in scenes are demo"),
            std::string::npos);
}

TEST_F(InputFiles, AFolderALinkLoopAndALongPathAreSaidAsSuch) {
  fs::create_directories(dir_ / "folder.json");
  EXPECT_EQ(refusal(dir_ / "folder.json"),
            (dir_ / "folder.json").string() + ": is a folder, not a scene or mesh file");
  auto file = load_scene_file(dir_ / "folder.json");  // no std::ios_failure escapes
  ASSERT_FALSE(file.ok());
  EXPECT_NE(file.error().message.find("is a folder, not a scene file"), std::string::npos);

  fs::create_symlink(dir_ / "loop2", dir_ / "loop1");
  fs::create_symlink(dir_ / "loop1", dir_ / "loop2");
  EXPECT_EQ(refusal(dir_ / "loop1"), (dir_ / "loop1").string() +
                                         ": too many levels of symbolic links (a link that "
                                         "leads to itself?)");

  std::string long_path = dir_.string();
  while (long_path.size() <= 4200) long_path += "/" + std::string(200, 'd');
  long_path += "/scene.json";
  EXPECT_NE(refusal(long_path).find(": the path is too long for the system (" +
                                    std::to_string(long_path.size()) + " characters)"),
            std::string::npos);
}

TEST_F(InputFiles, AnUpperCaseExtensionIsReadAsItsKind) {
  std::ofstream(dir_ / "LAMP.JSON") << R"({"camera": {"position": [0, 2, 5], "target": [0, 0, 0]},
                                           "lights": [{"position": [2, 4, 1]}],
                                           "objects": [{"shape": "box"}, {"shape": "ground"}]})";
  auto loaded = load_scene((dir_ / "LAMP.JSON").string());
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  EXPECT_EQ(loaded->scene.objects.size(), 2u);
}

}  // namespace
}  // namespace shadowvol
