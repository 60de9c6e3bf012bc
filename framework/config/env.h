// Configuration in nanoGolem's global.env style: lines `Section::key value`, `#` comments.
// Every key is registered with a type, a default and a one-line description; values are
// validated when set, so a typo fails at load time with the file, the line and the key.
#pragma once

#include "framework/config/env_key.h"

#include <nlohmann/json_fwd.hpp>

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace bvhlab {

// The set of known keys. Each component registers its own (the program's registry is put
// together in apps/runtime/program_keys.cpp) and every Env is made against one.
class EnvRegistry {
public:
    void add(EnvKey key);
    template <KeyType Type>
    void add(const Key<Type>& key) {
        add(key.declaration());
    }
    const EnvKey* find(const std::string& name) const;
    const std::map<std::string, EnvKey>& keys() const { return keys_; }
    // The known keys closest in edit distance to a misspelt one.
    std::vector<std::string> nearest(const std::string& name, size_t count = 3) const;

private:
    std::map<std::string, EnvKey> keys_;
};

// One `Section::key value` line of an env file, checked for its form only.
struct EnvLine {
    std::string name;
    std::string text;
    std::string origin;  // "file:line"
};
// The lines of an env file, in order, before any registry sees them (the plugins an env file
// names are loaded before its other keys are checked). Throws InputError naming file and line.
std::vector<EnvLine> readEnvLines(const std::filesystem::path& file);

// Resolved configuration: defaults, then env files in order, then -D overrides.
class Env {
public:
    // The registry must outlive the Env.
    explicit Env(const EnvRegistry& registry);

    // Throws InputError naming the file, the line and the key. A line with a key and no value
    // sets nothing: the key keeps what the earlier layers (or its default) gave it.
    void loadFile(const std::filesystem::path& file);
    // `origin` names where the value came from in errors and provenance (e.g. "-D").
    // Relative paths resolve against `baseDir`.
    void set(const std::string& key, const std::string& value, const std::string& origin,
             const std::filesystem::path& baseDir = std::filesystem::current_path());
    // "Section::key=value", as given on the command line after -D; errors and provenance name it
    // "-DSection::key", or `origin` where it came from elsewhere (bench --accel NAME:Key=value).
    void setOverride(const std::string& assignment, const std::string& origin = "");

    template <KeyType Type>
    void set(const Key<Type>& key, const std::string& value, const std::string& origin) {
        set(std::string(key.name()), value, origin);
    }

    bool get(const BoolKey& key) const;
    int get(const IntKey& key) const;
    float get(const FloatKey& key) const;
    std::string get(const TextKey& key) const;
    std::string get(const ChoiceKey& key) const;
    std::filesystem::path get(const PathKey& key) const;  // empty when not given
    std::optional<Vec3> get(const Vec3Key& key) const;
    std::vector<Vec3> get(const Vec3ListKey& key) const;
    // Set by a file or -D, not a default.
    template <KeyType Type>
    bool isExplicit(const Key<Type>& key) const {
        return isExplicit(std::string(key.name()));
    }
    bool isExplicit(const std::string& name) const;
    // Where a key's value came from: "default", "FILE:LINE", "-DSection::key", "--scene", ...
    std::string origin(std::string_view key) const;
    // For an error about the path a key gives: "Scene::dir is /p/scenes (its default; set it with
    // -DScene::dir=... or a line `Scene::dir ...` in an env file)", or "(from FILE:LINE; ...)".
    std::string howToSet(const PathKey& key) const;

    const EnvRegistry& registry() const { return *registry_; }
    // Every key with its resolved value and where it came from.
    nlohmann::json toJson() const;

private:
    struct Value {
        std::string text;    // validated; paths already resolved
        std::string origin;  // "default", "file:line" or "-D"
    };
    static Value defaultOf(const EnvKey& key);
    // The registry's key `name`; an unknown one is an InputError naming `origin` and near keys.
    const EnvKey& known(const std::string& name, const std::string& origin) const;
    Value value(std::string_view key, KeyType expected) const;

    const EnvRegistry* registry_;
    std::map<std::string, Value> values_;
};

}  // namespace bvhlab
