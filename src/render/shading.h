// shadowvol render: the shading both backends use (the OpenGL backend passes these to its
// shaders as uniforms): ambient * albedo, plus per unshadowed light Lambert + Blinn-Phong, lit on
// the side the eye sees, and only where that side of the face faces the light within its range
// (a face turned from a light lies in its own shadow, whatever its smooth normals say); a
// vertical gradient behind everything; sRGB out.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "scene/scene.h"

namespace shadowvol::shading {

inline constexpr float kSpecular = 0.25f;
inline constexpr float kShininess = 48.0f;
inline constexpr glm::vec3 kBackgroundTop{0.26f, 0.28f, 0.22f};
inline constexpr glm::vec3 kBackgroundBottom{0.16f, 0.18f, 0.22f};
// cos_half^kShininess (Blinn-Phong) for cos_half in [0, 1], by multiplications: a frame takes it
// millions of times, and pow is slow (within float rounding of std::pow).
inline float specular_power(float cos_half) {
  static_assert(kShininess == 48.0f, "x^48 = ((x^3)^2)^2)^2)^2");
  float x = cos_half * cos_half * cos_half;
  for (int k = 0; k < 4; ++k) x *= x;
  return x;
}
// A point light with a range r (SceneLight::range) falls off as the inverse square of the
// distance d, as 1 / (1 + d^2) in scene units (finite at the light), windowed by
// max(0, 1 - (d / r)^4)^2 so that it ends exactly at r (Karis 2013, "Real Shading in Unreal
// Engine 4"): nothing lies beyond the range for the shadows to miss. A light without a range
// does not fall off. Per light, the two factors the falloff is made of:
struct Falloff {
  float inv_range2 = 0.0f;      // 1 / r^2; 0 without a range
  float inverse_square = 0.0f;  // 1 with a range, else 0
};
inline Falloff falloff_of(float range, bool limited) {
  return limited ? Falloff{1.0f / (range * range), 1.0f} : Falloff{};
}
// Whether squared distance d2 lies within the range (always, without one).
inline bool within_range(float d2, const Falloff& f) {
  const float x = d2 * f.inv_range2;
  return x * x < 1.0f;
}
// The falloff at squared distance d2.
inline float falloff(float d2, const Falloff& f) {
  const float x = d2 * f.inv_range2;
  const float window = within_range(d2, f) ? 1.0f - x * x : 0.0f;
  return window * window / (1.0f + d2 * f.inverse_square);
}

// The barycentric coordinates of `point` in the face with corners c[0..2], those below 0 taken
// as 0 (a pixel's point may stray past an edge by rounding: nothing outside the corners' span),
// scaled to sum to 1; false where the face has no area or the point lies beyond a corner.
inline bool barycentric(const glm::vec3* c, glm::vec3 point, glm::vec3& weights) {
  const glm::vec3 across = glm::cross(c[1] - c[0], c[2] - c[0]);
  if (!(glm::dot(across, across) > 0.0f)) return false;
  const glm::vec3 w(std::max(0.0f, glm::dot(glm::cross(c[2] - c[1], point - c[1]), across)),
                    std::max(0.0f, glm::dot(glm::cross(c[0] - c[2], point - c[2]), across)),
                    std::max(0.0f, glm::dot(glm::cross(c[1] - c[0], point - c[0]), across)));
  const float sum = w.x + w.y + w.z;
  if (!(sum > 0.0f) || !std::isfinite(sum)) return false;
  weights = w / sum;
  return true;
}

// Smooth shading with barycentric weights w: the corner normals n[0..2] (one space, any length)
// and terminator offsets t[0..2] (core/shading_normals.h) interpolated. The normal is unit
// length, or `face` where the normals cancel. The OpenGL backend's lit shader computes the same.
struct SmoothPoint {
  glm::vec3 normal;
  float offset;
};
inline SmoothPoint interpolate_smooth(glm::vec3 w, const glm::vec3* n, const float* t,
                                      glm::vec3 face) {
  const glm::vec3 mixed = w.x * n[0] + w.y * n[1] + w.z * n[2];
  const float len = glm::length(mixed);
  if (!(len > 0.0f && std::isfinite(len))) return {face, 0.0f};
  return {mixed / len, w.x * t[0] + w.y * t[1] + w.z * t[2]};
}

// A texture's colour at texture coordinates uv (Texture: bilinear in linear light, repeating, v
// up), linear RGB; white where the texture holds no pixels.
glm::vec3 sample_texture(const Texture& texture, glm::vec2 uv);

// The Lambert term of smooth shading, the terminator offset taken off (1 stays 1; offset 0: as
// flat shading).
inline float smooth_lambert(float cos_light, float offset) {
  return (cos_light - offset) / (1.0f - offset);
}

// The background at row y of h (row 0 at the top).
glm::vec3 background(int y, int h);
float to_srgb(float linear);

// lround(to_srgb(linear) * 255), exactly, by a search among the 255 linear values where the 8-bit
// code steps (found once): a frame encodes millions of channels, and pow is most of its cost.
// Floats in [0, 1) fall into buckets by their top bits (2^15 neighbouring floats each), each
// narrower than the gap between two codes' first values, so that a bucket's code is the code of
// its least float, or one more from where the next code begins (steps[code]).
struct SrgbTable {
  static constexpr int kDropBits = 15;
  static constexpr std::uint32_t kOne = 0x3f800000u;  // the bits of 1.0f
  std::array<std::uint8_t, (kOne >> kDropBits)> bucket_code;
  std::array<float, 256> steps;  // steps[k]: the least float whose code is more than k
};
const SrgbTable& srgb_table();  // made on first use
// With the table in hand: a loop over pixels takes it once.
inline std::uint8_t to_srgb8(float linear, const SrgbTable& table) {
  if (!(linear > 0.0f)) return 0;  // NaN too, as to_srgb's clamp makes it
  if (!(linear < 1.0f)) return 255;
  const std::uint8_t c =
      table.bucket_code[std::bit_cast<std::uint32_t>(linear) >> SrgbTable::kDropBits];
  return static_cast<std::uint8_t>(c + (linear >= table.steps[c]));
}
inline std::uint8_t to_srgb8(float linear) { return to_srgb8(linear, srgb_table()); }

}  // namespace shadowvol::shading
