// Polygons as triangles (framework/scene/polygon_triangulation.h): non-convex ones covered
// exactly (their triangles' areas sum to the polygon's, and a dense grid of rays hits exactly
// what Haines' crossings test says is inside), the winding kept, convex ones left as the fan,
// and every polygon without a defined cover refused with its reason.
#include "accel/naive/naive_accelerator.h"
#include "framework/core/error.h"
#include "framework/scene/polygon_triangulation.h"
#include "framework/scene/scene_loader.h"
#include "tests/support/polygons.h"

#include <gtest/gtest.h>

#include <fstream>

namespace bvhlab {
namespace {

using namespace bvhlab::test;

// A plane tilted so that no axis is special: the projection must not depend on it.
PolygonPlane tiltedPlane() {
    const DVec3 u = glm::normalize(DVec3(0.8, 0.3, -0.5));
    const DVec3 v = glm::normalize(glm::cross(DVec3(0.2, -0.4, 0.9), u));
    return {DVec3(3.0, -2.0, 1.5), u, v};
}

struct Triangulated {
    std::vector<Vec3> positions;
    std::vector<uint32_t> corners;
    PolygonProblem problem = PolygonProblem::None;
    std::vector<glm::uvec3> triangles;
    bool earClipped = false;
};

Triangulated triangulate(const Polygon2& polygon, const PolygonPlane& plane = tiltedPlane()) {
    Triangulated t;
    for (const glm::dvec2& q : polygon) {
        t.corners.push_back(uint32_t(t.positions.size()));
        t.positions.push_back(Vec3(plane.at(q)));
    }
    PolygonTriangulator triangulator;
    t.problem = triangulator.triangulate(t.positions, t.corners);
    t.triangles.assign(triangulator.triangles().begin(), triangulator.triangles().end());
    t.earClipped = triangulator.wasEarClipped();
    return t;
}

const std::vector<std::pair<const char*, Polygon2>>& nonConvexPolygons() {
    static const std::vector<std::pair<const char*, Polygon2>> polygons = {
        {"star", starPolygon()}, {"comb", combPolygon()}, {"notch", notchedSquare()}, {"gear", gearPolygon()}};
    return polygons;
}

TEST(PolygonTriangulation, NonConvexPolygonsAreCoveredByTrianglesOfTheirArea) {
    for (const auto& [name, polygon] : nonConvexPolygons()) {
        SCOPED_TRACE(name);
        const PolygonPlane plane = tiltedPlane();
        const Triangulated t = triangulate(polygon, plane);
        ASSERT_EQ(t.problem, PolygonProblem::None);
        EXPECT_TRUE(t.earClipped);
        EXPECT_LE(t.triangles.size(), polygon.size() - 2);
        double area = 0.0;
        for (const glm::uvec3& tri : t.triangles) {
            const DVec3 a(t.positions[tri.x]), b(t.positions[tri.y]), c(t.positions[tri.z]);
            const DVec3 n = glm::cross(b - a, c - a);
            // The polygon's winding: every triangle faces the plane's normal.
            EXPECT_GE(glm::dot(n, plane.normal()), 0.0);
            area += 0.5 * glm::length(n);
        }
        EXPECT_NEAR(area, polygonArea(polygon), 1e-5 * polygonArea(polygon));
    }
}

// Rays through a dense grid of points of the polygon's plane, along its normal, against its
// triangles: every point inside (by the crossings test, beyond a rounding margin) is hit and
// every point outside, the notches and gaps included, is missed; the hit area is the polygon's.
TEST(PolygonTriangulation, ADenseGridOfRaysHitsExactlyThePolygon) {
    for (const auto& [name, polygon] : nonConvexPolygons()) {
        SCOPED_TRACE(name);
        const PolygonPlane plane = tiltedPlane();
        const Triangulated t = triangulate(polygon, plane);
        ASSERT_EQ(t.problem, PolygonProblem::None);
        Scene scene;
        scene.positions = t.positions;
        scene.indices = t.triangles;
        scene.finalize();
        NaiveAccelerator naive;
        naive.build(scene.primitives());

        glm::dvec2 lower(1e30), upper(-1e30);
        for (const glm::dvec2& q : polygon) lower = glm::min(lower, q), upper = glm::max(upper, q);
#if defined(__SANITIZE_ADDRESS__)
        // Under AddressSanitizer (tests/sanitize.sh) 100 by 100: every ray runs the same code, and
        // the exactness at the boundary is the Release suite's check at 300.
        constexpr int kGrid = 100;
#else
        constexpr int kGrid = 300;
#endif
        const glm::dvec2 cell = (upper - lower) / double(kGrid);
        size_t hits = 0, wrong = 0;
        QueryCounters counters;
        for (int i = 0; i < kGrid; ++i)
            for (int j = 0; j < kGrid; ++j) {
                const glm::dvec2 q = lower + (glm::dvec2(i, j) + 0.5) * cell;
                const DVec3 origin = plane.at(q) + plane.normal();
                Hit hit;
                const bool hitIt = naive.findNearest({Vec3(origin), Vec3(-plane.normal()), 0.0f, 10.0f}, hit, counters);
                hits += hitIt;
                if (distanceToBoundary(polygon, q) > 1e-5 && hitIt != insidePolygon(polygon, q)) ++wrong;
            }
        EXPECT_EQ(wrong, 0u);
        const double cellArea = cell.x * cell.y, area = polygonArea(polygon);
        // Only cells the boundary crosses can go either way.
        double perimeter = 0.0;
        for (size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++)
            perimeter += glm::length(polygon[i] - polygon[j]);
        EXPECT_NEAR(double(hits) * cellArea, area, perimeter * std::max(cell.x, cell.y));
    }
}

TEST(PolygonTriangulation, ConvexPolygonsStayTheFanFromTheirFirstCorner) {
    Polygon2 hexagon;
    for (int i = 0; i < 6; ++i)
        hexagon.emplace_back(std::cos(i * std::numbers::pi / 3), std::sin(i * std::numbers::pi / 3));
    // A quad with a corner on the straight line between its neighbours is convex too.
    for (const Polygon2& polygon : {hexagon, Polygon2{{0, 0}, {1, 0}, {2, 0}, {2, 1}, {0, 1}}}) {
        const Triangulated t = triangulate(polygon);
        ASSERT_EQ(t.problem, PolygonProblem::None);
        EXPECT_FALSE(t.earClipped);
        ASSERT_EQ(t.triangles.size(), polygon.size() - 2);
        for (uint32_t i = 0; i < t.triangles.size(); ++i) EXPECT_EQ(t.triangles[i], glm::uvec3(0, i + 1, i + 2));
    }
}

TEST(PolygonTriangulation, RepeatedCornersAreDroppedAndTheRestCovered) {
    Polygon2 notch = notchedSquare();
    notch.insert(notch.begin() + 3, notch[3]);  // a corner given twice
    notch.push_back(notch.front());             // and the first again at the end
    const Triangulated t = triangulate(notch);
    ASSERT_EQ(t.problem, PolygonProblem::None);
    double area = 0.0;
    for (const glm::uvec3& tri : t.triangles) {
        const DVec3 a(t.positions[tri.x]), b(t.positions[tri.y]), c(t.positions[tri.z]);
        area += 0.5 * glm::length(glm::cross(b - a, c - a));
    }
    EXPECT_NEAR(area, polygonArea(notchedSquare()), 1e-5);
}

TEST(PolygonTriangulation, PolygonsWithoutAnExactCoverAreRefusedWithTheReason) {
    const auto problem = [](const Polygon2& polygon) { return triangulate(polygon).problem; };
    // Edges that cross: a bow tie, a pentagram (every corner turns left, the boundary winds
    // twice), a figure with two edges touching at a corner given twice, an edge that doubles back.
    EXPECT_EQ(problem({{0, 0}, {1, 1}, {1, 0}, {0, 1}}), PolygonProblem::SelfIntersecting);
    Polygon2 pentagram;
    for (int i = 0; i < 5; ++i)
        pentagram.emplace_back(std::cos(i * 4 * std::numbers::pi / 5), std::sin(i * 4 * std::numbers::pi / 5));
    EXPECT_EQ(problem(pentagram), PolygonProblem::SelfIntersecting);
    EXPECT_EQ(problem({{0, 0}, {2, 0}, {2, 2}, {1, 1}, {0, 2}, {1, 1}}), PolygonProblem::SelfIntersecting);
    EXPECT_EQ(problem({{0, 0}, {2, 0}, {1, 0}, {1, 1}, {0, 1}}), PolygonProblem::SelfIntersecting);
    // No area: every corner on one line, or fewer than three distinct corners.
    EXPECT_EQ(problem({{0, 0}, {1, 1}, {2, 2}, {3, 3}}), PolygonProblem::ZeroArea);
    EXPECT_EQ(problem({{0, 0}, {1, 1}, {1, 1}, {0, 0}}), PolygonProblem::ZeroArea);

    // A square with one corner lifted off the plane by a tenth of its side.
    std::vector<Vec3> positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.1f}, {0, 1, 0}};
    const std::vector<uint32_t> corners = {0, 1, 2, 3};
    PolygonTriangulator triangulator;
    EXPECT_EQ(triangulator.triangulate(positions, corners), PolygonProblem::NotPlanar);
    EXPECT_TRUE(triangulator.triangles().empty());
    positions[2].z = 1e-5f;  // within what printing can move
    EXPECT_EQ(triangulator.triangulate(positions, corners), PolygonProblem::None);
    positions[2].z = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(triangulator.triangulate(positions, corners), PolygonProblem::NotFinite);
}

