#include "framework/scene/readers/nff_entities.h"

namespace bvhlab::nff {
namespace {

// The next line's keyword, which must be `keyword`.
void expectKeyword(TextParser& text, std::string_view keyword) {
    text.endLine();
    const std::string_view found = text.next();
    if (found != keyword) {
        throw text.error(fmt::format("expected '{}' in the viewpoint block, found {}", keyword, quoted(found)));
    }
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

Vec3 readVec3(TextParser& text, std::string_view what, bool startsLine) {
    const float x = startsLine ? text.read<float>(what) : text.readOnLine<float>(what);
    const float y = text.readOnLine<float>(what);
    const float z = text.readOnLine<float>(what);
    return {x, y, z};
}

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

PointLight readLight(TextParser& text) {
    PointLight light;
    light.position = readVec3(text, "the light position");
    if (!text.atLineEnd()) light.intensity = readVec3(text, "the light colour");
    return light;
}

Material readFill(TextParser& text) {
    const Vec3 colour = readVec3(text, "the fill colour");
    const float kd = text.readOnLine<float>("Kd");
    const float ks = text.readOnLine<float>("Ks");
    const float shine = text.readOnLine<float>("Shine");
    const float transmission = text.readOnLine<float>("T");
    const float ior = text.readOnLine<float>("the index of refraction");
    return Material{.diffuse = kd * colour, .mirror = ks, .shine = shine, .transmission = transmission, .ior = ior};
}

Sphere readSphere(TextParser& text) {
    const Vec3 centre = readVec3(text, "the sphere centre");
    return {centre, text.readOnLine<float>("the sphere radius")};
}

Cone readCone(TextParser& text) {
    Vec3 ends[2];
    float radii[2];
    for (int k = 0; k < 2; ++k) {
        const char* part = k == 0 ? "the cone base" : "the cone apex";
        ends[k].x = text.read<float>(part);
        ends[k].y = text.readOnLine<float>(part);
        ends[k].z = text.readOnLine<float>(part);
        radii[k] = text.readOnLine<float>(part);
    }
    return {ends[0], radii[0], ends[1], radii[1]};
}

void readPolygon(TextParser& text, Scene& scene, PolygonTriangulator& triangulator, std::vector<uint32_t>& corners,
                 bool withNormals, const std::filesystem::path& file) {
    const uint64_t count = text.readOnLine<uint64_t>("the polygon's vertex count");
    if (count < 3) throw text.error(fmt::format("polygon with {} vertices; a polygon needs at least 3", count));
    const size_t first = scene.positions.size(), line = text.line();
    corners.clear();
    for (uint64_t k = 0; k < count; ++k) {
        text.endLine();
        corners.push_back(uint32_t(scene.positions.size()));
        scene.positions.push_back(readVec3(text, "a vertex", /*startsLine=*/true));
        if (withNormals) scene.normals.push_back(readVec3(text, "a vertex normal"));
    }
    if (!withNormals) {
        const Vec3 normal = polygonNormal(std::span(scene.positions).subspan(first));
        scene.normals.resize(scene.positions.size(), normal);
    }
    appendPolygon(scene, triangulator, corners, file, line);
}

}  // namespace bvhlab::nff
