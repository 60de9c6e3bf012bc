// Creates accelerators by name. `ASDS::type` in env chooses one; adding an accelerator
// means one entry in registry.cpp (see docs/adding-an-accelerator.md).
#pragma once

#include "framework/config/env.h"
#include "framework/core/accelerator.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace bvhlab {

namespace keys::ASDS {
// Its choices, the accelerators' names, are given when it is registered.
inline constexpr ChoiceKey type{"ASDS::type", "sahbvh", {}, "acceleration structure to build and trace with"};
}

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
    return createAccelerator(env.get(keys::ASDS::type), env);
}

// ASDS::type and every accelerator's keys.
void registerAcceleratorKeys(EnvRegistry& registry);

}  // namespace bvhlab