TEST(PolygonTriangulation, HugeNonConvexPolygonsAreRefusedNotLeftToHang) {
    Polygon2 star = starPolygon(int(PolygonTriangulator::kMaxNonConvexCorners / 2 + 1), 0.9);
    EXPECT_EQ(triangulate(star).problem, PolygonProblem::TooComplex);
    // Convex ones of any size are fans (here a rectangle with 100 000 corners on one side).
    Polygon2 rectangle;
    for (int i = 0; i <= 100000; ++i) rectangle.emplace_back(i, 0);
    rectangle.insert(rectangle.end(), {{100000, 1}, {0, 1}});
    const Triangulated t = triangulate(rectangle, PolygonPlane{});
    EXPECT_EQ(t.problem, PolygonProblem::None);
    EXPECT_FALSE(t.earClipped);
}

// --- Through the readers ------------------------------------------------------------------------

TEST(PolygonTriangulation, TheReadersSkipAndNameAPolygonWithoutACover) {
    const std::string nff = "f 1 0 0 1 0 0 0 0\n" + nffPolygon(notchedSquare(), {}) +
                            "p 4\n0 0 0\n1 1 0\n1 0 0\n0 1 0\n";  // a bow tie, at line 12
    const Scene scene = readNff("bowtie.nff", nff);
    EXPECT_EQ(scene.report.skippedPolygons, 1u);
    EXPECT_EQ(scene.report.earClippedPolygons, 1u);
    ASSERT_EQ(scene.report.warnings.size(), 1u);
    EXPECT_EQ(scene.report.warnings[0],
              "bowtie.nff:12: polygon of 4 vertices skipped: self-intersecting "
              "(edges cross, touch or double back)");
    EXPECT_EQ(scene.materialIds.size(), scene.indices.size());

    const std::string obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0.5 0.2 0\nv 0 1 0\nf 1 2 3 4 5\nf 1 3 2 5\n";
    const Scene fromObj = readObj("arrow.obj", obj);
    EXPECT_EQ(fromObj.report.earClippedPolygons, 1u);
    EXPECT_EQ(fromObj.report.skippedPolygons, 1u);
    EXPECT_EQ(fromObj.indices.size(), 3u);
    ASSERT_FALSE(fromObj.report.warnings.empty());
    EXPECT_EQ(fromObj.report.warnings[0].rfind("arrow.obj:7: polygon of 4 vertices skipped", 0), 0u)
        << fromObj.report.warnings[0];
}

TEST(PolygonTriangulation, ASceneOfOnlySkippedPolygonsIsAnError) {
    const std::filesystem::path file = std::filesystem::temp_directory_path() / "bvhlab_only_bowties.nff";
    {
        std::ofstream out(file);
        out << "p 4\n0 0 0\n1 1 0\n1 0 0\n0 1 0\n";
    }
    try {
        loadScene(file);
        ADD_FAILURE() << "loaded";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("all 1 polygons were skipped"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find(":1: polygon of 4 vertices skipped: self-intersecting"), std::string::npos)
            << e.what();
    }
    std::filesystem::remove(file);
}

TEST(PolygonTriangulation, APlyFaceOfManyCornersBeforeItsVerticesIsAnError) {
    const std::string ply =
        "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int vertex_indices\n"
        "element vertex 4\nproperty float x\nproperty float y\nproperty float z\nend_header\n"
        "4 0 1 2 3\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n";
    EXPECT_THROW(readPly("faces_first.ply", ply), InputError);
}

}  // namespace
}  // namespace bvhlab
