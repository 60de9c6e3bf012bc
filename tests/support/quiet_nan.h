// The NaN the tests put into rays and primitives.
#pragma once

#include <limits>

namespace bvhlab::test {

inline constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

}  // namespace bvhlab::test
