#include "framework/config/plugin_settings.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <stdexcept>

namespace bvhlab {
namespace {

const char* keyTypeName(KeyType type) {
    switch (type) {
        case KeyType::Bool:
            return "Bool";
        case KeyType::Int:
            return "Int";
        case KeyType::Float:
            return "Float";
        case KeyType::String:
            return "String";
        case KeyType::Choice:
            return "Choice";
        case KeyType::Path:
            return "Path";
        case KeyType::Vec3:
            return "Vec3";
        case KeyType::Vec3List:
            return "Vec3List";
    }
    return nullptr;
}

// The getter that reads a key of `type`.
const char* getterOf(KeyType type) {
    switch (type) {
        case KeyType::Bool:
            return "getBool";
        case KeyType::Int:
            return "getInt";
        case KeyType::Float:
            return "getFloat";
        case KeyType::Vec3:
            return "getVec3";
        case KeyType::Vec3List:
            return "getVec3List";
        default:
            return "getText";
    }
}

}  // namespace

EnvKey declarationOf(const PluginKey& key) {
    if (!key.name || std::string_view(key.name).find("::") == std::string_view::npos)
        throw std::invalid_argument(fmt::format("env key '{}' is not 'Section::key'", key.name ? key.name : ""));
    const auto refuse = [&](const std::string& why) {
        return std::invalid_argument(fmt::format("env key '{}': {}", key.name, why));
    };
    if (!keyTypeName(key.type)) throw refuse(fmt::format("unknown type {}", int(key.type)));
    if (!key.defaultValue) throw refuse("no default value (\"\" for none)");
    if (!key.description) throw refuse("no description");
    EnvKey declared{key.name, key.type, key.defaultValue, key.description, key.min, key.max, {}};
    if ((key.type == KeyType::Int || key.type == KeyType::Float) && !(key.min <= key.max))
        throw refuse(fmt::format("its range {} to {} is not in order", key.min, key.max));
    for (const char* choice : key.choices) {
        if (!choice) throw refuse("a choice is a null pointer");
        declared.choices.emplace_back(choice);
    }
    if (key.type == KeyType::Choice && declared.choices.empty()) throw refuse("a Choice key without choices");
    return declared;
}

PluginKeyList::PluginKeyList(std::vector<EnvKey> keys) : keys_(std::move(keys)) {
    for (const EnvKey& key : keys_) {
        std::vector<const char*>& words = choices_.emplace_back();
        for (const std::string& choice : key.choices) words.push_back(choice.c_str());
        pluginKeys_.push_back(
            {key.name.c_str(), key.type, key.defaultValue.c_str(), key.description.c_str(), key.min, key.max, words});
    }
}

std::string EnvPluginSettings::checked(const char* key, std::initializer_list<KeyType> types,
                                       const char* getter) const {
    const std::string name = key ? key : "";
    if (name != kThreadsKey && std::find(keys_.begin(), keys_.end(), name) == keys_.end())
        throw std::invalid_argument(fmt::format("{} read the key '{}', which it did not declare (its keys: {})", owner_,
                                                name,
                                                keys_.empty() ? "none" : fmt::format("{}", fmt::join(keys_, ", "))));
    const EnvKey* declared = env_.registry().find(name);
    if (!declared) throw std::logic_error(fmt::format("{}: key '{}' is not registered", owner_, name));
    if (std::find(types.begin(), types.end(), declared->type) == types.end())
        throw std::invalid_argument(fmt::format("{} read the {} key '{}' with {}: read it with {}", owner_,
                                                keyTypeName(declared->type), name, getter, getterOf(declared->type)));
    return name;
}

bool EnvPluginSettings::getBool(const char* key) const {
    return env_.get(BoolKey(checked(key, {KeyType::Bool}, "getBool"), "", ""));
}

int EnvPluginSettings::getInt(const char* key) const {
    return env_.get(IntKey(checked(key, {KeyType::Int}, "getInt"), "", 0, 0, ""));
}

float EnvPluginSettings::getFloat(const char* key) const {
    return env_.get(FloatKey(checked(key, {KeyType::Float}, "getFloat"), "", 0, 0, ""));
}

const char* EnvPluginSettings::getText(const char* key) const {
    const std::string name = checked(key, {KeyType::String, KeyType::Choice, KeyType::Path}, "getText");
    switch (env_.registry().find(name)->type) {
        case KeyType::Choice:
            texts_.push_back(env_.get(ChoiceKey(name, "", {}, "")));
            break;
        case KeyType::Path:
            texts_.push_back(env_.get(PathKey(name, "", "")).string());
            break;
        default:
            texts_.push_back(env_.get(TextKey(name, "", "")));
            break;
    }
    return texts_.back().c_str();
}

bool EnvPluginSettings::getVec3(const char* key, Vec3& value) const {
    const std::optional<Vec3> given = env_.get(Vec3Key(checked(key, {KeyType::Vec3}, "getVec3"), "", ""));
    if (given) value = *given;
    return given.has_value();
}

View<const Vec3> EnvPluginSettings::getVec3List(const char* key) const {
    lists_.push_back(env_.get(Vec3ListKey(checked(key, {KeyType::Vec3List}, "getVec3List"), "", "")));
    return lists_.back();
}

bool EnvPluginSettings::isExplicit(const char* key) const {
    return env_.isExplicit(checked(key,
                                   {KeyType::Bool, KeyType::Int, KeyType::Float, KeyType::String, KeyType::Choice,
                                    KeyType::Path, KeyType::Vec3, KeyType::Vec3List},
                                   "isExplicit"));
}

}  // namespace bvhlab
