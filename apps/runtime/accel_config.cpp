#include "apps/runtime/accel_config.h"

#include "accel/registry.h"
#include "apps/runtime/comma_list.h"
#include "apps/runtime/env_options.h"
#include "apps/runtime/plugins.h"
#include "framework/core/error.h"

#include <fmt/ranges.h>

#include <algorithm>

namespace bvhlab {

AccelConfig parseAccelConfig(const std::string& text) {
    AccelConfig config{text, text.substr(0, text.find(':')), {}};
    size_t start = text.find(':');
    while (start != std::string::npos) {
        const size_t end = text.find(':', text.find('=', start));
        config.overrides.push_back(text.substr(start + 1, end == std::string::npos ? end : end - start - 1));
        start = end;
    }
    if (config.label == "embree:Embree::robust=true") config.label = "embree-robust";
    return config;
}

std::vector<AccelConfig> parseAccelConfigList(const std::string& list) {
    std::vector<AccelConfig> configs;
    for (const std::string& item : splitCommaList(list)) configs.push_back(parseAccelConfig(item));
    return configs;
}

void nameAccelerators(const std::vector<AccelConfig>& configs, EnvOptions& env) {
    for (const AccelConfig& config : configs) env.accelerators.push_back(config.name);
}

std::string ourAccelerators() {
    std::vector<std::string> names;
    for (const AcceleratorInfo& info : acceleratorInfos())
        if (info.name != "naive" && info.name != "embree" && info.plugin.empty()) names.push_back(info.name);
    return fmt::format("{}", fmt::join(names, ","));
}

namespace {

// The config as the user typed it (its label may be a short name: embree-robust).
std::string typed(const AccelConfig& config) {
    return config.overrides.empty() ? config.name : fmt::format("{}:{}", config.name, fmt::join(config.overrides, ":"));
}

}  // namespace

Env accelConfigEnv(const AccelConfig& config, const Env& base, const std::string& option) {
    Env env = base;
    for (const std::string& o : config.overrides) env.setOverride(o, fmt::format("{} {}", option, typed(config)));
    return env;
}

void checkAccelConfigs(const std::vector<AccelConfig>& configs, const Env& base, const std::string& option) {
    if (configs.empty()) throw InputError(fmt::format("{}: no accelerator given", option));
    for (const AccelConfig& config : configs) {
        if (!loadPluginFor(config.name))
            throw InputError(fmt::format("{} {}: {}", option, typed(config), unknownAcceleratorMessage(config.name)));
        for (const std::string& o : config.overrides)
            checkKeyIsNotAnUnloadedPlugins(o.substr(0, o.find('=')), fmt::format("{} {}", option, typed(config)));
        accelConfigEnv(config, base, option);
    }
}

}  // namespace bvhlab
