// shadowvol scene: textures from image files (PNG, JPEG, BMP, TGA, ... through stb_image).
//
// Owns: decoding an image into a Texture (scene.h: 8-bit sRGB RGBA, rows from the top), with its
// size checked before any pixel is decoded.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "core/expected.h"
#include "scene/scene.h"

namespace shadowvol {

// The largest texture side accepted (the OpenGL backend's textures must hold it too).
inline constexpr int kMaxTextureSide = 16384;

// An image file as a texture. Errors name `path` and the problem: a missing or unreadable file,
// a format stb_image cannot decode, a side above kMaxTextureSide.
Expected<Texture> load_texture(const std::filesystem::path& path);
// The same from encoded bytes in memory (a texture embedded in a glTF or FBX file); `source`
// names it in messages.
Expected<Texture> decode_texture(const std::uint8_t* bytes, std::size_t size,
                                 const std::string& source);

}  // namespace shadowvol
