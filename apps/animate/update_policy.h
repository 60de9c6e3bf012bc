// How a structure follows an animation from frame to frame (Animate::policy; docs/animation.md):
// - rebuild: a new build over the frame's primitives, every frame;
// - refit: the structure's own update (our BVHs by BVH::update: a refit, or a refit and the
//   insertion optimiser; Embree at Embree::quality=refit), never a rebuild;
// - adaptive: refit, but rebuild instead when the SAH of the last refitted tree has grown past
//   Animate::sahGrowth times that of the last build, or Animate::rebuildEvery frames after it.
//   Reading the SAH is part of its update time (it is what the policy decides by);
// - twolevel: a structure per rigid part and one over the animated triangles, under a top level
//   (framework/scene/scene_instances.h); a frame moves the instances and updates the deforming one.
// Any policy but twolevel rebuilds on a frame whose set of valid primitives changed (a moving
// triangle became degenerate): no update can keep counts that changed. Two levels build their
// instances over primitive sets of their own, which no frame changes.
#pragma once

#include "framework/config/env.h"
#include "framework/core/error.h"
#include "framework/core/instanced_accelerator.h"
#include "framework/scene/animated_scene.h"
#include "framework/scene/scene_instances.h"

#include <memory>
#include <optional>
#include <string>

namespace bvhlab {

enum class UpdatePolicy { Rebuild, Refit, Adaptive, TwoLevel };
UpdatePolicy parseUpdatePolicy(const std::string& name);  // one of keys::Animate::kPolicies
const char* toString(UpdatePolicy policy);

// What a frame's update did: the first frame builds; then a rebuild, a refit (the structure's
// update), or a move of the instances (two levels).
enum class FrameAction { Build, Rebuild, Refit, Move };
const char* toString(FrameAction action);

struct FrameUpdate {
    FrameAction action = FrameAction::Build;
    BuildStats stats;  // the structure's statistics after the update; buildMs, buildCpuMs: T_update
};

// What start() throws for a structure that cannot refit (no update at its settings): a
// combination to skip, not a failure.
class NoUpdateError : public InputError {
public:
    using InputError::InputError;
};

// A structure kept at the animation's current time by a policy.
class AnimatedStructure {
public:
    // The accelerator `accelName` made with `env`, which also gives the policy and its keys.
    // Twolevel puts `accelName` under each instance (Embree's instances for embree). Keeps a
    // reference to `animated`.
    AnimatedStructure(const AnimatedScene& animated, const std::string& accelName, const Env& env);
    ~AnimatedStructure();

    // At the scene's current time: the first build. Refit and adaptive then check that the
    // structure has an update (an untimed update over the same primitives) and throw
    // NoUpdateError naming it when it has none.
    FrameUpdate start();
    // After AnimatedScene::setTime, whose answer is `validChanged`: the policy's update.
    FrameUpdate advance(bool validChanged);

    const Accelerator& accelerator() const { return *accel_; }
    UpdatePolicy policy() const { return policy_; }

private:
    FrameUpdate rebuild(FrameAction action);
    FrameUpdate refit(bool readSah);

    const AnimatedScene& animated_;
    std::string name_;
    UpdatePolicy policy_;
    double sahGrowth_;
    int rebuildEvery_;
    std::unique_ptr<SceneInstances> instances_;  // twolevel
    std::unique_ptr<Accelerator> accel_;
    InstancedAccelerator* instanced_ = nullptr;  // accel_ as two levels
    double builtSah_ = 0.0, lastSah_ = 0.0;      // adaptive: at the last build, after the last refit
    int framesSinceBuild_ = 0;
};

}  // namespace bvhlab
