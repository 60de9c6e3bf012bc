// Loading plugins end to end (apps/runtime/plugins.h): refused with an error naming the file and
// why, errors thrown inside a plugin reported with the plugin and the accelerator, found by
// name in the plugin folders, listed by `bvhlab keys` and in the JSON provenance with how they
// were compiled, a warning when not optimised.
#include "tests/support/cli_run.h"
#include "tests/support/scratch_dir.h"
#include "tests/support/test_paths.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <csignal>
#include <fstream>
#include <regex>

namespace bvhlab::test {
namespace {

const std::string kPlugins = test::testPlugins();
const std::string kThrowing = kPlugins + "/throwing.so";
const std::string kBuilders = kPlugins + "/builders.so";
const std::string kCrashing = kPlugins + "/crashing.so";
const std::string kUnoptimized = kPlugins + "/throwing_unoptimized.so";
// The test plugins but throwing_unoptimized.so are compiled as this file is, but for the sanitizer
// build, which compiles them at -O1 and the test sources at -O0 (tests/CMakeLists.txt).
#if defined(__OPTIMIZE__) || defined(__SANITIZE_ADDRESS__)
constexpr bool kPluginsOptimized = true;
#else
constexpr bool kPluginsOptimized = false;
#endif
constexpr std::string_view kUnoptimizedWarning = "was compiled without optimisation";

// A small render of the default scene, into a scratch folder.
Result render(const std::string& args) {
    const std::filesystem::path image = scratchDir("plugins") / "image";
    std::filesystem::remove(image.string() + ".json");
    return run("render -DCamera::width=16 -DCamera::height=12 " + args + " --out " + image.string());
}

// The statistics JSON of the last render().
nlohmann::json renderedJson() {
    std::ifstream in((scratchDir("plugins") / "image").string() + ".json");
    return nlohmann::json::parse(in);
}

// changed_abi.so is throwing.so compiled against the plugin API with a float added to Ray.
TEST(Plugins, APluginBuiltAgainstAnotherAbiIsRefusedNamingBothAndWhereTheyDiffer) {
    const Result r = render("--plugin " + kPlugins + "/changed_abi.so -DASDS::type=throwing");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_TRUE(std::regex_search(r.output, std::regex("changed_abi.so: built against another ABI \\(plugin ABI "
                                                       "[0-9a-f]{16}, bvhlab ABI [0-9a-f]{16}\\): it was built "
                                                       "against other headers \\(")))
        << r.output;
    EXPECT_NE(r.output.find("sizeof(Ray) is 36 in the plugin, 32 in bvhlab"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("field count of Ray is 5 in the plugin, 4 in bvhlab"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("rebuild it against this bvhlab's include/bvhlab"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("build() threw"), std::string::npos) << "it was called: " << r.output;
}

// swapped_enum.so is throwing.so compiled against the plugin API with KeyType's Int and Float
// swapped: its Int key would be read as a Float.
TEST(Plugins, APluginBuiltWithOtherEnumValuesIsRefusedNamingThem) {
    const Result r = render("--plugin " + kPlugins + "/swapped_enum.so -DASDS::type=throwing");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("swapped_enum.so: built against another ABI"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("it was built against other headers (KeyType::Int is 2 in the plugin, 1 in bvhlab; "
                            "KeyType::Float is 1 in the plugin, 2 in bvhlab): rebuild it against this bvhlab's "
                            "include/bvhlab"),
              std::string::npos)
        << r.output;
}

// added_counter.so is scan.so compiled against the plugin API with a query counter added, as
// counters.h says to add one: the same ABI, so bvhlab loads it, and it counts as scan.so does.
TEST(Plugins, APluginBuiltWithAQueryCounterAddedLoadsAndCountsAsBefore) {
    const Result added = render("--plugin " + kPlugins + "/added_counter.so -DASDS::type=scan");
    ASSERT_EQ(added.exitCode, 0) << added.output;
    EXPECT_EQ(added.output.find("another ABI"), std::string::npos) << added.output;
    const nlohmann::json withCounter = renderedJson();
    const Result before = render("--plugin " + kPlugins + "/scan-1/scan.so -DASDS::type=scan");
    ASSERT_EQ(before.exitCode, 0) << before.output;
    const nlohmann::json asBefore = renderedJson();
    EXPECT_GT(withCounter["primary"]["n_it"].get<double>(), 0.0);
    for (const char* query : {"primary", "shadow"}) {
        nlohmann::json counted = withCounter[query], expected = asBefore[query];
        counted.erase("t_r_us"), expected.erase("t_r_us");  // times: not compared
        EXPECT_EQ(counted, expected) << query;
    }
}

TEST(Plugins, APluginOfAnOlderBvhlabIsRefusedAskingForARebuild) {
    const Result r = render("--plugin " + kPlugins + "/older_api.so");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("older_api.so: built for an older bvhlab, whose plugins carry an API version instead of an "
                            "ABI: rebuild it"),
              std::string::npos)
        << r.output;
}

TEST(Plugins, AFileThatIsNotAPluginIsRefused) {
    const auto text = scratchDir("plugins") / "not_a_plugin.so";
    std::ofstream(text) << "hello\n";
    Result r = render("--plugin " + text.string());
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("not_a_plugin.so: cannot load as a plugin"), std::string::npos) << r.output;

    // A shared library, but not a plugin: the program's own dependency.
    r = render("--plugin /lib/x86_64-linux-gnu/libz.so.1");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("not a bvhlab plugin"), std::string::npos) << r.output;

    r = render("--plugin /no/such/plugin.so");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("/no/such/plugin.so: plugin file not found"), std::string::npos) << r.output;
}

TEST(Plugins, ExceptionsInsideAPluginNameThePluginAndTheAccelerator) {
    Result r = render("--plugin " + kThrowing + " -DASDS::type=throwing");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("throwing.so, accelerator 'throwing': build() threw: no build today"), std::string::npos)
        << r.output;

