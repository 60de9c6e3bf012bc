#include "apps/runtime/result_key.h"

#include "accel/registry.h"
#include "apps/runtime/accel_config.h"
#include "apps/runtime/app_keys.h"
#include "apps/runtime/plugins.h"
#include "apps/runtime/scene_loading.h"
#include "framework/report/provenance.h"
#include "framework/scene/scene_cache.h"
#include "framework/scene/scene_loader.h"

#include <fmt/core.h>
#include <fmt/ranges.h>

#include <fstream>
#include <set>

namespace bvhlab {
namespace {

using nlohmann::json;

// "SIZE-CRC32" of a file's bytes.
std::string contentOf(const std::filesystem::path& file) {
    const SceneCacheKey key = sceneCacheKey(file);
    return fmt::format("{}-{:08x}", key.size, key.crc32);
}

// The files of the mapped shared libraries whose names start with one of `prefixes`.
std::set<std::filesystem::path> mappedLibraries(std::initializer_list<std::string_view> prefixes) {
    std::set<std::filesystem::path> files;
    std::ifstream maps("/proc/self/maps");
    std::string line;
    while (std::getline(maps, line)) {
        const size_t slash = line.find('/');
        if (slash == std::string::npos) continue;
        const std::filesystem::path file = line.substr(slash);
        const std::string name = file.filename().string();
        for (const std::string_view prefix : prefixes)
            if (name.starts_with(prefix) && name.find(".so") != std::string::npos) files.insert(file);
    }
    return files;
}

// The checksums of a scene file, read once per process (a tradeoff asks for every configuration).
const json& sceneFileContent(const std::filesystem::path& file) {
    static std::map<std::filesystem::path, json> known;
    const std::filesystem::path absolute = std::filesystem::absolute(file).lexically_normal();
    const auto it = known.find(absolute);
    if (it != known.end()) return it->second;
    const SceneCacheKey key = sceneCacheKey(absolute);
    json content = {{"name", absolute.filename().string()},
                    {"size", key.size},
                    {"crc32", fmt::format("{:08x}", key.crc32)},
                    {"adler32", fmt::format("{:08x}", key.adler32)}};
    // The files it includes decide the scene too (AFF).
    for (const std::filesystem::path& included : includedFiles(absolute))
        content["includes"][included.lexically_relative(absolute.parent_path()).string()] = contentOf(included);
    return known[absolute] = content;
}

// The key's values by a path of readable names: "structure BVH::maxLeaf", "plugin crc32",
// "scene file crc32", "program bvhlab" (the grouping objects keys, settings and files unnamed).
void flatten(const json& j, const std::string& path, std::map<std::string, std::string>& out) {
    if (!j.is_object() || j.empty()) {
        out[path] = j.is_string() ? j.get<std::string>() : j.dump();
        return;
    }
    for (const auto& [name, value] : j.items()) {
        const bool grouping = name == "keys" || name == "settings" || name == "files";
        const std::string inner = name == "plugin" ? "plugin"
                                  : path.empty()   ? name
                                  : grouping       ? path
                                                   : path + " " + name;
        flatten(value, inner, out);
    }
}

}  // namespace

const json& programIdentity() {
    static const json identity = [] {
        json files = json::object();
        files["bvhlab"] = contentOf("/proc/self/exe");
        for (const std::filesystem::path& library : mappedLibraries({"libbvhlab", "libembree"}))
            files[library.filename().string()] = contentOf(library);
        return json{{"commit", gitCommit()}, {"files", files}};
    }();
    return identity;
}

json structureKey(const std::string& accelerator, const Env& env) {
    json key = {{"accel", accelerator}, {"keys", json::object()}, {"plugin", nullptr}};
    const AcceleratorInfo* info = findAccelerator(accelerator);
    if (!info) return key;
    const json values = env.toJson();
    for (const std::string& name : info->envKeys) key["keys"][name] = values.at(name).at("value");
    for (const LoadedPlugin& plugin : loadedPlugins())
        if (plugin.file.string() == info->plugin)
            key["plugin"] = {{"file", plugin.file.filename().string()},
                             {"size", plugin.size},
                             {"crc32", fmt::format("{:08x}", plugin.crc32)},
                             {"abi", plugin.abi},
                             {"compiler", plugin.compiler},
                             {"cxx_flags", plugin.cxxFlags},
                             {"optimized", plugin.optimized}};
    return key;
}

std::string describeStructure(const json& structure) {
    std::vector<std::string> settings;
    for (const auto& [name, value] : structure.at("keys").items())
        settings.push_back(fmt::format("{}={}", name, value.get<std::string>()));
    std::string text = settings.empty() ? "no settings of its own" : fmt::format("{}", fmt::join(settings, ", "));
    const json& plugin = structure.at("plugin");
    if (!plugin.is_null())
        text += fmt::format("; plugin {}, CRC-32 {}{}", plugin.at("file").get<std::string>(),
                            plugin.at("crc32").get<std::string>(),
                            plugin.at("optimized").get<bool>() ? "" : ", unoptimised");
    return text;
}

json sceneKey(const Env& env) {
    const std::filesystem::path file = sceneFileOf(env);  // says which key to set when it is not there
    // A key that some accelerator reads belongs to the structures that read it, not the scene;
    // the frame decides only an animated scene.
    const bool animated = !file.empty() && isAnimatedScene(file);
    json settings = json::object();
    const json values = env.toJson();
    for (const auto& [name, entry] : values.items())
        if (acceleratorsReading(name).empty() && !changesNoFigure(name) && !name.starts_with("ASDS::") &&
            name != keys::Scene::dir.name() && name != keys::Scene::file.name() &&
            (animated || name != keys::Scene::frame.name()))
            settings[name] = entry.at("value");
    return {{"file", file.empty() ? json("embedded") : sceneFileContent(file)}, {"settings", settings}};
}

json resultKey(const std::string& accelerator, const Env& env, const json& measurement) {
    return {{"program", programIdentity()},
            {"structure", structureKey(accelerator, env)},
            {"scene", sceneKey(env)},
            {"measurement", measurement}};
}

std::vector<std::string> resultKeyChanges(const json& before, const json& after) {
    std::map<std::string, std::string> old, now;
    flatten(before, "", old);
    flatten(after, "", now);
    std::set<std::string> paths;
    for (const auto& [path, value] : old) paths.insert(path);
    for (const auto& [path, value] : now) paths.insert(path);
    std::vector<std::string> lines;
    for (const std::string& path : paths) {
        const auto o = old.find(path), n = now.find(path);
        const std::string from = o == old.end() ? "(none)" : o->second, to = n == now.end() ? "(none)" : n->second;
        if (from != to) lines.push_back(fmt::format("{}: {} -> {}", path, from, to));
    }
    return lines;
}

StoredResult checkStoredResult(const std::filesystem::path& file, const json& key) {
    if (!std::filesystem::exists(file)) return {false, "new"};
    json stored;
    try {
        std::ifstream in(file);
        stored = json::parse(in);
    } catch (const std::exception&) {
        return {false, "the earlier result is unreadable"};
    }
    if (stored.contains("failed")) return {false, "it failed in the earlier run"};
    if (!stored.contains("result_key") || stored.at("result_key").is_null())
        return {false, "no result key in the earlier result (an older bvhlab's)"};
    return checkStoredKey(stored.at("result_key"), key);
}

StoredResult checkStoredKey(const json& stored, const json& key) {
    const std::vector<std::string> changes = resultKeyChanges(stored, key);
    if (changes.empty()) return {true, ""};
    return {false, changes.size() == 1 ? changes.front()
                                       : fmt::format("{} (and {} more)", changes.front(), changes.size() - 1)};
}

void ResumeCount::add(const StoredResult& stored) {
    if (stored.keep)
        ++kept_;
    else
        ++reasons_[stored.why];
}

size_t ResumeCount::toMeasure() const {
    size_t n = 0;
    for (const auto& [why, count] : reasons_) n += count;
    return n;
}

std::string ResumeCount::summary(const std::string& things, const std::string& verb) const {
    std::vector<std::string> reasons;
    for (const auto& [why, count] : reasons_)
        reasons.push_back(why == "new" ? fmt::format("{} new", count) : fmt::format("{} because {}", count, why));
    return fmt::format("{} {} kept from an earlier run (same result key); {} to {}{}{}", kept_, things, toMeasure(),
                       verb, reasons.empty() ? "" : ": ", fmt::join(reasons, "; "));
}

}  // namespace bvhlab
