// How much memory this process can still allocate, so that a large allocation is refused up
// front with its size, not by std::bad_alloc after minutes of work.
#pragma once

#include <cstddef>
#include <string>

namespace bvhlab {

struct AvailableMemory {
    size_t bytes = 0;   // the least of the limits below that apply
    std::string limit;  // which: "MemAvailable", "cgroup memory.max", "ulimit -v"
};

// From /proc/meminfo (MemAvailable), the cgroup's memory.max less memory.current, and
// RLIMIT_AS less the process's VmSize. SIZE_MAX with limit "unknown" where none can be read.
AvailableMemory availableMemory();

// "1.5 GiB", "12.0 MiB"
std::string formatBytes(size_t bytes);

}  // namespace bvhlab
