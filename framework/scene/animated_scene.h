// A scene that moves: a normal Scene (everything in world space at the current time, usable by
// all code that takes a Scene) and what moves in it, evaluated at a time t by setTime. Made by
// the AFF reader (readers/aff_reader.h) for BART's animated scenes.
//
// What moves:
// - rigid parts: a range of the Scene's vertices, triangles, spheres and cones under a chain of
//   transforms of which at least one is animated. A part keeps its object-space geometry and
//   its transform apart (transformAt), so that a two-level structure can make it an instance.
// - animated triangles (AFF's `tpa`): one triangle each whose vertices and normals are keyed,
//   linearly interpolated between keys and held before the first and after the last.
// - the camera (`k camera`) and animated lights (`la NAME`).
// Everything else was put in world space once, at load time, and setTime never touches it.
#pragma once

#include "framework/scene/kochanek_bartels.h"
#include "framework/scene/scene.h"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace bvhlab {

// A named AFF animation (`k NAME { transl ... rot ... scale ... }`): T * R * S at a time, each
// the identity where the block has none.
struct TransformTrack {
    std::string name;
    std::optional<PositionSpline> translation;
    std::optional<RotationSpline> rotation;
    std::optional<PositionSpline> scale;

    glm::dmat4 at(double time) const;
};

// A node of the transform tree: a static transform (`xs`) or an animated one (`x NAME`, then
// `track` indexes AnimatedScene::tracks). Parents come before their children.
struct TransformNode {
    int parent = -1;
    int track = -1;
    glm::dmat4 local{1.0};  // static nodes
};

// Elements first .. first + count - 1 of one of the Scene's arrays.
struct IndexRange {
    uint32_t first = 0, count = 0;
    uint32_t end() const { return first + count; }
};

struct RigidPart {
    int node = -1;  // its innermost animated transform, whose chain up to the root places the part
    IndexRange vertices, triangles, spheres, cones;
    // The geometry in the part's object space: the static transforms below `node` applied (at
    // load), those of `node`'s chain not.
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;  // empty when the scene has no normals; zero: none at this vertex
    std::vector<Sphere> objectSpheres;
    std::vector<Cone> objectCones;
};

struct AnimatedTriangle {
    uint32_t triangle = 0;     // in the Scene; its three vertices are its own
    int node = -1;             // its innermost animated transform, or -1: keys in world space
    std::vector<float> times;  // ascending
    std::vector<std::array<Vec3, 3>> positions, normals;  // per key
};

class AnimatedScene {
public:
    Scene scene;

    // `a START END FRAMES`: frame i is at start + i (end - start) / (frames - 1).
    float startTime = 0.0f, endTime = 0.0f;
    int frameCount = 1;
    float frameTime(int frame) const;

    std::vector<TransformTrack> tracks;
    std::vector<TransformNode> nodes;
    std::vector<RigidPart> parts;
    std::vector<AnimatedTriangle> animatedTriangles;
    int cameraTrack = -1;  // `k camera`: its translation is the eye, its rotation looks along -z with y up
    std::optional<CameraSpec> staticCamera;  // the `v` block, which the track overrides
    struct AnimatedLight {
        uint32_t light;
        int track;
    };
    std::vector<AnimatedLight> animatedLights;

    // The transform of a node or a part (its chain from the root) at a time.
    glm::dmat4 nodeTransformAt(int node, double time) const;
    glm::mat4 transformAt(const RigidPart& part, float time) const {
        return glm::mat4(nodeTransformAt(part.node, time));
    }
    std::optional<CameraSpec> cameraAt(float time) const;

    // Puts the moving geometry, the camera and the lights at `time`: only the primitives that
    // move are written (positions, normals, triangles, the quadrics), Scene::bounds is the
    // static part's bounds joined with theirs. Allocates nothing. Returns true when the set of
    // valid primitives changed (a moving triangle became degenerate or stopped being so).
    bool setTime(float time);
    float time() const { return time_; }

    // After the reader filled the above (the Scene finalized at some time): the static bounds and
    // the buffers setTime needs; then the scene is put at startTime.
    void prepare();

    // The primitives setTime moves (PrimitiveSet's index space), ascending.
    const std::vector<uint32_t>& movingPrimitives() const { return moving_; }
    // The valid primitives that never move, ascending.
    const std::vector<uint32_t>& staticPrimitives() const { return staticValid_; }

private:
    void rebuildValidPrimitives();

    float time_ = 0.0f;
    std::vector<glm::dmat4> nodeMatrices_;
    std::vector<uint32_t> moving_;
    std::vector<uint8_t> movingValid_;   // per moving primitive
    std::vector<uint32_t> staticValid_;  // the valid primitives that never move, ascending
    Bounds3 staticBounds_;
};

}  // namespace bvhlab
