#include "framework/core/available_memory.h"

#include <fmt/core.h>

#include <cstdint>
#include <fstream>
#include <sstream>

#include <sys/resource.h>

namespace bvhlab {
namespace {

// The value after `key` in a "Key:   123 kB" file such as /proc/meminfo, in bytes.
bool readKilobytes(const char* file, const std::string& key, size_t& bytes) {
    std::ifstream in(file);
    std::string line;
    while (std::getline(in, line))
        if (line.rfind(key, 0) == 0) {
            std::istringstream value(line.substr(key.size()));
            size_t kilobytes = 0;
            if (!(value >> kilobytes)) return false;
            bytes = kilobytes * 1024;
            return true;
        }
    return false;
}

bool readNumber(const char* file, size_t& value) {
    std::ifstream in(file);
    return bool(in >> value);  // "max" (no limit) fails to parse
}

}  // namespace

AvailableMemory availableMemory() {
    AvailableMemory result{SIZE_MAX, "unknown"};
    auto consider = [&](size_t bytes, const char* limit) {
        if (bytes < result.bytes) result = {bytes, limit};
    };
    if (size_t bytes = 0; readKilobytes("/proc/meminfo", "MemAvailable:", bytes)) consider(bytes, "MemAvailable");
    if (size_t max = 0, current = 0;
        readNumber("/sys/fs/cgroup/memory.max", max) && readNumber("/sys/fs/cgroup/memory.current", current))
        consider(max > current ? max - current : 0, "cgroup memory.max");
    rlimit limit{};
    if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
        size_t used = 0;
        readKilobytes("/proc/self/status", "VmSize:", used);
        consider(limit.rlim_cur > used ? size_t(limit.rlim_cur) - used : 0, "ulimit -v");
    }
    return result;
}

std::string formatBytes(size_t bytes) {
    const double b = double(bytes);
    if (b >= 1024.0 * 1024.0 * 1024.0) return fmt::format("{:.1f} GiB", b / (1024.0 * 1024.0 * 1024.0));
    if (b >= 1024.0 * 1024.0) return fmt::format("{:.1f} MiB", b / (1024.0 * 1024.0));
    return fmt::format("{:.0f} KiB", b / 1024.0);
}

}  // namespace bvhlab
