// `bvhlab raycast`: answer a file of rays with the chosen accelerator and write the hits.
#include "accel/registry.h"
#include "apps/cli/command_line.h"
#include "apps/cli/commands.h"
#include "apps/runtime/build_accelerator.h"
#include "apps/runtime/progress.h"
#include "apps/runtime/scene_choice.h"
#include "apps/runtime/trace_rays.h"
#include "framework/config/common_keys.h"
#include "framework/io/ray_file.h"

#include <fmt/core.h>
#include <chrono>

namespace bvhlab {

void addRaycastCommand(CLI::App& app) {
    struct Options {
        EnvOptions env;
        std::string scene, rays, out;
        bool any = false;
        bool coherent = false;
        bool count = false;
    };
    auto options = std::make_shared<Options>();
    CLI::App* command = app.add_subcommand("raycast", "answer every ray of a BVHRAYS1 file, write a BVHHITS1 file");
    addEnvOptions(*command, options->env);
    addThreadsOption(*command, options->env);
    command->add_option("--scene", options->scene,
                        "scene file, or NAME for env/scenes/NAME.env (default: Scene::file, else the embedded scene)");
    command->add_option("--rays", options->rays, "input rays (BVHRAYS1)")->required();
    command->add_option("--out", options->out, "output hits (BVHHITS1)")->required();
    command->add_flag("--any", options->any, "any-hit queries (isOccluded) instead of closest hit");
    command->add_flag("--coherent", options->coherent,
                      "the rays are a coherent batch (a camera's rays row by row, shadow rays towards a light: "
                      "`bvhlab rays --kind primary` or `shadow`), the hint the batch calls pass on; without it, "
                      "incoherent. The answers are the same either way");
    command->add_flag("--count", options->count,
                      "also print N_IT and N_TR: the rays answered again, untimed, with counting on (the timed pass "
                      "and the hits written count nothing)");
    command->callback([options] {
        const int code = runGuarded([&] {
            Progress progress;
            const auto [env, scene] = loadChosenScene(options->scene, options->env, options->out, progress);
            progress.phase(fmt::format("building {}", env.get(keys::ASDS::type)));
            const BuiltAccelerator built = buildAccelerator(scene, env);
            const std::vector<Ray> rays = readRayFile(options->rays);
            progress.phase(fmt::format("tracing {} rays", rays.size()),
                           (rays.size() + kRaysPerRange - 1) / kRaysPerRange);
            const int threads = env.get(keys::SetRayTracing::threads);
            const RayCoherence coherence = options->coherent ? RayCoherence::Coherent : RayCoherence::Incoherent;
            std::vector<Hit> hits(rays.size());
            std::vector<uint8_t> occluded(options->any ? rays.size() : 0);

            // The timed pass counts nothing, so that its time (and an instruction count of the
            // whole run) is the form of the queries that counts nothing.
            const auto start = std::chrono::steady_clock::now();
            const QueryCounters timed =
                traceRays(*built.accel, rays, options->any, coherence, threads, /*counting=*/false,
                          {hits, occluded, {}}, [&](size_t traced) { progress.advance(1, traced); });
            const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            progress.finish();
            const double n = std::max<double>(1.0, double(timed.queries));
            std::string counts;
            if (options->count) {
                // Answers of their own, so the file holds the timed pass's whatever the counting one answers.
                progress.phase("counting");
                std::vector<Hit> countedHits(options->any ? 0 : rays.size());
                std::vector<uint8_t> countedOccluded(occluded.size());
                const QueryCounters total = traceRays(*built.accel, rays, options->any, coherence, threads,
                                                      /*counting=*/true, {countedHits, countedOccluded, {}});
                progress.finish();
                const bool counted = built.accel->hasCounters();
                for (const QueryCounter& c : kQueryCounters)
                    if (c.column)
                        counts += fmt::format("  {} {}", c.column,
                                              counted ? fmt::format("{:.2f}", double(total.*c.count) / n) : "n/a");
            }
            // An any-hit answer is written as a hit at t = 0 on primitive 0 (docs/file-formats.md).
            for (size_t i = 0; i < occluded.size(); ++i)
                if (occluded[i]) hits[i] = {0.0f, 0, 0.0f, 0.0f};
            writeHitFile(options->out, hits);
            fmt::print("{} {} queries: {}{}  T_R {:.3f} us (wall time / queries)\n", built.accel->name(),
                       options->any ? "any-hit" : "closest-hit", timed.queries, counts, seconds * 1e6 / n);
        });
        if (code != 0) throw CLI::RuntimeError(code);
    });
}

}  // namespace bvhlab
