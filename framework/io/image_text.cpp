#include "framework/io/image_text.h"

#include <stb_easy_font.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace bvhlab {

void fillRect(Rgb8Image& image, int x0, int y0, int x1, int y1, Rgb color) {
    x0 = std::max(x0, 0), y0 = std::max(y0, 0), x1 = std::min(x1, image.width), y1 = std::min(y1, image.height);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x)
            std::copy(color.begin(), color.end(), &image.pixels[(size_t(y) * image.width + x) * 3]);
}

std::string printableText(std::string text) {
    for (char& c : text)
        if ((c < 32 || c > 126) && c != '\n') c = '?';
    return text;
}

int textWidth(const std::string& text) { return stb_easy_font_width(const_cast<char*>(text.c_str())); }

void drawText(Rgb8Image& image, int x, int y, std::string text, int scale, Rgb color) {
    text = printableText(std::move(text));
    // stb_easy_font stops quietly when its buffer is full (a digit takes up to 9 quads of 64 bytes):
    // grow it until the text fits with a quad to spare.
    std::vector<char> vertices(text.size() * 640 + 64);
    int quads = 0;
    while ((quads = stb_easy_font_print(0, 0, text.data(), nullptr, vertices.data(), int(vertices.size()))) * 64 + 64 >
           int(vertices.size()))
        vertices.resize(vertices.size() * 2);
    for (int q = 0; q < quads; ++q) {
        // Four vertices of 16 bytes (x, y, z, rgba); the strokes are axis-aligned rectangles.
        float minX = 1e30f, minY = 1e30f, maxX = -1e30f, maxY = -1e30f;
        for (int v = 0; v < 4; ++v) {
            const float* p = reinterpret_cast<const float*>(vertices.data() + (q * 4 + v) * 16);
            minX = std::min(minX, p[0]), maxX = std::max(maxX, p[0]);
            minY = std::min(minY, p[1]), maxY = std::max(maxY, p[1]);
        }
        fillRect(image, x + int(std::lround(minX * scale)), y + int(std::lround(minY * scale)),
                 x + int(std::lround(maxX * scale)), y + int(std::lround(maxY * scale)), color);
    }
}

}  // namespace bvhlab
