#include "framework/config/env.h"

#include "framework/config/install_paths.h"
#include "framework/core/error.h"
#include "framework/core/parse_number.h"

#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <sstream>

namespace bvhlab {
namespace {

std::string trim(std::string_view s) {
    const size_t b = s.find_first_not_of(" \t\r");
    if (b == std::string_view::npos) return {};
    const size_t e = s.find_last_not_of(" \t\r");
    return std::string(s.substr(b, e - b + 1));
}

size_t editDistance(const std::string& a, const std::string& b) {
    std::vector<size_t> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        size_t diagonal = row[0];
        row[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t substitute = diagonal + (std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                                                          std::tolower(static_cast<unsigned char>(b[j - 1]))
                                                      ? 0
                                                      : 1);
            diagonal = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, substitute});
        }
    }
    return row[b.size()];
}

std::optional<bool> parseBool(const std::string& s) {
    if (s == "true" || s == "on" || s == "yes" || s == "1") return true;
    if (s == "false" || s == "off" || s == "no" || s == "0") return false;
    return std::nullopt;
}

template <typename T>
std::optional<T> numberIn(std::string_view s) {
    T v{};
    if (!parseNumber(s, v)) return std::nullopt;
    return v;
}

std::optional<Vec3> parseVec3(const std::string& s) {
    std::istringstream in(s);
    std::string a, b, c, extra;
    if (!(in >> a >> b >> c) || (in >> extra)) return std::nullopt;
    const auto x = numberIn<float>(a), y = numberIn<float>(b), z = numberIn<float>(c);
    if (!x || !y || !z || !std::isfinite(*x) || !std::isfinite(*y) || !std::isfinite(*z)) return std::nullopt;
    return Vec3(*x, *y, *z);
}

std::vector<std::string> splitList(const std::string& s) {
    std::vector<std::string> items;
    std::string item;
    std::istringstream in(s);
    while (std::getline(in, item, ',')) items.push_back(trim(item));
    return items;
}

const char* typeName(KeyType type) {
    switch (type) {
        case KeyType::Bool:
            return "a boolean (true/false)";
        case KeyType::Int:
            return "an integer";
        case KeyType::Float:
            return "a number";
        case KeyType::String:
            return "text";
        case KeyType::Choice:
            return "one of the listed words";
        case KeyType::Path:
            return "a path";
        case KeyType::Vec3:
            return "three numbers 'x y z'";
        case KeyType::Vec3List:
            return "a list 'x y z, x y z, ...'";
    }
    return "?";
}

// Checks `text` against the key's type; returns the canonical text or an error message.
std::string validate(const EnvKey& key, const std::string& text, const std::filesystem::path& baseDir,
                     std::string& error) {
    auto fail = [&](const std::string& why) {
        error = fmt::format("{}: bad value '{}': {}", key.name, text, why);
        return std::string();
    };
    switch (key.type) {
        case KeyType::Bool: {
            const auto b = parseBool(text);
            if (!b) return fail("expected true or false");
            return *b ? "true" : "false";
        }
        case KeyType::Int: {
            const auto v = numberIn<long long>(text);
            if (!v) return fail("expected an integer");
            if (*v < key.min || *v > key.max) return fail(fmt::format("expected {} to {}", key.min, key.max));
            return text;
        }
        case KeyType::Float: {
            const auto v = numberIn<double>(text);
            if (!v || !std::isfinite(*v)) return fail("expected a finite number");
            if (*v < key.min || *v > key.max) return fail(fmt::format("expected {} to {}", key.min, key.max));
            return text;
        }
        case KeyType::String:
            return text;
        case KeyType::Choice:
            if (std::find(key.choices.begin(), key.choices.end(), text) == key.choices.end())
                return fail(fmt::format("expected one of: {}", fmt::join(key.choices, ", ")));
            return text;
        case KeyType::Path:
            if (text.empty()) return text;
            return (baseDir / text).lexically_normal().string();
        case KeyType::Vec3:
            if (text.empty()) return text;
            if (!parseVec3(text)) return fail("expected three finite numbers 'x y z'");
            return text;
        case KeyType::Vec3List:
            if (text.empty()) return text;
            for (const std::string& item : splitList(text))
                if (!parseVec3(item)) return fail(fmt::format("'{}' is not three finite numbers 'x y z'", item));
            return text;
    }
    return text;
}

}  // namespace

