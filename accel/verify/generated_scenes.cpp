#include "accel/verify/generated_scenes.h"

#include "accel/verify/closed_meshes.h"
#include "accel/verify/verify_rng.h"
#include "framework/scene/procedural.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>

namespace bvhlab::verify {

namespace {

using D3 = glm::dvec3;

constexpr float kNaNf = std::numeric_limits<float>::quiet_NaN();

// A soup's triangle: of a log-uniform size in [minSize, maxSize], near a uniform point of `box`.
void addSoupTriangle(Scene& scene, VerifyRng& rng, const Bounds3& box, double minSize, double maxSize) {
    const D3 c(rng.inBox(box));
    const double size = rng.logUniform(minSize, maxSize);
    addLooseTriangle(scene, Vec3(c + rng.unitVector() * size), Vec3(c + rng.unitVector() * size),
                     Vec3(c + rng.unitVector() * size));
}

}  // namespace

Scene sceneFromTriangles(const std::vector<Triangle>& triangles, const std::string& name) {
    Scene scene;
    scene.name = name;
    for (const Triangle& t : triangles) addLooseTriangle(scene, t.v0, t.v1, t.v2);
    scene.finalize();
    return scene;
}

Scene makeSoupScene(size_t count, uint32_t seed, float minSize, float maxSize, float extent) {
    VerifyRng rng(seed);
    Scene scene;
    scene.name = "soup";
    const Bounds3 box(Vec3(-0.5f * extent), Vec3(0.5f * extent));
    for (size_t i = 0; i < count; ++i) addSoupTriangle(scene, rng, box, minSize, maxSize);
    scene.finalize();
    return scene;
}

Scene makeTerrainScene(int cells, uint32_t seed) {
    VerifyRng rng(seed);
    Scene scene;
    scene.name = "terrain";
    const int n = cells + 1;
    const double phase = rng.uniform(0, 6.28);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const float x = float(i) / float(cells) * 20.0f - 10.0f, z = float(j) / float(cells) * 20.0f - 10.0f;
            // A flat plateau at exactly 0 in one quarter (zero-thickness boxes), hills elsewhere.
            float h = 0.0f;
            if (i > n / 2 || j > n / 2)
                h = float(1.5 * std::sin(0.7 * x + phase) * std::cos(0.5 * z) + 0.05 * rng.uniform(-1, 1));
            scene.positions.emplace_back(x, h, z);
        }
    for (int i = 0; i < cells; ++i)
        for (int j = 0; j < cells; ++j) {
            const uint32_t a = uint32_t(i * n + j), b = a + 1, c = a + uint32_t(n), d = c + 1;
            scene.indices.emplace_back(a, b, d);
            scene.indices.emplace_back(a, d, c);
        }
    scene.finalize();
    return scene;
}

Scene makeCostScene() {
    VerifyRng rng(21);
    Scene scene;
    scene.name = "cost";
    addQuad(scene, Vec3(-20, 0, -20), Vec3(0, 0, 40), Vec3(40, 0, 0), 0);
    for (int i = 0; i < 6; ++i) {
        const Vec3 corner(-14.0f + 5.0f * float(i), 0.0f, -12.0f + 2.0f * float(i % 3));
        addBox(scene, corner, corner + Vec3(2.0f, 1.0f + float(i), 1.5f), 0);
    }
    addIcosphere(scene, Vec3(-4.0f, 2.0f, 0.0f), 2.0f, 5, 0);
    addTorus(scene, Vec3(4.0f, 1.0f, 2.0f), 2.0f, 0.6f, 96, 48, 0);
    const Bounds3 air(Vec3(-15.0f, 3.0f, -15.0f), Vec3(15.0f, 10.0f, 15.0f));
    for (int i = 0; i < 2000; ++i) addSoupTriangle(scene, rng, air, 0.05, 0.5);
    scene.finalize();
    return scene;
}

