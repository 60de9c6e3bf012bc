// A plugin whose build() never returns, for the time-outs of the commands that run jobs
// (tests/apps/test_job_timeouts.cpp): `hanging` sleeps in build() until it is killed.
#include <bvhlab/plugin.h>

#include <chrono>
#include <thread>

namespace {

class Hanging final : public bvhlab::Accelerator {
public:
    const char* name() const override { return "hanging"; }
    void build(const bvhlab::PrimitiveSet&) override {
        for (;;) std::this_thread::sleep_for(std::chrono::hours(1));
    }
    void statistics(bvhlab::BuildStatistics&) const override {}
    bool findNearest(const bvhlab::Ray&, bvhlab::Hit&, bvhlab::QueryCounters&) const override { return false; }
    bool isOccluded(const bvhlab::Ray&, bvhlab::QueryCounters&) const override { return false; }
};

}  // namespace

BVHLAB_PLUGIN(registrar) {
    registrar.addAccelerator(
        {"hanging", "a build() that never returns", {}, [](const bvhlab::PluginSettings&) -> bvhlab::Accelerator* {
             return new Hanging;
         }});
}
