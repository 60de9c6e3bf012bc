#include "framework/image_io.h"

#include "framework/error.h"

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

// Google's Turbo colour map, polynomial fit (Mikhailov 2019): dark blue -> green -> dark red.
Vec3 turbo(float x) {
    x = std::clamp(x, 0.0f, 1.0f);
    const glm::vec4 v4(1.0f, x, x * x, x * x * x);
    const glm::vec2 v2 = glm::vec2(v4.z, v4.w) * v4.z;
    const glm::vec4 kR(0.13572138f, 4.61539260f, -42.66032258f, 132.13108234f);
    const glm::vec4 kG(0.09140261f, 2.19418839f, 4.84296658f, -14.18503333f);
    const glm::vec4 kB(0.10667330f, 12.64194608f, -60.58204836f, 110.36276771f);
    const glm::vec2 kR2(-152.94239396f, 59.28637943f), kG2(4.27729857f, 2.82956604f), kB2(-89.90310912f, 27.34824973f);
    return glm::clamp(Vec3(glm::dot(v4, kR) + glm::dot(v2, kR2), glm::dot(v4, kG) + glm::dot(v2, kG2),
                           glm::dot(v4, kB) + glm::dot(v2, kB2)),
                      0.0f, 1.0f);
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
    slices.insert("primitive", Imf::Slice(Imf::UINT, reinterpret_cast<char*>(const_cast<uint32_t*>(fb.primitive.data())),
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

float writeHeatmapPng(const std::filesystem::path& file, const Framebuffer& fb) {
    std::vector<float> sorted = fb.traversalSteps;
    const size_t p99 = sorted.empty() ? 0 : (sorted.size() - 1) * 99 / 100;
    std::nth_element(sorted.begin(), sorted.begin() + p99, sorted.end());
    const float scale = sorted.empty() ? 1.0f : std::max(sorted[p99], 1.0f);
    std::vector<uint8_t> rgb(fb.traversalSteps.size() * 3);
    for (size_t i = 0; i < fb.traversalSteps.size(); ++i) {
        const Vec3 c = turbo(fb.traversalSteps[i] / scale);
        for (int k = 0; k < 3; ++k) rgb[3 * i + k] = uint8_t(std::lround(c[k] * 255.0f));
    }
    writeRgb8(file, fb.width, fb.height, rgb);
    return scale;
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