Scene makeCoincidentScene(size_t groups, size_t copies, bool slid, uint64_t seed) {
    VerifyRng rng(seed);
    Scene scene;
    scene.name = fmt::format("coincident{}", groups * (copies + (slid ? 1 : 0)));
    const Bounds3 box(Vec3(-5.0f), Vec3(5.0f));
    for (size_t i = 0; i < groups; ++i) {
        const D3 c(rng.inBox(box));
        const double size = rng.logUniform(0.05, 2.0);
        const Vec3 a = Vec3(c + rng.unitVector() * size), b = Vec3(c + rng.unitVector() * size),
                   d = Vec3(c + rng.unitVector() * size);
        for (size_t k = 0; k < copies; ++k) {
            switch (k % 4) {
                case 0:
                case 1:
                    addLooseTriangle(scene, a, b, d);
                    break;  // identical
                case 2:
                    addLooseTriangle(scene, a, d, b);
                    break;  // reversed winding
                default:
                    addLooseTriangle(scene, b, d, a);
                    break;  // rotated vertex order
            }
        }
        // Coplanar, overlapping: the same triangle slid within its plane.
        const Vec3 shift = 0.3f * (b - a);
        if (slid) addLooseTriangle(scene, a + shift, b + shift, d + shift);
    }
    scene.finalize();
    return scene;
}

void addTriangleAround(Scene& scene, VerifyRng& rng, const DVec3& centre, double size) {
    const DVec3 a = size * rng.unitVector(), b = size * rng.unitVector();
    addLooseTriangle(scene, Vec3(centre + a), Vec3(centre + b), Vec3(centre - a - b));
}

Scene makeTrianglesAroundScene(std::string name, size_t count, uint64_t seed,
                               const std::function<DVec3(VerifyRng&)>& centre,
                               const std::function<double(VerifyRng&)>& size) {
    VerifyRng rng(seed);
    Scene scene;
    scene.name = std::move(name);
    scene.positions.reserve(3 * count);
    scene.indices.reserve(count);
    for (size_t i = 0; i < count; ++i) {
        const DVec3 c = centre(rng);  // the centre first, then the size, on every compiler
        const double s = size(rng);
        addTriangleAround(scene, rng, c, s);
    }
    scene.finalize();
    return scene;
}

Scene makeCollinearCentroidsScene(size_t n, uint64_t seed) {
    const DVec3 origin(-3.0, 1.0, 2.0), axis = glm::normalize(DVec3(1.0, 2.0, 3.0));
    return makeTrianglesAroundScene(
        fmt::format("collinear{}", n), n, seed, [&](VerifyRng& rng) { return origin + rng.uniform(0.0, 100.0) * axis; },
        [](VerifyRng& rng) { return rng.logUniform(0.01, 1.0); });
}

Scene makeCentroidsOnPlaneScene(size_t count, uint32_t seed) {
    // Braced, so that x is drawn before y on every compiler.
    return makeTrianglesAroundScene(
        "centroids_plane", count, seed,
        [](VerifyRng& rng) {
            return D3{rng.uniform(-10, 10), rng.uniform(-10, 10), 0.0};
        },
        [](VerifyRng& rng) { return rng.uniform(0.1, 1.0); });
}

Scene makeCentroidsAtPointScene(size_t count, uint32_t seed) {
    return makeTrianglesAroundScene(
        "centroids_point", count, seed, [](VerifyRng&) { return D3(1.0, 2.0, 3.0); },
        [](VerifyRng& rng) { return rng.logUniform(1e-2, 10.0); });
}

