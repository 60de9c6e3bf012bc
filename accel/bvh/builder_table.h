// bvhlab's own BVH builders, one entry each: adding a builder in tree is one entry in
// builder_table.cpp (docs/adding-an-accelerator.md). Each adds, through the registrar a plugin's
// entry point is given, the accelerator NAME and, per wide layout listed, NAME4 or NAME8; a
// plugin's builders join them at load time (accel/plugins/plugin_builder.h).
#pragma once

#include "accel/bvh/builders/bvh_builder.h"
#include "accel/bvh/bvh_env.h"

#include <bvhlab/registrar.h>

#include <string>
#include <string_view>
#include <vector>

namespace bvhlab {

struct BuilderTableEntry {
    BuilderRecord builder;
    std::string description;           // of the binary accelerator, NAME
    std::vector<const BvhKeys*> keys;  // the BVH:: keys it reads besides those every BVH accelerator reads
    std::vector<int> wideLayouts;      // 4 and/or 8: NAME4, NAME8 too
};

// Adds the accelerators of every builder of the table to `registrar`.
void addBvhAccelerators(PluginRegistrar& registrar);

// The description of a builder's accelerator in a wide layout, NAME4 or NAME8.
std::string wideBvhDescription(const std::string& builder, int width);

// The builder of that name in the table; throws std::invalid_argument for an unknown one.
const BuilderRecord& builderRecord(std::string_view name);

}  // namespace bvhlab
