// shadowvol render: the shading both backends use (the OpenGL backend passes these to its
// shaders as uniforms): ambient * albedo, plus per unshadowed light Lambert + Blinn-Phong, lit on
// the side the eye sees; a vertical gradient behind everything; sRGB out.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

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
// The falloff at squared distance d2.
inline float falloff(float d2, const Falloff& f) {
  const float x = d2 * f.inv_range2;
  const float window = x * x < 1.0f ? 1.0f - x * x : 0.0f;
  return window * window / (1.0f + d2 * f.inverse_square);
}

// Smooth shading at `point` of a face with corners c[0..2], corner normals n[0..2] (one space,
// any length) and terminator offsets t[0..2] (core/shading_normals.h): both interpolated by the
// point's barycentric coordinates, those below 0 taken as 0 (a pixel's point may stray past an
// edge by rounding; nothing outside the corners' span). The normal is unit length, or `face`
// where the normals cancel or the face has no area. The OpenGL backend's lit shader computes
// the same.
struct SmoothPoint {
  glm::vec3 normal;
  float offset;
};
inline SmoothPoint interpolate_smooth(const glm::vec3* c, const glm::vec3* n, const float* t,
                                      glm::vec3 point, glm::vec3 face) {
  const glm::vec3 across = glm::cross(c[1] - c[0], c[2] - c[0]);
  const float area2 = glm::dot(across, across);
  if (!(area2 > 0.0f)) return {face, 0.0f};
  const float w0 = std::max(0.0f, glm::dot(glm::cross(c[2] - c[1], point - c[1]), across));
  const float w1 = std::max(0.0f, glm::dot(glm::cross(c[0] - c[2], point - c[2]), across));
  const float w2 = std::max(0.0f, glm::dot(glm::cross(c[1] - c[0], point - c[0]), across));
  const glm::vec3 mixed = w0 * n[0] + w1 * n[1] + w2 * n[2];
  const float len = glm::length(mixed), sum = w0 + w1 + w2;
  if (!(len > 0.0f && std::isfinite(len) && sum > 0.0f)) return {face, 0.0f};
  return {mixed / len, (w0 * t[0] + w1 * t[1] + w2 * t[2]) / sum};
}
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
