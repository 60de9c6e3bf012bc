// The registry of the bvhlab program: the framework's keys, every accelerator's and the
// program's own (app_keys.h). Every Env the program and its tests make is made against it.
#pragma once

#include "framework/config/env.h"

#include <string>
#include <vector>

namespace bvhlab {

const EnvRegistry& programKeys();

// Adds a plugin's keys (after its accelerators are registered, whose names become choices of
// ASDS::type). Throws InputError, adding none, if one is declared already. Envs made before
// read the new keys' defaults.
void registerPluginKeys(const std::string& plugin, const std::vector<EnvKey>& keys);

// docs/env-keys.md: every key (type, default, the value env/global.env gives it, meaning) and
// every accelerator with the keys it reads, those of the plugins loaded included (a plugin bvhlab
// ships named by its file name, another by its path). `globalEnv` is an Env with env/global.env loaded.
// `bvhlab keys` prints it; a test keeps the committed file equal to it.
std::string envKeysMarkdown(const Env& globalEnv);

// A key's type as the reference lists it: "int 1..256", "float 0.001..1000" (a float range as
// declared, not as its double widening), "a | b | c".
std::string envKeyType(const EnvKey& key);

}  // namespace bvhlab
