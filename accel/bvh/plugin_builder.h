// A plugin's builder (framework/plugin/builder_api.h) as one of ours: its split rule under the
// shared top-down recursion, or its merge tree with leaves formed by SAH. Either way its
// PrimRefs are checked afterwards, so a rule that loses or invents a primitive, or changes a
// box, fails the build with an error naming it instead of giving a wrong tree.
#pragma once

#include "accel/bvh/builders/bvh_builder.h"
#include "framework/plugin/builder_api.h"

namespace bvhlab {

// `env` (copied) is what the builder's settings show it; leafBlock as BuilderSettings says.
BvhBuilder pluginBvhBuilder(const PluginBuilder& builder, const Env& env, uint32_t leafBlock);

}  // namespace bvhlab
