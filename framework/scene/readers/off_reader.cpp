// OFF, Geomview's Object File Format: a keyword line (OFF, or NOFF, COFF, CNOFF, whose extra
// per-vertex values we ignore), the counts "vertices faces [edges]", one vertex "x y z" per
// line, then one face "n i0 ... i(n-1) [colour]" per line. '#' starts a comment.
#include "framework/scene/readers/reader_util.h"
#include "framework/scene/scene_loader.h"

namespace bvhlab {

Scene readOff(const std::filesystem::path& file, const std::string& bytes) {
    TextParser text(file, bytes, /*hashComments=*/true);
    const std::string_view keyword = text.next();
    if (keyword != "OFF" && keyword != "NOFF" && keyword != "COFF" && keyword != "CNOFF") {
        throw text.error(fmt::format("not an OFF file: expected 'OFF', found {}", quoted(keyword)));
    }
    const uint64_t vertexCount = text.read<uint64_t>("the vertex count");
    const uint64_t faceCount = text.readOnLine<uint64_t>("the face count");
    if (!text.atLineEnd()) text.readOnLine<uint64_t>("the edge count");  // unused, but it must be a count
    text.endLine();
    if (vertexCount > std::numeric_limits<uint32_t>::max()) {
        throw text.error("more vertices than 32-bit indices can address");
    }

    // Each vertex line holds at least "0 0 0\n", each face line "3 0 0 0\n".
    Scene scene;
    scene.positions.reserve(plausibleCount(vertexCount, bytes.size(), 6));
    for (uint64_t i = 0; i < vertexCount; ++i) {
        const float x = text.read<float>("a vertex's x coordinate");
        const float y = text.readOnLine<float>("a vertex's y coordinate");
        const float z = text.readOnLine<float>("a vertex's z coordinate");
        scene.positions.emplace_back(x, y, z);
        text.skipLine();  // NOFF normals, COFF colours
    }

    scene.indices.reserve(plausibleCount(faceCount, bytes.size(), 8));
    std::vector<uint32_t> polygon;
    PolygonTriangulator triangulator;
    for (uint64_t f = 0; f < faceCount; ++f) {
        const uint64_t corners = text.read<uint64_t>("a face's vertex count");
        if (corners < 3) throw text.error(fmt::format("face with {} vertices; a face needs at least 3", corners));
        polygon.clear();
        for (uint64_t k = 0; k < corners; ++k) {
            const uint64_t index = text.readOnLine<uint64_t>("a vertex index");
            if (index >= vertexCount) {
                throw text.error(
                    fmt::format("vertex index {} out of range (the file has {} vertices)", index, vertexCount));
            }
            polygon.push_back(uint32_t(index));
        }
        appendPolygon(scene, triangulator, polygon, file, text.line());
        text.skipLine();  // an optional face colour
    }
    return scene;
}

}  // namespace bvhlab
