// Structures measured through an animation, frame by frame. Each contender (a structure under an
// update policy, update_policy.h) is brought to the frame's time (T_update) and traces the frame's
// primary and shadow rays (T_R, medians of rounds interleaved over the contenders, so that their
// ratios hold on a noisy machine); its statistics (SAH, EPO, bytes) and counters (N_IT, N_TR per
// ray) are read untimed, and on request its answers are checked against Embree's. `bvhlab animate`
// runs many contenders at once, `bvhlab batch` one per job; a contender's record is the one
// docs/animation.md describes.
#pragma once

#include "apps/animate/update_policy.h"
#include "apps/runtime/accel_config.h"
#include "framework/config/env.h"
#include "framework/scene/animated_scene.h"

#include <nlohmann/json.hpp>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace bvhlab {

// Frames as `--frames` and Animate::frames give them: all, or FIRST:END[:STRIDE] (END excluded,
// as Python's slices), within [0, count). Throws InputError naming `source` and the frames there are.
std::vector<int> parseFrames(const std::string& text, int count, const std::string& source);

struct AnimationSettings {
    std::vector<int> frames;  // measured, ascending; the first is built
    int rounds = 1;           // traces of each frame's rays per contender
    bool check = false;       // every answer against Embree's, a double-precision brute force deciding
    int threads = 1;          // of the traces and updates; > 0
};

class AnimationRun {
public:
    // Puts `animated` at the first frame and keeps a reference to it; `base` configures Embree,
    // which makes each frame's rays (and is the reference with `check`), and the camera.
    AnimationRun(AnimatedScene& animated, const Env& base, AnimationSettings settings);
    ~AnimationRun();

    // `config` under `policy`, labelled "ACCEL/POLICY": its env is the base's with the config's
    // overrides, the policy and the threads.
    void addContender(const AccelConfig& config, const std::string& policy);

    // Builds every contender at the first frame, then measures frame by frame. After each frame,
    // `afterFrame` gets its number and the frame's reference structure (Embree over the frame).
    // A contender that throws is failed with the reason and left out of the frames after; one
    // that cannot run its policy (NoUpdateError) is skipped.
    using AfterFrame = std::function<void(int frame, const Accelerator& reference)>;
    void run(const AfterFrame& afterFrame);

    // {"scene", "frames", "threads", "rounds"}: what every contender was measured on.
    nlohmann::json header(const std::filesystem::path& file) const;
    nlohmann::json contenders() const;  // an array, in the order they were added
    size_t failedCount() const;

private:
    struct Contender;
    template <typename Body>
    void guard(Contender& c, Body&& body);
    void measureFrame(size_t f, bool validChanged, const AfterFrame& afterFrame);

    AnimatedScene& animated_;
    Env base_;
    AnimationSettings settings_;
    std::vector<std::unique_ptr<Contender>> contenders_;
};

}  // namespace bvhlab
