// shadowvol view: drawing into the viewer's window and reading it back: a text overlay in the
// top-left corner, an image blitted to the window, the window's pixels as an Image. Needs the
// window's OpenGL 4.5 context current.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/expected.h"
#include "gl/objects.h"
#include "render/frame.h"

namespace shadowvol {

// Text in the top-left corner: the lines drawn with cairo (canvas.h) into a texture, blended
// over the window.
class TextOverlay {
 public:
  static Expected<TextOverlay> create();
  void draw(const std::vector<std::string>& lines, int width, int height);

 private:
  gl::Object program_, texture_, vao_;
};

// Copies an image (row 0 at the top) to the window's framebuffer.
void show_image(const Image& image);
// The window's back buffer, row 0 at the top.
Image read_window(int width, int height);
// How many different RGB colours the image holds (a blank window has one).
std::size_t distinct_colours(const Image& image);

}  // namespace shadowvol
