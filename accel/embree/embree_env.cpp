#include "accel/embree/embree_env.h"

namespace bvhlab {

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

EmbreeConfig EmbreeConfig::fromEnv(const Env& env) {
    EmbreeConfig config;
    embreeKeys().read(env, config);
    if (config.threads == 0) config.threads = env.get(keys::SetRayTracing::threads);
    return config;
}

}  // namespace bvhlab
