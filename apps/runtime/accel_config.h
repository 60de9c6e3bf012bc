// An accelerator as a command runs it: a name from the registry plus env overrides, written
// NAME or NAME:Key=value:Key=value (e.g. embree:Embree::robust=true). Used by every subcommand
// that takes --accel.
#pragma once

#include "framework/config/env.h"

#include <string>
#include <vector>

namespace bvhlab {

struct EnvOptions;

struct AccelConfig {
    std::string label;  // the text as given, except embree:Embree::robust=true -> "embree-robust"
    std::string name;
    std::vector<std::string> overrides;
};

AccelConfig parseAccelConfig(const std::string& text);

// Every accelerator of bvhlab's own but the brute force and Embree, comma-separated: the default of
// the subcommands that measure all of our structures (stress, tradeoff).
std::string ourAccelerators();

// A comma-separated list of configs.
std::vector<AccelConfig> parseAccelConfigList(const std::string& list);

// Names the configs' accelerators to `env` (EnvOptions::accelerators), so that a plugin's
// structure is found by name before the env layers, which may set its keys, are read. Every
// command that takes --accel calls it before loading its env, then checkAccelConfigs.
void nameAccelerators(const std::vector<AccelConfig>& configs, EnvOptions& env);

// The env `config` runs with: `base` and its overrides. An override that is not a key or not a
// value of it is an InputError naming it as typed: "--accel sahbvh:BVH::binz=8: unknown key".
Env accelConfigEnv(const AccelConfig& config, const Env& base, const std::string& option = "--accel");

// Checks every config before any work (a subcommand calls it first): a registered accelerator
// (its plugin loaded by name if need be), overrides that accelConfigEnv takes. Throws InputError
// naming the option and the config. Warns on stderr of the keys that change nothing
// (unreadKeyWarnings).
void checkAccelConfigs(const std::vector<AccelConfig>& configs, const Env& base, const std::string& option = "--accel");

// The accelerators that read `key` (AcceleratorInfo::envKeys); none for a key of the framework's
// or a command's.
std::vector<std::string> acceleratorsReading(const std::string& key);

// A key that only structures read, set where it reaches none that reads it: a -D key in `base`
// that none of the configs' accelerators reads ("BVH::maxLeaf is read by none of the chosen
// structures (scan); it is ignored"), and a config's own key that its accelerator does not read.
std::vector<std::string> unreadKeyWarnings(const std::vector<AccelConfig>& configs, const Env& base,
                                           const std::string& option = "--accel");

}  // namespace bvhlab
