// The env keys of the framework and of bvhlab's own accelerators, without the program's own
// (apps/): what the checks make their reference structures against (naive, sahbvh), and the
// tests of framework/ and accel/ their Envs.
#pragma once

#include "framework/config/env.h"

namespace bvhlab::verify {

const EnvRegistry& verifyKeys();

}  // namespace bvhlab::verify
