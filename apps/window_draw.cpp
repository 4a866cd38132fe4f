#include "window_draw.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include <epoxy/gl.h>
#include <stb/stb_easy_font.h>

namespace shadowvol {

Expected<TextOverlay> TextOverlay::create() {
  auto program = gl::link_program("text", {{GL_VERTEX_SHADER, R"(#version 450 core
layout(location = 0) in vec2 position;  // pixels, y down
layout(location = 1) in vec4 colour;
layout(location = 0) uniform vec2 viewport;
out vec4 tint;
void main() {
  tint = colour;
  gl_Position = vec4(position.x / viewport.x * 2.0 - 1.0, 1.0 - position.y / viewport.y * 2.0, 0.0, 1.0);
}
)"},
                                           {GL_FRAGMENT_SHADER, R"(#version 450 core
in vec4 tint;
layout(location = 0) out vec4 colour;
void main() { colour = tint; }
)"}});
  if (!program) return program.error();
  TextOverlay t;
  t.program_ = std::move(*program);
  return t;
}

void TextOverlay::draw(const std::vector<std::string>& lines, int width, int height) {
  struct Vertex {
    float x, y, z;
    unsigned char rgba[4];
  };
  std::vector<Vertex> quads;
  std::vector<Vertex> scratch(4 * 2000);
  const float scale = width >= 1200 ? 2.0f : 1.5f;
  float y = 6.0f;
  for (const std::string& line : lines) {
    std::vector<char> text(line.begin(), line.end());
    text.push_back('\0');
    for (int shadow = 1; shadow >= 0; --shadow) {  // a dark copy behind, for contrast
      unsigned char colour[4] = {255, 255, 255, 255};
      if (shadow) colour[0] = colour[1] = colour[2] = 0;
      const int n = stb_easy_font_print(0, 0, text.data(), colour, scratch.data(),
                                        static_cast<int>(scratch.size() * sizeof(Vertex)));
      for (int i = 0; i < 4 * n; ++i) {
        Vertex v = scratch[static_cast<std::size_t>(i)];
        v.x = 8.0f + v.x * scale + shadow;
        v.y = y + v.y * scale + shadow;
        quads.push_back(v);
      }
    }
    y += 12.0f * scale;
  }
  std::vector<Vertex> triangles;
  for (std::size_t q = 0; q + 3 < quads.size(); q += 4)
    for (int k : {0, 1, 2, 0, 2, 3}) triangles.push_back(quads[q + static_cast<std::size_t>(k)]);
  if (triangles.empty()) return;
  buffer_ = gl::make_buffer();
  glNamedBufferStorage(buffer_.get(), static_cast<GLsizeiptr>(triangles.size() * sizeof(Vertex)),
                       triangles.data(), 0);
  if (!vao_) vao_ = gl::make_vertex_array();
  glVertexArrayVertexBuffer(vao_.get(), 0, buffer_.get(), 0, sizeof(Vertex));
  glVertexArrayAttribFormat(vao_.get(), 0, 2, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribFormat(vao_.get(), 1, 4, GL_UNSIGNED_BYTE, GL_TRUE, offsetof(Vertex, rgba));
  for (GLuint a : {0u, 1u}) {
    glVertexArrayAttribBinding(vao_.get(), a, 0);
    glEnableVertexArrayAttrib(vao_.get(), a);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_STENCIL_TEST);
  glUseProgram(program_.get());
  glUniform2f(0, static_cast<float>(width), static_cast<float>(height));
  glBindVertexArray(vao_.get());
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(triangles.size()));
  glBindVertexArray(0);
  glUseProgram(0);
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
