// The smallest plugin: one accelerator, brute force over the triangles (spheres and cones are
// not answered), with one env key of its own read by the factory. It is built, not loaded, by the
// package tests (tests/package/): the .so and its two exported entry points are what they check.
#include "framework/plugin/plugin_api.h"

#include <chrono>
#include <memory>

namespace {

using namespace bvhlab;

inline constexpr IntKey kRepeat{"Minimal::repeat", "1", 1, 16, "how many times each triangle is tested"};

class MinimalAccelerator final : public Accelerator {
public:
    explicit MinimalAccelerator(int repeat) : repeat_(repeat) {}

    std::string_view name() const override { return "minimal"; }

    BuildStats build(const PrimitiveSet& prims) override {
        const auto start = std::chrono::steady_clock::now();
        prims_ = prims;
        BuildStats stats;
        stats.primitives = prims.validTriangles().size();
        stats.buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        return stats;
    }

    bool findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const override {
        ++counters.queries;
        if (!ray.isValid()) return false;
        const ShearedRay sheared(ray);
        float tmax = ray.tmax;
        bool found = false;
        for (int r = 0; r < repeat_; ++r)
            for (uint32_t prim : prims_.validTriangles()) {
                ++counters.intersectionTests;
                TriangleHitT<float> h;
                if (intersectTriangle(sheared, prims_.triangles[prim], ray.tmin, tmax, h)) {
                    tmax = h.t;
                    hit = {h.t, prim, h.u, h.v};
                    found = true;
                }
            }
        return found;
    }

    bool isOccluded(const Ray& ray, QueryCounters& counters) const override {
        Hit hit;
        return findNearest(ray, hit, counters);
    }

private:
    int repeat_;
    PrimitiveSet prims_;
};

}  // namespace

BVHLAB_PLUGIN(registrar) {
    registrar.addAccelerator({"minimal", "brute force over the triangles (the package tests' plugin)",
                              {kRepeat.declaration()},
                              [](const Env& env) { return std::make_unique<MinimalAccelerator>(env.get(kRepeat)); }});
}
