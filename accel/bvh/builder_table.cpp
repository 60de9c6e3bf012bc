#include "accel/bvh/builder_table.h"

#include "accel/bvh/builders/binned_sah_builder.h"
#include "accel/bvh/builders/ploc_builder.h"
#include "accel/bvh/builders/sbvh_builder.h"
#include "accel/bvh/builders/spatial_median_builder.h"
#include "accel/bvh/builders/sweep_sah_builder.h"

#include <fmt/core.h>

#include <stdexcept>

namespace bvhlab {

namespace {

BuilderRecord splitRule(std::string name, SplitRuleFactory make) { return {std::move(name), std::move(make), {}}; }

BuilderRecord wholeTree(std::string name, BinaryBvh (*build)(const BvhBuildConfig&, const PrimitiveSet&)) {
    return {std::move(name), {}, build};
}

// Each builder given the shared options and its own.
std::unique_ptr<BvhSplitRule> spatialMedian(const BvhBuildConfig& c) {
    return std::make_unique<SpatialMedianBuilder>(c.shared, c.spatialMedian);
}
std::unique_ptr<BvhSplitRule> binnedSah(const BvhBuildConfig& c) {
    return std::make_unique<BinnedSahBuilder>(c.shared, c.binnedSah);
}
std::unique_ptr<BvhSplitRule> sweepSah(const BvhBuildConfig& c) { return std::make_unique<SweepSahBuilder>(c.shared); }
BinaryBvh sbvh(const BvhBuildConfig& c, const PrimitiveSet& prims) {
    return buildSbvh(c.shared, c.binnedSah, c.sbvh, prims);
}
BinaryBvh ploc(const BvhBuildConfig& c, const PrimitiveSet& prims) { return buildPlocBvh(c.shared, c.ploc, prims); }

}  // namespace

const std::vector<BuilderTableEntry>& bvhBuilderTable() {
    static const std::vector<BuilderTableEntry> table = {
        {splitRule("tdbvh", spatialMedian),
         "BVH by spatial median: the middle of the longest axis (BVH::tdbvhSplit), object median fallback",
         {&spatialMedianKeys()},
         {}},
        {splitRule("sahbvh", binnedSah),
         "BVH by binned SAH (Wald 2007): BVH::bins bins along the widest centre axis, SSE binning",
         {&sahTerminationKeys(), &binnedSahKeys()},
         {4, 8}},
        {wholeTree("sbvh", sbvh),
         "split BVH (Stich et al. 2009): sahbvh's object splits and, where their children overlap "
         "(BVH::sbvhAlpha), spatial splits that clip triangles to bins, within BVH::sbvhGrowth more references",
         {&sahTerminationKeys(), &binnedSahKeys(), &sbvhKeys()},
         {8}},
        {wholeTree("ploc", ploc),
         "BVH by PLOC (Meister & Bittner 2018): Morton order, mutual nearest neighbours within BVH::plocRadius "
         "merged bottom-up in parallel, leaves formed by SAH",
         {&sahTerminationKeys(), &plocKeys()},
         {8}},
        {splitRule("sweepbvh", sweepSah),
         "BVH by full-sweep SAH over all N-1 planes per axis: the exact reference for sahbvh; slow build",
         {&sahTerminationKeys()},
         {}},
    };
    return table;
}

const BuilderRecord& builderRecord(std::string_view name) {
    for (const BuilderTableEntry& entry : bvhBuilderTable())
        if (entry.builder.name == name) return entry.builder;
    throw std::invalid_argument(fmt::format("no BVH builder named '{}'", name));
}

}  // namespace bvhlab
