// A key declared once, next to the code that reads it: its name, type, default, range or
// choices and meaning, in a constant that is also the typed handle it is read through
// (`env.get(kShadows)` is a bool). Components register their keys with an EnvRegistry.
#pragma once

#include <bvhlab/math.h>

#include <bvhlab/settings.h>

#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace bvhlab {

// A registered key, as the registry and the docs see it (KeyType: <bvhlab/settings.h>).
struct EnvKey {
    std::string name;  // Section::key
    KeyType type = KeyType::String;
    std::string defaultValue;
    std::string description;
    double min = 0.0, max = 0.0;       // Int and Float
    std::vector<std::string> choices;  // Choice
};

// The value a key of each type reads as.
template <KeyType Type>
struct EnvValue;
template <>
struct EnvValue<KeyType::Bool> {
    using type = bool;
};
template <>
struct EnvValue<KeyType::Int> {
    using type = int;
};
template <>
struct EnvValue<KeyType::Float> {
    using type = float;
};
template <>
struct EnvValue<KeyType::String> {
    using type = std::string;
};
template <>
struct EnvValue<KeyType::Choice> {
    using type = std::string;
};
template <>
struct EnvValue<KeyType::Path> {
    using type = std::filesystem::path;
};  // empty when not given
template <>
struct EnvValue<KeyType::Vec3> {
    using type = std::optional<Vec3>;
};  // nullopt when not given
template <>
struct EnvValue<KeyType::Vec3List> {
    using type = std::vector<Vec3>;
};

// The declaration and typed handle. Constant-initialised (string views only), so a key can be
// read from any static initialiser without an initialisation-order question.
template <KeyType Type>
class Key {
public:
    using Value = typename EnvValue<Type>::type;

    // Int and Float: the inclusive range.
    constexpr Key(std::string_view name, std::string_view defaultValue, double min, double max,
                  std::string_view description) requires(Type == KeyType::Int || Type == KeyType::Float)
        : name_(name), default_(defaultValue), description_(description), min_(min), max_(max) {}
    constexpr Key(std::string_view name, std::string_view defaultValue, std::span<const std::string_view> choices,
                  std::string_view description) requires(Type == KeyType::Choice)
        : name_(name), default_(defaultValue), description_(description), choices_(choices) {}
    constexpr Key(std::string_view name, std::string_view defaultValue,
                  std::string_view description) requires(Type != KeyType::Int && Type != KeyType::Float &&
                                                         Type != KeyType::Choice)
        : name_(name), default_(defaultValue), description_(description) {}

    constexpr std::string_view name() const { return name_; }

    // What the registry holds; a Choice key whose words are known only at run time (ASDS::type:
    // the accelerators) is given them here.
    EnvKey declaration(std::vector<std::string> runtimeChoices = {}) const {
        EnvKey key{std::string(name_),
                   Type,
                   defaultText_ ? defaultText_(choices_) : std::string(default_),
                   std::string(description_),
                   min_,
                   max_,
                   {}};
        for (std::string_view c : choices_) key.choices.emplace_back(c);
        for (std::string& c : runtimeChoices) key.choices.push_back(std::move(c));
        return key;
    }

protected:
    // A key declared by the field it fills (field_key.h) has no default text: the field's
    // initialiser, written out by this function (given the words of an enum) when declared.
    std::string (*defaultText_)(std::span<const std::string_view> choices) = nullptr;

private:
    std::string_view name_, default_, description_;
    double min_ = 0.0, max_ = 0.0;
    std::span<const std::string_view> choices_;
};

using BoolKey = Key<KeyType::Bool>;
using IntKey = Key<KeyType::Int>;
using FloatKey = Key<KeyType::Float>;
using TextKey = Key<KeyType::String>;
using ChoiceKey = Key<KeyType::Choice>;
using PathKey = Key<KeyType::Path>;
using Vec3Key = Key<KeyType::Vec3>;
using Vec3ListKey = Key<KeyType::Vec3List>;

}  // namespace bvhlab
