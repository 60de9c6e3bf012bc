// Configuration in nanoGolem's global.env style: lines `Section::key value`, `#` comments.
// Every key is registered with a type, a default and a one-line description; values are
// validated when set, so a typo fails at load time with the file, the line and the key.
#pragma once

#include "framework/core/math.h"

#include <nlohmann/json_fwd.hpp>

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace bvhlab {

enum class EnvType {
    Bool,      // true/false, on/off, yes/no, 1/0
    Int,       // with an inclusive range
    Float,     // with an inclusive range
    String,    // free text
    Choice,    // one of a fixed list of words
    Path,      // relative paths resolve against the folder of the env file that set them
    Vec3,      // "x y z", or empty for "not given"
    Vec3List,  // "x y z, x y z, ...", possibly empty
};

struct EnvKey {
    std::string name;  // Section::key
    EnvType type = EnvType::String;
    std::string defaultValue;
    std::string description;
    double min = 0.0, max = 0.0;       // Int and Float
    std::vector<std::string> choices;  // Choice
};

// The set of known keys. The framework and every accelerator register theirs at start-up.
class EnvRegistry {
public:
    void add(EnvKey key);
    const EnvKey* find(const std::string& name) const;
    const std::map<std::string, EnvKey>& keys() const { return keys_; }
    // The known keys closest in edit distance to a misspelt one.
    std::vector<std::string> nearest(const std::string& name, size_t count = 3) const;

private:
    std::map<std::string, EnvKey> keys_;
};

// The full registry: framework keys plus every accelerator's (defined in accel/registry.cpp).
const EnvRegistry& envRegistry();

// Resolved configuration: defaults, then env files in order, then -D overrides.
class Env {
public:
    explicit Env(const EnvRegistry& registry = envRegistry());

    // Throws InputError naming the file, the line and the key.
    void loadFile(const std::filesystem::path& file);
    // `origin` names where the value came from in errors and provenance (e.g. "-D").
    // Relative paths resolve against `baseDir`.
    void set(const std::string& key, const std::string& value, const std::string& origin,
             const std::filesystem::path& baseDir = std::filesystem::current_path());
    // "Section::key=value", as given on the command line after -D.
    void setOverride(const std::string& assignment);

    bool getBool(const std::string& key) const;
    int getInt(const std::string& key) const;
    float getFloat(const std::string& key) const;
    std::string getString(const std::string& key) const;  // String and Choice
    std::filesystem::path getPath(const std::string& key) const;  // empty when not given
    std::optional<Vec3> getVec3(const std::string& key) const;
    std::vector<Vec3> getVec3List(const std::string& key) const;
    bool isExplicit(const std::string& key) const;  // set by a file or -D, not a default

    const EnvRegistry& registry() const { return *registry_; }
    // Every key with its resolved value and where it came from.
    nlohmann::json toJson() const;

private:
    struct Value {
        std::string text;    // validated; paths already resolved
        std::string origin;  // "default", "file:line" or "-D"
    };
    const Value& value(const std::string& key, EnvType expected) const;

    const EnvRegistry* registry_;
    std::map<std::string, Value> values_;
};

}  // namespace bvhlab
