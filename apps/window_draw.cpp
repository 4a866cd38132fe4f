#include "window_draw.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include <epoxy/gl.h>

#include "canvas.h"

namespace shadowvol {

Expected<TextOverlay> TextOverlay::create() {
  // A quad over the text's pixels (gl_VertexID 0..3 as a strip), its picture blended over.
  auto program = gl::link_program("text", {{GL_VERTEX_SHADER, R"(#version 450 core
layout(location = 0) uniform vec4 rect;  // x, y, width, height in pixels, y down
layout(location = 1) uniform vec2 viewport;
out vec2 uv;
void main() {
  uv = vec2(gl_VertexID & 1, gl_VertexID >> 1);
  vec2 p = rect.xy + uv * rect.zw;
  gl_Position = vec4(p.x / viewport.x * 2.0 - 1.0, 1.0 - p.y / viewport.y * 2.0, 0.0, 1.0);
}
)"},
                                           {GL_FRAGMENT_SHADER, R"(#version 450 core
in vec2 uv;
layout(binding = 0) uniform sampler2D text;
layout(location = 0) out vec4 colour;
void main() { colour = texture(text, uv); }
)"}});
  if (!program) return program.error();
  TextOverlay t;
  t.program_ = std::move(*program);
  t.vao_ = gl::make_vertex_array();
  return t;
}

void TextOverlay::draw(const std::vector<std::string>& lines, int width, int height) {
  if (lines.empty()) return;
  // The lines drawn with cairo on a transparent picture: white, over a dark shadow for contrast.
  const double size = width >= 1200 ? 18.0 : 14.0, step = size * 1.3;
  Canvas measure = Canvas::image(1, 1, glm::vec3(0.0f), 0.0f);
  double widest = 0.0;
  for (const std::string& line : lines) widest = std::max(widest, measure.text_width(line, size));
  const int w = static_cast<int>(std::ceil(widest)) + 4;
  const int h = static_cast<int>(std::ceil(step * lines.size())) + 4;
  Canvas canvas = Canvas::image(w, h, glm::vec3(0.0f), 0.0f);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    canvas.text(2, 2 + step * i, lines[i], size, glm::vec3(0.0f));
    canvas.text(1, 1 + step * i, lines[i], size, glm::vec3(1.0f));
  }
  const Image picture = canvas.pixels();
  texture_ = gl::make_texture(GL_TEXTURE_2D);
  glTextureStorage2D(texture_.get(), 1, GL_RGBA8, w, h);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(texture_.get(), 0, 0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE,
                      picture.rgba.data());
  glTextureParameteri(texture_.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(texture_.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_STENCIL_TEST);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glUseProgram(program_.get());
  glUniform4f(0, 8.0f, 6.0f, static_cast<float>(w), static_cast<float>(h));
  glUniform2f(1, static_cast<float>(width), static_cast<float>(height));
  glBindTextureUnit(0, texture_.get());
  glBindVertexArray(vao_.get());
  glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
  glBindVertexArray(0);
  glUseProgram(0);
  glDisable(GL_BLEND);
}

void show_image(const Image& image) {
  gl::Object texture = gl::make_texture(GL_TEXTURE_2D);
  glTextureStorage2D(texture.get(), 1, GL_RGBA8, image.width, image.height);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(texture.get(), 0, 0, 0, image.width, image.height, GL_RGBA, GL_UNSIGNED_BYTE,
                      image.rgba.data());
  gl::Object fbo = gl::make_framebuffer();
  glNamedFramebufferTexture(fbo.get(), GL_COLOR_ATTACHMENT0, texture.get(), 0);
  glBlitNamedFramebuffer(fbo.get(), 0, 0, 0, image.width, image.height, 0, image.height,
                         image.width, 0, GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

Image read_window(int width, int height) {
  Image image{width, height,
              std::vector<std::uint8_t>(static_cast<std::size_t>(width) * height * 4)};
  std::vector<std::uint8_t> rows(image.rgba.size());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
  const std::size_t stride = static_cast<std::size_t>(width) * 4;
  for (int y = 0; y < height; ++y)
    std::copy_n(&rows[static_cast<std::size_t>(height - 1 - y) * stride], stride,
                &image.rgba[static_cast<std::size_t>(y) * stride]);
  return image;
}

std::size_t distinct_colours(const Image& image) {
  std::vector<std::uint32_t> colours;
  for (std::size_t p = 0; p + 3 < image.rgba.size(); p += 4)
    colours.push_back(image.rgba[p] | image.rgba[p + 1] << 8 | image.rgba[p + 2] << 16);
  std::sort(colours.begin(), colours.end());
  return static_cast<std::size_t>(std::unique(colours.begin(), colours.end()) - colours.begin());
}

}  // namespace shadowvol
