// The grid plugin's parts (accel/grid/): the resolution formulas of Havran's text on known boxes,
// the conservative overlap tests, references covering every point of every primitive, and the
// plugin end to end (found by name, its figures in the JSON). `bvhlab check --accel grid`
// (ctest CheckGridPlugin) holds it to the conformance suite.
#include "accel/grid/grid_accelerator.h"
#include "accel/grid/grid_cells.h"
#include "accel/grid/grid_resolution.h"
#include "tests/support/cli_run.h"
#include "tests/support/json_figures.h"
#include "tests/support/scratch_dir.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>

namespace bvhlab::test {
namespace {

using grid::GridResolution;
using grid::gridResolution;
using grid::GridSetting;

TEST(GridResolution, WooGivesDTimesNCubicCells) {
    // tetra: 4096 triangles in a 2x2x2 box: 16^3 cells at D = 1, as Havran's table.
    EXPECT_EQ(gridResolution(GridSetting::Woo, 1.0, 4096, DVec3(2.0)), (GridResolution{16, 16, 16}));
    // lattice: 8281 objects in a cube: 20^3 and 44^3 (Havran's figures).
    EXPECT_EQ(gridResolution(GridSetting::Woo, 1.0, 8281, DVec3(1.044)), (GridResolution{20, 20, 20}));
    EXPECT_EQ(gridResolution(GridSetting::Woo, 10.0, 8281, DVec3(1.044)), (GridResolution{44, 44, 44}));
    // A 4 x 2 x 1 box, 512 objects: at D = 1 cubic cells of side (4*2*1/512)^(1/3) = 0.25 make
    // 16 x 8 x 4; at D = 8 half that side, 32 x 16 x 8.
    EXPECT_EQ(gridResolution(GridSetting::Woo, 1.0, 512, DVec3(4.0, 2.0, 1.0)), (GridResolution{16, 8, 4}));
    EXPECT_EQ(gridResolution(GridSetting::Woo, 8.0, 512, DVec3(4.0, 2.0, 1.0)), (GridResolution{32, 16, 8}));
}

TEST(GridResolution, FlatAxesGetOneCellAndTheOthersShareTheCells) {
    EXPECT_EQ(gridResolution(GridSetting::Woo, 1.0, 100, DVec3(1.0, 1.0, 0.0)), (GridResolution{10, 10, 1}));
    EXPECT_EQ(gridResolution(GridSetting::Heterogeneous, 1.0, 100, DVec3(1.0, 1.0, 0.0)), (GridResolution{10, 10, 1}));
    EXPECT_EQ(gridResolution(GridSetting::Woo, 1.0, 7, DVec3(0.0)), (GridResolution{1, 1, 1}));
    EXPECT_EQ(gridResolution(GridSetting::Woo, 1.0, 0, DVec3(1.0)), (GridResolution{1, 1, 1}));
}

TEST(GridResolution, RegularAndHeterogeneousFollowHavransFormulas) {
    // Regular: D * N^(1/3) on every axis, whatever the box.
    EXPECT_EQ(gridResolution(GridSetting::Regular, 1.0, 1000, DVec3(4.0, 2.0, 1.0)), (GridResolution{10, 10, 10}));
    EXPECT_EQ(gridResolution(GridSetting::Regular, 2.0, 1000, DVec3(4.0, 2.0, 1.0)), (GridResolution{20, 20, 20}));
    // Heterogeneous: x = (V sx^2/(sy sz))^(1/3) = (512*16/2)^(1/3) = 16, y = (V sy/(x sz))^(1/2) = 8,
    // z = V/(x y) = 4.
    EXPECT_EQ(gridResolution(GridSetting::Heterogeneous, 1.0, 512, DVec3(4.0, 2.0, 1.0)), (GridResolution{16, 8, 4}));
    EXPECT_EQ(grid::parseGridSetting("heterogeneous"), GridSetting::Heterogeneous);
    EXPECT_FALSE(grid::parseGridSetting("hierarchical"));
}

TEST(GridCells, OverlapTestsSeparateAndTouch) {
    const DVec3 lo(0.0), hi(1.0);
    // A triangle whose box overlaps the cell's but which passes by its corner.
    const Triangle corner{Vec3(1.5f, 0.6f, 0.5f), Vec3(0.6f, 1.5f, 0.5f), Vec3(1.5f, 1.5f, 0.5f)};
    EXPECT_FALSE(grid::triangleOverlapsBox(corner, lo, hi));
    const Triangle through{Vec3(1.2f, 0.4f, 0.5f), Vec3(0.4f, 1.2f, 0.5f), Vec3(1.5f, 1.5f, 0.5f)};
    EXPECT_TRUE(grid::triangleOverlapsBox(through, lo, hi));
    // Lying in a face of the cell: touches.
    const Triangle onFace{Vec3(0.2f, 0.2f, 1.0f), Vec3(0.8f, 0.2f, 1.0f), Vec3(0.2f, 0.8f, 1.0f)};
    EXPECT_TRUE(grid::triangleOverlapsBox(onFace, lo, hi));
    // A sphere near the corner: inside the box's box, outside the box.
    EXPECT_FALSE(grid::sphereOverlapsBox(Sphere{Vec3(1.5f, 1.5f, 1.5f), 0.8f}, lo, hi));
    EXPECT_TRUE(grid::sphereOverlapsBox(Sphere{Vec3(1.5f, 1.5f, 1.5f), 0.9f}, lo, hi));
}

// Every point of every triangle lies in a cell that references it.
TEST(GridCells, EveryPointOfATriangleIsInACellReferencingIt) {
    std::mt19937 rng(29);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::vector<Triangle> tris;
    for (int i = 0; i < 300; ++i) {
        const Vec3 c(u(rng), u(rng), u(rng));
        tris.push_back({c, c + 0.3f * Vec3(u(rng), u(rng), u(rng)), c + 0.3f * Vec3(u(rng), u(rng), u(rng))});
    }
    std::vector<uint32_t> valid(tris.size());
    for (uint32_t i = 0; i < valid.size(); ++i) valid[i] = i;
    const PrimitiveSet prims{tris, valid};
    const grid::GridCells g = grid::buildGridCells(prims, {GridSetting::Woo, 5.0, 0.0, std::nullopt, true});
    EXPECT_EQ(g.cells(), uint64_t(g.res.x) * g.res.y * g.res.z);
    EXPECT_EQ(g.cells(), g.cellStart.size() - 1);
    EXPECT_GT(g.res.x, 10);
    std::uniform_real_distribution<double> w(0.0, 1.0);
    for (uint32_t p = 0; p < tris.size(); ++p) {
        for (int k = 0; k < 50; ++k) {
            double a = w(rng), b = w(rng);
            if (a + b > 1.0) a = 1.0 - a, b = 1.0 - b;
            const DVec3 q = DVec3(tris[p].v0) + a * DVec3(tris[p].v1 - tris[p].v0) + b * DVec3(tris[p].v2 - tris[p].v0);
            int cell[3];
            for (int axis = 0; axis < 3; ++axis)
                cell[axis] = std::clamp(int(std::floor((q[axis] - g.lower[axis]) * g.inverseCellSize[axis])), 0,
                                        g.res[axis] - 1);
            const size_t c = g.cellIndex(cell[0], cell[1], cell[2]);
            const auto begin = g.refs.begin() + g.cellStart[c], end = g.refs.begin() + g.cellStart[c + 1];
            ASSERT_TRUE(std::find(begin, end, p) != end) << "triangle " << p << " not in its cell";
        }
    }
}

TEST(GridCells, AFixedResolutionOverridesTheSetting) {
    const std::vector<Triangle> tris = {{Vec3(0.0f), Vec3(1.0f, 0.0f, 0.0f), Vec3(0.0f, 1.0f, 1.0f)}};
    const std::vector<uint32_t> valid = {0};
    const grid::GridCells g =
        grid::buildGridCells(PrimitiveSet{tris, valid}, {GridSetting::Woo, 1.0, 0.0, GridResolution{3, 4, 5}});
    EXPECT_EQ(g.res, (GridResolution{3, 4, 5}));
    EXPECT_EQ(g.cells(), 60u);
    EXPECT_GT(g.references(), 3u);
    EXPECT_LT(g.emptyCells(), 60u);
}

TEST(GridCells, ABudgetBoundsTheReferencesOfHugeOverlappingTriangles) {
    // 20000 triangles each spanning the whole scene: D*N cells would make 20000 * 20000 references.
    std::vector<Triangle> tris;
    for (int i = 0; i < 20000; ++i) {
        const float z = float(i) / 20000.0f;
        tris.push_back({Vec3(-1.0f, -1.0f, z), Vec3(1.0f, -1.0f, 1.0f - z), Vec3(0.0f, 1.0f, z)});
    }
    std::vector<uint32_t> valid(tris.size());
    for (uint32_t i = 0; i < valid.size(); ++i) valid[i] = i;
    const grid::GridCells g =
        grid::buildGridCells(PrimitiveSet{tris, valid}, {GridSetting::Woo, 1.0, 0.0, std::nullopt});
    EXPECT_LE(g.references(), std::max<uint64_t>(grid::kMinReferenceBudget, 32 * tris.size()));
    EXPECT_LT(g.densityUsed, 1.0);
}

TEST(GridPlugin, FoundByNameItsFiguresInTheJson) {
    const auto out = scratchDir("grid_plugin") / "image";
    const Result r =
        run("render -DCamera::width=16 -DCamera::height=12 -DASDS::type=grid -DGrid::density=2 --out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("grid N_OIV:"), std::string::npos) << r.output;
    std::ifstream in(out.string() + ".json");
    const nlohmann::json json = nlohmann::json::parse(in);
    const std::vector<nlohmann::json> found = figuresWith(json, "N_V");  // Havran's build figures
    ASSERT_FALSE(found.empty()) << json.dump();
    const nlohmann::json& f = found.front();
    for (const char* name : {"res_x", "res_y", "res_z", "N_V", "N_EV", "N_OIV"}) EXPECT_TRUE(f.contains(name)) << name;
    EXPECT_EQ(f["N_V"]["value"].get<double>(), f["res_x"]["value"].get<double>() * f["res_y"]["value"].get<double>() *
                                                   f["res_z"]["value"].get<double>());
    EXPECT_LE(f["N_EV"]["value"].get<double>(), f["N_V"]["value"].get<double>());
}

TEST(GridPlugin, AnUnknownSettingIsRefused) {
    const Result r = run("render -DCamera::width=8 -DCamera::height=8 -DASDS::type=grid -DGrid::setting=octree --out " +
                         (scratchDir("grid_plugin") / "bad").string());
    EXPECT_NE(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("Grid::setting"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace bvhlab::test
