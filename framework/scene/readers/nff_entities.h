// NFF's entities, read from the line after their keyword on: the NFF reader's and the AFF
// reader's (AFF extends NFF) one implementation.
#pragma once

#include "framework/scene/readers/reader_util.h"

#include <vector>

namespace bvhlab::nff {

// Three numbers on the current line; with startsLine, they begin the next non-blank line.
Vec3 readVec3(TextParser& text, std::string_view what, bool startsLine = false);

// After "v": the lines from, at, up, angle, hither, resolution, in that order.
CameraSpec readViewpoint(TextParser& text);

// After "l": a position and an optional colour on the same line.
PointLight readLight(TextParser& text);

// After "f": red green blue Kd Ks Shine T index_of_refraction.
Material readFill(TextParser& text);

// After "s": centre and radius.
Sphere readSphere(TextParser& text);

// After "c": base and apex, each "x y z radius", on lines of their own or on the "c" line.
Cone readCone(TextParser& text);

// After "p" (withNormals false) or "pp": the vertex count, then a vertex a line. Appends the
// vertices to scene.positions and scene.normals (a "p" polygon's normal for every vertex of
// it) and the triangles to scene.indices (appendPolygon). `corners` is scratch space.
void readPolygon(TextParser& text, Scene& scene, PolygonTriangulator& triangulator, std::vector<uint32_t>& corners,
                 bool withNormals, const std::filesystem::path& file);

}  // namespace bvhlab::nff
