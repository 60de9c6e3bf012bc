// Errors about user input (scene files, env files, command lines). Their message is one
// line that names where the problem is, e.g. "scene.obj:12: face index 9 out of range".
#pragma once

#include <fmt/format.h>

#include <filesystem>
#include <stdexcept>
#include <string>

namespace bvhlab {

class InputError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// file:line: message (line 0 means the file as a whole).
inline InputError inputError(const std::filesystem::path& file, size_t line, const std::string& message) {
    if (line == 0) return InputError(fmt::format("{}: {}", file.string(), message));
    return InputError(fmt::format("{}:{}: {}", file.string(), line, message));
}

}  // namespace bvhlab
