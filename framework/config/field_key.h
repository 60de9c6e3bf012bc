// A key declared by the Config field it fills, beside that field: the field's type is the key's
// (bool, an integer, float, or an enum read as one of its words), the field's initialiser its
// default; the declaration adds the name, the range or words and the meaning. A tunable is thus
// one field and one declaration; KeyBindings (key_bindings.h) registers, lists and reads it.
#pragma once

#include "framework/config/env_key.h"

#include <charconv>
#include <concepts>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>

namespace bvhlab {

template <typename Field>
constexpr KeyType keyTypeOf() {
    if constexpr (std::is_same_v<Field, bool>)
        return KeyType::Bool;
    else if constexpr (std::is_enum_v<Field>)
        return KeyType::Choice;
    else if constexpr (std::is_integral_v<Field>)
        return KeyType::Int;
    else {
        static_assert(std::is_same_v<Field, float>, "a field key is bool, an integer, float or an enum");
        return KeyType::Float;
    }
}

// The shortest text that reads back as `value`, exponents without leading zeros: 1e-5, 0.3, 1.
inline std::string shortestText(float value) {
    char buffer[32];
    std::string text(buffer, std::to_chars(buffer, buffer + sizeof buffer, value).ptr);
    if (const size_t e = text.find('e'); e != std::string::npos) {
        const size_t digits = e + (text[e + 1] == '-' || text[e + 1] == '+' ? 2 : 1);
        while (digits + 1 < text.size() && text[digits] == '0') text.erase(digits, 1);
    }
    return text;
}

template <typename Member>
struct MemberPointer;
template <typename C, typename F>
struct MemberPointer<F C::*> {
    using Config = C;
    using Field = F;
};

// `Field` is a pointer to the member, &BinnedSahConfig::bins; an enum's words are in the order of
// its values. The key is also the typed handle it is read through (env.get(keys::BVH::bins)).
template <auto Field>
class FieldKey : public Key<keyTypeOf<typename MemberPointer<decltype(Field)>::Field>()> {
public:
    using Config = typename MemberPointer<decltype(Field)>::Config;
    using FieldType = typename MemberPointer<decltype(Field)>::Field;
    static constexpr KeyType kType = keyTypeOf<FieldType>();
    using Handle = Key<kType>;
    using Value = typename Handle::Value;

    // Int and Float: the inclusive range.
    constexpr FieldKey(std::string_view name, double min, double max,
                       std::string_view description) requires(kType == KeyType::Int || kType == KeyType::Float)
        : Handle(name, {}, min, max, description) {
        this->defaultText_ = &defaultText;
    }
    constexpr FieldKey(std::string_view name, std::span<const std::string_view> words,
                       std::string_view description) requires(kType == KeyType::Choice)
        : Handle(name, {}, words, description), words_(words) {
        this->defaultText_ = &defaultText;
    }
    constexpr FieldKey(std::string_view name, std::string_view description) requires(kType == KeyType::Bool)
        : Handle(name, {}, description) {
        this->defaultText_ = &defaultText;
    }

    // Sets the field of `config` to `value`, as Env::get reads it (a word the env has checked).
    void assign(Config& config, const Value& value) const {
        if constexpr (kType == KeyType::Choice) {
            for (size_t i = 0; i < words_.size(); ++i)
                if (value == words_[i]) config.*Field = FieldType(i);
        } else {
            config.*Field = FieldType(value);
        }
    }

private:
    static std::string defaultText(std::span<const std::string_view> words) {
        const FieldType value = Config{}.*Field;
        if constexpr (kType == KeyType::Bool)
            return value ? "true" : "false";
        else if constexpr (kType == KeyType::Choice)
            return std::string(words[size_t(value)]);
        else if constexpr (kType == KeyType::Int)
            return std::to_string(value);
        else
            return shortestText(value);
    }

    std::span<const std::string_view> words_;
};

}  // namespace bvhlab
