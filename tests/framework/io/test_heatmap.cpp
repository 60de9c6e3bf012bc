// Heat maps: a colour bar with its numbers under the image; a fixed full scale
// (Output::heatmapScale) or the image's own 99th percentile, recorded in the render's JSON; none
// for a structure without counters.
#include "framework/io/heatmap.h"
#include "framework/io/image_io.h"
#include "framework/io/image_text.h"
#include "tests/support/cli_run.h"
#include "tests/support/json_file.h"
#include "tests/support/scratch_dir.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>

using namespace bvhlab;

namespace {

using test::readJson;

namespace fs = std::filesystem;

Rgb pixel(const Rgb8Image& image, int x, int y) {
    const size_t i = (size_t(y) * image.width + x) * 3;
    return {image.pixels[i], image.pixels[i + 1], image.pixels[i + 2]};
}

bool near(const Rgb& a, const Rgb& b) {
    for (int k = 0; k < 3; ++k)
        if (std::abs(int(a[k]) - int(b[k])) > 12) return false;
    return true;
}

// The rows from `y0` on, as bytes.
std::vector<uint8_t> rowsFrom(const Rgb8Image& image, int y0) {
    return {image.pixels.begin() + ptrdiff_t(y0) * image.width * 3, image.pixels.end()};
}

}  // namespace

TEST(Heatmap, ColourBarAndItsNumbersUnderTheImage) {
    const fs::path dir = test::scratchDir("heatmap");
    const int w = 64, h = 16;
    const std::vector<float> zeros(size_t(w) * h, 0.0f);
    writeHeatmapPng(dir / "seven.png", zeros, w, h, 7.0f);
    writeHeatmapPng(dir / "three_hundred.png", zeros, w, h, 300.0f);
    const Rgb8Image a = readPng(dir / "seven.png"), b = readPng(dir / "three_hundred.png");
    ASSERT_GT(heatmapLegendHeight(w), 0);
    ASSERT_EQ(a.width, w);
    ASSERT_EQ(a.height, h + heatmapLegendHeight(w));

    // The render part is the bottom colour at either scale; the legend says which scale it was.
    EXPECT_TRUE(std::equal(a.pixels.begin(), a.pixels.begin() + w * h * 3, b.pixels.begin()));
    EXPECT_NE(rowsFrom(a, h), rowsFrom(b, h)) << "the numbers under the bar should differ";

    // A bar from the bottom colour (left) to the top one (right) on the legend's background, and
    // light digits under it.
    bool bar = false;
    size_t textPixels = 0;
    for (int y = h; y < a.height; ++y) {
        const Rgb background{28, 28, 32}, left = pixel(a, 0, y), right = pixel(a, w - 1, y);
        bar |= left != background && right != background && !near(left, right);
        for (int x = 0; x < w; ++x) textPixels += pixel(a, x, y) == Rgb{235, 235, 235};
    }
    EXPECT_TRUE(bar);
    EXPECT_GT(textPixels, 10u);
}

TEST(Heatmap, FixedScaleSaturatesAboveIt) {
    const fs::path dir = test::scratchDir("heatmap");
    std::vector<float> ramp(100);
    for (size_t i = 0; i < ramp.size(); ++i) ramp[i] = float(i);
    EXPECT_EQ(heatmapPercentile99(ramp), 98.0f);
    EXPECT_EQ(heatmapPercentile99(std::vector<float>(10, 0.0f)), 1.0f);  // a flat image still has a scale

    writeHeatmapPng(dir / "fixed.png", ramp, 100, 1, 50.0f);
    writeHeatmapPng(dir / "own.png", ramp, 100, 1, heatmapPercentile99(ramp));
    const Rgb8Image fixed = readPng(dir / "fixed.png"), own = readPng(dir / "own.png");
    EXPECT_EQ(pixel(fixed, 50, 0), pixel(fixed, 99, 0));  // both at or above the full scale
    EXPECT_NE(pixel(own, 50, 0), pixel(own, 98, 0));
    EXPECT_EQ(pixel(own, 98, 0), pixel(fixed, 50, 0));  // the top colour
}

TEST(Heatmap, RenderRecordsTheScaleInItsJson) {
    const fs::path dir = test::scratchDir("heatmap");
    const std::string args = "render -DCamera::width=32 -DCamera::height=24 -DOutput::heatmap=true -DOutput::exr=false";
    const test::Result fixed = test::run(args + " -DOutput::heatmapScale=40 --out " + (dir / "fixed").string());
    ASSERT_EQ(fixed.exitCode, 0) << fixed.output;
    EXPECT_NE(fixed.output.find("full scale 40 (Output::heatmapScale"), std::string::npos) << fixed.output;
    const nlohmann::json j = readJson(dir / "fixed.json");
    EXPECT_EQ(j["heatmap"]["scale"], 40.0);
    EXPECT_EQ(j["heatmap"]["scale_from"], "Output::heatmapScale");
    EXPECT_GE(j["heatmap"]["p99"].get<double>(), 1.0);
    EXPECT_EQ(j["heatmap"]["file"], (dir / "fixed.heatmap.png").string());
    EXPECT_EQ(readPng(dir / "fixed.heatmap.png").height, 24 + heatmapLegendHeight(32));

    const test::Result own = test::run(args + " --out " + (dir / "own").string());
    ASSERT_EQ(own.exitCode, 0) << own.output;
    const nlohmann::json o = readJson(dir / "own.json");
    EXPECT_EQ(o["heatmap"]["scale"], o["heatmap"]["p99"]);
    EXPECT_EQ(o["heatmap"]["scale_from"], "99th percentile of this image");
    EXPECT_EQ(o["env"]["Output::heatmapScale"]["value"], "0");  // the default: per image
}

TEST(Heatmap, NoneForAStructureWithoutCounters) {
    const fs::path dir = test::scratchDir("heatmap");
    const test::Result r = test::run(
        "render -DASDS::type=embree -DCamera::width=16 -DCamera::height=12 "
        "-DOutput::heatmap=true --out " +
        (dir / "embree").string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_FALSE(fs::exists(dir / "embree.heatmap.png"));
    EXPECT_NE(r.output.find("heat map: none written: embree counts no traversal steps"), std::string::npos) << r.output;
    const nlohmann::json j = readJson(dir / "embree.json");
    EXPECT_NE(j["heatmap"].value("skipped", std::string()).find("embree"), std::string::npos) << j["heatmap"];
    EXPECT_FALSE(j["heatmap"].contains("file"));
}
