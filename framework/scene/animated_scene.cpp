#include "framework/scene/animated_scene.h"

#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>

namespace bvhlab {
namespace {

// The uniform scale of a similarity transform (the part's quadrics are refused otherwise).
float uniformScale(const glm::mat4& m) { return glm::length(Vec3(m[0])); }

Vec3 transformPoint(const glm::mat4& m, const Vec3& p) { return Vec3(m * glm::vec4(p, 1.0f)); }

Bounds3 primitiveBounds(const Scene& scene, uint32_t prim) {
    const size_t triangles = scene.triangleCount(), coneBase = triangles + scene.spheres.size();
    if (prim < triangles) return scene.triangles[prim].bounds();
    if (prim < coneBase) return scene.spheres[prim - triangles].bounds();
    return scene.cones[prim - coneBase].bounds();
}

}  // namespace

glm::dmat4 TransformTrack::at(double time) const {
    glm::dmat4 m(1.0);
    if (rotation) m = glm::mat4_cast(rotation->at(time));
    if (scale) m = m * glm::scale(glm::dmat4(1.0), scale->at(time));
    if (translation) m[3] = glm::dvec4(translation->at(time), 1.0);
    return m;
}

float AnimatedScene::frameTime(int frame) const {
    if (frameCount <= 1) return startTime;
    return startTime + float(frame) * (endTime - startTime) / float(frameCount - 1);
}

glm::dmat4 AnimatedScene::nodeTransformAt(int node, double time) const {
    glm::dmat4 m(1.0);
    for (; node >= 0; node = nodes[size_t(node)].parent) {
        const TransformNode& n = nodes[size_t(node)];
        m = (n.track >= 0 ? tracks[size_t(n.track)].at(time) : n.local) * m;
    }
    return m;
}

std::optional<CameraSpec> AnimatedScene::cameraAt(float time) const {
    if (cameraTrack < 0) return staticCamera;
    CameraSpec camera = staticCamera.value_or(CameraSpec{});
    const TransformTrack& track = tracks[size_t(cameraTrack)];
    const Vec3 view = camera.at - camera.from;
    if (track.translation) camera.from = Vec3(track.translation->at(time));
    camera.at = camera.from + view;
    if (track.rotation) {
        const glm::dmat3 r = glm::mat3_cast(track.rotation->at(time));
        camera.at = camera.from - Vec3(r[2]);
        camera.up = Vec3(r[1]);
    }
    return camera;
}

void AnimatedScene::prepare() {
    nodeMatrices_.resize(nodes.size());
    moving_.clear();
    const uint32_t triangles = uint32_t(scene.triangleCount());
    const uint32_t sphereBase = triangles, coneBase = triangles + uint32_t(scene.spheres.size());
    for (const RigidPart& part : parts) {
        for (uint32_t i = part.triangles.first; i < part.triangles.end(); ++i) moving_.push_back(i);
        for (uint32_t i = part.spheres.first; i < part.spheres.end(); ++i) moving_.push_back(sphereBase + i);
        for (uint32_t i = part.cones.first; i < part.cones.end(); ++i) moving_.push_back(coneBase + i);
    }
    for (const AnimatedTriangle& tri : animatedTriangles) moving_.push_back(tri.triangle);
    std::sort(moving_.begin(), moving_.end());
    movingValid_.assign(moving_.size(), 0);

    staticValid_.clear();
    staticBounds_ = Bounds3();
    for (const uint32_t prim : scene.validPrimitives) {
        if (std::binary_search(moving_.begin(), moving_.end(), prim)) continue;
        staticValid_.push_back(prim);
        staticBounds_.extend(primitiveBounds(scene, prim));
    }
    scene.validPrimitives.reserve(scene.primitiveCount());
    time_ = startTime;
    setTime(startTime);
    rebuildValidPrimitives();
}

bool AnimatedScene::setTime(float time) {
    time_ = time;
    for (size_t i = 0; i < nodes.size(); ++i) {
        const TransformNode& n = nodes[i];
        const glm::dmat4 local = n.track >= 0 ? tracks[size_t(n.track)].at(time) : n.local;
        nodeMatrices_[i] = n.parent >= 0 ? nodeMatrices_[size_t(n.parent)] * local : local;
    }

    const bool hasNormals = !scene.normals.empty();
    for (const RigidPart& part : parts) {
        const glm::mat4 m(nodeMatrices_[size_t(part.node)]);
        for (uint32_t k = 0; k < part.vertices.count; ++k)
            scene.positions[part.vertices.first + k] = transformPoint(m, part.positions[k]);
        if (hasNormals && !part.normals.empty()) {
            const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(m)));
            for (uint32_t k = 0; k < part.vertices.count; ++k) {
                const Vec3 n = normalMatrix * part.normals[k];
                const float length = glm::length(n);
                scene.normals[part.vertices.first + k] = length > 0.0f ? n / length : Vec3(0.0f);
            }
        }
        const float s = uniformScale(m);
        for (uint32_t k = 0; k < part.spheres.count; ++k) {
            const Sphere& o = part.objectSpheres[k];
            scene.spheres[part.spheres.first + k] = {transformPoint(m, o.centre), o.radius * s};
        }
        for (uint32_t k = 0; k < part.cones.count; ++k) {
            const Cone& o = part.objectCones[k];
            scene.cones[part.cones.first + k] = {transformPoint(m, o.base), o.baseRadius * s, transformPoint(m, o.apex),
                                                 o.apexRadius * s};
        }
    }

    for (const AnimatedTriangle& tri : animatedTriangles) {
        const size_t last = tri.times.size() - 1;
        const size_t upper = size_t(std::upper_bound(tri.times.begin(), tri.times.end(), time) - tri.times.begin());
        const size_t k1 = std::min(upper, last), k0 = upper == 0 ? 0 : upper - 1;
        const float span = tri.times[k1] - tri.times[k0];
        const float w = span > 0.0f ? (time - tri.times[k0]) / span : 0.0f;
        const glm::mat4 m = tri.node >= 0 ? glm::mat4(nodeMatrices_[size_t(tri.node)]) : glm::mat4(1.0f);
        const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(m)));
        const glm::uvec3 idx = scene.indices[tri.triangle];
        for (int c = 0; c < 3; ++c) {
            const Vec3 p = glm::mix(tri.positions[k0][size_t(c)], tri.positions[k1][size_t(c)], w);
            scene.positions[idx[c]] = transformPoint(m, p);
            if (hasNormals) {
                const Vec3 n = normalMatrix * glm::mix(tri.normals[k0][size_t(c)], tri.normals[k1][size_t(c)], w);
                const float length = glm::length(n);
                scene.normals[idx[c]] = length > 0.0f ? n / length : Vec3(0.0f);
            }
        }
    }

    // The derived arrays of the moved primitives; the rest of them stay as finalize left them.
    const uint32_t triangles = uint32_t(scene.triangleCount());
    const uint32_t sphereBase = triangles, coneBase = triangles + uint32_t(scene.spheres.size());
    bool validityChanged = false;
    scene.bounds = staticBounds_;
    for (size_t k = 0; k < moving_.size(); ++k) {
        const uint32_t prim = moving_[k];
        bool valid;
        Bounds3 box;
        if (prim < triangles) {
            const glm::uvec3 idx = scene.indices[prim];
            Triangle& tri = scene.triangles[prim];
            tri = {scene.positions[idx.x], scene.positions[idx.y], scene.positions[idx.z]};
            valid = !isDegenerate(tri);
            box = tri.bounds();
        } else if (prim < coneBase) {
            const Sphere& sphere = scene.spheres[prim - sphereBase];
            valid = !isDegenerate(sphere);
            box = sphere.bounds();
        } else {
            const Cone& cone = scene.cones[prim - coneBase];
            valid = !isDegenerate(cone);
            box = cone.bounds();
        }
        if (valid) scene.bounds.extend(box);
        validityChanged |= valid != bool(movingValid_[k]);
        movingValid_[k] = valid;
    }
    if (validityChanged) rebuildValidPrimitives();
    if (cameraTrack >= 0) scene.camera = cameraAt(time);
    for (const AnimatedLight& light : animatedLights) {
        const TransformTrack& track = tracks[size_t(light.track)];
        if (track.translation) scene.lights[light.light].position = Vec3(track.translation->at(time));
    }
    return validityChanged;
}

// The static valid primitives merged with the moving ones valid now, ascending; within the
// capacity reserved by prepare.
void AnimatedScene::rebuildValidPrimitives() {
    std::vector<uint32_t>& valid = scene.validPrimitives;
    valid.clear();
    size_t s = 0;
    for (size_t k = 0; k < moving_.size(); ++k) {
        if (!movingValid_[k]) continue;
        while (s < staticValid_.size() && staticValid_[s] < moving_[k]) valid.push_back(staticValid_[s++]);
        valid.push_back(moving_[k]);
    }
    valid.insert(valid.end(), staticValid_.begin() + std::ptrdiff_t(s), staticValid_.end());
    const auto quadrics = std::lower_bound(valid.begin(), valid.end(), uint32_t(scene.triangleCount()));
    scene.report.degenerateTriangles = scene.triangleCount() - size_t(quadrics - valid.begin());
}

}  // namespace bvhlab
