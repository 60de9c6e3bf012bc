// The names of every accelerator in the registry, for the suites instantiated over all of them.
#pragma once

#include "accel/registry.h"

#include <string>
#include <vector>

namespace bvhlab::test {

inline std::vector<std::string> registeredAccelerators() {
    std::vector<std::string> names;
    for (const AcceleratorInfo& info : acceleratorInfos()) names.push_back(info.name);
    return names;
}

}  // namespace bvhlab::test
