#include "image_file.h"

#include <stb/stb_image_write.h>

namespace shadowvol {

Expected<void> write_png(const std::string& path, const Image& img) {
  if (stbi_write_png(path.c_str(), img.width, img.height, 4, img.rgba.data(), img.width * 4) == 0)
    return make_error(path + ": cannot write the image (is the directory there and writable?)");
  return {};
}

}  // namespace shadowvol
