// Creates accelerators by name. `ASDS::type` in env chooses one; adding an accelerator
// means one entry in registry.cpp (see docs/adding-an-accelerator.md).
#pragma once

#include "framework/core/accelerator.h"
#include "framework/config/env.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace bvhlab {

struct AcceleratorInfo {
    std::string name;
    std::string description;
    std::vector<std::string> envKeys;  // the keys it reads, besides the framework's
    std::function<std::unique_ptr<Accelerator>(const Env&)> create;
};

const std::vector<AcceleratorInfo>& acceleratorInfos();

// Throws InputError naming the unknown accelerator and the known ones.
std::unique_ptr<Accelerator> createAccelerator(const std::string& name, const Env& env);
inline std::unique_ptr<Accelerator> createAccelerator(const Env& env) {
    return createAccelerator(env.getString("ASDS::type"), env);
}

}  // namespace bvhlab

namespace bvhlab {

// docs/env-keys.md: every env key (type, default, meaning) and every accelerator with the
// keys it reads. `bvhlab keys` prints it; a test keeps the committed file equal to it.
std::string envKeysMarkdown();

}  // namespace bvhlab
