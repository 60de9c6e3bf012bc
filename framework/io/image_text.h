// Rectangles and text drawn into an 8-bit RGB image: the contact sheet's labels and the heat
// map's colour bar numbers. The text is stb_easy_font's strokes (printable ASCII), rasterised.
#pragma once

#include "framework/io/image_io.h"

#include <array>
#include <cstdint>
#include <string>

namespace bvhlab {

using Rgb = std::array<uint8_t, 3>;

// stb_easy_font's line height in font units; a glyph is about 7 units tall.
constexpr int kTextLineHeight = 12;

// Fills [x0, x1) x [y0, y1), clipped to the image.
void fillRect(Rgb8Image& image, int x0, int y0, int x1, int y1, Rgb color);

// `text` with characters outside printable ASCII (line breaks aside) replaced by '?'.
std::string printableText(std::string text);

// Width of `text` in font units (its widest line).
int textWidth(const std::string& text);

// Draws `text` with its top left at (x, y), each font unit `scale` pixels, clipped to the image.
void drawText(Rgb8Image& image, int x, int y, std::string text, int scale, Rgb color);

}  // namespace bvhlab
