#include "gl/objects.h"

#include <vector>

namespace shadowvol::gl {

Object make_buffer() {
  GLuint n = 0;
  glCreateBuffers(1, &n);
  return {n, [](GLuint name) { glDeleteBuffers(1, &name); }};
}

Object make_vertex_array() {
  GLuint n = 0;
  glCreateVertexArrays(1, &n);
  return {n, [](GLuint name) { glDeleteVertexArrays(1, &name); }};
}

Object make_texture(GLenum target) {
  GLuint n = 0;
  glCreateTextures(target, 1, &n);
  return {n, [](GLuint name) { glDeleteTextures(1, &name); }};
}

Object make_framebuffer() {
  GLuint n = 0;
  glCreateFramebuffers(1, &n);
  return {n, [](GLuint name) { glDeleteFramebuffers(1, &name); }};
}

Object make_query(GLenum target) {
  GLuint n = 0;
  glCreateQueries(target, 1, &n);
  return {n, [](GLuint name) { glDeleteQueries(1, &name); }};
}

namespace {

std::string info_log(GLuint object, bool program) {
  GLint length = 0;
  (program ? glGetProgramiv : glGetShaderiv)(object, GL_INFO_LOG_LENGTH, &length);
  std::vector<char> log(static_cast<std::size_t>(std::max(length, 1)), '\0');
  (program ? glGetProgramInfoLog : glGetShaderInfoLog)(object, length, nullptr, log.data());
  return log.data();
}

const char* stage_name(GLenum stage) {
  switch (stage) {
    case GL_VERTEX_SHADER:
      return "vertex";
    case GL_GEOMETRY_SHADER:
      return "geometry";
    case GL_FRAGMENT_SHADER:
      return "fragment";
    default:
      return "other";
  }
}

}  // namespace

Expected<Object> link_program(const char* name, std::initializer_list<ShaderSource> sources) {
  Object program(glCreateProgram(), [](GLuint n) { glDeleteProgram(n); });
  std::vector<Object> shaders;
  for (const ShaderSource& source : sources) {
    Object shader(glCreateShader(source.stage), [](GLuint n) { glDeleteShader(n); });
    glShaderSource(shader.get(), 1, &source.text, nullptr);
    glCompileShader(shader.get());
    GLint ok = GL_FALSE;
    glGetShaderiv(shader.get(), GL_COMPILE_STATUS, &ok);
    if (ok != GL_TRUE)
      return make_error(std::string("the ") + stage_name(source.stage) + " shader of '" + name +
                        "' does not compile: " + info_log(shader.get(), false));
    glAttachShader(program.get(), shader.get());
    shaders.push_back(std::move(shader));
  }
  glLinkProgram(program.get());
  GLint ok = GL_FALSE;
  glGetProgramiv(program.get(), GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE)
    return make_error(std::string("the program '") + name +
                      "' does not link: " + info_log(program.get(), true));
  for (const Object& shader : shaders) glDetachShader(program.get(), shader.get());
  return program;
}

std::string take_error() {
  switch (glGetError()) {
    case GL_NO_ERROR:
      return "";
    case GL_INVALID_ENUM:
      return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
      return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
      return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
      return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY:
      return "GL_OUT_OF_MEMORY";
    default:
      return "an OpenGL error";
  }
}

}  // namespace shadowvol::gl
