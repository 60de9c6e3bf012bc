// A binary cache of loaded scenes, so that a scene file is parsed once: the cache file is named
// by the source file's name, size and checksums (CRC-32 and Adler-32 of its raw bytes, gzip
// included) and the format version, so an edited source simply misses. Entries are validated
// when read (magic, version, key, sizes against the file size, CRC-32 of the payload, index
// ranges); a corrupt or stale entry is ignored and rewritten, never trusted. Writes go to a
// temporary file renamed into place, so concurrent shards sharing the folder are safe.
#pragma once

#include "framework/scene/scene.h"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace bvhlab {

// Bump when the cache layout changes or when a reader's output for the same bytes changes
// (old entries then miss and are rewritten).
constexpr uint32_t kSceneCacheVersion = 4;

// What identifies a source file's content: its size and checksums of its raw bytes.
struct SceneCacheKey {
    std::string fileName;  // the source's file name: the reader is chosen by its extension
    uint64_t size = 0;
    uint32_t crc32 = 0;
    uint32_t adler32 = 0;

    // NAME.SIZE-CRCADLER.vVERSION.scene
    std::string cacheFileName() const;
};

// Reads `source` once (about 1 GB/s) and checksums its bytes. Throws InputError if unreadable.
SceneCacheKey sceneCacheKey(const std::filesystem::path& source);

// The cached scene, or nullopt with `why` saying what was wrong (missing, truncated, corrupt,
// other version or key). `source` becomes the scene's source path; finalize() is done.
std::optional<Scene> readSceneCache(const std::filesystem::path& cacheFile, const SceneCacheKey& key,
                                    const std::filesystem::path& source, std::string* why = nullptr);

// Writes atomically (temporary file, then rename). Throws std::runtime_error on I/O errors.
void writeSceneCache(const std::filesystem::path& cacheFile, const SceneCacheKey& key, const Scene& scene);

struct CachedScene {
    Scene scene;
    bool fromCache = false;
    std::filesystem::path cacheFile;
    std::string note;  // why the cache was not used or not written; empty when all went well
};

// The scene of `source` from the cache in `cacheDir` if a valid entry exists, else parsed by
// loadScene and then stored (a failure to store is a note, not an error). Throws what loadScene
// throws, and the same "nothing to render" error for an entry with nothing to render.
CachedScene loadSceneCached(const std::filesystem::path& source, const std::filesystem::path& cacheDir);

}  // namespace bvhlab
