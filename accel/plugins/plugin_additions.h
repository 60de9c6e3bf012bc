// What an entry point adds through the registrar (<bvhlab/registrar.h>), copied and checked in
// itself: a plugin's, which the loader opens (plugin_loader.h), and bvhlab's own structures',
// which the registry adds through the same registrar (registry.cpp).
#pragma once

#include "accel/plugins/plugin_builder.h"
#include "framework/config/env_key.h"

#include <bvhlab/registrar.h>

#include <string>
#include <vector>

namespace bvhlab {

// Text a plugin gave: "" for a null pointer.
std::string pluginText(const char* text);

// An accelerator as its entry point added it, copied.
struct PluginAcceleratorEntry {
    std::string name, description;
    std::vector<EnvKey> keys;
    Accelerator* (*create)(const PluginSettings&) = nullptr;
};

// A builder as its entry point added it, copied; it adds the accelerators NAME, NAME4 and NAME8
// (acceleratorNames).
struct PluginBuilderEntry {
    LoadedBuilder builder;
    std::string description;
    std::vector<EnvKey> keys;

    std::vector<std::string> acceleratorNames() const;
};

struct PluginAdditions {
    std::vector<PluginAcceleratorEntry> accelerators;
    std::vector<PluginBuilderEntry> builders;

    std::vector<std::string> acceleratorNames() const;  // its accelerators', then its builders'
    // Every key it declares, once: several of its accelerators may read one key.
    std::vector<EnvKey> keys() const;
};

// The registrar an entry point is given: it keeps copies of what it is given in `additions`.
// A key's declaration that is not well formed throws std::invalid_argument naming the key.
class RecordingRegistrar final : public PluginRegistrar {
public:
    void addAccelerator(const PluginAccelerator& accelerator) override;
    void addBuilder(const PluginBuilder& builder) override;

    PluginAdditions additions;
};

// Throws InputError naming `origin` (a plugin file, or "bvhlab") when what it adds is malformed:
// nothing at all, a name that is not one word, an accelerator name given twice, one key declared
// two ways, an accelerator without a factory, a builder without exactly one of its two functions.
void checkAdditions(const std::string& origin, const PluginAdditions& additions);

}  // namespace bvhlab