Scene makeHugeAmongTinyScene(size_t n, uint64_t seed) {
    VerifyRng rng(seed);
    Scene scene;
    scene.name = fmt::format("huge+tiny{}", n);
    scene.positions.reserve(3 * n + 3);
    scene.indices.reserve(n + 1);
    addLooseTriangle(scene, Vec3(-1000.0f, -900.0f, -800.0f), Vec3(1100.0f, -700.0f, 950.0f),
                     Vec3(-50.0f, 1000.0f, 20.0f));
    for (size_t i = 0; i < n; ++i) {
        const DVec3 c(rng.uniform(-100, 100), rng.uniform(-100, 100), rng.uniform(-100, 100));
        const double s = 1e-3;
        addLooseTriangle(scene, Vec3(c + s * rng.unitVector()), Vec3(c + s * rng.unitVector()),
                         Vec3(c + s * rng.unitVector()));
    }
    scene.finalize();
    return scene;
}

Scene makeDegenerateMixScene(size_t count, uint32_t seed) {
    VerifyRng rng(seed);
    Scene scene;
    scene.name = "degenerate_mix";
    const Bounds3 box(Vec3(-10.0f), Vec3(10.0f));
    // Small integers / 4: sums of these are exact, so the segments below are exactly collinear.
    auto grid = [&] {
        return Vec3(float(int(rng.index(64)) - 32), float(int(rng.index(64)) - 32), float(int(rng.index(64)) - 32)) *
               0.25f;
    };
    const float inf = std::numeric_limits<float>::infinity();
    for (size_t i = 0; i < count; ++i) {
        if (!rng.chance(0.25)) {
            addSoupTriangle(scene, rng, box, 1e-2, 5.0);
            continue;
        }
        const Vec3 p = grid(), q = grid();
        const Vec3 d =
            Vec3(float(int(rng.index(5)) - 2), float(int(rng.index(5)) - 2), float(int(rng.index(5)) - 2)) * 0.25f;
        switch (rng.index(6)) {
            case 0:
                addLooseTriangle(scene, p, p, p);
                break;  // a point
            case 1:
                addLooseTriangle(scene, p, p + d, p + 2.0f * d);
                break;  // an exact segment
            case 2:
                addLooseTriangle(scene, p, q, p);
                break;  // a repeated vertex
            case 3:
                addLooseTriangle(scene, p, q, Vec3(q.x, kNaNf, q.z));
                break;
            case 4:
                addLooseTriangle(scene, Vec3(inf, p.y, p.z), p, q);
                break;
            default:
                addLooseTriangle(scene, p, Vec3(kNaNf), q);
                break;
        }
    }
    scene.finalize();
    return scene;
}

const std::vector<NamedSceneFactory>& generatedScenes() {
    static const std::vector<NamedSceneFactory> scenes = {
        {"soup_mixed", [] { return makeSoupScene(3000, 1); }},  // sizes 1e-6 .. 1e3 in a 100 box
        {"soup_small", [] { return makeSoupScene(2000, 2, 1e-3f, 1.0f, 10.0f); }},
        {"default", [] { return makeDefaultScene(); }},
        {"closed", [] { return makeClosedTrioScene(3, 1, 32, 16); }},
        {"terrain", [] { return makeTerrainScene(48, 3); }},
        {"coincident", [] { return makeCoincidentScene(200, 4, true, 4); }},
        {"centroids_line", [] { return makeCollinearCentroidsScene(1500, 5); }},
        {"centroids_plane", [] { return makeCentroidsOnPlaneScene(1500, 6); }},
        {"centroids_point", [] { return makeCentroidsAtPointScene(300, 7); }},
        // Scenes of 0 to 3 triangles, about as large as their bounds.
        {"tiny0", [] { return makeSoupScene(0, 8, 0.3f, 1.0f, 2.0f); }},
        {"tiny1", [] { return makeSoupScene(1, 9, 0.3f, 1.0f, 2.0f); }},
        {"tiny2", [] { return makeSoupScene(2, 10, 0.3f, 1.0f, 2.0f); }},
        {"tiny3", [] { return makeSoupScene(3, 11, 0.3f, 1.0f, 2.0f); }},
        {"degenerate_mix", [] { return makeDegenerateMixScene(2000, 12); }},
    };
    return scenes;
}

