// What a plugin adds to bvhlab: accelerators, and builders (<bvhlab/builder.h>), each with its
// own keys. The plugin's entry point (<bvhlab/plugin.h>) is given a PluginRegistrar.
#pragma once

#include <bvhlab/accelerator.h>
#include <bvhlab/builder.h>
#include <bvhlab/settings.h>
#include <bvhlab/view.h>

namespace bvhlab {

// One accelerator a plugin adds: chosen by `ASDS::type name` (one word), described in
// `bvhlab keys`, with the keys it reads.
struct PluginAccelerator {
    const char* name;
    const char* description;
    View<const PluginKey> keys;
    // Makes the accelerator with `new` (bvhlab deletes it) from the resolved values of its keys.
    Accelerator* (*create)(const PluginSettings& settings) = nullptr;
};

// What the entry point is given. It copies what it is given: the views may point to temporaries.
class PluginRegistrar {
public:
    virtual void addAccelerator(const PluginAccelerator& accelerator) = 0;
    virtual void addBuilder(const PluginBuilder& builder) = 0;

protected:
    ~PluginRegistrar() = default;
};

}  // namespace bvhlab
