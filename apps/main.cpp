// bvhlab: build, trace and measure bounding volume hierarchies.
#include "apps/commands.h"

int main(int argc, char** argv) {
    CLI::App app("bvhlab: a research ray tracer for building, measuring and comparing BVHs");
    app.require_subcommand(1);
    bvhlab::addRenderCommand(app);
    bvhlab::addRaycastCommand(app);
    bvhlab::addBenchCommand(app);
    bvhlab::addBatchCommand(app);
    bvhlab::addStressCommand(app);
    bvhlab::addTradeoffCommand(app);
    bvhlab::addKeysCommand(app);
    CLI11_PARSE(app, argc, argv);
    return 0;
}
