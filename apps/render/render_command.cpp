// `bvhlab render`: load, build, render, write PATH.exr/.png/.json and print the statistics row.
#include "apps/cli/commands.h"

#include "accel/registry.h"
#include "apps/cli/command_line.h"
#include "apps/runtime/accel_config.h"
#include "apps/runtime/app_keys.h"
#include "apps/runtime/build_accelerator.h"
#include "apps/runtime/output_paths.h"
#include "apps/runtime/progress.h"
#include "apps/runtime/render_with_progress.h"
#include "apps/runtime/run_record.h"
#include "apps/runtime/scene_choice.h"
#include "apps/runtime/scene_loading.h"
#include "framework/io/heatmap.h"
#include "framework/io/image_io.h"
#include "framework/render/camera.h"
#include "framework/render/renderer.h"
#include "framework/report/provenance.h"
#include "framework/report/statistics.h"

#include <fmt/core.h>

#include <fstream>

namespace bvhlab {

void addRenderCommand(CLI::App& app) {
    struct Options {
        EnvOptions env;
        std::string scene, sceneEnv;
        std::string out = "out/render";
    };
    auto options = std::make_shared<Options>();
    CLI::App* command = app.add_subcommand("render", "render a scene and print its statistics row");
    addEnvOptions(*command, options->env);
    addThreadsOption(*command, options->env);
    command->add_option("--scene", options->scene,
                        "scene file, or NAME for env/scenes/NAME.env (default: Scene::file, else the embedded scene); "
                        "a file that an env/scenes/ file names is seen with that file's camera and lights");
    command->add_option("--scene-env", options->sceneEnv,
                        "the scene's env file (camera, lights), layered on env/global.env");
    command->add_option("--out", options->out, "output path without extension: writes PATH.exr, PATH.png, PATH.json")
        ->capture_default_str();
    command->callback([options] {
        const int code = runGuarded([&] {
            const SceneChoice choice = chooseScene(options->scene, options->sceneEnv, options->env);
            const Env env = choice.load(options->env);
            for (const std::string& warning : unreadKeyWarnings({parseAccelConfig(env.get(keys::ASDS::type))}, env))
                fmt::print(stderr, "warning: {}\n", warning);
            const std::filesystem::path out = prepareOutputFile(options->out);
            if (!choice.envFile.empty()) fmt::print(stderr, "scene env: {}\n", choice.envFile.string());

            Progress progress;
            progress.phase("loading the scene");
            const Scene scene = loadSceneFor(env);
            progress.phase(fmt::format("building {}", env.get(keys::ASDS::type)));
            const BuiltAccelerator built = buildAccelerator(scene, env);
            progress.finish();
            const Camera camera(resolveCamera(scene, env));
            const RenderSettings settings = RenderSettings::fromEnv(env, scene, camera.spec());
            Framebuffer fb(camera.width(), camera.height());
            const RenderStats stats = renderWithProgress(scene, *built.accel, camera, settings, fb, progress,
                                                         fmt::format("rendering {}x{}", fb.width, fb.height));

            if (env.get(keys::Output::exr)) writeExr(out.string() + ".exr", fb);
            if (env.get(keys::Output::png)) writePng(out.string() + ".png", fb);
            nlohmann::json heatmap;  // for the JSON: the heat map's file and scale, or why there is none
            if (env.get(keys::Output::heatmap)) {
                const HeatmapScale scale =
                    chooseHeatmapScale(env.get(keys::Output::heatmapScale), heatmapPercentile99(fb.traversalSteps),
                                       "99th percentile of this image");
                heatmap = writeHeatmap(out.string() + ".heatmap.png", out.string() + ".heatmap.png", fb.traversalSteps,
                                       fb.width, fb.height, built.accel->hasCounters(), built.accel->name(), scale);
                fmt::print(stderr, "{}\n", heatmapNote(heatmap));
            }
            const StatsRow row{scene.name,   std::string(built.accel->name()), scene.primitiveCount(),
                               scene.report, built.accel->hasCounters(),       built.stats,
                               stats};
            nlohmann::json json = statsJson(row);
            json["image"] = {{"width", fb.width}, {"height", fb.height}, {"samples", settings.samples}};
            json["scene_file"] = sceneFileJson(scene);
            json["run"] = runJson();
            json["env_files"] = options->env.files(choice.envFile);
            json["env"] = env.toJson();
            json["provenance"] = provenanceJson();
            if (!heatmap.is_null()) json["heatmap"] = heatmap;
            std::ofstream(out.string() + ".json") << json.dump(2) << "\n";
            fmt::print("{}\n", formatStatsTable(row));
            fmt::print(stderr, "wrote {}.{{exr,png,json}}\n", out.string());
        });
        if (code != 0) throw CLI::RuntimeError(code);
    });
}

}  // namespace bvhlab
