// The work of queries as JSON, the one writer of every output that reports N_IT and N_TR: the
// render's statistics row, the Python module's, and the records of raycast's callers, bench,
// builders, tradeoff and spd.
#pragma once

#include <bvhlab/counters.h>

#include <nlohmann/json.hpp>

namespace bvhlab {

// Every counter of kQueryCounters under its key, as its mean per `per` (the queries, or the rays
// of a run), 0 when per is 0; null for each when `counted` is false (nothing counted or traced).
nlohmann::json queryCountersJson(const QueryCounters& counters, double per, bool counted);

}  // namespace bvhlab
