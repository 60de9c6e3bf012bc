#include "accel/guarded_accelerator.h"

#include <type_traits>

namespace bvhlab {
namespace {

class GuardedAccelerator final : public Accelerator {
public:
    GuardedAccelerator(std::unique_ptr<Accelerator> inner, std::string plugin, std::string accelerator)
        : inner_(std::move(inner)), plugin_(std::move(plugin)), accelerator_(std::move(accelerator)) {}

    std::string_view name() const override { return accelerator_; }

    void build(const PrimitiveSet& prims) override {
        guard("build()", [&] { inner_->build(prims); });
    }
    BuildStats statistics() const override {
        return guard("statistics()", [&] { return inner_->statistics(); });
    }
    bool findNearest(const Ray& ray, Hit& hit, QueryCounters& counters) const override {
        return guard("findNearest()", [&] { return inner_->findNearest(ray, hit, counters); });
    }
    bool isOccluded(const Ray& ray, QueryCounters& counters) const override {
        return guard("isOccluded()", [&] { return inner_->isOccluded(ray, counters); });
    }
    void findNearestBatch(std::span<const Ray> rays, std::span<Hit> hits, QueryCounters& counters,
                          std::span<RayCost> costs) const override {
        guard("findNearestBatch()", [&] { inner_->findNearestBatch(rays, hits, counters, costs); });
    }
    void isOccludedBatch(std::span<const Ray> rays, std::span<uint8_t> occluded, QueryCounters& counters,
                         std::span<RayCost> costs) const override {
        guard("isOccludedBatch()", [&] { inner_->isOccludedBatch(rays, occluded, counters, costs); });
    }
    bool hasCounters() const override {
        return guard("hasCounters()", [&] { return inner_->hasCounters(); });
    }
    std::unique_ptr<NativeRayBatch> prepareNativeBatch(const std::vector<Ray>& rays) const override {
        return guard("prepareNativeBatch()", [&] { return inner_->prepareNativeBatch(rays); });
    }

private:
    template <typename Body>
    std::invoke_result_t<Body> guard(std::string_view what, Body&& body) const {
        return guardPlugin(plugin_, accelerator_, what, std::forward<Body>(body));
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
