// A plugin whose accelerators crash, for the report of a fatal signal (tests/apps/test_plugins.cpp,
// tests/apps/test_check_command.cpp): `crashing` writes through a bad pointer in findNearest(),
// `crashing_build` recurses without end in build() until its stack overflows.
#include <bvhlab/plugin.h>

#include <cstdint>

namespace {

using namespace bvhlab;

// A write to address 8, which the compiler cannot see is bad: a segmentation fault, not a trap.
void writeThroughABadPointer() {
    volatile uintptr_t address = 8;
    *reinterpret_cast<volatile int*>(address) = 1;
}

// Each frame keeps a buffer the compiler cannot drop; the end is never reached.
[[gnu::noinline]] int recurse(uint64_t depth) {
    volatile char frame[256];
    frame[depth % 256] = char(depth);
    if (depth == UINT64_MAX) return frame[0];
    return recurse(depth + 1) + frame[1];
}

class Crashing final : public Accelerator {
public:
    explicit Crashing(bool inBuild) : inBuild_(inBuild) {}
    const char* name() const override { return inBuild_ ? "crashing_build" : "crashing"; }
    void build(const PrimitiveSet& prims) override {
        primitives_ = prims.valid.size();
        if (inBuild_) recurse(0);
    }
    void statistics(BuildStatistics& out) const override { out.set("primitives", double(primitives_)); }
    bool findNearest(const Ray&, Hit&, QueryCounters&) const override {
        writeThroughABadPointer();
        return false;
    }
    bool isOccluded(const Ray&, QueryCounters& counters) const override {
        ++counters.queries;
        return false;
    }

private:
    bool inBuild_;
    size_t primitives_ = 0;
};

}  // namespace

BVHLAB_PLUGIN(registrar) {
    registrar.addAccelerator(
        {"crashing", "a segmentation fault in findNearest()", {}, [](const PluginSettings&) -> Accelerator* {
             return new Crashing(false);
         }});
    registrar.addAccelerator(
        {"crashing_build", "a stack overflow in build()", {}, [](const PluginSettings&) -> Accelerator* {
             return new Crashing(true);
         }});
}
