#include "scene/texture_io.h"

#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <vector>

#include <stb/stb_image.h>

#include "scene/input_file.h"

namespace shadowvol {
namespace {
std::string why_not() {
  const char* reason = stbi_failure_reason();
  return reason ? reason : "no reason given";
}
}  // namespace

Expected<Texture> decode_texture(const std::uint8_t* bytes, std::size_t size,
                                 const std::string& source) {
  if (size == 0) return make_error(source + ": the image is empty");
  if (size > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    return make_error(source + ": the image is larger than 2 GB");
  const int length = static_cast<int>(size);
  int w = 0, h = 0, channels = 0;
  if (!stbi_info_from_memory(bytes, length, &w, &h, &channels))
    return make_error(source + ": not an image stb_image can read (" + why_not() + ")");
  if (w <= 0 || h <= 0 || w > kMaxTextureSide || h > kMaxTextureSide)
    return make_error(source + ": " + std::to_string(w) + "x" + std::to_string(h) +
                      " pixels; a texture may be at most " + std::to_string(kMaxTextureSide) +
                      " a side");
  const std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
      stbi_load_from_memory(bytes, length, &w, &h, &channels, 4), stbi_image_free);
  if (!pixels) return make_error(source + ": the image cannot be decoded (" + why_not() + ")");
  Texture texture;
  texture.width = w;
  texture.height = h;
  texture.rgba.assign(pixels.get(), pixels.get() + std::size_t(w) * std::size_t(h) * 4);
  texture.source = source;
  return texture;
}

Expected<Texture> load_texture(const std::filesystem::path& path) {
  const std::string name = path.string();
  if (auto ok = check_input_file(path, "texture"); !ok) return ok.error();
  std::ifstream in(path, std::ios::binary);
  if (!in) return make_error(name + ": cannot be opened for reading");
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                        std::istreambuf_iterator<char>());
  return decode_texture(bytes.data(), bytes.size(), name);
}

}  // namespace shadowvol
