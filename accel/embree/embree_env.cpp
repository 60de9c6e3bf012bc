#include "accel/embree/embree_env.h"

#include "framework/config/plugin_settings.h"

namespace bvhlab {

namespace {

const KeyBindings<EmbreeConfig>& embreeKeys() {
    static const KeyBindings<EmbreeConfig> bound = {
        {keys::Embree::quality,
         [](EmbreeConfig& c, const std::string& v) {
             // The choices the key allows, medium the remaining one.
             c.quality = v == "low"     ? EmbreeQuality::Low
                         : v == "high"  ? EmbreeQuality::High
                         : v == "refit" ? EmbreeQuality::Refit
                                        : EmbreeQuality::Medium;
         }},
        {keys::Embree::robust, [](EmbreeConfig& c, bool v) { c.robust = v; }},
        {keys::Embree::threads, [](EmbreeConfig& c, int v) { c.threads = v; }},
        {keys::Embree::isa, [](EmbreeConfig& c, const std::string& v) { c.maxIsa = v == "auto" ? "" : v; }},
    };
    return bound;
}

}  // namespace

std::vector<EnvKey> embreeKeyDeclarations() {
    std::vector<EnvKey> keys;
    embreeKeys().appendDeclarations(keys);
    return keys;
}

EmbreeConfig EmbreeConfig::from(const PluginSettings& keys) {
    EmbreeConfig config;
    embreeKeys().read(keys, config);
    if (config.threads == 0) config.threads = keys.getInt(kThreadsKey);
    return config;
}

EmbreeConfig EmbreeConfig::fromEnv(const Env& env) {
    std::vector<std::string> names;
    for (const EnvKey& key : embreeKeyDeclarations()) names.push_back(key.name);
    return from(EnvPluginSettings(env, std::move(names), "accelerator 'embree'"));
}

}  // namespace bvhlab
