#include "framework/scene/scene_cache.h"

#include "framework/core/error.h"
#include "framework/scene/scene_loader.h"

#include <fmt/format.h>
#include <zlib.h>

#include <cstring>
#include <fstream>
#include <random>
#include <type_traits>

namespace bvhlab {
namespace {

constexpr char kMagic[8] = {'B', 'V', 'H', 'S', 'C', 'E', 'N', 'E'};
constexpr uint32_t kEndianMarker = 0x01020304u;

static_assert(sizeof(Vec3) == 12 && std::is_trivially_copyable_v<Vec3>);
static_assert(sizeof(glm::uvec3) == 12 && std::is_trivially_copyable_v<glm::uvec3>);
static_assert(sizeof(Sphere) == 16 && std::is_trivially_copyable_v<Sphere>);
static_assert(sizeof(Cone) == 32 && std::is_trivially_copyable_v<Cone>);

// The fixed-size part at the start of a cache file; all counts are element counts.
struct Header {
    char magic[8];
    uint32_t version;
    uint32_t endian;
    uint64_t sourceSize;
    uint32_t sourceCrc32;
    uint32_t sourceAdler32;
    uint64_t nameBytes, positions, normals, indices, materialIds, materials, lights, warnings;
    uint64_t degenerate, spheres, cones;  // triangles degenerate; spheres and cones stored
    uint64_t skippedPolygons, earClippedPolygons;
    uint32_t hasCamera, hasBackground;
    float camera[10];  // from, at, up, fovy
    int32_t cameraWidth, cameraHeight;
    float background[3];
    uint32_t reserved;
};
static_assert(std::is_trivially_copyable_v<Header> && sizeof(Header) % 8 == 0);

// zlib answers a null buffer with the initial value, so empty arrays must not reach it.
uint32_t crcOf(uint32_t crc, const void* data, size_t bytes) {
    return bytes == 0 ? crc : uint32_t(crc32_z(crc, static_cast<const Bytef*>(data), bytes));
}

// Appends to the file and keeps the CRC-32 of everything written.
class Writer {
public:
    explicit Writer(const std::filesystem::path& file) : out_(file, std::ios::binary | std::ios::trunc) {
        if (!out_) throw std::runtime_error(fmt::format("{}: cannot create: {}", file.string(), std::strerror(errno)));
    }
    void bytes(const void* data, size_t n) {
        out_.write(static_cast<const char*>(data), std::streamsize(n));
        crc_ = crcOf(crc_, data, n);
    }
    template <typename T>
    void array(const std::vector<T>& v) {
        bytes(v.data(), v.size() * sizeof(T));
    }
    void finish() {
        const uint32_t crc = crc_;
        out_.write(reinterpret_cast<const char*>(&crc), sizeof(crc));
        out_.close();
        if (!out_) throw std::runtime_error("write failed (disk full?)");
    }

private:
    std::ofstream out_;
    uint32_t crc_ = 0;
};

// Reads from the file, refusing to go past the payload, and keeps the CRC-32 of what was read.
class Reader {
public:
    Reader(std::ifstream& in, uint64_t payloadBytes) : in_(in), left_(payloadBytes) {}
    bool bytes(void* data, uint64_t n) {
        if (n > left_) return false;
        if (n && !in_.read(static_cast<char*>(data), std::streamsize(n))) return false;
        crc_ = crcOf(crc_, data, n);
        left_ -= n;
        return true;
    }
    template <typename T>
    bool array(std::vector<T>& v, uint64_t count) {
        if (count > left_ / sizeof(T)) return false;
        v.resize(count);
        return bytes(v.data(), count * sizeof(T));
    }
    uint64_t left() const { return left_; }
    uint32_t crc() const { return crc_; }

private:
    std::ifstream& in_;
    uint64_t left_;
    uint32_t crc_ = 0;
};

struct PackedMaterial {
    float diffuse[3];
    float mirror, shine, transmission, ior;
};
struct PackedLight {
    float position[3];
    float intensity[3];
};

}  // namespace

std::string SceneCacheKey::cacheFileName() const {
    return fmt::format("{}.{}-{:08x}{:08x}.v{}.scene", fileName, size, crc32, adler32, kSceneCacheVersion);
}

SceneCacheKey sceneCacheKey(const std::filesystem::path& source) {
    std::ifstream in(source, std::ios::binary);
    if (!in) throw inputError(source, 0, fmt::format("cannot open: {}", std::strerror(errno)));
    SceneCacheKey key;
    key.fileName = source.filename().string();
    key.crc32 = 0;
    key.adler32 = uint32_t(adler32_z(0, nullptr, 0));
    std::vector<char> buffer(size_t(1) << 22);
    while (in) {
        in.read(buffer.data(), std::streamsize(buffer.size()));
        const size_t n = size_t(in.gcount());
        if (n == 0) break;
        key.crc32 = crcOf(key.crc32, buffer.data(), n);
        key.adler32 = uint32_t(adler32_z(key.adler32, reinterpret_cast<const Bytef*>(buffer.data()), n));
        key.size += n;
    }
    if (in.bad()) throw inputError(source, 0, "cannot read");
    return key;
}

std::optional<Scene> readSceneCache(const std::filesystem::path& cacheFile, const SceneCacheKey& key,
                                    const std::filesystem::path& source, std::string* why) {
    auto fail = [&](const std::string& reason) -> std::optional<Scene> {
        if (why) *why = reason;
        return std::nullopt;
    };
    // The size of the file opened, not of the path: a shard sharing the folder may rename
    // another (complete) entry over it in between.
    // Missing is decided before opening: checked after a failed open, an entry that another
    // shard renamed into place in between would read as "cannot open".
    if (!std::filesystem::exists(cacheFile)) return fail("missing");
    std::ifstream in(cacheFile, std::ios::binary | std::ios::ate);
    if (!in) return fail("cannot open");
    const std::streamoff end = in.tellg();
    if (end < 0 || !in.seekg(0)) return fail("cannot read");
    const uint64_t fileSize = uint64_t(end);
    if (fileSize < sizeof(Header) + sizeof(uint32_t)) return fail("truncated");
    Reader r(in, fileSize - sizeof(uint32_t));
    Header h;
    if (!r.bytes(&h, sizeof(h))) return fail("truncated");
    if (std::memcmp(h.magic, kMagic, sizeof(kMagic)) != 0) return fail("not a scene cache file");
    if (h.endian != kEndianMarker) return fail("written on a machine of other byte order");
    if (h.version != kSceneCacheVersion)
        return fail(fmt::format("format version {}, not {}", h.version, kSceneCacheVersion));
    if (h.sourceSize != key.size || h.sourceCrc32 != key.crc32 || h.sourceAdler32 != key.adler32)
        return fail("written for other source bytes");

    Scene scene;
    std::string name(std::min<uint64_t>(h.nameBytes, r.left()), '\0');
    std::vector<PackedMaterial> materials;
    std::vector<PackedLight> lights;
    if (h.nameBytes > r.left() || !r.bytes(name.data(), name.size()) || !r.array(scene.positions, h.positions) ||
        !r.array(scene.normals, h.normals) || !r.array(scene.indices, h.indices) ||
        !r.array(scene.materialIds, h.materialIds) || !r.array(scene.spheres, h.spheres) ||
        !r.array(scene.sphereMaterialIds, h.spheres) || !r.array(scene.cones, h.cones) ||
        !r.array(scene.coneMaterialIds, h.cones) || !r.array(materials, h.materials) || !r.array(lights, h.lights))
        return fail("truncated");
    for (uint64_t w = 0; w < h.warnings; ++w) {
        uint64_t length = 0;
        if (!r.bytes(&length, sizeof(length)) || length > r.left()) return fail("truncated");
        std::string text(length, '\0');
        r.bytes(text.data(), length);
        scene.report.warnings.push_back(std::move(text));
    }
    if (r.left() != 0) return fail("longer than its contents");
    uint32_t storedCrc = 0;
    if (!in.read(reinterpret_cast<char*>(&storedCrc), sizeof(storedCrc))) return fail("truncated");
    if (storedCrc != r.crc()) return fail("checksum mismatch (corrupt)");

    // Ranges the renderer relies on, checked so that even a forged entry cannot crash it (its
    // camera is checked where every camera is, in resolveCamera).
    if (!scene.normals.empty() && scene.normals.size() != scene.positions.size())
        return fail("normals do not match the vertices");
    for (const glm::uvec3& idx : scene.indices)
        if (idx.x >= scene.positions.size() || idx.y >= scene.positions.size() || idx.z >= scene.positions.size())
            return fail("vertex index out of range");
    if (!scene.materialIds.empty() && scene.materialIds.size() != scene.indices.size())
        return fail("material ids do not match the triangles");
    for (const auto* ids : {&scene.materialIds, &scene.sphereMaterialIds, &scene.coneMaterialIds})
        for (uint32_t id : *ids)
            if (id >= std::max<size_t>(materials.size(), 1)) return fail("material id out of range");

    scene.name = std::move(name);
    scene.source = source;
    scene.materials.clear();
    for (const PackedMaterial& m : materials)
        scene.materials.push_back(
            {Vec3(m.diffuse[0], m.diffuse[1], m.diffuse[2]), m.mirror, m.shine, m.transmission, m.ior});
    for (const PackedLight& l : lights)
        scene.lights.push_back(
            {Vec3(l.position[0], l.position[1], l.position[2]), Vec3(l.intensity[0], l.intensity[1], l.intensity[2])});
    if (h.hasCamera) {
        const float* c = h.camera;
        scene.camera = CameraSpec{Vec3(c[0], c[1], c[2]), Vec3(c[3], c[4], c[5]), Vec3(c[6], c[7], c[8]), c[9],
                                  h.cameraWidth,          h.cameraHeight};
    }
    if (h.hasBackground) scene.background = Vec3(h.background[0], h.background[1], h.background[2]);
    scene.report.skippedPolygons = h.skippedPolygons;
    scene.report.earClippedPolygons = h.earClippedPolygons;
    scene.finalize();  // derives triangles, valid primitives, bounds and the degenerate count
    if (scene.report.degenerateTriangles != h.degenerate) return fail("degenerate count differs");
    return scene;
}

void writeSceneCache(const std::filesystem::path& cacheFile, const SceneCacheKey& key, const Scene& scene) {
    Header h{};
    std::memcpy(h.magic, kMagic, sizeof(kMagic));
    h.version = kSceneCacheVersion;
    h.endian = kEndianMarker;
    h.sourceSize = key.size;
    h.sourceCrc32 = key.crc32;
    h.sourceAdler32 = key.adler32;
    h.nameBytes = scene.name.size();
    h.positions = scene.positions.size();
    h.normals = scene.normals.size();
    h.indices = scene.indices.size();
    h.materialIds = scene.materialIds.size();
    h.materials = scene.materials.size();
    h.lights = scene.lights.size();
    h.warnings = scene.report.warnings.size();
    h.degenerate = scene.report.degenerateTriangles;
    h.skippedPolygons = scene.report.skippedPolygons;
    h.earClippedPolygons = scene.report.earClippedPolygons;
    h.spheres = scene.spheres.size();
    h.cones = scene.cones.size();
    h.hasCamera = scene.camera.has_value();
    if (scene.camera) {
        const CameraSpec& c = *scene.camera;
        const float values[10] = {c.from.x, c.from.y, c.from.z, c.at.x, c.at.y,
                                  c.at.z,   c.up.x,   c.up.y,   c.up.z, c.fovyDegrees};
        std::memcpy(h.camera, values, sizeof(values));
        h.cameraWidth = c.width;
        h.cameraHeight = c.height;
    }
    h.hasBackground = scene.background.has_value();
    if (scene.background)
        for (int k = 0; k < 3; ++k) h.background[k] = (*scene.background)[k];
    std::vector<PackedMaterial> materials;
    for (const Material& m : scene.materials)
        materials.push_back({{m.diffuse.x, m.diffuse.y, m.diffuse.z}, m.mirror, m.shine, m.transmission, m.ior});
    std::vector<PackedLight> lights;
    for (const PointLight& l : scene.lights)
        lights.push_back({{l.position.x, l.position.y, l.position.z}, {l.intensity.x, l.intensity.y, l.intensity.z}});

    // A unique temporary name (shards on several machines may share the folder), renamed into place.
    std::random_device random;
    const std::filesystem::path temporary = cacheFile.string() + fmt::format(".tmp-{:08x}{:08x}", random(), random());
    try {
        Writer w(temporary);
        w.bytes(&h, sizeof(h));
        w.bytes(scene.name.data(), scene.name.size());
        w.array(scene.positions);
        w.array(scene.normals);
        w.array(scene.indices);
        w.array(scene.materialIds);
        w.array(scene.spheres);
        w.array(scene.sphereMaterialIds);
        w.array(scene.cones);
        w.array(scene.coneMaterialIds);
        w.array(materials);
        w.array(lights);
        for (const std::string& text : scene.report.warnings) {
            const uint64_t length = text.size();
            w.bytes(&length, sizeof(length));
            w.bytes(text.data(), text.size());
        }
        w.finish();
        std::filesystem::rename(temporary, cacheFile);
    } catch (...) {
        std::error_code ignored;
        std::filesystem::remove(temporary, ignored);
        throw;
    }
}

CachedScene loadSceneCached(const std::filesystem::path& source, const std::filesystem::path& cacheDir) {
    const SceneCacheKey key = sceneCacheKey(source);
    CachedScene result;
    result.cacheFile = cacheDir / key.cacheFileName();
    std::string why;
    if (std::filesystem::exists(result.cacheFile)) {
        if (std::optional<Scene> cached = readSceneCache(result.cacheFile, key, source, &why)) {
            requireSomethingToRender(*cached);  // what loadScene refuses, an entry must not let through
            result.scene = std::move(*cached);
            result.fromCache = true;
            return result;
        }
        result.note =
            fmt::format("ignored cache entry {} ({}); parsing and rewriting it", result.cacheFile.string(), why);
    }
    result.scene = loadScene(source);
    try {
        std::filesystem::create_directories(cacheDir);
        writeSceneCache(result.cacheFile, key, result.scene);
    } catch (const std::exception& e) {
        result.note += fmt::format("{}could not write cache entry {}: {}", result.note.empty() ? "" : "; ",
                                   result.cacheFile.string(), e.what());
    }
    return result;
}

}  // namespace bvhlab
