#include "apps/runtime/output_paths.h"

#include "framework/core/error.h"

#include <fmt/core.h>

#include <cctype>

namespace bvhlab {

std::filesystem::path prepareOutputFile(const std::string& path, const std::string& option) {
    const std::filesystem::path file = path;
    if (path.empty()) throw InputError(option + ": empty path (give a file, e.g. out/render)");
    if (!file.has_filename() || file.filename() == "." || file.filename() == ".." ||
        std::filesystem::is_directory(file))
        throw InputError(fmt::format("{} {}: names a folder; give a file in it, e.g. {}", option, path,
                                     (file / "render").lexically_normal().string()));
    if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
    return file;
}

std::filesystem::path prepareOutputFolder(const std::string& path, const std::string& option) {
    if (path.empty()) throw InputError(option + ": empty path (give a folder, e.g. out/batch)");
    const std::filesystem::path folder = path;
    if (std::filesystem::exists(folder) && !std::filesystem::is_directory(folder))
        throw InputError(fmt::format("{} {}: is a file, not a folder", option, path));
    std::filesystem::create_directories(folder);
    return folder;
}

std::string labelAsFileName(const std::string& label) {
    std::string name = label;
    for (char& c : name) {
        const bool safe = std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-' || c == '+';
        if (!safe) c = c == '=' ? '-' : '_';
    }
    return name;
}

}  // namespace bvhlab
