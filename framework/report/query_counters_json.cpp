#include "framework/report/query_counters_json.h"

namespace bvhlab {

nlohmann::json queryCountersJson(const QueryCounters& counters, double per, bool counted) {
    nlohmann::json j = nlohmann::json::object();
    for (const QueryCounter& c : kQueryCounters)
        j[c.key] = counted ? nlohmann::json(per > 0 ? double(counters.*c.count) / per : 0.0) : nlohmann::json();
    return j;
}

}  // namespace bvhlab
