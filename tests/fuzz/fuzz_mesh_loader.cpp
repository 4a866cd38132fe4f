// libFuzzer target: any bytes as a mesh file, the first byte choosing the format by extension (as
// assimp chooses its reader). Loading must end in a mesh that validates or in a message, never a
// crash, a hang or an allocation past libFuzzer's limit.
#include <array>
#include <cstddef>
#include <cstdint>

#include "fuzz_input.h"
#include "scene/mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static constexpr std::array<const char*, 10> kExtensions = {
      ".obj", ".ply", ".off", ".stl", ".gltf", ".glb", ".dae", ".fbx", ".3ds", ".x3d"};
  if (size == 0) return 0;
  const auto path =
      shadowvol::fuzz::write_input(data + 1, size - 1, kExtensions[data[0] % kExtensions.size()]);
  auto loaded = shadowvol::load_mesh(path);
  if (loaded) {  // what loads is a valid mesh
    if (!shadowvol::validate_mesh(loaded->mesh, "fuzz").ok()) __builtin_trap();
  } else if (loaded.error().message.empty()) {
    __builtin_trap();  // a refusal says why
  }
  return 0;
}
