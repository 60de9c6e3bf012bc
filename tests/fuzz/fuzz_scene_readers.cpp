// libFuzzer target for the scene readers (OBJ, PLY, OFF, NFF, AFF). The first byte chooses the
// format (its value modulo 5: obj, ply, off, nff, aff; an AFF scene is also moved to its last
// frame), the rest is the file's content. Malformed
// input must end in an InputError; anything else (a crash, a sanitizer report, another
// exception, a hang, an allocation beyond -rss_limit_mb) is a finding. Built with
// -DBVHLAB_FUZZ=ON (clang); see docs/accuracy.md, "Robustness", for how to run it.
#include "framework/core/error.h"
#include "framework/scene/scene_loader.h"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size == 0) return 0;
    using Reader = bvhlab::Scene (*)(const std::filesystem::path&, const std::string&);
    static constexpr Reader kReaders[] = {bvhlab::readObj, bvhlab::readPly, bvhlab::readOff, bvhlab::readNff};
    static constexpr const char* kNames[] = {"fuzz.obj", "fuzz.ply", "fuzz.off", "fuzz.nff", "fuzz.aff"};
    const unsigned format = data[0] % 5;
    const std::string bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
    // A folder that does not exist: an OBJ's mtllib and an AFF's includes must not read whatever
    // lies around.
    const std::filesystem::path file = std::filesystem::path("/nonexistent-bvhlab-fuzz") / kNames[format];
    try {
        bvhlab::Scene scene;
        if (format == 4) {
            bvhlab::AnimatedScene animated = bvhlab::readAnimatedAff(file, bytes);
            animated.setTime(animated.frameTime(animated.frameCount - 1));
            scene = std::move(animated.scene);
        } else {
            scene = kReaders[format](file, bytes);
        }
        scene.finalize();
        // What a loaded scene promises (scene.h): indices in range, per-triangle material ids
        // valid, normals per vertex or none.
        for (const auto& idx : scene.indices)
            if (idx.x >= scene.positions.size() || idx.y >= scene.positions.size() || idx.z >= scene.positions.size())
                __builtin_trap();
        if (!scene.materialIds.empty() && scene.materialIds.size() != scene.indices.size()) __builtin_trap();
        for (uint32_t id : scene.materialIds)
            if (id >= scene.materials.size()) __builtin_trap();
        if (!scene.normals.empty() && scene.normals.size() != scene.positions.size()) __builtin_trap();
    } catch (const bvhlab::InputError&) {
    }
    return 0;
}