void EnvRegistry::add(EnvKey key) {
    const std::string name = key.name;
    keys_[name] = std::move(key);
}

const EnvKey* EnvRegistry::find(const std::string& name) const {
    const auto it = keys_.find(name);
    return it == keys_.end() ? nullptr : &it->second;
}

std::vector<std::string> EnvRegistry::nearest(const std::string& name, size_t count) const {
    std::vector<std::pair<size_t, std::string>> scored;
    for (const auto& [known, key] : keys_) scored.emplace_back(editDistance(name, known), known);
    std::sort(scored.begin(), scored.end());
    std::vector<std::string> result;
    // Only suggest keys that are plausibly what was meant.
    const size_t limit = std::max<size_t>(3, name.size() / 3);
    for (size_t i = 0; i < scored.size() && result.size() < count; ++i)
        if (scored[i].first <= limit) result.push_back(scored[i].second);
    return result;
}

// Relative default paths resolve against bvhlab's data folder (the repository root in a build
// tree), so they work from any folder; "$XDG_CACHE_HOME/..." against the user's cache folder.
Env::Value Env::defaultOf(const EnvKey& key) {
    std::string text = key.defaultValue;
    constexpr std::string_view cache = "$XDG_CACHE_HOME/";
    if (key.type == KeyType::Path && text.starts_with(cache))
        text = (userCacheRoot() / text.substr(cache.size())).lexically_normal().string();
    else if (key.type == KeyType::Path && !text.empty())
        text = (dataFolder() / text).lexically_normal().string();
    return {text, "default"};
}

Env::Env(const EnvRegistry& registry) : registry_(&registry) {
    for (const auto& [name, key] : registry.keys()) values_[name] = defaultOf(key);
}

const EnvKey& Env::known(const std::string& name, const std::string& origin) const {
    const EnvKey* key = registry_->find(name);
    if (!key) {
        const auto near = registry_->nearest(name);
        throw InputError(fmt::format("{}: unknown key '{}'{}", origin, name,
                                     near.empty() ? "" : fmt::format(" (did you mean {}?)", fmt::join(near, ", "))));
    }
    return *key;
}

void Env::set(const std::string& name, const std::string& text, const std::string& origin,
              const std::filesystem::path& baseDir) {
    const EnvKey& key = known(name, origin);
    std::string error;
    std::string canonical = validate(key, text, baseDir, error);
    if (!error.empty()) throw InputError(fmt::format("{}: {}", origin, error));
    values_[name] = {std::move(canonical), origin};
}

void Env::setOverride(const std::string& assignment, const std::string& origin) {
    const size_t eq = assignment.find('=');
    if (eq == std::string::npos)
        throw InputError(fmt::format("{}: expected Section::key=value", origin.empty() ? "-D" + assignment : origin));
    const std::string key = trim(assignment.substr(0, eq));
    set(key, trim(assignment.substr(eq + 1)), origin.empty() ? "-D" + key : origin);
}

