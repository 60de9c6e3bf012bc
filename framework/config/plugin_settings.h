// A plugin's keys on bvhlab's side: its declarations (PluginKey, <bvhlab/settings.h>) checked and
// turned into bvhlab's own, and the typed view of their values it reads (PluginSettings), which
// holds the plugin to the keys it declared.
#pragma once

#include "framework/config/env.h"

#include <bvhlab/settings.h>

#include <deque>
#include <string>
#include <vector>

namespace bvhlab {

// `key` as the registry holds it. Throws std::invalid_argument naming what is wrong with the
// declaration: no name or one without a section, an unknown type, a missing default or
// description, a range whose ends are not in order, a Choice without words.
EnvKey declarationOf(const PluginKey& key);

// bvhlab's own declarations as PluginKeys, for its structures to give the registrar as a plugin
// does. Owns the text the PluginKeys point to, so it neither copies nor moves.
class PluginKeyList {
public:
    explicit PluginKeyList(std::vector<EnvKey> keys);
    PluginKeyList(const PluginKeyList&) = delete;
    PluginKeyList& operator=(const PluginKeyList&) = delete;

    View<const PluginKey> view() const { return pluginKeys_; }

private:
    std::vector<EnvKey> keys_;
    std::vector<std::vector<const char*>> choices_;
    std::vector<PluginKey> pluginKeys_;
};

// The values in `env` of the keys `keys` (their names), for their owner, "accelerator 'scan'".
// A getter throws std::invalid_argument naming the key when it is none of `keys` or is of
// another type. Not for two threads at once (it keeps the text it returns).
class EnvPluginSettings final : public PluginSettings {
public:
    EnvPluginSettings(const Env& env, std::vector<std::string> keys, std::string owner)
        : env_(env), keys_(std::move(keys)), owner_(std::move(owner)) {}

    bool getBool(const char* key) const override;
    int getInt(const char* key) const override;
    float getFloat(const char* key) const override;
    const char* getText(const char* key) const override;
    bool getVec3(const char* key, Vec3& value) const override;
    View<const Vec3> getVec3List(const char* key) const override;
    bool isExplicit(const char* key) const override;

private:
    // `key`, checked to be one of keys_, of one of `types`.
    std::string checked(const char* key, std::initializer_list<KeyType> types, const char* getter) const;

    const Env& env_;
    std::vector<std::string> keys_;
    std::string owner_;
    mutable std::deque<std::string> texts_;
    mutable std::deque<std::vector<Vec3>> lists_;
};

}  // namespace bvhlab
