#include "apps/runtime/atomic_write.h"

#include "framework/core/error.h"

#include <fmt/core.h>

#include <fstream>

#include <unistd.h>

namespace bvhlab {

void writeFileAtomically(const std::filesystem::path& file, const std::string& text) {
    const std::filesystem::path temporary = file.string() + fmt::format(".tmp-{}", ::getpid());
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        out << text;
        if (!out) throw InputError(fmt::format("{}: cannot write", temporary.string()));
    }
    std::filesystem::rename(temporary, file);
}

}  // namespace bvhlab
