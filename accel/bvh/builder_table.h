// bvhlab's own BVH builders, one entry each: adding a builder in tree is one entry in
// builder_table.cpp (docs/adding-an-accelerator.md). The registry makes the accelerators NAME and,
// per wide layout listed, NAME4 or NAME8 of each; a plugin's builders join them at load time
// (accel/plugins/plugin_builder.h).
#pragma once

#include "accel/bvh/builders/bvh_builder.h"
#include "accel/bvh/bvh_env.h"

#include <string>
#include <string_view>
#include <vector>

namespace bvhlab {

struct BuilderTableEntry {
    BuilderRecord builder;
    std::string description;           // of the binary accelerator, NAME
    std::vector<const BvhKeys*> keys;  // the BVH:: keys it reads besides bvhCommonKeys()
    std::vector<int> wideLayouts;      // 4 and/or 8: NAME4, NAME8 too
};

const std::vector<BuilderTableEntry>& bvhBuilderTable();

// The builder of that name in the table; throws std::invalid_argument for an unknown one.
const BuilderRecord& builderRecord(std::string_view name);

}  // namespace bvhlab
