#include "accel/plugins/guarded_accelerator.h"

#include "framework/core/fatal_signal_report.h"

#include <type_traits>

namespace bvhlab {
namespace {

class GuardedAccelerator final : public Accelerator {
public:
    GuardedAccelerator(std::unique_ptr<Accelerator> inner, std::string plugin, std::string accelerator)
        : inner_(std::move(inner)), plugin_(std::move(plugin)), accelerator_(std::move(accelerator)) {}

    const char* name() const override { return accelerator_.c_str(); }

    void build(const PrimitiveSet& prims) override {
        guard(running("build()", nullptr, prims.valid.size()), [&] { inner_->build(prims); });
    }
    bool update(const PrimitiveSet& prims) override {
        return guard(running("update()", nullptr, prims.valid.size()), [&] { return inner_->update(prims); });
    }
    void statistics(BuildStatistics& out) const override {
        guard(running("statistics()"), [&] { inner_->statistics(out); });
    }
    bool findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const override {
        return guard(running("findNearest()", &ray, 1), [&] { return inner_->findNearest(ray, hit, counters); });
    }
    bool isOccluded(const Ray& ray, QueryCounters& counters) const override {
        return guard(running("isOccluded()", &ray, 1), [&] { return inner_->isOccluded(ray, counters); });
    }
    void findNearestBatch(View<const Ray> rays, View<Hit> hits, QueryCounters& counters, View<RayCost> costs,
                          RayCoherence coherence) const override {
        guard(running("findNearestBatch()", rays),
              [&] { inner_->findNearestBatch(rays, hits, counters, costs, coherence); });
    }
    void isOccludedBatch(View<const Ray> rays, View<uint8_t> occluded, QueryCounters& counters, View<RayCost> costs,
                         RayCoherence coherence) const override {
        guard(running("isOccludedBatch()", rays),
              [&] { inner_->isOccludedBatch(rays, occluded, counters, costs, coherence); });
    }
    bool hasCounters() const override {
        return guard(running("hasCounters()"), [&] { return inner_->hasCounters(); });
    }

private:
    // The call as the report of a fatal signal names it (framework/core/fatal_signal_report.h).
    PluginCall running(const char* call, const Ray* ray = nullptr, size_t count = 0) const {
        return {plugin_.c_str(), accelerator_.c_str(), call, ray, count};
    }
    PluginCall running(const char* call, View<const Ray> rays) const {
        return running(call, rays.empty() ? nullptr : rays.data(), rays.size());
    }

    // Runs `body` as the thread's running plugin call, naming the plugin in what it throws.
    template <typename Body>
    std::invoke_result_t<Body> guard(const PluginCall& call, Body&& body) const {
        const PluginCallScope scope(call);
        return guardPlugin(plugin_, accelerator_, call.call, std::forward<Body>(body));
    }

    std::unique_ptr<Accelerator> inner_;
    std::string plugin_, accelerator_;
};

}  // namespace

std::unique_ptr<Accelerator> guardAccelerator(std::unique_ptr<Accelerator> inner, std::string plugin,
                                              std::string accelerator) {
    return std::make_unique<GuardedAccelerator>(std::move(inner), std::move(plugin), std::move(accelerator));
}

}  // namespace bvhlab