std::vector<NamedSceneFactory> edgeBuildScenes(size_t n, uint64_t seed) {
    return {{"coincident", [n, seed] { return makeCoincidentScene(1, n, false, seed); }},
            {"collinear", [n, seed] { return makeCollinearCentroidsScene(n, seed); }},
            {"huge+tiny", [n, seed] { return makeHugeAmongTinyScene(n, seed); }}};
}

Scene makeMixedScene(uint32_t seed) {
    VerifyRng rng(seed);
    const auto point = [&] { return rng.pointWithin(10.0); };
    const auto unit = [&] { return float(rng.uniform()); };
    Scene scene;
    scene.name = "mixed";
    for (int i = 0; i < 300; ++i) {
        const Vec3 c = point();
        const float size = 0.2f + 2.0f * unit();
        const auto base = uint32_t(scene.positions.size());
        for (int k = 0; k < 3; ++k) scene.positions.push_back(c + size * Vec3(rng.unitVector()));
        scene.indices.push_back({base, base + 1, base + 2});
    }
    scene.indices.push_back({0, 0, 0});  // degenerate
    for (int i = 0; i < 300; ++i) {
        const float r = 0.05f + 1.5f * unit();
        scene.spheres.push_back({point(), i % 10 == 0 ? -r : r});
    }
    scene.spheres.push_back({point(), 0.0f});  // degenerate
    for (int i = 0; i < 300; ++i) {
        const Vec3 base = point();
        const Vec3 apex = base + (0.3f + 3.0f * unit()) * Vec3(rng.unitVector());
        const float r0 = 0.05f + unit(), kind = unit();
        const float r1 = kind < 0.3f ? r0 : (kind < 0.6f ? 0.0f : r0 * unit());  // cylinder, cone, truncated
        scene.cones.push_back({base, r0, apex, r1});
    }
    scene.cones.push_back({point(), 1.0f, point(), -1.0f});  // degenerate: radii of opposite signs
    scene.finalize();
    return scene;
}

Scene makeBatchScene() {
    Scene scene;
    scene.name = "batch";
    scene.materials = {{Vec3(0.6f), 0.0f}, {Vec3(0.3f), 0.7f}};
    addQuad(scene, Vec3(-6, -2, -6), Vec3(0, 0, 12), Vec3(12, 0, 0), 1);
    addIcosphere(scene, Vec3(-2, 0, 0), 1.5f, 3, 0);
    addBox(scene, Vec3(1, -1, -1), Vec3(3, 1.5f, 1), 0);
    VerifyRng rng(7);
    for (int i = 0; i < 40; ++i) scene.spheres.push_back({rng.pointWithin(5.0), 0.1f + 0.02f * float(i)});
    for (int i = 0; i < 40; ++i) {
        const Vec3 base = rng.pointWithin(5.0);
        scene.cones.push_back({base, 0.3f, base + Vec3(rng.unitVector()), i % 2 ? 0.0f : 0.2f});
    }
    scene.finalize();
    return scene;
}

std::vector<Ray> makeBatchRays() {
    VerifyRng rng(11);
    std::vector<Ray> rays;
    for (int i = 0; i < 3000; ++i) {
        const Vec3 org = rng.pointWithin(12.0);
        Ray r{org, rng.pointWithin(4.0) - org};
        if (i % 7 == 0) r.dir = Vec3(0.0f), r.dir[i % 3] = i % 2 ? 1.0f : -1.0f;
        if (i % 5 == 0) r.tmin = -10.0f * float(rng.uniform());
        if (i % 11 == 0) r.tmax = 2.0f * float(rng.uniform());
        if (i % 13 == 0) r.tmin = 3.0f, r.tmax = 1.0f;
        if (i % 17 == 0) r.org.y = std::numeric_limits<float>::quiet_NaN();
        rays.push_back(r);
    }
    return rays;
}

}  // namespace bvhlab::verify