    r = render("--plugin " + kThrowing + " -DASDS::type=throwing_query");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("accelerator 'throwing_query': findNearestBatch() threw: no queries today"),
              std::string::npos)
        << r.output;

    r = render("--plugin " + kThrowing + " -DASDS::type=throwing_factory");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("accelerator 'throwing_factory': its factory threw: no accelerator today"),
              std::string::npos)
        << r.output;

    r = render("--plugin " + kThrowing + " -DASDS::type=throwing_misread");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(
        r.output.find("accelerator 'throwing_misread': its factory threw: accelerator 'throwing_misread' read the "
                      "Int key 'Throwing::count' with getFloat: read it with getInt"),
        std::string::npos)
        << r.output;
}

// How a process that received SIGSEGV ends: by the signal, or under AddressSanitizer, whose
// handler runs after bvhlab's report, with its exit code 1.
#ifdef __SANITIZE_ADDRESS__
constexpr int kEndedBySegv = 1;
#else
constexpr int kEndedBySegv = 128 + SIGSEGV;
#endif

TEST(Plugins, ACrashInsideAPluginNamesThePluginTheCallAndItsRayAndEndsTheRunByTheSignal) {
    Result r = render("--plugin " + kCrashing + " -DASDS::type=crashing");
    EXPECT_EQ(r.exitCode, kEndedBySegv) << r.output;
    EXPECT_NE(r.output.find("bvhlab: SIGSEGV (Segmentation fault) in plugin " + kCrashing +
                            ", accelerator 'crashing': findNearestBatch() of "),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find(" rays, the first org=("), std::string::npos) << r.output;

    // A stack overflow too (on a signal stack of its own), under the usual stack limit.
    r = runShell("ulimit -s 8192; " + test::bvhlabProgram() +
                 " render -DCamera::width=16 -DCamera::height=12 --plugin " + kCrashing +
                 " -DASDS::type=crashing_build --out " + (scratchDir("plugins") / "image").string());
    EXPECT_EQ(r.exitCode, kEndedBySegv) << r.output;
    EXPECT_NE(r.output.find("accelerator 'crashing_build': build() over "), std::string::npos) << r.output;
}

