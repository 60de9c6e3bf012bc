#include "framework/report/build_stats_json.h"

namespace bvhlab {
namespace {

template <typename T>
nlohmann::json optionalJson(const std::optional<T>& value) {
    return value ? nlohmann::json(*value) : nlohmann::json();
}

}  // namespace

nlohmann::json figuresJson(const std::vector<NamedFigure>& figures) {
    nlohmann::json j = nlohmann::json::object();
    for (const NamedFigure& f : figures) j[f.name] = {{"value", f.value}, {"meaning", f.meaning}};
    return j;
}

nlohmann::json buildStatsJson(const BuildStats& b, const LeafFigureNames& leafNames) {
    return {
        {"nodes", optionalJson(b.nodes)},
        {"leaves", optionalJson(b.leaves)},
        {leafNames.mean, optionalJson(b.avgLeafPrimitives)},
        {leafNames.largest, optionalJson(b.maxLeafPrimitives)},
        {"max_depth", optionalJson(b.maxDepth)},
        {"bytes", optionalJson(b.bytes)},
        {"sah", b.sah ? nlohmann::json(b.sah->cost) : nlohmann::json()},
        {"sah_c_trav", b.sah ? nlohmann::json(b.sah->cTraversal) : nlohmann::json()},
        {"sah_c_isect", b.sah ? nlohmann::json(b.sah->cIntersect) : nlohmann::json()},
        {"epo", optionalJson(b.epo)},
        {"leaf_sizes", b.leafSizes.empty() ? nlohmann::json() : nlohmann::json(b.leafSizes)},
        {"figures", figuresJson(b.figures)},
    };
}

}  // namespace bvhlab
