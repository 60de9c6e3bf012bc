// Heat maps of the per-pixel traversal steps (N_TR summed over every query of a pixel) through
// the Turbo colour map, with a colour bar and its numbers under the image: two heat maps drawn
// at one full scale (Output::heatmapScale, or the batch's one scale per scene) compare by eye,
// and the bar says what a colour means.
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace bvhlab {

// The 99th percentile of `steps` (at least 1): a full scale a few expensive pixels do not wash out.
float heatmapPercentile99(const std::vector<float>& steps);

// Writes the `width` x `height` heat map of `steps` at full scale `scale` (> 0; steps above it
// take the top colour), then under it a colour bar from 0 to `scale` labelled at both ends and
// the middle. The PNG is taller than the render by the bar: heatmapLegendHeight(width).
void writeHeatmapPng(const std::filesystem::path& file, const std::vector<float>& steps, int width, int height,
                     float scale);
int heatmapLegendHeight(int width);

// A full scale and how it was chosen ("Output::heatmapScale", "99th percentile of this image", ...).
struct HeatmapScale {
    float steps = 1.0f;
    std::string from;
};
// `fixed` (Output::heatmapScale) when positive, else `fallback`, chosen as `fallbackFrom` says.
HeatmapScale chooseHeatmapScale(float fixed, float fallback, const std::string& fallbackFrom);

// The heat map of one render, written to `file` at `scale`, unless the structure that rendered it
// counts no traversal steps (Accelerator::hasCounters() false: a flat image would say nothing).
// Returns the JSON record: {"file": `recorded`, "scale", "scale_from", "p99": the image's own
// 99th percentile}, or {"skipped": why}.
nlohmann::json writeHeatmap(const std::filesystem::path& file, const std::string& recorded,
                            const std::vector<float>& steps, int width, int height, bool hasCounters,
                            std::string_view accel, const HeatmapScale& scale);
// The line for stderr about a record.
std::string heatmapNote(const nlohmann::json& record);

}  // namespace bvhlab