TEST(Plugins, AnAcceleratorIsFoundByNameInThePluginFolders) {
    Result r = runShell("BVHLAB_PLUGIN_PATH=/nowhere:" + kPlugins + " " + test::bvhlabProgram() +
                        " render -DCamera::width=16 -DCamera::height=12 -DASDS::type=throwing --out " +
                        (scratchDir("plugins") / "image").string());
    EXPECT_NE(r.output.find("accelerator 'throwing': build() threw"), std::string::npos) << r.output;

    r = render("-DASDS::type=throwing");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("unknown accelerator 'throwing'"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("no throwing.so in the plugin folders"), std::string::npos) << r.output;
}

TEST(Plugins, AnEnvFileLoadsPluginsRelativeToItsFolder) {
    const auto dir = scratchDir("plugins_env");
    std::ofstream(dir / "plugin.env") << "ASDS::plugins " << std::filesystem::relative(kThrowing, dir).string()
                                      << "\nASDS::type throwing\nThrowing::unused 4\n";
    const Result r = render("--env " + (dir / "plugin.env").string());
    EXPECT_NE(r.output.find("accelerator 'throwing': build() threw"), std::string::npos) << r.output;
}

TEST(Plugins, AMissingPluginOfAnEnvFileNamesTheFileAndLine) {
    const auto dir = scratchDir("plugins_env_missing");
    std::ofstream(dir / "plugin.env") << "# a plugin that is not there\nASDS::plugins no_such_plugin.so\n";
    const Result r = render("--env " + (dir / "plugin.env").string());
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find((dir / "plugin.env").string() + ":2: ASDS::plugins: no plugin file " +
                            (dir / "no_such_plugin.so").string()),
              std::string::npos)
        << r.output;
}

// As the commands would find them by name: the plugins bvhlab ships, and those on BVHLAB_PLUGIN_PATH
// (a file that does not load is left out with a warning).
TEST(Plugins, KeysListsTheShippedPluginsAndThoseOnThePluginPath) {
    Result r = run("keys");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    for (const std::string name : {"grid", "octree", "kdtree"}) {
        const size_t row = r.output.find("| `" + name + "` | ");
        ASSERT_NE(row, std::string::npos) << name << "\n" << r.output;
        EXPECT_NE(r.output.find("(plugin `" + name + ".so`, shipped with bvhlab)", row), std::string::npos) << name;
    }
    r = runShell("BVHLAB_PLUGIN_PATH=" + kPlugins + " " + test::bvhlabProgram() + " keys");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("| `crashing` | "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("(plugin `" + kCrashing + "`)"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("| `grid` | "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("warning: " + kPlugins + "/older_api.so is not listed: "), std::string::npos) << r.output;
}

// A file on BVHLAB_PLUGIN_PATH named as a shipped plugin does not replace it unseen.
TEST(Plugins, APluginOnThePathNamedAsAShippedOneIsRefusedNamingBoth) {
    const auto dir = scratchDir("plugins_named_as_shipped");
    std::filesystem::copy_file(kThrowing, dir / "grid.so", std::filesystem::copy_options::overwrite_existing);
    const Result r =
        runShell("BVHLAB_PLUGIN_PATH=" + dir.string() + " " + test::bvhlabProgram() +
                 " render -DASDS::type=grid -DCamera::width=16 -DCamera::height=12 --out " + (dir / "image").string());
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find((dir / "grid.so").string() + " (on BVHLAB_PLUGIN_PATH) has the name of a plugin bvhlab "
                                                         "ships, "),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("plugins/grid.so: which one 'grid' means is not clear"), std::string::npos) << r.output;
}

TEST(Plugins, KeysListsAPluginsAcceleratorsAndKeysWithItsFile) {
    const Result r = run("keys --plugin " + kThrowing);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("| `throwing_query` | throws in its queries (plugin `" + kThrowing + "`)"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("| `Throwing::unused` | int 1..9 | `3` |"), std::string::npos) << r.output;
}

TEST(Plugins, TheJsonProvenanceNamesEveryPluginLoaded) {
    const Result r = render("-DASDS::type=naive --plugin " + kThrowing);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const nlohmann::json provenance = renderedJson()["provenance"];
    const nlohmann::json plugins = provenance["plugins"];
    ASSERT_EQ(plugins.size(), 1u) << plugins.dump();
    EXPECT_EQ(plugins[0]["path"], kThrowing);
    EXPECT_TRUE(std::regex_match(plugins[0]["abi"].get<std::string>(), std::regex("[0-9a-f]{16}"))) << plugins.dump();
    EXPECT_EQ(plugins[0]["crc32"].get<std::string>().size(), 8u);
    EXPECT_EQ(plugins[0]["accelerators"],
              nlohmann::json({"throwing", "throwing_query", "throwing_factory", "throwing_misread"}));
    // How it was compiled: the compiler as bvhlab's own provenance names it, the flags
    // bvhlab_record_plugin_flags passed (with the one bvhlab::plugin_api carries).
    EXPECT_EQ(plugins[0]["compiler"], provenance["compiler"]);
    EXPECT_NE(plugins[0]["cxx_flags"].get<std::string>().find("-ffp-contract=off"), std::string::npos)
        << plugins.dump();
    EXPECT_EQ(plugins[0]["optimized"], kPluginsOptimized);
    if (kPluginsOptimized) {
        EXPECT_EQ(r.output.find(kUnoptimizedWarning), std::string::npos) << r.output;
    }
}

TEST(Plugins, APluginCompiledWithoutOptimisationIsMeasuredWithAWarning) {
    const Result r = render("-DASDS::type=naive --plugin " + kUnoptimized);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find(fmt::format("warning: plugin {} {}", kUnoptimized, kUnoptimizedWarning)), std::string::npos)
        << r.output;
    const nlohmann::json plugin = renderedJson()["provenance"]["plugins"][0];
    EXPECT_EQ(plugin["optimized"], false) << plugin.dump();
    EXPECT_NE(plugin["cxx_flags"].get<std::string>().find("-O0"), std::string::npos) << plugin.dump();
}

