// Polygons of any vertex count, convex or not, as triangles that cover exactly the polygon.
// A convex polygon becomes the fan from its first corner (so that primitive indices follow
// file order, as they always have); a non-convex one is ear-clipped in the plane of its Newell
// normal. Either way every triangle keeps the polygon's winding, which the one-sided SPD rules
// read as its outside. A polygon whose coverage is not defined (self-intersecting, not planar,
// of zero area) is refused with the reason, never covered approximately.
#pragma once

#include <bvhlab/math.h>
#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace bvhlab {

enum class PolygonProblem {
    None,
    ZeroArea,          // fewer than three distinct corners, or all of them on one line
    NotPlanar,         // a corner farther from the polygon's plane than kPlanarTolerance allows
    SelfIntersecting,  // two edges cross or touch, or an edge doubles back on the one before
    NotFinite,         // a NaN or infinite coordinate
    TooComplex,        // non-convex, and more corners or ear tests than the bounds below allow
};

// Why a polygon was refused, as a phrase for a warning ("self-intersecting").
std::string_view describe(PolygonProblem problem);

class PolygonTriangulator {
public:
    // A corner may lie off the plane by this fraction of the polygon's bounding-box diagonal
    // (plus what printing the coordinates with six digits can move it).
    static constexpr double kPlanarTolerance = 1e-3;
    // Checking that a non-convex polygon is simple takes time quadratic in its corners, and
    // clipping it at most cubic: both are bounded, so that no file can make loading hang.
    static constexpr size_t kMaxNonConvexCorners = size_t(1) << 14;
    static constexpr uint64_t kMaxEarTests = uint64_t(1) << 31;

    // Triangulates the polygon whose corners are positions[corners[i]], in order; the result
    // is triangles() (indices into positions), empty unless None is returned. Consecutive
    // repeated corners are dropped first (they add no area). Every index must be in range.
    PolygonProblem triangulate(std::span<const Vec3> positions, std::span<const uint32_t> corners);

    std::span<const glm::uvec3> triangles() const { return triangles_; }
    bool wasEarClipped() const { return earClipped_; }  // non-convex: not a fan

private:
    bool project(std::span<const Vec3> positions, PolygonProblem& problem);
    bool isConvex() const;
    bool isSimple() const;
    PolygonProblem earClip();
    bool isEar(uint32_t i);
    double orient(uint32_t a, uint32_t b, uint32_t c) const;  // > 0: a, b, c turn left

    // Scratch kept between calls, so that a reader does not allocate per polygon.
    std::vector<uint32_t> corners_;      // distinct consecutive corners, as indices into positions
    std::vector<glm::dvec2> points_;     // corners_ projected, counter-clockwise
    std::vector<uint32_t> prev_, next_;  // the ring of corners not yet clipped
    std::vector<uint8_t> ear_;           // isEar as last computed: a hint, checked again before a clip
    uint64_t earTests_ = 0;
    std::vector<glm::uvec3> triangles_;
    bool earClipped_ = false;
};

}  // namespace bvhlab
