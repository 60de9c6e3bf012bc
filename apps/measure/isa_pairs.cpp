#include "apps/measure/isa_pairs.h"

#include "apps/runtime/comma_list.h"
#include "framework/core/cpu_levels.h"
#include "framework/core/error.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

namespace bvhlab {

namespace {

// The ISAs both key sets name alike, in rising order: BVH::isa has no SSE kernels, Embree no
// scalar ones.
constexpr const char* kPairIsas[] = {"avx2", "avx512"};

}  // namespace

IsaPairs parseIsaPairs(const std::string& list) {
    IsaPairs pairs;
    const CpuLevels cpu = cpuLevels();
    pairs.best = cpu.v4 ? "avx512" : cpu.v3 ? "avx2" : "scalar";
    for (const std::string& isa : splitCommaList(list)) {
        const auto known = std::find(std::begin(kPairIsas), std::end(kPairIsas), isa);
        if (known == std::end(kPairIsas) || std::find(pairs.isas.begin(), pairs.isas.end(), isa) != pairs.isas.end())
            throw InputError(fmt::format("--isa-pairs {}: '{}' is not avx2 or avx512 (or is given twice)", list, isa));
        if (!(isa == "avx2" ? cpu.v3 : cpu.v4))
            throw InputError(
                fmt::format("--isa-pairs {}: this CPU does not run {} (it runs up to {})", list, isa, pairs.best));
        if (isa == pairs.best)
            pairs.note = fmt::format(
                "--isa-pairs {}: {} is this CPU's best ISA, so the headline pair is the {} pair "
                "(timed once)",
                list, isa, isa);
        else
            pairs.isas.push_back(isa);
    }
    return pairs;
}

std::string labelAtIsa(const std::string& label, const std::string& isa) {
    return isa == "best" ? label : fmt::format("{}@{}", label, isa);
}

std::optional<AccelConfig> configAtIsa(const AccelConfig& config, const std::string& isa) {
    for (const char* key : {"BVH::isa", "Embree::isa"}) {
        const std::vector<std::string> readers = acceleratorsReading(key);
        if (std::find(readers.begin(), readers.end(), config.name) == readers.end()) continue;
        AccelConfig copy = config;
        copy.label = labelAtIsa(config.label, isa);
        copy.overrides.push_back(fmt::format("{}={}", key, isa));  // the last override wins
        return copy;
    }
    return std::nullopt;
}

}  // namespace bvhlab
