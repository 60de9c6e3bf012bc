#include "accel/verify/moved_scene.h"

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <map>
#include <stdexcept>

namespace bvhlab::verify {

namespace {

// The bits of a position: vertices at one position are one vertex, however a mesh stores them.
using PositionKey = std::array<uint32_t, 3>;
PositionKey keyOf(const Vec3& p) {
    return {std::bit_cast<uint32_t>(p.x), std::bit_cast<uint32_t>(p.y), std::bit_cast<uint32_t>(p.z)};
}

// Where a point goes, a function of the point alone (and of the scene's triangles around it).
// A rigid motion of the part of the scene beyond its centre along x, blended in smoothly across
// a band around the centre, so that no small triangle is torn into a needle; then a push of one
// point in four by up to a quarter of the shortest edge that meets it (a triangle keeps its
// shape, however small).
class Motion {
public:
    explicit Motion(const Scene& scene)
        : centre_(scene.bounds.isEmpty() ? Vec3(0.0f) : scene.bounds.center()),
          size_(scene.bounds.isEmpty() ? 1.0f : std::max(glm::length(scene.bounds.diagonal()), 1e-6f)),
          turn_(glm::rotate(glm::mat4(1.0f), 0.35f, glm::normalize(glm::vec3(1.0f, 2.0f, 3.0f)))) {
        for (const uint32_t prim : scene.validPrimitives) {
            if (prim >= scene.triangleCount()) break;
            const Triangle& t = scene.triangles[prim];
            const float shortest =
                std::min({glm::length(t.v1 - t.v0), glm::length(t.v2 - t.v1), glm::length(t.v0 - t.v2)});
            for (const Vec3& v : {t.v0, t.v1, t.v2}) {
                const auto [it, added] = shortestEdge_.emplace(keyOf(v), shortest);
                if (!added) it->second = std::min(it->second, shortest);
            }
        }
    }

    Vec3 operator()(const Vec3& p) const {
        const float band = 0.25f * size_;
        const float w = glm::smoothstep(centre_.x - band, centre_.x + band, p.x);
        const Vec3 rigid = centre_ + Vec3(turn_ * glm::vec4(p - centre_, 0.0f)) + Vec3(0.05f * size_, 0.0f, 0.0f);
        Vec3 q = p + w * (rigid - p);
        const PositionKey key = keyOf(p);
        const uint64_t h = hash(key);
        if (const auto edge = shortestEdge_.find(key); edge != shortestEdge_.end() && h % 4 == 0) {
            const Vec3 push(float(h >> 8 & 255) - 127.5f, float(h >> 16 & 255) - 127.5f, float(h >> 24 & 255) - 127.5f);
            q += push * (0.25f * edge->second / (127.5f * std::sqrt(3.0f)));
        }
        return q;
    }

private:
    static uint64_t hash(const PositionKey& key) {
        uint64_t h = 14695981039346656037ull;
        for (const uint32_t bits : key) h = (h ^ bits) * 1099511628211ull;
        return h ^ (h >> 29);
    }

    Vec3 centre_;
    float size_;
    glm::mat4 turn_;
    std::map<PositionKey, float> shortestEdge_;
};

// Primitives valid in `before`, not in `after` (both ascending).
std::vector<uint32_t> lostPrimitives(const std::vector<uint32_t>& before, const std::vector<uint32_t>& after) {
    std::vector<uint32_t> lost;
    std::set_difference(before.begin(), before.end(), after.begin(), after.end(), std::back_inserter(lost));
    return lost;
}

}  // namespace

Scene movedScene(const Scene& scene) {
    const Motion motion(scene);
    Scene moved = scene;
    for (Vec3& p : moved.positions) p = motion(p);
    for (Sphere& s : moved.spheres) s.centre = motion(s.centre);
    for (Cone& c : moved.cones) c.base = motion(c.base), c.apex = motion(c.apex);
    // A primitive that became degenerate stays where it was (with the vertices it shares).
    for (int attempt = 0; attempt < 4; ++attempt) {
        moved.finalize();
        const std::vector<uint32_t> lost = lostPrimitives(scene.validPrimitives, moved.validPrimitives);
        if (lost.empty()) break;
        for (const uint32_t prim : lost) {
            if (prim < scene.triangleCount()) {
                for (int k = 0; k < 3; ++k)
                    moved.positions[scene.indices[prim][k]] = scene.positions[scene.indices[prim][k]];
            } else if (prim < scene.triangleCount() + scene.spheres.size()) {
                moved.spheres[prim - scene.triangleCount()] = scene.spheres[prim - scene.triangleCount()];
            } else {
                const size_t cone = prim - scene.triangleCount() - scene.spheres.size();
                moved.cones[cone] = scene.cones[cone];
            }
        }
    }
    if (!lostPrimitives(scene.validPrimitives, moved.validPrimitives).empty())
        throw std::logic_error(fmt::format("movedScene: the motion of '{}' makes primitives degenerate", scene.name));
    // Primitives the motion made valid stay out, as they were.
    moved.validPrimitives = scene.validPrimitives;
    moved.bounds = Bounds3();
    for (const uint32_t prim : moved.validPrimitives) {
        if (prim < moved.triangleCount())
            moved.bounds.extend(moved.triangles[prim].bounds());
        else
            moved.bounds.extend(boundsOf(moved.primitives().quadric(prim)));
    }
    moved.name = scene.name;
    return moved;
}

}  // namespace bvhlab::verify
