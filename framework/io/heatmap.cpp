#include "framework/io/heatmap.h"

#include <bvhlab/math.h>
#include <glm/glm.hpp>
#include "framework/io/image_io.h"
#include "framework/io/image_text.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

namespace bvhlab {
namespace {

constexpr Rgb kLegendBackground{28, 28, 32}, kLegendText{235, 235, 235};

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

// Legend text: two font units per pixel on images wide enough for it.
int legendTextScale(int width) { return width >= 320 ? 2 : 1; }

// A bar label: whole steps from 100 on, else three significant digits (12.5, 0.75).
std::string label(float steps) { return steps >= 100.0f ? fmt::format("{:.0f}", steps) : fmt::format("{:.3g}", steps); }

}  // namespace

float heatmapPercentile99(const std::vector<float>& steps) {
    if (steps.empty()) return 1.0f;
    std::vector<float> sorted = steps;
    const size_t p99 = (sorted.size() - 1) * 99 / 100;
    std::nth_element(sorted.begin(), sorted.begin() + p99, sorted.end());
    return std::max(sorted[p99], 1.0f);
}

int heatmapLegendHeight(int width) {
    const int s = legendTextScale(width);
    return 2 * s + 8 * s + 2 * s + 9 * s + 2 * s;  // gap, bar, gap, digits (7 font units and a margin), gap
}

void writeHeatmapPng(const std::filesystem::path& file, const std::vector<float>& steps, int width, int height,
                     float scale) {
    const int s = legendTextScale(width);
    Rgb8Image image{width, height + heatmapLegendHeight(width), {}};
    image.pixels.resize(size_t(image.width) * image.height * 3);
    auto paint = [&](size_t pixel, float x) {
        const Vec3 c = turbo(x);
        for (int k = 0; k < 3; ++k) image.pixels[3 * pixel + k] = uint8_t(std::lround(c[k] * 255.0f));
    };
    for (size_t i = 0; i < steps.size(); ++i) paint(i, steps[i] / scale);

    fillRect(image, 0, height, image.width, image.height, kLegendBackground);
    const int barTop = height + 2 * s, textTop = barTop + 8 * s + 2 * s;
    for (int y = barTop; y < barTop + 8 * s; ++y)
        for (int x = 0; x < width; ++x) paint(size_t(y) * width + x, (float(x) + 0.5f) / float(width));
    const std::string low = "0", middle = label(scale / 2.0f), high = label(scale);
    drawText(image, 0, textTop, low, s, kLegendText);
    drawText(image, width - textWidth(high) * s, textTop, high, s, kLegendText);
    // The middle number only where it keeps clear of the two ends.
    const int middleLeft = (width - textWidth(middle) * s) / 2;
    if (middleLeft > (textWidth(low) + 2) * s && middleLeft + (textWidth(middle) + 2) * s < width - textWidth(high) * s)
        drawText(image, middleLeft, textTop, middle, s, kLegendText);
    writePng(file, image);
}

HeatmapScale chooseHeatmapScale(float fixed, float fallback, const std::string& fallbackFrom) {
    return fixed > 0.0f ? HeatmapScale{fixed, "Output::heatmapScale"} : HeatmapScale{fallback, fallbackFrom};
}

nlohmann::json writeHeatmap(const std::filesystem::path& file, const std::string& recorded,
                            const std::vector<float>& steps, int width, int height, bool hasCounters,
                            std::string_view accel, const HeatmapScale& scale) {
    if (!hasCounters)
        return {{"skipped", fmt::format("{} counts no traversal steps, so its heat map would be flat", accel)}};
    writeHeatmapPng(file, steps, width, height, scale.steps);
    return {
        {"file", recorded}, {"scale", scale.steps}, {"scale_from", scale.from}, {"p99", heatmapPercentile99(steps)}};
}

std::string heatmapNote(const nlohmann::json& record) {
    if (record.contains("skipped"))
        return fmt::format("heat map: none written: {}", record["skipped"].get<std::string>());
    const float scale = record["scale"].get<float>(), p99 = record["p99"].get<float>();
    return fmt::format("heat map: traversal steps per pixel, full scale {} ({}{}): {}", label(scale),
                       record["scale_from"].get<std::string>(),
                       scale != p99 ? fmt::format("; this image's 99th percentile {}", label(p99)) : "",
                       record["file"].get<std::string>());
}

}  // namespace bvhlab
