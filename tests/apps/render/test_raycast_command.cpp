// `bvhlab raycast` answers with counting off, so that its T_R and an instruction count of a run
// (docs/plots/count_instructions.sh) are of the queries that count nothing; `--count` adds N_IT
// and N_TR of a counting pass over the same rays, and leaves the hits written as they were.
#include "accel/registry.h"
#include "apps/runtime/program_keys.h"
#include "apps/runtime/trace_rays.h"
#include "framework/io/ray_file.h"
#include "framework/render/camera.h"
#include "framework/scene/procedural.h"
#include "tests/support/cli_run.h"
#include "tests/support/scratch_dir.h"

#include <fmt/core.h>
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

namespace bvhlab {
namespace {

std::string fileBytes(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

TEST(RaycastCommand, CountsOnlyWhenAskedAsACountingPass) {
    const std::filesystem::path dir = test::scratchDir("raycast_command");
    const Scene scene = makeDefaultScene();
    CameraSpec spec = *scene.camera;
    spec.width = 40;
    spec.height = 30;
    const Camera camera(spec);
    std::vector<Ray> rays;
    for (int y = 0; y < spec.height; ++y)
        for (int x = 0; x < spec.width; ++x) rays.push_back(camera.generateRay(float(x) + 0.5f, float(y) + 0.5f));
    const auto raysFile = dir / "rays.bin";
    writeRayFile(raysFile, rays);

    for (const std::string name : {"sahbvh8", "naive"})
        for (const bool any : {false, true}) {
            SCOPED_TRACE(name + (any ? " --any" : ""));
            // The embedded scene and the registry's defaults, as the structure built here.
            const std::string args = fmt::format("raycast --no-global-env --threads 1 -DASDS::type={} --rays {}{}",
                                                 name, raysFile.string(), any ? " --any" : "");
            const test::Result timed = test::run(args + " --out " + (dir / "timed.hits").string());
            ASSERT_EQ(timed.exitCode, 0) << timed.output;
            EXPECT_NE(timed.output.find(fmt::format(" queries: {}  T_R ", rays.size())), std::string::npos)
                << timed.output;
            EXPECT_EQ(timed.output.find("N_IT"), std::string::npos) << timed.output;

            const test::Result counted = test::run(args + " --count --out " + (dir / "counted.hits").string());
            ASSERT_EQ(counted.exitCode, 0) << counted.output;
            const auto accel = createAccelerator(name, Env(programKeys()));
            accel->build(scene.primitives());
            std::vector<Hit> hits(rays.size());
            std::vector<uint8_t> occluded(any ? rays.size() : 0);
            const QueryCounters expected =
                traceRays(*accel, rays, any, RayCoherence::Incoherent, 1, /*counting=*/true, {hits, occluded, {}});
            EXPECT_GT(expected.traversalSteps, 0u);
            const double n = double(rays.size());
            EXPECT_NE(counted.output.find(fmt::format(" queries: {}  N_IT {:.2f}  N_TR {:.2f}  T_R ", rays.size(),
                                                      expected.intersectionTests / n, expected.traversalSteps / n)),
                      std::string::npos)
                << counted.output;
            EXPECT_EQ(fileBytes(dir / "timed.hits"), fileBytes(dir / "counted.hits"));
        }
}

}  // namespace
}  // namespace bvhlab
