#include "framework/scene_loader.h"

#include "framework/error.h"

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <memory>
#include <string_view>

namespace bvhlab {
namespace {

struct SceneFormat {
    const char* extension;
    Scene (*read)(const std::filesystem::path&, const std::string&);
};

constexpr SceneFormat kSceneFormats[] = {{".obj", readObj}, {".ply", readPly}, {".off", readOff}, {".nff", readNff}};

std::string lowercaseExtension(const std::filesystem::path& file) {
    std::string ext = file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

}  // namespace

std::string readFileBytes(const std::filesystem::path& file) {
    // zlib's gz* API checks for the gzip magic itself and passes other files through unchanged.
    std::unique_ptr<gzFile_s, decltype(&gzclose)> gz(gzopen(file.c_str(), "rb"), gzclose);
    if (!gz) throw inputError(file, 0, fmt::format("cannot open: {}", std::strerror(errno)));
    gzbuffer(gz.get(), 1 << 20);

    constexpr unsigned kChunkBytes = 1 << 24;
    std::string bytes;
    for (;;) {
        const size_t used = bytes.size();
        bytes.resize(used + kChunkBytes);  // std::string grows its capacity geometrically
        const int n = gzread(gz.get(), bytes.data() + used, kChunkBytes);
        bytes.resize(used + std::max(n, 0));
        if (n <= 0) break;
    }
    // A truncated or corrupt gzip stream shows up here, after the data that could be read.
    int status = Z_OK;
    std::string_view message = gzerror(gz.get(), &status);
    if (status == Z_OK) return bytes;
    if (status == Z_ERRNO) message = std::strerror(errno);
    const std::string pathPrefix = file.string() + ": ";  // zlib names the file itself
    if (message.starts_with(pathPrefix)) message.remove_prefix(pathPrefix.size());
    throw inputError(file, 0, fmt::format("cannot read: {}", message));
}

Scene loadScene(const std::filesystem::path& file) {
    std::filesystem::path uncompressed = file;  // the name without .gz
    if (lowercaseExtension(file) == ".gz") uncompressed = file.stem();
    const std::string ext = lowercaseExtension(uncompressed);
    const auto format = std::find_if(std::begin(kSceneFormats), std::end(kSceneFormats),
                                     [&](const SceneFormat& f) { return ext == f.extension; });
    if (format == std::end(kSceneFormats)) {
        throw inputError(file, 0, "unknown scene format; supported: .obj .ply .off .nff, each optionally .gz");
    }

    Scene scene = format->read(file, readFileBytes(file));
    scene.name = uncompressed.stem().string();
    scene.source = file;
    scene.finalize();
    return scene;
}

}  // namespace bvhlab
