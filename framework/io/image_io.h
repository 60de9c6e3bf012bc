// Writing the framebuffer: OpenEXR with every channel, PNG for looking at (the traversal-cost
// heat map is framework/io/heatmap.h).
#pragma once

#include "framework/render/framebuffer.h"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace bvhlab {

// Channels R G B, Z (depth), primitive (uint), N.X N.Y N.Z, cost.traversal, cost.intersection.
void writeExr(const std::filesystem::path& file, const Framebuffer& fb);

// Tone-mapped colour: clamped to [0,1], sRGB-encoded.
void writePng(const std::filesystem::path& file, const Framebuffer& fb);

// An 8-bit RGB image, rows top to bottom, 3 bytes per pixel (what a PNG holds).
struct Rgb8Image {
    int width = 0, height = 0;
    std::vector<uint8_t> pixels;
};
void writePng(const std::filesystem::path& file, const Rgb8Image& image);
// Any PNG (grey, alpha and palette converted to RGB); throws InputError if unreadable.
Rgb8Image readPng(const std::filesystem::path& file);

// One float channel of an EXR file (for tests and image comparisons).
std::vector<float> readExrChannel(const std::filesystem::path& file, const std::string& channel, int& width,
                                  int& height);

}  // namespace bvhlab
