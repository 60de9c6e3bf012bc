#include "apps/batch/batch_settings.h"

#include "accel/registry.h"
#include "apps/runtime/accel_config.h"
#include "apps/runtime/app_keys.h"
#include "apps/runtime/atomic_write.h"
#include "framework/core/error.h"
#include "framework/render/render_keys.h"

#include <fmt/core.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <fstream>
#include <set>
#include <tuple>

namespace bvhlab {
namespace {

using nlohmann::json;

constexpr const char* kFormat = "bvhlab-batch-settings-1";

// Keys that change no figure of a job, or that batch sets per job, or that only structures read
// and none of `accels` does (see makeBatchSettings).
bool outsideTheSettings(const std::string& key, const std::vector<std::string>& accels) {
    if (changesNoFigure(key) || key == keys::ASDS::type.name() || key == keys::SetRayTracing::shadows.name() ||
        key == keys::SetRayTracing::threads.name())
        return true;
    const std::vector<std::string> readers = acceleratorsReading(key);
    return !readers.empty() && std::none_of(accels.begin(), accels.end(), [&](const std::string& label) {
        return std::find(readers.begin(), readers.end(), parseAccelConfig(label).name) != readers.end();
    });
}

// 64-bit FNV-1a of `text`, as 16 hex digits: a name for settings, not a guard against forgery.
std::string hashText(const std::string& text) {
    uint64_t h = 14695981039346656037ull;
    for (const unsigned char c : text) h = (h ^ c) * 1099511628211ull;
    return fmt::format("{:016x}", h);
}

// Fills in the hashes from the ids, envs and accelerators.
void computeHashes(BatchSettings& s) {
    json all = {{"accels", s.accels}, {"scenes", json::array()}};
    for (BatchSettings::Scene& scene : s.scenes) {
        scene.hash = hashText(json{{"id", scene.id}, {"env", scene.env}}.dump());
        all["scenes"].push_back(scene.hash);
    }
    s.hash = hashText(all.dump());
}

std::string shown(const std::string& value) { return value.empty() ? "(empty)" : value; }

size_t jobFileCount(const std::filesystem::path& dir) {
    size_t n = 0;
    if (std::filesystem::is_directory(dir / "jobs"))
        for (const auto& entry : std::filesystem::directory_iterator(dir / "jobs"))
            n += entry.path().extension() == ".json";
    return n;
}

}  // namespace

const BatchSettings::Scene* BatchSettings::scene(const std::string& id) const {
    const auto it = std::find_if(scenes.begin(), scenes.end(), [&](const Scene& s) { return s.id == id; });
    return it == scenes.end() ? nullptr : &*it;
}

BatchSettings makeBatchSettings(const std::vector<std::pair<std::string, Env>>& scenes,
                                const std::vector<std::string>& accels) {
    BatchSettings s;
    s.accels = accels;
    for (const auto& [id, env] : scenes) {
        BatchSettings::Scene scene{id, {}, {}};
        const json values = env.toJson();  // kept alive for the loop
        for (const auto& [key, v] : values.items())
            if (!outsideTheSettings(key, accels)) scene.env[key] = v.at("value").get<std::string>();
        s.scenes.push_back(std::move(scene));
    }
    computeHashes(s);
    return s;
}

std::optional<BatchSettings> readBatchSettings(const std::filesystem::path& dir) {
    const std::filesystem::path file = dir / "batch.json";
    if (!std::filesystem::exists(file)) return std::nullopt;
    try {
        std::ifstream in(file);
        const json j = json::parse(in);
        if (j.value("format", std::string()) != kFormat)
            throw std::runtime_error(fmt::format("not a {} file", kFormat));
        BatchSettings s;
        s.accels = j.at("accels").get<std::vector<std::string>>();
        for (const json& scene : j.at("scenes"))
            s.scenes.push_back(
                {scene.at("id").get<std::string>(), scene.at("env").get<std::map<std::string, std::string>>(), {}});
        computeHashes(s);
        return s;
    } catch (const std::exception& e) {
        throw InputError(fmt::format("{}: cannot read the batch settings: {}", file.string(), e.what()));
    }
}

void writeBatchSettings(const std::filesystem::path& dir, const BatchSettings& settings) {
    json j = {{"format", kFormat}, {"hash", settings.hash}, {"accels", settings.accels}, {"scenes", json::array()}};
    for (const BatchSettings::Scene& scene : settings.scenes)
        j["scenes"].push_back({{"id", scene.id}, {"hash", scene.hash}, {"env", scene.env}});
    writeFileAtomically(dir / "batch.json", j.dump(2) + "\n");
}

std::vector<std::string> batchDifferences(const BatchSettings& before, const BatchSettings& after) {
    std::vector<std::string> lines;
    if (before.accels != after.accels)
        lines.push_back(fmt::format("--accel: {} -> {}", fmt::join(before.accels, ","), fmt::join(after.accels, ",")));
    auto ids = [](const BatchSettings& s) {
        std::vector<std::string> v;
        for (const BatchSettings::Scene& scene : s.scenes) v.push_back(scene.id);
        return v;
    };
    if (ids(before) != ids(after))
        lines.push_back(fmt::format("--scenes: {} -> {}", fmt::join(ids(before), ", "), fmt::join(ids(after), ", ")));

    // Env values of the scenes in both, one line per key and change with the scenes it applies to.
    std::map<std::tuple<std::string, std::string, std::string>, std::vector<std::string>> changes;
    for (const BatchSettings::Scene& b : before.scenes) {
        const BatchSettings::Scene* a = after.scene(b.id);
        if (!a) continue;
        std::set<std::string> keys;
        for (const auto& [key, v] : b.env) keys.insert(key);
        for (const auto& [key, v] : a->env) keys.insert(key);
        for (const std::string& key : keys) {
            const auto old = b.env.find(key), now = a->env.find(key);
            const std::string oldValue = old == b.env.end() ? "(unknown key)" : shown(old->second);
            const std::string newValue = now == a->env.end() ? "(unknown key)" : shown(now->second);
            if (oldValue != newValue) changes[{key, oldValue, newValue}].push_back(b.id);
        }
    }
    for (const auto& [change, scenes] : changes) {
        const auto& [key, oldValue, newValue] = change;
        lines.push_back(fmt::format("{}: {} -> {} ({})", key, oldValue, newValue, fmt::join(scenes, ", ")));
    }
    return lines;
}

void checkBatchFolder(const std::filesystem::path& dir, const BatchSettings& settings) {
    const size_t jobs = jobFileCount(dir);
    if (jobs == 0) return;
    const std::string way =
        "choose --fresh to delete that batch first (its jobs/, images/, results.*, "
        "contact_sheet.png, batch.json), or another --out folder";
    const std::optional<BatchSettings> folder = readBatchSettings(dir);
    if (!folder)
        throw InputError(
            fmt::format("{} holds {} job files but no batch.json (written by an older bvhlab): their "
                        "settings are unknown, and a folder holds one batch; {}",
                        dir.string(), jobs, way));
    if (folder->hash == settings.hash) return;
    std::vector<std::string> lines = batchDifferences(*folder, settings);
    constexpr size_t kMostLines = 12;
    if (lines.size() > kMostLines) {
        const size_t more = lines.size() - kMostLines;
        lines.resize(kMostLines);
        lines.push_back(fmt::format("... and {} more", more));
    }
    throw InputError(
        fmt::format("{} holds {} jobs of another batch (a folder holds one batch); its settings -> "
                    "this run's:\n  {}\n{}",
                    dir.string(), jobs, fmt::join(lines, "\n  "), way));
}

void clearBatchFolder(const std::filesystem::path& dir) {
    // Only a batch's folder: `--out docs --fresh` must not take docs/images with it.
    if (!std::filesystem::exists(dir / "batch.json") && !std::filesystem::is_directory(dir / "jobs")) return;
    for (const char* folder : {"jobs", "images"}) std::filesystem::remove_all(dir / folder);
    for (const char* file : {"results.md", "results.csv", "results.json", "contact_sheet.png", "batch.json"})
        std::filesystem::remove(dir / file);
}

}  // namespace bvhlab
