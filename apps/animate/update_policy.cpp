#include "apps/animate/update_policy.h"

#include "accel/registry.h"
#include "apps/runtime/app_keys.h"
#include "framework/core/error.h"
#include "framework/core/timed_build.h"

#include <fmt/format.h>

#include <iterator>

namespace bvhlab {

UpdatePolicy parseUpdatePolicy(const std::string& name) {
    for (size_t i = 0; i < std::size(keys::Animate::kPolicies); ++i)
        if (name == keys::Animate::kPolicies[i]) return UpdatePolicy(i);
    throw InputError(fmt::format("unknown policy '{}' (rebuild, refit, adaptive or twolevel)", name));
}

const char* toString(UpdatePolicy policy) { return keys::Animate::kPolicies[size_t(policy)].data(); }

const char* toString(FrameAction action) {
    switch (action) {
        case FrameAction::Build:
            return "build";
        case FrameAction::Rebuild:
            return "rebuild";
        case FrameAction::Refit:
            return "refit";
        case FrameAction::Move:
            break;
    }
    return "move";
}

AnimatedStructure::AnimatedStructure(const AnimatedScene& animated, const std::string& accelName, const Env& env)
    : animated_(animated),
      name_(accelName),
      policy_(parseUpdatePolicy(env.get(keys::Animate::policy))),
      sahGrowth_(env.get(keys::Animate::sahGrowth)),
      rebuildEvery_(env.get(keys::Animate::rebuildEvery)) {
    if (policy_ == UpdatePolicy::TwoLevel) {
        instances_ = std::make_unique<SceneInstances>(animated);
        std::unique_ptr<InstancedAccelerator> instanced = createInstanced(instances_->instances(), accelName, env);
        instanced_ = instanced.get();
        accel_ = std::move(instanced);
    } else {
        accel_ = createAccelerator(accelName, env);
    }
}

AnimatedStructure::~AnimatedStructure() = default;

FrameUpdate AnimatedStructure::start() {
    FrameUpdate first = rebuild(FrameAction::Build);
    if (policy_ == UpdatePolicy::Refit || policy_ == UpdatePolicy::Adaptive) {
        if (!accel_->update(animated_.scene.primitives()))
            throw NoUpdateError(
                fmt::format("{} has no update at its settings, which policy {} needs (for Embree: "
                            "Embree::quality=refit)",
                            name_, toString(policy_)));
        // The refitted tree's statistics, which the next frames start from, with the build's time.
        const BuildStats built = first.stats;
        first.stats = statisticsOf(*accel_);
        first.stats.buildMs = built.buildMs;
        first.stats.buildCpuMs = built.buildCpuMs;
        builtSah_ = lastSah_ = first.stats.sah ? first.stats.sah->cost : 0.0;
    }
    return first;
}

FrameUpdate AnimatedStructure::advance(bool validChanged) {
    // Two levels keep their instances' primitive sets whatever the world's validity (see
    // scene_instances.h): a frame moves them.
    if (validChanged && policy_ != UpdatePolicy::TwoLevel) return rebuild(FrameAction::Rebuild);
    switch (policy_) {
        case UpdatePolicy::Rebuild:
            return rebuild(FrameAction::Rebuild);
        case UpdatePolicy::Refit:
            return refit(false);
        case UpdatePolicy::Adaptive: {
            // Decided by the last refit's SAH, so that no refit is made only to be thrown away.
            const bool grown = builtSah_ > 0.0 && lastSah_ > sahGrowth_ * builtSah_;
            const bool due = rebuildEvery_ > 0 && framesSinceBuild_ + 1 >= rebuildEvery_;  // this frame is K after
            return grown || due ? rebuild(FrameAction::Rebuild) : refit(true);
        }
        case UpdatePolicy::TwoLevel:
            break;
    }
    ++framesSinceBuild_;
    return {FrameAction::Move,
            timedChange(*accel_, [&] { instanced_->moveInstances(instances_->transforms(), instances_->deformed()); })};
}

FrameUpdate AnimatedStructure::rebuild(FrameAction action) {
    FrameUpdate update{action, timedBuild(*accel_, animated_.scene.primitives())};
    framesSinceBuild_ = 0;
    builtSah_ = lastSah_ = update.stats.sah ? update.stats.sah->cost : 0.0;
    return update;
}

FrameUpdate AnimatedStructure::refit(bool readSah) {
    std::optional<BuildStats> stats = timedUpdate(*accel_, animated_.scene.primitives(), readSah);
    if (!stats) throw InputError(fmt::format("{}: its update refused a frame", name_));
    ++framesSinceBuild_;
    lastSah_ = stats->sah ? stats->sah->cost : 0.0;
    return {FrameAction::Refit, *stats};
}

}  // namespace bvhlab
