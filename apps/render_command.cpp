// `bvhlab render`: load, build, render, write PATH.exr/.png/.json and print the statistics row.
#include "apps/commands.h"

#include "apps/cli_common.h"
#include "framework/camera.h"
#include "framework/heatmap.h"
#include "framework/image_io.h"
#include "framework/provenance.h"
#include "framework/renderer.h"
#include "framework/statistics.h"

#include <fmt/core.h>

#include <fstream>

namespace bvhlab {

void addRenderCommand(CLI::App& app) {
    struct Options {
        EnvOptions env;
        std::string scene;
        std::string out = "render";
    };
    auto options = std::make_shared<Options>();
    CLI::App* command = app.add_subcommand("render", "render a scene and print its statistics row");
    options->env.addTo(*command);
    command->add_option("--scene", options->scene, "scene file (default: Scene::file, else the embedded scene)");
    command->add_option("--out", options->out, "output path without extension: writes PATH.exr, PATH.png, PATH.json")
        ->capture_default_str();
    command->callback([options] {
        const int code = runGuarded([&] {
            const Env env = options->env.load();
            const Scene scene = loadSceneFor(options->scene, env);
            const BuiltAccelerator built = buildAccelerator(scene, env);
            const Camera camera(resolveCamera(scene, env));
            const RenderSettings settings = RenderSettings::fromEnv(env, scene, camera.spec());
            Framebuffer fb(camera.width(), camera.height());
            const RenderStats stats = render(scene, *built.accel, camera, settings, fb);

            const std::filesystem::path out = options->out;
            if (out.has_parent_path()) std::filesystem::create_directories(out.parent_path());
            if (env.getBool("Output::exr")) writeExr(out.string() + ".exr", fb);
            if (env.getBool("Output::png")) writePng(out.string() + ".png", fb);
            nlohmann::json heatmap;  // for the JSON: the heat map's file and scale, or why there is none
            if (env.getBool("Output::heatmap")) {
                const HeatmapScale scale = chooseHeatmapScale(env.getFloat("Output::heatmapScale"),
                                                              heatmapPercentile99(fb.traversalSteps),
                                                              "99th percentile of this image");
                heatmap = writeHeatmap(out.string() + ".heatmap.png", out.string() + ".heatmap.png", fb.traversalSteps,
                                       fb.width, fb.height, built.accel->hasCounters(), built.accel->name(), scale);
                fmt::print(stderr, "{}\n", heatmapNote(heatmap));
            }
            const StatsRow row{scene.name, std::string(built.accel->name()), scene.triangleCount(),
                               scene.report.degenerateTriangles, built.accel->hasCounters(), built.stats, stats};
            nlohmann::json json = statsJson(row);
            json["image"] = {{"width", fb.width}, {"height", fb.height}, {"samples", settings.samples}};
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
