// NFF, Eric Haines' Neutral File Format of the Standard Procedural Databases (SPD): a
// viewpoint block, background, point lights, materials ("fill colours"), polygons with
// and without vertex normals (convex or not: appendPolygon), spheres and cones (native
// primitives; degenerate ones are counted and skipped by Scene::finalize).
#include "framework/scene/readers/nff_entities.h"
#include "framework/scene/scene_loader.h"

namespace bvhlab {

Scene readNff(const std::filesystem::path& file, const std::string& bytes) {
    TextParser text(file, bytes, /*hashComments=*/true);
    Scene scene;
    uint32_t material = 0;    // the default material until the first "f"
    bool hasNormals = false;  // some polygon was a "pp"
    std::vector<uint32_t> polygon;
    PolygonTriangulator triangulator;

    // Each entity starts on a line of its own; the loop ends its last line.
    for (std::string_view keyword = text.next(); !keyword.empty(); text.endLine(), keyword = text.next()) {
        if (keyword == "v") {
            scene.camera = nff::readViewpoint(text);
        } else if (keyword == "b") {
            scene.background = nff::readVec3(text, "the background colour");
        } else if (keyword == "l") {
            scene.lights.push_back(nff::readLight(text));
        } else if (keyword == "f") {
            scene.materials.push_back(nff::readFill(text));
            material = uint32_t(scene.materials.size() - 1);
        } else if (keyword == "s") {
            scene.spheres.push_back(nff::readSphere(text));
            scene.sphereMaterialIds.push_back(material);
        } else if (keyword == "c") {
            scene.cones.push_back(nff::readCone(text));
            scene.coneMaterialIds.push_back(material);
        } else if (keyword == "p" || keyword == "pp") {
            const bool withNormals = keyword == "pp";
            nff::readPolygon(text, scene, triangulator, polygon, withNormals, file);
            hasNormals |= withNormals;
            scene.materialIds.resize(scene.indices.size(), material);
        } else {
            throw text.error(fmt::format("unknown NFF entity {}", quoted(keyword)));
        }
    }
    if (!hasNormals) scene.normals.clear();
    return scene;
}

}  // namespace bvhlab
