// A plugin built as a plugin is rebuilt after an edit (tests/CMakeLists.txt: scan-1/scan.so and
// scan-2/scan.so differ in SCAN_VARIANT alone, scan-unoptimised/scan.so is built with -O0):
// `scan` tests every primitive against every ray, so every build answers alike; what differs is
// the file. It reads one key of its own, Scan::passes (which changes nothing), and no BVH:: key.
#include <bvhlab/plugin.h>
#include <bvhlab/reference_tests.h>

namespace {

using namespace bvhlab;

inline constexpr PluginKey kPasses{"Scan::passes", KeyType::Int, "1", "times over the primitives (no effect)", 1, 9};

class Scan final : public Accelerator {
public:
    const char* name() const override { return "scan"; }
    void build(const PrimitiveSet& prims) override { prims_ = prims; }
    void statistics(BuildStatistics& out) const override { out.set("primitives", double(prims_.valid.size())); }
    bool findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const override {
        ++counters.queries;
        return findNearestAlong(
            prims_, ray, counters, [&](auto visit) { visit(prims_.valid, double(ray.tmax)); }, hit);
    }
    bool isOccluded(const Ray& ray, QueryCounters& counters) const override {
        ++counters.queries;
        return isOccludedAlong(prims_, ray, counters, [&](auto visit) { visit(prims_.valid, double(ray.tmax)); });
    }

private:
    PrimitiveSet prims_;
};

}  // namespace

BVHLAB_PLUGIN(registrar) {
    registrar.addAccelerator({"scan",
                              "every primitive against every ray (build " SCAN_VARIANT ")",
                              {kPasses},
                              [](const PluginSettings&) -> Accelerator* { return new Scan; }});
}
