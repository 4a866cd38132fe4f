#include "image_file.h"

#include <bit>
#include <cstring>
#include <fstream>

#include <stb/stb_image_write.h>

namespace shadowvol {
namespace {

Error cannot_write(const std::string& path) {
  return make_error(path + ": cannot write the image (is the directory there and writable?)");
}

}  // namespace

Expected<void> write_png(const std::string& path, const Image& img) {
  if (stbi_write_png(path.c_str(), img.width, img.height, 4, img.rgba.data(), img.width * 4) == 0)
    return cannot_write(path);
  return {};
}

Expected<void> write_png(const std::string& path, const GreyImage& img) {
  if (stbi_write_png(path.c_str(), img.width, img.height, 1, img.value.data(), img.width) == 0)
    return cannot_write(path);
  return {};
}

Expected<void> write_pfm(const std::string& path, const DepthImage& img) {
  static_assert(std::endian::native == std::endian::little, "PFM's scale -1 says little-endian");
  std::ofstream out(path, std::ios::binary);
  out << "Pf\n" << img.width << " " << img.height << "\n-1.0\n";
  for (int y = img.height - 1; y >= 0; --y)
    out.write(reinterpret_cast<const char*>(&img.depth[std::size_t(y) * img.width]),
              static_cast<std::streamsize>(sizeof(float) * img.width));
  out.close();
  if (!out) return cannot_write(path);
  return {};
}

}  // namespace shadowvol