// Under AddressSanitizer (tests/sanitize.sh) pairs8 alone: the three share the adapter's code up
// to the wide layouts' collapse, and the layouts' traversal runs there in the conformance suite.
#if defined(__SANITIZE_ADDRESS__)
constexpr const char* kPairsTrees[] = {"pairs8"};
#else
constexpr const char* kPairsTrees[] = {"pairs", "pairs4", "pairs8"};
#endif

TEST(Plugins, ABuilderBecomesThreeAcceleratorsThatAnswerAsTheReference) {
    for (const char* name : kPairsTrees) {
        const Result r =
            run(fmt::format("check --plugin {} --accel {} --checks agreement,mixed-primitives", kBuilders, name));
        EXPECT_EQ(r.exitCode, 0) << name << "\n" << r.output;
        EXPECT_NE(r.output.find("all checks passed"), std::string::npos) << r.output;
    }
    const Result keys = run("keys --plugin " + kBuilders);
    EXPECT_NE(keys.output.find("| `pairs8` | pairs's tree"), std::string::npos) << keys.output;
}

TEST(Plugins, ABuilderReadsTheRunsSahConstants) {
    // costed keeps a node of n primitives whole where n <= 2 * cTraversal / cIntersect; its
    // median splits halve the default scene's 7440 triangles down to 7 or 8, then 3 or 4.
    auto largestLeaf = [](const std::string& costs) {
        const Result r = render("--plugin " + kBuilders + " -DASDS::type=costed " + costs);
        EXPECT_EQ(r.exitCode, 0) << r.output;
        return r.exitCode == 0 ? renderedJson()["max_leaf_prims"].get<int>() : 0;
    };
    EXPECT_EQ(largestLeaf(""), 2);  // 1 and 1: splits down to BVH::maxLeaf
    EXPECT_EQ(largestLeaf("-DBVH::cTraversal=5"), 8);
    EXPECT_EQ(largestLeaf("-DBVH::cTraversal=5 -DBVH::cIntersect=2.5"), 4);
}

TEST(Plugins, ABuilderThatBreaksItsContractFailsTheBuildNamingIt) {
    Result r = render("--plugin " + kBuilders + " -DASDS::type=lossy8");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("accelerator 'lossy8': build() threw: builder 'lossy' changed the primitives"),
              std::string::npos)
        << r.output;
    r = render("--plugin " + kBuilders + " -DASDS::type=twice");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("builder 'twice': its merge tree over"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("uses node"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace bvhlab::test
