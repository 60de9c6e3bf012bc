// NFF, Eric Haines' Neutral File Format of the Standard Procedural Databases (SPD): a
// viewpoint block, background, point lights, materials ("fill colours"), polygons with
// and without vertex normals (convex or not: appendPolygon), spheres and cones (native
// primitives; degenerate ones are counted and skipped by Scene::finalize).
#include "framework/scene/readers/reader_util.h"
#include "framework/scene/scene_loader.h"

namespace bvhlab {
namespace {

// Three numbers on the current line; with startsLine, they begin the next non-blank line.
Vec3 readVec3(TextParser& text, std::string_view what, bool startsLine = false) {
    const float x = startsLine ? text.read<float>(what) : text.readOnLine<float>(what);
    const float y = text.readOnLine<float>(what);
    const float z = text.readOnLine<float>(what);
    return {x, y, z};
}

// The next line's keyword, which must be `keyword`.
void expectKeyword(TextParser& text, std::string_view keyword) {
    text.endLine();
    const std::string_view found = text.next();
    if (found != keyword) {
        throw text.error(fmt::format("expected '{}' in the viewpoint block, found {}", keyword, quoted(found)));
    }
}

// "v" then the lines from, at, up, angle, hither, resolution, in that order.
CameraSpec readViewpoint(TextParser& text) {
    CameraSpec camera;
    expectKeyword(text, "from");
    camera.from = readVec3(text, "the eye position");
    expectKeyword(text, "at");
    camera.at = readVec3(text, "the position looked at");
    expectKeyword(text, "up");
    camera.up = readVec3(text, "the up vector");
    expectKeyword(text, "angle");
    camera.fovyDegrees = text.readOnLine<float>("the field of view in degrees");
    if (!(camera.fovyDegrees > 0.0f && camera.fovyDegrees < 180.0f))
        throw text.error("the field of view must lie between 0 and 180 degrees");
    expectKeyword(text, "hither");
    text.readOnLine<float>("the hither distance");  // we do not clip near the eye
    expectKeyword(text, "resolution");
    camera.width = text.readOnLine<int>("the image width");
    camera.height = text.readOnLine<int>("the image height");
    if (camera.width <= 0 || camera.height <= 0 || camera.width > kMaxImageSide || camera.height > kMaxImageSide)
        throw text.error(fmt::format("the resolution must be 1 to {} pixels a side", kMaxImageSide));
    return camera;
}

// Newell's normal of a polygon: its geometric normal even when it is not quite planar.
Vec3 polygonNormal(std::span<const Vec3> vertices) {
    Vec3 normal{0.0f};
    for (size_t i = 0; i < vertices.size(); ++i) {
        const Vec3& a = vertices[i];
        const Vec3& b = vertices[(i + 1) % vertices.size()];
        normal += Vec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
    }
    const float length = glm::length(normal);
    return length > 0.0f ? normal / length : normal;
}

}  // namespace

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
            scene.camera = readViewpoint(text);
        } else if (keyword == "b") {
            scene.background = readVec3(text, "the background colour");
        } else if (keyword == "l") {
            PointLight light;
            light.position = readVec3(text, "the light position");
            if (!text.atLineEnd()) light.intensity = readVec3(text, "the light colour");
            scene.lights.push_back(light);
        } else if (keyword == "f") {
            // f red green blue Kd Ks Shine T index_of_refraction
            const Vec3 colour = readVec3(text, "the fill colour");
            const float kd = text.readOnLine<float>("Kd");
            const float ks = text.readOnLine<float>("Ks");
            const float shine = text.readOnLine<float>("Shine");
            const float transmission = text.readOnLine<float>("T");
            const float ior = text.readOnLine<float>("the index of refraction");
            scene.materials.push_back(Material{
                .diffuse = kd * colour, .mirror = ks, .shine = shine, .transmission = transmission, .ior = ior});
            material = uint32_t(scene.materials.size() - 1);
        } else if (keyword == "s") {
            const Vec3 centre = readVec3(text, "the sphere centre");
            scene.spheres.push_back({centre, text.readOnLine<float>("the sphere radius")});
            scene.sphereMaterialIds.push_back(material);
        } else if (keyword == "c") {
            // Base and apex, each "x y z radius": on lines of their own as the format says,
            // or on the "c" line as the SPD programs write them; read() takes either.
            Vec3 ends[2];
            float radii[2];
            for (int k = 0; k < 2; ++k) {
                const char* part = k == 0 ? "the cone base" : "the cone apex";
                ends[k].x = text.read<float>(part);
                ends[k].y = text.readOnLine<float>(part);
                ends[k].z = text.readOnLine<float>(part);
                radii[k] = text.readOnLine<float>(part);
            }
            scene.cones.push_back({ends[0], radii[0], ends[1], radii[1]});
            scene.coneMaterialIds.push_back(material);
        } else if (keyword == "p" || keyword == "pp") {
            const bool withNormals = keyword == "pp";
            const uint64_t corners = text.readOnLine<uint64_t>("the polygon's vertex count");
            if (corners < 3) {
                throw text.error(fmt::format("polygon with {} vertices; a polygon needs at least 3", corners));
            }
            const size_t first = scene.positions.size(), line = text.line();
            polygon.clear();
            for (uint64_t k = 0; k < corners; ++k) {
                text.endLine();
                polygon.push_back(uint32_t(scene.positions.size()));
                scene.positions.push_back(readVec3(text, "a vertex", /*startsLine=*/true));
                if (withNormals) scene.normals.push_back(readVec3(text, "a vertex normal"));
            }
            if (!withNormals) {
                const Vec3 normal = polygonNormal(std::span(scene.positions).subspan(first));
                scene.normals.resize(scene.positions.size(), normal);
            }
            hasNormals |= withNormals;
            appendPolygon(scene, triangulator, polygon, file, line);
            scene.materialIds.resize(scene.indices.size(), material);
        } else {
            throw text.error(fmt::format("unknown NFF entity {}", quoted(keyword)));
        }
    }
    if (!hasNormals) scene.normals.clear();
    return scene;
}

}  // namespace bvhlab
