// `bvhlab bench --isa-pairs`: ours and Embree at one ISA, timed beside the headline pair (each at
// the best ISA this CPU runs). Counts under valgrind are of AVX2 code while times on an AVX-512
// machine are of AVX-512 code; the AVX2 pair times what the counts count. At an ISA of the pairs,
// each structure that reads BVH::isa or Embree::isa is measured again as a copy labelled
// LABEL@ISA with that key set to ISA, and its ratios are to Embree's rows at that ISA.
#pragma once

#include "apps/runtime/accel_config.h"

#include <optional>
#include <string>
#include <vector>

namespace bvhlab {

struct IsaPairs {
    std::string best;               // the best ISA this CPU runs, in BVH::isa's terms
    std::vector<std::string> isas;  // the ISAs timed beside the headline pair
    std::string note;               // what the output says once: an ISA that is the headline's
};

// --isa-pairs LIST: avx2 and avx512, comma-separated. One that is this CPU's best is the headline
// pair's and not timed twice (the note says so); one above it is an InputError.
IsaPairs parseIsaPairs(const std::string& list);

// The label of a copy at `isa`, LABEL@ISA; the label itself for the headline's ("best").
std::string labelAtIsa(const std::string& label, const std::string& isa);

// The copy of `config` at `isa` where its structure reads BVH::isa or Embree::isa: labelled
// LABEL@ISA, that key set to `isa` over its own overrides. None for a structure that reads neither.
std::optional<AccelConfig> configAtIsa(const AccelConfig& config, const std::string& isa);

}  // namespace bvhlab
