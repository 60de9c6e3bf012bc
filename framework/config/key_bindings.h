// The keys of one component bound to the settings they fill: each key is declared once (a Key
// constant, env_key.h, bound here to what its value sets; or a FieldKey, field_key.h, which
// knows its field, in a list of a Config's keys bound as a part of the settings). That one list
// registers the keys, names them (the keys an accelerator reads, docs/env-keys.md) and reads an
// Env into the settings, so no key is listed a second time for any of the three.
#pragma once

#include "framework/config/env.h"
#include "framework/config/field_key.h"

#include <functional>
#include <initializer_list>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

namespace bvhlab {

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
              read([&key, set](const Env& env, Settings& settings) { set(settings, env.get(key)); }) {}
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
        std::function<void(const Env&, Settings&)> read;
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

    void registerWith(EnvRegistry& registry) const {
        for (const Binding& b : bindings_) registry.add(b.declare());
    }
    // The keys' names, in the order they were bound, after those already in `names`.
    void appendNames(std::vector<std::string>& names) const {
        for (const Binding& b : bindings_) names.emplace_back(b.name);
    }
    void read(const Env& env, Settings& settings) const {
        for (const Binding& b : bindings_) b.read(env, settings);
    }

private:
    std::vector<Binding> bindings_;
};

}  // namespace bvhlab
