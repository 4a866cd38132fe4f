// The command line's text and boxes on images: a 5x7 pixel font, drawn at any integer scale.
//
// Owns the glyphs (digits, letters, which are drawn as lower case, and the punctuation that
// charts and labels use) and their placement; a character without a glyph is drawn as a box, so
// that nothing is dropped silently. Pure: draws into the caller's image.
#pragma once

#include <string_view>

#include <glm/vec3.hpp>

#include "render/renderer.h"

namespace shadowvol {

inline constexpr int kGlyphWidth = 5, kGlyphHeight = 7;
inline constexpr int kGlyphAdvance = kGlyphWidth + 1;  // one column of space between glyphs

// Fills the pixels [x0, x1) x [y0, y1), clipped to the image; colour in 0..1 sRGB.
void fill_rect(Image& image, int x0, int y0, int x1, int y1, const glm::vec3& color);

// The width in pixels of `text` at `scale`.
int text_width(std::string_view text, int scale);

// Draws `text` with its top left corner at (x, y), clipped to the image; colour in 0..1 sRGB.
void draw_text(Image& image, int x, int y, std::string_view text, const glm::vec3& color,
               int scale);

}  // namespace shadowvol