std::vector<EnvLine> readEnvLines(const std::filesystem::path& file) {
    std::ifstream in(file);
    if (!in) throw inputError(file, 0, "cannot open env file");
    std::vector<EnvLine> lines;
    std::string line;
    for (size_t lineNo = 1; std::getline(in, line); ++lineNo) {
        const size_t hash = line.find('#');
        const std::string content = trim(std::string_view(line).substr(0, hash));
        if (content.empty()) continue;
        const size_t split = content.find_first_of(" \t");
        const std::string name = content.substr(0, split);
        const std::string text = split == std::string::npos ? "" : trim(content.substr(split));
        if (name.find("::") == std::string::npos || name.size() < 4)
            throw inputError(file, lineNo, fmt::format("expected 'Section::key value', got '{}'", content));
        // Key=value is the form of -D, not of env files: say so rather than "unknown key".
        if (const size_t eq = content.find('=');
            eq != std::string::npos && (name.find('=') != std::string::npos || text.starts_with('='))) {
            const std::string key = trim(content.substr(0, eq)), value = trim(content.substr(eq + 1));
            throw inputError(file, lineNo,
                             fmt::format("'{}': env lines are 'Section::key value', with a space; write '{} {}' "
                                         "('=' is for -D{}={})",
                                         content, key, value, key, value));
        }
        lines.push_back({name, text, fmt::format("{}:{}", file.string(), lineNo)});
    }
    return lines;
}

void Env::loadFile(const std::filesystem::path& file) {
    const std::filesystem::path baseDir = std::filesystem::absolute(file).parent_path();
    for (const EnvLine& line : readEnvLines(file)) {
        // A key without a value names the key and leaves it as the earlier layers set it.
        if (line.text.empty())
            known(line.name, line.origin);
        else
            set(line.name, line.text, line.origin, baseDir);
    }
}

Env::Value Env::value(std::string_view keyName, KeyType expected) const {
    const std::string name(keyName);
    const EnvKey* key = registry_->find(name);
    // Reading a key the registry does not hold, or with another type, is a programming error.
    if (!key || key->type != expected)
        throw std::logic_error(fmt::format("env key '{}' is not registered as {}", name, typeName(expected)));
    // A key registered after this Env was made (a plugin's, loaded later) reads its default.
    const auto it = values_.find(name);
    return it != values_.end() ? it->second : defaultOf(*key);
}

bool Env::get(const BoolKey& key) const { return value(key.name(), KeyType::Bool).text == "true"; }
int Env::get(const IntKey& key) const { return *numberIn<int>(value(key.name(), KeyType::Int).text); }
// Validated as a double in the key's range; a value too small for a float (1e-50) becomes 0 or a
// subnormal here instead of failing to parse as one.
float Env::get(const FloatKey& key) const { return float(*numberIn<double>(value(key.name(), KeyType::Float).text)); }
std::string Env::get(const TextKey& key) const { return value(key.name(), KeyType::String).text; }
std::string Env::get(const ChoiceKey& key) const { return value(key.name(), KeyType::Choice).text; }
std::filesystem::path Env::get(const PathKey& key) const { return value(key.name(), KeyType::Path).text; }
std::optional<Vec3> Env::get(const Vec3Key& key) const { return parseVec3(value(key.name(), KeyType::Vec3).text); }

std::vector<Vec3> Env::get(const Vec3ListKey& key) const {
    const std::string text = value(key.name(), KeyType::Vec3List).text;
    std::vector<Vec3> list;
    if (text.empty()) return list;
    for (const std::string& item : splitList(text)) list.push_back(*parseVec3(item));
    return list;
}

bool Env::isExplicit(const std::string& key) const {
    const auto it = values_.find(key);
    return it != values_.end() && it->second.origin != "default";
}

std::string Env::origin(std::string_view key) const {
    const auto it = values_.find(std::string(key));
    return it != values_.end() ? it->second.origin : "default";
}

std::string Env::howToSet(const PathKey& key) const {
    const std::string text = get(key).string(), from = origin(key.name());
    return fmt::format("{} is {} ({}; set it with -D{}=... or a line '{} ...' in an env file)", key.name(),
                       text.empty() ? "empty" : text, from == "default" ? "its default" : "from " + from, key.name(),
                       key.name());
}

nlohmann::json Env::toJson() const {
    nlohmann::json j = nlohmann::json::object();
    for (const auto& [name, key] : registry_->keys()) {
        const auto it = values_.find(name);
        const Value v = it != values_.end() ? it->second : defaultOf(key);
        j[name] = {{"value", v.text}, {"from", v.origin}};
    }
    return j;
}

}  // namespace bvhlab
