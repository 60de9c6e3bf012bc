// The result key: everything that decides a measured result, in one place. A result stored by
// batch (a job file), tradeoff (a configuration's file) or bench (a scene's rows) carries the key
// it was measured with; a rerun keeps it only when the key it would be measured with now is the
// same, and says which part changed when it is not. The parts:
//   program     the bvhlab program's files as this process runs them (not just the commit: a
//               rebuild with uncommitted changes differs), and Embree's library;
//   structure   the accelerator, the values of the keys it reads (no other structure's), and its
//               plugin's file, size, CRC-32, ABI, compiler and flags;
//   scene       the scene file's content (size and checksums; an AFF file's includes too), and
//               every other value of the env that can change a figure: camera, lights, image
//               size, samples, threads, the frame of an animated scene, ...;
//   measurement what the command measures with (tradeoff's sizes and series, bench's rounds, ...).
#pragma once

#include "framework/config/env.h"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace bvhlab {

// {"commit", "files": {NAME: "SIZE-CRC32"}}: /proc/self/exe and the shared libraries of bvhlab
// and Embree it has mapped. Read once per process.
const nlohmann::json& programIdentity();

// The structure `accelerator` as `env` configures it: {"accel", "keys": {KEY: value}, "plugin":
// {"file", "size", "crc32", "abi", "compiler", "cxx_flags", "optimized"} or null}.
nlohmann::json structureKey(const std::string& accelerator, const Env& env);

// The scene `env` names: {"file": {"name", "size", "crc32", "adler32", and for an AFF file
// "includes": {PATH: "SIZE-CRC32"} of the files it includes} or "embedded", "settings":
// {KEY: value}} with every key but the accelerators' own, ASDS::*, Scene::dir and Scene::file (the
// content stands for them), those that change no figure (changesNoFigure) and, for a still scene,
// Scene::frame.
nlohmann::json sceneKey(const Env& env);

// A structure's part of a key as the tables show what ran: its own settings ("BVH::bins=16,
// BVH::maxLeaf=2", or "no settings of its own"), then for a plugin's "; plugin scan.so, CRC-32
// 1a2b3c4d", and ", unoptimised" when it was compiled without optimisation.
std::string describeStructure(const nlohmann::json& structure);

// {"program", "structure", "scene", "measurement"} of a result of `accelerator` run with `env`.
nlohmann::json resultKey(const std::string& accelerator, const Env& env, const nlohmann::json& measurement);

// What changed from `before` to `after`, a line per value ("structure BVH::maxLeaf: 2 -> 3",
// "plugin crc32: 1a2b3c4d -> 5e6f7a8b", "program bvhlab: 812-1a2b3c4d -> 812-77aa0011"); empty
// when they are the same key.
std::vector<std::string> resultKeyChanges(const nlohmann::json& before, const nlohmann::json& after);

// Whether a result stored in `file` (a JSON object with its key under "result_key") can be kept
// for `key`, and if not, why: "new" (no such file), "unreadable", or the first change of the key.
struct StoredResult {
    bool keep = false;
    std::string why;
};
StoredResult checkStoredResult(const std::filesystem::path& file, const nlohmann::json& key);
// The same for a stored key already read.
StoredResult checkStoredKey(const nlohmann::json& stored, const nlohmann::json& key);

// The results a run kept and those it measures, with why, for one line on stderr:
// "7 jobs kept from an earlier run (same result key); 2 to run: 1 new, 1 plugin crc32: ... -> ...".
class ResumeCount {
public:
    void add(const StoredResult& stored);
    size_t kept() const { return kept_; }
    size_t toMeasure() const;
    std::string summary(const std::string& things, const std::string& verb) const;

private:
    size_t kept_ = 0;
    std::map<std::string, size_t> reasons_;  // why -> how many
};

}  // namespace bvhlab
