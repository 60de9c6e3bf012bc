// What makes the jobs in a batch folder one batch: their settings, recorded in DIR/batch.json.
// A job's figures depend on its scene, its accelerator and the resolved env; the tables of a
// folder must never mix jobs of two settings, so a run (or a merge) into a folder holding jobs of
// other settings is refused with what differs, and every job file carries the hash of its
// scene's settings, which the tables check.
#pragma once

#include "framework/config/env.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace bvhlab {

struct BatchSettings {
    struct Scene {
        std::string id;                          // the env file's stem
        std::map<std::string, std::string> env;  // the resolved values that change its figures
        std::string hash;                        // of `env` (and the id): the jobs' settings key
    };
    std::vector<Scene> scenes;        // the scene list, in table order
    std::vector<std::string> accels;  // --accel, in table order
    std::string hash;                 // of all of it

    const Scene* scene(const std::string& id) const;
    size_t jobCount() const { return scenes.size() * accels.size(); }
};

// The settings of a batch of `scenes` (id, resolved env as the jobs start from) x `accels`. Left
// out of the env, as they do not change a figure or are set per job: origins, Output::* (which
// images are written and how a heat map is scaled), Scene::cacheDir, ASDS::type (--accel),
// SetRayTracing::shadows (both renders are made), SetRayTracing::threads (Batch::threads is kept),
// and the keys that only structures read, none of `accels` (BVH::* in a batch of Embree and a plugin).
BatchSettings makeBatchSettings(const std::vector<std::pair<std::string, Env>>& scenes,
                                const std::vector<std::string>& accels);

// DIR/batch.json; nullopt if the folder has none. Throws InputError when it cannot be read.
std::optional<BatchSettings> readBatchSettings(const std::filesystem::path& dir);
void writeBatchSettings(const std::filesystem::path& dir, const BatchSettings& settings);

// What differs from `before` to `after`, a line each ("Camera::width: 800 -> 200 (a10, sibenik)",
// "--accel: naive,sahbvh -> tdbvh,sahbvh,embree"); empty when they are the same batch.
std::vector<std::string> batchDifferences(const BatchSettings& before, const BatchSettings& after);

// Throws InputError, naming both settings and the way out (`--fresh`, another `--out`), unless
// `dir` holds no job files or only jobs of `settings`.
void checkBatchFolder(const std::filesystem::path& dir, const BatchSettings& settings);

// Deletes what `bvhlab batch` wrote into `dir`: jobs/, images/, the tables, the contact sheet
// and batch.json (nothing else), if `dir` is a batch's folder (has batch.json or jobs/).
void clearBatchFolder(const std::filesystem::path& dir);

}  // namespace bvhlab
