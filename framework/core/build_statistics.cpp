#include "framework/core/accelerator.h"

#include <fmt/format.h>

#include <cmath>
#include <set>
#include <stdexcept>

namespace bvhlab {
namespace {

// A BuildStats filled by name, each statistic once.
class StatsCollector final : public BuildStatistics {
public:
    explicit StatsCollector(const Accelerator& accel) : accel_(accel) {}

    void set(const char* name, double value) override {
        const std::string key = name ? name : "";
        once(key);
        const auto count = [&] {
            if (value < 0 || value != std::floor(value))
                refuse(fmt::format("statistic '{}' = {} is not a count", key, value));
            return size_t(value);
        };
        if (key == "primitives")
            stats.primitives = count();
        else if (key == "nodes")
            stats.nodes = count();
        else if (key == "leaves")
            stats.leaves = count();
        else if (key == "avg_leaf_prims")
            stats.avgLeafPrimitives = value;
        else if (key == "max_leaf_prims")
            stats.maxLeafPrimitives = count();
        else if (key == "max_depth")
            stats.maxDepth = int(count());
        else if (key == "depth_bound")
            stats.depthBound = int(count());
        else if (key == "leaf_bound")
            stats.leafBound = count();
        else if (key == "sah")
            sah().cost = value;
        else if (key == "sah_c_trav")
            sah().cTraversal = value;
        else if (key == "sah_c_isect")
            sah().cIntersect = value;
        else if (key == "epo")
            stats.epo = value;
        else if (key == "bytes")
            stats.bytes = count();
        else
            refuse(fmt::format("unknown statistic '{}' (a figure of its own is reported with figure())", key));
    }
    void figure(const char* name, double value, const char* meaning) override {
        const std::string key = name ? name : "";
        if (key.empty() || key.find_first_of(" \t\n\"") != std::string::npos)
            refuse(fmt::format("figure name '{}' is not one word", key));
        once("figures." + key);
        stats.figures.push_back({key, value, meaning ? meaning : ""});
    }
    void leafSizes(View<const size_t> leavesOfSize) override {
        once("leaf sizes");
        stats.leafSizes.assign(leavesOfSize.begin(), leavesOfSize.end());
    }

    BuildStats stats;

private:
    SahCost& sah() {
        if (!stats.sah) stats.sah = SahCost{};
        return *stats.sah;
    }
    void once(const std::string& key) {
        if (!given_.insert(key).second) refuse(fmt::format("statistic '{}' given twice", key));
    }
    [[noreturn]] void refuse(const std::string& why) const {
        throw std::invalid_argument(fmt::format("{}: {}", accel_.name(), why));
    }

    const Accelerator& accel_;
    std::set<std::string> given_;
};

}  // namespace

BuildStats statisticsOf(const Accelerator& accel) {
    if (const auto* own = dynamic_cast<const BuildStatsAccelerator*>(&accel)) return own->buildStats();
    StatsCollector collector(accel);
    accel.statistics(collector);
    return std::move(collector.stats);
}

void writeStatistics(const BuildStats& stats, BuildStatistics& out) {
    out.set("primitives", double(stats.primitives));
    const auto optional = [&](const char* name, const auto& value) {
        if (value) out.set(name, double(*value));
    };
    optional("nodes", stats.nodes);
    optional("leaves", stats.leaves);
    optional("avg_leaf_prims", stats.avgLeafPrimitives);
    optional("max_leaf_prims", stats.maxLeafPrimitives);
    optional("max_depth", stats.maxDepth);
    optional("depth_bound", stats.depthBound);
    optional("leaf_bound", stats.leafBound);
    if (stats.sah) {
        out.set("sah", stats.sah->cost);
        out.set("sah_c_trav", stats.sah->cTraversal);
        out.set("sah_c_isect", stats.sah->cIntersect);
    }
    optional("epo", stats.epo);
    optional("bytes", stats.bytes);
    if (!stats.leafSizes.empty()) out.leafSizes(stats.leafSizes);
    for (const NamedFigure& f : stats.figures) out.figure(f.name.c_str(), f.value, f.meaning.c_str());
}

}  // namespace bvhlab
