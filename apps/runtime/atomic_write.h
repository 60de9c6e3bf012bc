// Result files written whole or not at all.
#pragma once

#include <filesystem>
#include <string>

namespace bvhlab {

// Writes `text` to `file` by way of a temporary file beside it, so a reader (or a run resumed
// after an interruption) never sees half a file.
void writeFileAtomically(const std::filesystem::path& file, const std::string& text);

}  // namespace bvhlab
