// The keys of one component bound to the settings they fill: each key is declared once (a Key
// constant, env_key.h, bound here to what its value sets; or a FieldKey, field_key.h, which
// knows its field, in a list of a Config's keys bound as a part of the settings). That one list
// declares the keys to the registrar (as a plugin's are: <bvhlab/registrar.h>) and reads their
// values, through the PluginSettings every structure is given, into the settings.
#pragma once

#include "framework/config/env_key.h"
#include "framework/config/field_key.h"

#include <bvhlab/settings.h>

#include <functional>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

namespace bvhlab {

// The value of the key `name`, of type Type, read with the getter of its type.
template <KeyType Type>
typename Key<Type>::Value readKey(const PluginSettings& keys, const char* name) {
    if constexpr (Type == KeyType::Bool)
        return keys.getBool(name);
    else if constexpr (Type == KeyType::Int)
        return keys.getInt(name);
    else if constexpr (Type == KeyType::Float)
        return keys.getFloat(name);
    else if constexpr (Type == KeyType::Vec3) {
        Vec3 value;
        return keys.getVec3(name, value) ? std::optional<Vec3>(value) : std::nullopt;
    } else if constexpr (Type == KeyType::Vec3List) {
        const View<const Vec3> list = keys.getVec3List(name);
        return std::vector<Vec3>(list.begin(), list.end());
    } else
        return typename Key<Type>::Value(keys.getText(name));
}

template <typename Settings>
class KeyBindings {
public:
    // A key and what its value sets: set(settings, value), the value as Env::get reads it. `key`
    // is one of the Key constants, which outlive every binding.
    struct Binding {
        template <KeyType Type, typename Set>
        requires std::invocable<Set, Settings&, typename Key<Type>::Value> Binding(const Key<Type>& key, Set set)
            : name(key.name()),
              declare([&key] { return key.declaration(); }),
              read([name = std::string(key.name()), set](const PluginSettings& keys, Settings& settings) {
                  set(settings, readKey<Type>(keys, name.c_str()));
              }) {}
        // A FieldKey of the Config that `partOf(settings)` returns.
        template <auto Field, typename PartOf>
        requires std::is_invocable_r_v<typename FieldKey<Field>::Config&, PartOf, Settings&> Binding(
            const FieldKey<Field>& key, PartOf partOf)
            : Binding(static_cast<const typename FieldKey<Field>::Handle&>(key),
                      [&key, partOf](Settings& settings, const typename FieldKey<Field>::Value& value) {
                          key.assign(partOf(settings), value);
                      }) {}

        std::string_view name;
        std::function<EnvKey()> declare;
        std::function<void(const PluginSettings&, Settings&)> read;
    };

    KeyBindings(std::initializer_list<Binding> bindings) : bindings_(bindings) {}
    // A Config's keys, a tuple of pointers to its FieldKeys (the list beside the Config), bound
    // to the Config that `partOf(settings)` returns.
    template <auto... Fields, typename PartOf>
    KeyBindings(const std::tuple<const FieldKey<Fields>*...>& keys, PartOf partOf) {
        std::apply([&](const auto*... key) { (bindings_.emplace_back(*key, partOf), ...); }, keys);
    }
    // Several lists one after the other.
    static KeyBindings join(std::initializer_list<KeyBindings> parts) {
        KeyBindings joined{};
        for (const KeyBindings& part : parts)
            joined.bindings_.insert(joined.bindings_.end(), part.bindings_.begin(), part.bindings_.end());
        return joined;
    }

    // The keys' declarations, in the order they were bound, after those already in `keys`.
    void appendDeclarations(std::vector<EnvKey>& keys) const {
        for (const Binding& b : bindings_) keys.push_back(b.declare());
    }
    void read(const PluginSettings& keys, Settings& settings) const {
        for (const Binding& b : bindings_) b.read(keys, settings);
    }

private:
    std::vector<Binding> bindings_;
};

}  // namespace bvhlab
