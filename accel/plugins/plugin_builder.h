// A plugin's builder (<bvhlab/builder.h>) as one of ours: its split rule under the shared
// top-down recursion, or its merge tree with leaves formed by SAH. Either way its PrimRefs are
// checked afterwards, so a rule that loses or invents a primitive, or changes a box, fails the
// build with an error naming it instead of giving a wrong tree.
#pragma once

#include "accel/bvh/builders/bvh_builder.h"
#include "framework/config/env.h"

#include <bvhlab/builder.h>

#include <string>
#include <vector>

namespace bvhlab {

// A plugin's builder as bvhlab keeps it: PluginBuilder's functions, with its name and the names
// of its keys copied.
struct LoadedBuilder {
    std::string name;
    std::vector<std::string> keys;
    SplitRule* (*splitRule)(const BuilderSettings&) = nullptr;
    void (*mergeTree)(View<const PrimRef>, View<Merge>, const BuilderSettings&) = nullptr;
};

// `env` (copied) holds the values of the builder's keys.
BuilderRecord pluginBuilderRecord(const LoadedBuilder& builder, const Env& env);

}  // namespace bvhlab
