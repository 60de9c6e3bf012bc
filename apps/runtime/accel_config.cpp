#include "apps/runtime/accel_config.h"

#include "accel/registry.h"
#include "apps/runtime/comma_list.h"
#include "apps/runtime/env_options.h"
#include "apps/runtime/plugins.h"
#include "framework/core/error.h"

#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

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
    for (const std::string& warning : unreadKeyWarnings(configs, base, option))
        fmt::print(stderr, "warning: {}\n", warning);
}

std::vector<std::string> acceleratorsReading(const std::string& key) {
    std::vector<std::string> readers;
    for (const AcceleratorInfo& info : acceleratorInfos())
        if (std::find(info.envKeys.begin(), info.envKeys.end(), key) != info.envKeys.end())
            readers.push_back(info.name);
    return readers;
}

namespace {

bool reads(const std::string& accelerator, const std::string& key) {
    const std::vector<std::string> readers = acceleratorsReading(key);
    return std::find(readers.begin(), readers.end(), accelerator) != readers.end();
}

}  // namespace

std::vector<std::string> unreadKeyWarnings(const std::vector<AccelConfig>& configs, const Env& base,
                                           const std::string& option) {
    std::vector<std::string> chosen, warnings;
    for (const AccelConfig& config : configs)
        if (std::find(chosen.begin(), chosen.end(), config.name) == chosen.end()) chosen.push_back(config.name);
    const nlohmann::json values = base.toJson();
    for (const auto& [key, entry] : values.items()) {
        if (!entry.at("from").get<std::string>().starts_with("-D") || acceleratorsReading(key).empty()) continue;
        if (std::none_of(chosen.begin(), chosen.end(), [&](const std::string& name) { return reads(name, key); }))
            warnings.push_back(fmt::format("{} is read by none of the chosen structures ({}); it is ignored", key,
                                           fmt::join(chosen, ", ")));
    }
    for (const AccelConfig& config : configs)
        for (const std::string& o : config.overrides) {
            const std::string key = o.substr(0, o.find('='));
            if (!acceleratorsReading(key).empty() && !reads(config.name, key))
                warnings.push_back(
                    fmt::format("{} {}: {} is not read by {}; it is ignored", option, typed(config), key, config.name));
        }
    return warnings;
}

}  // namespace bvhlab
