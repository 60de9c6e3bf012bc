// The registry of the bvhlab program: the framework's keys, every accelerator's and the
// program's own (app_keys.h). Every Env the program and its tests make is made against it.
#pragma once

#include "framework/config/env.h"

#include <string>

namespace bvhlab {

const EnvRegistry& programKeys();

// docs/env-keys.md: every key (type, default, meaning) and every accelerator with the keys it
// reads. `bvhlab keys` prints it; a test keeps the committed file equal to it.
std::string envKeysMarkdown();

}  // namespace bvhlab
