#include "framework/io/image_io.h"

#include "framework/core/error.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cstdint>
#include <memory>

namespace bvhlab {
namespace {

uint8_t toSrgb8(float linear) {
    const float c = std::clamp(linear, 0.0f, 1.0f);
    const float s = c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
    return uint8_t(std::lround(s * 255.0f));
}

void writeRgb8(const std::filesystem::path& file, int width, int height, const std::vector<uint8_t>& rgb) {
    if (!stbi_write_png(file.string().c_str(), width, height, 3, rgb.data(), width * 3))
        throw InputError(file.string() + ": cannot write PNG");
}

}  // namespace

void writePng(const std::filesystem::path& file, const Rgb8Image& image) {
    writeRgb8(file, image.width, image.height, image.pixels);
}

Rgb8Image readPng(const std::filesystem::path& file) {
    int width = 0, height = 0, channels = 0;
    std::unique_ptr<stbi_uc, decltype(&stbi_image_free)> data(
        stbi_load(file.string().c_str(), &width, &height, &channels, 3), stbi_image_free);
    if (!data) throw InputError(fmt::format("{}: cannot read image: {}", file.string(), stbi_failure_reason()));
    Rgb8Image image{width, height, {}};
    image.pixels.assign(data.get(), data.get() + size_t(width) * size_t(height) * 3);
    return image;
}

void writeExr(const std::filesystem::path& file, const Framebuffer& fb) {
    Imf::Header header(fb.width, fb.height);
    Imf::FrameBuffer slices;
    const size_t vec3Stride = sizeof(Vec3), pixelStride = sizeof(float);
    auto addFloat = [&](const char* name, const char* base, size_t xStride) {
        header.channels().insert(name, Imf::Channel(Imf::FLOAT));
        slices.insert(name, Imf::Slice(Imf::FLOAT, const_cast<char*>(base), xStride, xStride * fb.width));
    };
    const char* color = reinterpret_cast<const char*>(fb.color.data());
    const char* normal = reinterpret_cast<const char*>(fb.normal.data());
    addFloat("R", color, vec3Stride);
    addFloat("G", color + sizeof(float), vec3Stride);
    addFloat("B", color + 2 * sizeof(float), vec3Stride);
    addFloat("Z", reinterpret_cast<const char*>(fb.depth.data()), pixelStride);
    addFloat("N.X", normal, vec3Stride);
    addFloat("N.Y", normal + sizeof(float), vec3Stride);
    addFloat("N.Z", normal + 2 * sizeof(float), vec3Stride);
    addFloat("cost.traversal", reinterpret_cast<const char*>(fb.traversalSteps.data()), pixelStride);
    addFloat("cost.intersection", reinterpret_cast<const char*>(fb.intersectionTests.data()), pixelStride);
    header.channels().insert("primitive", Imf::Channel(Imf::UINT));
    slices.insert("primitive",
                  Imf::Slice(Imf::UINT, reinterpret_cast<char*>(const_cast<uint32_t*>(fb.primitive.data())),
                             sizeof(uint32_t), sizeof(uint32_t) * fb.width));
    try {
        Imf::OutputFile out(file.string().c_str(), header);
        out.setFrameBuffer(slices);
        out.writePixels(fb.height);
    } catch (const std::exception& e) {
        throw InputError(file.string() + ": cannot write EXR: " + e.what());
    }
}

void writePng(const std::filesystem::path& file, const Framebuffer& fb) {
    std::vector<uint8_t> rgb(fb.color.size() * 3);
    for (size_t i = 0; i < fb.color.size(); ++i)
        for (int c = 0; c < 3; ++c) rgb[3 * i + c] = toSrgb8(fb.color[i][c]);
    writeRgb8(file, fb.width, fb.height, rgb);
}

std::vector<float> readExrChannel(const std::filesystem::path& file, const std::string& channel, int& width,
                                  int& height) {
    try {
        Imf::InputFile in(file.string().c_str());
        const Imath::Box2i window = in.header().dataWindow();
        width = window.max.x - window.min.x + 1;
        height = window.max.y - window.min.y + 1;
        if (!in.header().channels().findChannel(channel))
            throw InputError(file.string() + ": no channel '" + channel + "'");
        std::vector<float> data(size_t(width) * height);
        Imf::FrameBuffer slices;
        char* base = reinterpret_cast<char*>(data.data()) -
                     (size_t(window.min.x) + size_t(window.min.y) * width) * sizeof(float);
        slices.insert(channel, Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * width));
        in.setFrameBuffer(slices);
        in.readPixels(window.min.y, window.max.y);
        return data;
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        throw InputError(file.string() + ": cannot read EXR: " + e.what());
    }
}

}  // namespace bvhlab
