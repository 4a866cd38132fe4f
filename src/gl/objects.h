// shadowvol gl: owning handles of OpenGL objects, and shader programs built from source.
//
// Owns: the lifetime of object names (deleted when the handle goes, so an early return leaks
// nothing) and turning GLSL into a linked program or an error that quotes the driver's log.
// Every function needs an OpenGL context current on the calling thread.
#pragma once

#include <initializer_list>
#include <string>
#include <utility>

#include <epoxy/gl.h>

#include "core/expected.h"

namespace shadowvol::gl {

// One object name and the function that deletes it.
class Object {
 public:
  using Deleter = void (*)(GLuint);
  Object() = default;
  Object(GLuint name, Deleter deleter) : name_(name), deleter_(deleter) {}
  Object(Object&& other) noexcept
      : name_(std::exchange(other.name_, 0)), deleter_(other.deleter_) {}
  Object& operator=(Object&& other) noexcept {
    if (this != &other) {
      reset();
      name_ = std::exchange(other.name_, 0);
      deleter_ = other.deleter_;
    }
    return *this;
  }
  Object(const Object&) = delete;
  Object& operator=(const Object&) = delete;
  ~Object() { reset(); }

  GLuint get() const { return name_; }
  explicit operator bool() const { return name_ != 0; }
  void reset() {
    if (name_ != 0) deleter_(name_);
    name_ = 0;
  }

 private:
  GLuint name_ = 0;
  Deleter deleter_ = nullptr;
};

Object make_buffer();
Object make_vertex_array();
Object make_texture(GLenum target);
Object make_framebuffer();
Object make_query(GLenum target);

struct ShaderSource {
  GLenum stage;  // GL_VERTEX_SHADER, GL_GEOMETRY_SHADER, GL_FRAGMENT_SHADER
  const char* text;
};

// Compiles and links; the error names the program and carries the driver's log.
Expected<Object> link_program(const char* name, std::initializer_list<ShaderSource> sources);

// The first pending OpenGL error as text ("GL_INVALID_OPERATION"), or "" when there is none.
std::string take_error();

}  // namespace shadowvol::gl
