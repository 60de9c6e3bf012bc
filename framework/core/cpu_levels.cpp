#include "framework/core/cpu_levels.h"

namespace bvhlab {

// Checked feature by feature: clang's check does not know the level names.
CpuLevels cpuLevels() {
    __builtin_cpu_init();
    CpuLevels levels;
    levels.v3 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi") &&
                __builtin_cpu_supports("bmi2");
    levels.v4 = levels.v3 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
                __builtin_cpu_supports("avx512cd") && __builtin_cpu_supports("avx512dq") &&
                __builtin_cpu_supports("avx512vl");
    return levels;
}

}  // namespace bvhlab
