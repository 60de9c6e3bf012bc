#include "accel/bvh/builder_table.h"

#include "accel/bvh/builders/binned_sah_builder.h"
#include "accel/bvh/builders/ploc_builder.h"
#include "accel/bvh/builders/sbvh_builder.h"
#include "accel/bvh/builders/spatial_median_builder.h"
#include "accel/bvh/builders/sweep_sah_builder.h"
#include "accel/bvh/bvh_accelerator.h"
#include "framework/config/plugin_settings.h"

#include <fmt/core.h>

#include <array>
#include <stdexcept>
#include <type_traits>
#include <utility>

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

// The table, its size known where the accelerators' factories are made (addBvhAccelerators).
const auto& table() {
    static const auto table = std::to_array<BuilderTableEntry>({
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
    });
    return table;
}

// The factory of the accelerator of table entry `Entry` in `Layout`: a plain function, as the
// registrar takes factories.
template <size_t Entry, typename Layout>
Accelerator* createBvh(const PluginSettings& keys) {
    const BuilderTableEntry& entry = table()[Entry];
    const BvhSettings settings = bvhSettings(keys, entry.keys);
    return new BvhAccelerator<Layout>(entry.builder, settings.build, settings.traversal, settings.stats,
                                      settings.update);
}

template <size_t Entry>
void addAccelerators(PluginRegistrar& registrar) {
    const BuilderTableEntry& entry = table()[Entry];
    const PluginKeyList keys(bvhKeyDeclarations(entry.keys));
    const std::string& name = entry.builder.name;
    registrar.addAccelerator({name.c_str(), entry.description.c_str(), keys.view(), createBvh<Entry, BinaryBvh>});
    for (int width : entry.wideLayouts)
        registrar.addAccelerator({(name + std::to_string(width)).c_str(), wideBvhDescription(name, width).c_str(),
                                  keys.view(),
                                  width == 4 ? createBvh<Entry, WideBvh<4>> : createBvh<Entry, WideBvh<8>>});
}

template <size_t... Entries>
void addEachEntry(PluginRegistrar& registrar, std::index_sequence<Entries...>) {
    (addAccelerators<Entries>(registrar), ...);
}

}  // namespace

void addBvhAccelerators(PluginRegistrar& registrar) {
    addEachEntry(registrar, std::make_index_sequence<std::tuple_size_v<std::remove_cvref_t<decltype(table())>>>());
}

std::string wideBvhDescription(const std::string& builder, int width) {
    return fmt::format(
        "{}'s tree (leaves charged by blocks of eight) in {}-wide nodes, {} child boxes tested at "
        "once, leaves eight triangles at once, in the SIMD kernels BVH::isa chooses at run time; N_TR "
        "counts wide steps",
        builder, width, width == 4 ? "four" : "eight");
}

const BuilderRecord& builderRecord(std::string_view name) {
    for (const BuilderTableEntry& entry : table())
        if (entry.builder.name == name) return entry.builder;
    throw std::invalid_argument(fmt::format("no BVH builder named '{}'", name));
}

}  // namespace bvhlab
