// `bvhlab rays`: the ray sets the bench traces (primary, shadow, incoherent; apps/runtime/ray_sets.h)
// of a scene's camera and lights, written as a BVHRAYS1 file for `bvhlab raycast` or a
// structure of one's own.
#include "apps/cli/command_line.h"
#include "apps/cli/commands.h"
#include "apps/runtime/progress.h"
#include "apps/runtime/ray_sets.h"
#include "apps/runtime/scene_choice.h"
#include "framework/io/ray_file.h"

#include <fmt/core.h>

namespace bvhlab {

void addRaysCommand(CLI::App& app) {
    struct Options {
        EnvOptions env;
        std::string scene, kind = "primary", out;
    };
    auto options = std::make_shared<Options>();
    CLI::App* command = app.add_subcommand(
        "rays", "write the bench's rays of a scene (primary, shadow or incoherent) as a BVHRAYS1 file for raycast");
    addEnvOptions(*command, options->env);
    addThreadsOption(*command, options->env);
    command->add_option("--scene", options->scene,
                        "scene file, or NAME for env/scenes/NAME.env (default: Scene::file, else the embedded scene)");
    command
        ->add_option("--kind", options->kind,
                     "primary: through the pixel centres; shadow: from their hits to each light; incoherent: "
                     "cosine-distributed bounces from their hits (shadow and incoherent are any-hit queries: "
                     "raycast --any)")
        ->check(CLI::IsMember({"primary", "shadow", "incoherent"}))
        ->capture_default_str();
    command->add_option("--out", options->out, "output rays (BVHRAYS1)")->required();
    command->callback([options] {
        const int code = runGuarded([&] {
            Progress progress;
            const auto [env, scene] = loadChosenScene(options->scene, options->env, options->out, progress);
            progress.phase("making the rays");
            const std::vector<Ray> rays = benchRays(scene, env, options->kind);
            writeRayFile(options->out, rays);
            fmt::print(stderr, "wrote {} {} rays of {} to {}{}\n", rays.size(), options->kind, scene.name, options->out,
                       options->kind == "primary" ? "" : " (any-hit queries: raycast --any)");
        });
        if (code != 0) throw CLI::RuntimeError(code);
    });
}

}  // namespace bvhlab
