#include "apps/runtime/env_options.h"

#include "accel/registry.h"
#include "apps/runtime/comma_list.h"
#include "apps/runtime/plugins.h"
#include "apps/runtime/program_keys.h"
#include "framework/config/common_keys.h"
#include "framework/config/install_paths.h"
#include "framework/core/error.h"

#include <fmt/core.h>

#include <algorithm>
#include <tuple>

namespace bvhlab {

std::vector<std::string> EnvOptions::files(const std::filesystem::path& sceneEnvFile) const {
    std::vector<std::string> candidates;
    if (!noGlobalEnv) candidates.push_back(dataFile("env/global.env").string());
    if (!sceneEnvFile.empty()) candidates.push_back(sceneEnvFile.string());
    candidates.insert(candidates.end(), envFiles.begin(), envFiles.end());
    // A file named twice (--env env/global.env) is read once, where it first comes.
    std::vector<std::string> result;
    for (const std::string& file : candidates) {
        std::error_code ec;
        const bool seen = std::any_of(result.begin(), result.end(), [&](const std::string& earlier) {
            return std::filesystem::equivalent(earlier, file, ec);
        });
        if (!seen) result.push_back(file);
    }
    return result;
}

void EnvOptions::loadPlugins(const std::vector<std::string>& layerFiles) const {
    for (const std::string& file : plugins) loadPlugin(file);
    // ASDS::plugins and ASDS::type as the layers give them, read before the registry checks the
    // layers, since a plugin they name adds keys and accelerators the layers may use.
    struct Assignment {
        EnvLine line;
        std::filesystem::path baseDir;  // relative plugin files resolve against it
    };
    std::vector<Assignment> assignments;
    for (const std::string& file : layerFiles)
        for (const EnvLine& line : readEnvLines(file))
            assignments.push_back({line, std::filesystem::absolute(file).parent_path()});
    for (const std::string& assignment : overrides) {
        const size_t eq = assignment.find('=');
        if (eq == std::string::npos) continue;  // reported by Env::setOverride
        const std::string name = assignment.substr(0, eq);
        assignments.push_back({{name, assignment.substr(eq + 1), "-D" + name}, std::filesystem::current_path()});
    }
    std::string type, typeOrigin;
    for (const auto& [line, baseDir] : assignments) {
        if (line.name == keys::ASDS::plugins.name())
            for (const std::string& file : splitCommaList(line.text)) {
                std::error_code ec;
                if (!std::filesystem::is_regular_file(baseDir / file, ec))
                    throw InputError(fmt::format("{}: ASDS::plugins: no plugin file {}", line.origin,
                                                 (baseDir / file).lexically_normal().string()));
                loadPlugin(baseDir / file);
            }
        if (line.name == keys::ASDS::type.name() && !line.text.empty())
            std::tie(type, typeOrigin) = std::pair(line.text, line.origin);
    }
    for (const std::string& name : accelerators) loadPluginFor(name);  // unknown: the command says so
    if (!type.empty() && !loadPluginFor(type))
        throw InputError(fmt::format("{}: {}", typeOrigin, unknownAcceleratorMessage(type)));
    for (const auto& [line, baseDir] : assignments) checkKeyIsNotAnUnloadedPlugins(line.name, line.origin);
}

Env EnvOptions::load(const std::filesystem::path& sceneEnvFile) const {
    loadPlugins(files(sceneEnvFile));
    Env env(programKeys());
    for (const std::string& file : files(sceneEnvFile)) env.loadFile(file);
    if (threads >= 0) env.set(keys::SetRayTracing::threads, std::to_string(threads), "--threads");
    for (const std::string& assignment : overrides) env.setOverride(assignment);
    return env;
}

}  // namespace bvhlab
