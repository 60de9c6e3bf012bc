#include "accel/plugins/plugin_additions.h"

#include "framework/config/plugin_settings.h"
#include "framework/core/error.h"

#include <fmt/format.h>

#include <algorithm>

namespace bvhlab {
namespace {

std::vector<EnvKey> declarationsOf(View<const PluginKey> keys) {
    std::vector<EnvKey> declared;
    for (const PluginKey& key : keys) declared.push_back(declarationOf(key));
    return declared;
}

std::vector<std::string> namesOf(const std::vector<EnvKey>& keys) {
    std::vector<std::string> names;
    for (const EnvKey& key : keys) names.push_back(key.name);
    return names;
}

bool sameDeclaration(const EnvKey& a, const EnvKey& b) {
    return a.name == b.name && a.type == b.type && a.defaultValue == b.defaultValue && a.description == b.description &&
           a.min == b.min && a.max == b.max && a.choices == b.choices;
}

// Every key declared by the accelerators and builders, in order, repeats included.
std::vector<EnvKey> allDeclarations(const PluginAdditions& additions) {
    std::vector<EnvKey> keys;
    for (const PluginAcceleratorEntry& a : additions.accelerators)
        keys.insert(keys.end(), a.keys.begin(), a.keys.end());
    for (const PluginBuilderEntry& b : additions.builders) keys.insert(keys.end(), b.keys.begin(), b.keys.end());
    return keys;
}

}  // namespace

std::string pluginText(const char* text) { return text ? text : ""; }

void RecordingRegistrar::addAccelerator(const PluginAccelerator& a) {
    additions.accelerators.push_back({pluginText(a.name), pluginText(a.description), declarationsOf(a.keys), a.create});
}

void RecordingRegistrar::addBuilder(const PluginBuilder& b) {
    std::vector<EnvKey> keys = declarationsOf(b.keys);
    additions.builders.push_back(
        {{pluginText(b.name), namesOf(keys), b.splitRule, b.mergeTree}, pluginText(b.description), std::move(keys)});
}

std::vector<std::string> PluginBuilderEntry::acceleratorNames() const {
    return {builder.name, builder.name + "4", builder.name + "8"};
}

std::vector<std::string> PluginAdditions::acceleratorNames() const {
    std::vector<std::string> names;
    for (const PluginAcceleratorEntry& a : accelerators) names.push_back(a.name);
    for (const PluginBuilderEntry& b : builders)
        for (std::string& name : b.acceleratorNames()) names.push_back(std::move(name));
    return names;
}

std::vector<EnvKey> PluginAdditions::keys() const {
    std::vector<EnvKey> keys;
    for (EnvKey& key : allDeclarations(*this))
        if (std::none_of(keys.begin(), keys.end(), [&](const EnvKey& k) { return k.name == key.name; }))
            keys.push_back(std::move(key));
    return keys;
}

void checkAdditions(const std::string& origin, const PluginAdditions& additions) {
    if (additions.accelerators.empty() && additions.builders.empty())
        throw inputError(origin, 0, "the plugin adds no accelerator and no builder");
    std::vector<std::string> names;
    for (const std::string& name : additions.acceleratorNames()) {
        if (name.empty() || name.find_first_of(" \t,:=/") != std::string::npos)
            throw inputError(origin, 0, fmt::format("accelerator name '{}' must be one word without , : = or /", name));
        if (std::count(names.begin(), names.end(), name))
            throw inputError(origin, 0, fmt::format("accelerator '{}' is already defined by this plugin", name));
        names.push_back(name);
    }
    std::vector<EnvKey> declared;
    for (const EnvKey& key : allDeclarations(additions)) {
        const auto same =
            std::find_if(declared.begin(), declared.end(), [&](const EnvKey& k) { return k.name == key.name; });
        if (same == declared.end())
            declared.push_back(key);
        else if (!sameDeclaration(*same, key))
            throw inputError(origin, 0, fmt::format("env key '{}' is declared twice, differently", key.name));
    }
    for (const PluginAcceleratorEntry& a : additions.accelerators)
        if (!a.create) throw inputError(origin, 0, fmt::format("accelerator '{}' has no factory", a.name));
    for (const PluginBuilderEntry& b : additions.builders)
        if (bool(b.builder.splitRule) == bool(b.builder.mergeTree))
            throw inputError(
                origin, 0,
                fmt::format("builder '{}' must give exactly one of splitRule and mergeTree", b.builder.name));
}

}  // namespace bvhlab
