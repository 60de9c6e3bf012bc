#include "framework/scene/scene_loader.h"

#include "framework/core/error.h"

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
    bool text;  // binary data is refused before the reader sees it
};

constexpr SceneFormat kSceneFormats[] = {{".obj", readObj, true},
                                         {".ply", readPly, false},
                                         {".off", readOff, true},
                                         {".nff", readNff, true},
                                         {".aff", readAff, true}};

// The text readers skip (OBJ) or misread what they do not know, so binary data would load as
// an empty or garbled scene. Text holds no control characters but whitespace (and DOS's
// end-of-file ^Z); binary data shows them in its first bytes (random bytes: one in nine).
void requireText(const std::filesystem::path& file, std::string_view bytes, std::string_view extension) {
    if (bytes.starts_with("ply\n") || bytes.starts_with("ply\r\n")) {
        throw inputError(file, 0, fmt::format("a PLY file (it starts with 'ply'), not {}: name it .ply", extension));
    }
    constexpr size_t kBytesChecked = 1 << 16;
    const std::string_view start = bytes.substr(0, kBytesChecked);
    const auto binary = std::find_if(start.begin(), start.end(), [](unsigned char c) {
        return (c < 0x20 && !std::isspace(c) && c != 0x1a) || c == 0x7f;
    });
    if (binary != start.end()) {
        throw inputError(file, 0,
                         fmt::format("binary data, not a text {} file (byte 0x{:02x} at offset {})", extension,
                                     (unsigned char)*binary, binary - start.begin()));
    }
}

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

    // Chunks that double up to 16 MiB: a small file (AFF includes many) zeroes little.
    constexpr unsigned kMaxChunkBytes = 1 << 24;
    std::string bytes;
    for (unsigned chunk = 1 << 16;; chunk = std::min(2 * chunk, kMaxChunkBytes)) {
        const size_t used = bytes.size();
        bytes.resize(used + chunk);  // std::string grows its capacity geometrically
        const int n = gzread(gz.get(), bytes.data() + used, chunk);
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

bool isAnimatedScene(const std::filesystem::path& file) { return lowercaseExtension(uncompressedName(file)) == ".aff"; }

bool readsOtherFiles(const std::filesystem::path& file) { return isAnimatedScene(file); }

std::vector<std::filesystem::path> includedFiles(const std::filesystem::path& file) {
    if (!readsOtherFiles(file)) return {};
    return affIncludedFiles(file);
}

std::filesystem::path uncompressedName(const std::filesystem::path& file) {
    return lowercaseExtension(file) == ".gz" ? file.stem() : file.filename();
}

Scene loadScene(const std::filesystem::path& file) {
    const std::filesystem::path uncompressed = uncompressedName(file);
    const std::string ext = lowercaseExtension(uncompressed);
    const auto format = std::find_if(std::begin(kSceneFormats), std::end(kSceneFormats),
                                     [&](const SceneFormat& f) { return ext == f.extension; });
    if (format == std::end(kSceneFormats)) {
        throw inputError(file, 0, "unknown scene format; supported: .obj .ply .off .nff .aff, each optionally .gz");
    }

    const std::string bytes = readFileBytes(file);
    if (format->text) requireText(file, bytes, format->extension);
    Scene scene = format->read(file, bytes);
    scene.name = uncompressed.stem().string();
    scene.source = file;
    scene.finalize();
    requireSomethingToRender(scene);
    return scene;
}

AnimatedScene loadAnimatedScene(const std::filesystem::path& file) {
    const std::filesystem::path uncompressed = uncompressedName(file);
    if (!isAnimatedScene(file)) throw inputError(file, 0, "not an animated scene: supported: .aff, optionally .gz");
    const std::string bytes = readFileBytes(file);
    requireText(file, bytes, ".aff");
    AnimatedScene animated = readAnimatedAff(file, bytes);
    animated.scene.name = uncompressed.stem().string();
    animated.scene.source = file;
    requireSomethingToRender(animated.scene);
    return animated;
}

void requireSomethingToRender(const Scene& scene) {
    if (!scene.validPrimitives.empty()) return;
    const LoadReport& r = scene.report;
    std::string why;
    if (scene.triangleCount() > 0) {
        why = fmt::format(
            "{} degenerate (zero area, NaN or infinite vertices, or a normal that cannot be "
            "normalised)",
            scene.triangleCount() == 1 ? "its one triangle is"
                                       : fmt::format("all {} triangles are", scene.triangleCount()));
    } else if (r.skippedPolygons > 0) {
        const auto named = std::find_if(r.warnings.begin(), r.warnings.end(),
                                        [](const std::string& w) { return w.find("polygon of") != std::string::npos; });
        why = fmt::format("all {} polygons were skipped{}", r.skippedPolygons,
                          named != r.warnings.end() ? " (the first: " + *named + ")" : "");
    } else if (scene.positions.empty()) {
        why = "no primitives";
    } else {
        why = fmt::format("no primitives ({} vertices but no faces)", scene.positions.size());
    }
    if (r.degenerateSpheres || r.degenerateCones) {
        why = fmt::format(
            "{} spheres and {} cones/cylinders are degenerate (a zero, NaN or infinite radius or "
            "axis), and {}",
            r.degenerateSpheres, r.degenerateCones, scene.triangleCount() > 0 ? why : "no polygons");
    }
    throw inputError(scene.source, 0, "nothing to render: " + why);
}

}  // namespace bvhlab
