// Wavefront OBJ. tinyobjloader parses faces, normals and materials; a pass of our own reads
// the vertex positions, because tinyobj turns "nan", "inf" and garbage into 0 without a word,
// and notes the line of every face, because tinyobj's messages cannot place a bad index.
// tinyobj's triangulation is off (it splits quads along the shorter diagonal); appendPolygon
// keeps primitive indices in file order and covers non-convex faces exactly. We call LoadObj
// on a stream rather than ObjReader: ObjReader reads either a file by name (no gzip) or a
// string without its mtllib.
#include "framework/scene/readers/reader_util.h"
#include "framework/scene/scene_loader.h"

#include <tiny_obj_loader.h>

#include <cctype>
#include <sstream>

namespace bvhlab {
namespace {

// tinyobj stores corner counts in an unsigned char.
constexpr size_t kMaxPolygonCorners = 255;

struct ObjScan {
    std::vector<Vec3> positions;
    std::vector<size_t> faceLines;  // line of each face, in file order
    std::string_view firstOther;    // the first line that is not blank, a comment, a v or an f
};

// Our pass over the text. Lines and statements are recognised exactly as tinyobj does,
// so the n-th face here is the n-th face tinyobj returns.
ObjScan scanObj(const std::filesystem::path& file, std::string_view text) {
    ObjScan scan;
    size_t lineNumber = 0;
    for (size_t pos = 0; pos < text.size();) {
        ++lineNumber;
        size_t end = pos;
        while (end < text.size() && text[end] != '\n' && text[end] != '\r') ++end;
        std::string_view line = text.substr(pos, end - pos);
        pos = end + (text.substr(end, 2) == "\r\n" ? 2 : 1);

        line.remove_prefix(std::min(line.find_first_not_of(" \t"), line.size()));
        if (line.size() < 2 || (line[1] != ' ' && line[1] != '\t') || (line[0] != 'v' && line[0] != 'f')) {
            if (scan.firstOther.empty() && !line.empty() && line[0] != '#') scan.firstOther = line;
            continue;
        }
        TextParser statement(file, line.substr(2), false, lineNumber);
        if (line[0] == 'v') {
            // Further values (w, vertex colours) are not ours to check.
            const float x = statement.readOnLine<float>("an x coordinate");
            const float y = statement.readOnLine<float>("a y coordinate");
            const float z = statement.readOnLine<float>("a z coordinate");
            scan.positions.emplace_back(x, y, z);
        } else if (line[0] == 'f') {
            size_t corners = 0;
            while (!statement.nextOnLine().empty()) ++corners;
            if (corners < 3 || corners > kMaxPolygonCorners) {
                throw statement.error(
                    fmt::format("face with {} corners; faces need 3 to {}", corners, kMaxPolygonCorners));
            }
            scan.faceLines.push_back(lineNumber);
        }
    }
    return scan;
}

// tinyobj's error messages end in "line N.)"; the number becomes ours.
InputError tinyobjError(const std::filesystem::path& file, std::string message) {
    while (!message.empty() && std::isspace(static_cast<unsigned char>(message.back()))) message.pop_back();
    size_t line = 0;
    if (const size_t at = message.rfind("line "); at != std::string::npos) {
        std::from_chars(message.data() + at + 5, message.data() + message.size(), line);
    }
    return inputError(file, line, message);
}

// What tinyobj reads of the file: vertices and normals, faces by shape, materials, and its
// messages (warnings, and errors that did not stop it).
struct TinyobjFile {
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string messages;
};

TinyobjFile loadWithTinyobj(const std::filesystem::path& file, const std::string& bytes) {
    TinyobjFile obj;
    std::string warnings, errors;
    std::istringstream stream(bytes);
    tinyobj::MaterialFileReader mtlReader(file.parent_path().string());  // mtllib is relative to the .obj
    if (!tinyobj::LoadObj(&obj.attrib, &obj.shapes, &obj.materials, &warnings, &errors, &stream, &mtlReader,
                          /*triangulate=*/false, /*default_vcols_fallback=*/false)) {
        throw tinyobjError(file, errors);
    }
    obj.messages = warnings + errors;
    return obj;
}

}  // namespace

Scene readObj(const std::filesystem::path& file, const std::string& bytes) {
    ObjScan scan = scanObj(file, bytes);
    // tinyobj ignores lines it does not know, so any text would load as an empty scene.
    if (scan.positions.empty() && scan.faceLines.empty() && !scan.firstOther.empty()) {
        throw inputError(file, 0,
                         fmt::format("not an OBJ file: text with no vertex or face statements (v, f); it "
                                     "starts {}",
                                     quoted(scan.firstOther)));
    }

    const TinyobjFile obj = loadWithTinyobj(file, bytes);
    const tinyobj::attrib_t& attrib = obj.attrib;
    const std::vector<tinyobj::shape_t>& shapes = obj.shapes;
    const std::vector<tinyobj::material_t>& objMaterials = obj.materials;

    Scene scene;
    scene.positions = std::move(scan.positions);
    for (const tinyobj::material_t& m : objMaterials) {
        scene.materials.push_back(Material{.diffuse = Vec3(m.diffuse[0], m.diffuse[1], m.diffuse[2])});
    }

    // Normals are per corner in OBJ; we keep them per vertex when every corner has one.
    const size_t vertexCount = scene.positions.size();
    const size_t normalCount = attrib.normals.size() / 3;
    bool everyCornerHasNormal = normalCount > 0;
    if (everyCornerHasNormal) scene.normals.resize(vertexCount);

    size_t triangleCount = 0;  // every face has at least 3 corners (scanObj checked)
    for (const tinyobj::shape_t& shape : shapes) {
        triangleCount += shape.mesh.indices.size() - 2 * shape.mesh.num_face_vertices.size();
    }
    scene.indices.reserve(triangleCount);

    size_t face = 0;
    std::vector<uint32_t> polygon;
    PolygonTriangulator triangulator;
    for (const tinyobj::shape_t& shape : shapes) {
        const tinyobj::mesh_t& mesh = shape.mesh;
        size_t corner = 0;
        for (size_t f = 0; f < mesh.num_face_vertices.size(); ++f, ++face) {
            const size_t line = face < scan.faceLines.size() ? scan.faceLines[face] : 0;
            polygon.clear();
            for (size_t k = 0; k < mesh.num_face_vertices[f]; ++k, ++corner) {
                const tinyobj::index_t index = mesh.indices[corner];
                if (index.vertex_index < 0 || size_t(index.vertex_index) >= vertexCount) {
                    throw inputError(file, line,
                                     fmt::format("face {}: vertex index out of range (the file has {} vertices)",
                                                 face + 1, vertexCount));
                }
                polygon.push_back(uint32_t(index.vertex_index));
                if (index.normal_index < 0) {
                    everyCornerHasNormal = false;
                } else if (size_t(index.normal_index) >= normalCount) {
                    throw inputError(file, line,
                                     fmt::format("face {}: normal index out of range (the file has {} normals)",
                                                 face + 1, normalCount));
                } else if (everyCornerHasNormal) {
                    const tinyobj::real_t* n = &attrib.normals[3 * size_t(index.normal_index)];
                    scene.normals[index.vertex_index] = Vec3(n[0], n[1], n[2]);
                }
            }
            appendPolygon(scene, triangulator, polygon, file, line);
            if (!objMaterials.empty()) {
                // Material 0 is the default, for faces before any usemtl or with an unknown one.
                const int id = mesh.material_ids[f];
                const bool known = id >= 0 && size_t(id) < objMaterials.size();
                scene.materialIds.resize(scene.indices.size(), known ? uint32_t(id + 1) : 0);
            }
        }
    }
    if (!everyCornerHasNormal) scene.normals.clear();

    // tinyobj's warnings (a missing .mtl, an unknown material) do not stop the load.
    std::istringstream warningLines(obj.messages);
    for (std::string w; std::getline(warningLines, w);) {
        if (!w.empty()) scene.report.warnings.push_back(fmt::format("{}: {}", file.string(), w));
    }
    return scene;
}

}  // namespace bvhlab
