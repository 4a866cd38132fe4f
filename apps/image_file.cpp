#include "image_file.h"

#include <bit>
#include <cstring>
#include <string>

#include <stb/stb_image_write.h>

#include "output_file.h"

namespace shadowvol {
namespace {

// The PNG in memory, so that it reaches the disk whole or not at all (write_file).
Expected<void> write_png(const std::string& path, int width, int height, int channels,
                         const std::uint8_t* pixels) {
  std::string bytes;
  const auto append = [](void* to, void* data, int size) {
    static_cast<std::string*>(to)->append(static_cast<const char*>(data),
                                          static_cast<std::size_t>(size));
  };
  if (stbi_write_png_to_func(append, &bytes, width, height, channels, pixels, width * channels) ==
      0)
    return make_error(path + ": the image cannot be encoded as a PNG");
  return write_file(path, bytes);
}

}  // namespace

Expected<void> write_png(const std::string& path, const Image& img) {
  return write_png(path, img.width, img.height, 4, img.rgba.data());
}

Expected<void> write_png(const std::string& path, const GreyImage& img) {
  return write_png(path, img.width, img.height, 1, img.value.data());
}

Expected<void> write_pfm(const std::string& path, const DepthImage& img) {
  static_assert(std::endian::native == std::endian::little, "PFM's scale -1 says little-endian");
  std::string bytes =
      "Pf\n" + std::to_string(img.width) + " " + std::to_string(img.height) + "\n-1.0\n";
  const std::size_t row = sizeof(float) * static_cast<std::size_t>(img.width);
  for (int y = img.height - 1; y >= 0; --y)
    bytes.append(reinterpret_cast<const char*>(&img.depth[std::size_t(y) * img.width]), row);
  return write_file(path, bytes);
}

}  // namespace shadowvol
