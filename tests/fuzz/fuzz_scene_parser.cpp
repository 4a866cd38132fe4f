// libFuzzer target: any bytes as a scene file (JSON). Reading must end in a scene or in a message
// that names the file, never a crash or an escaped exception.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_input.h"
#include "scene/scene_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = shadowvol::fuzz::write_input(data, size, ".json");
  auto scene = shadowvol::load_scene_file(path);
  if (!scene && scene.error().message.rfind(path.string() + ": ", 0) != 0) __builtin_trap();
  if (scene && scene->lights.empty()) __builtin_trap();  // a scene has a light at least
  return 0;
}
