// bvhlab.build and the Accelerator it returns: a structure of the registry built over a scene
// (timed as the CLI times it) and its queries over NumPy arrays, the GIL released while they run.
#include "apps/python/python_accelerator.h"
#include "accel/registry.h"
#include "apps/python/bindings.h"
#include "apps/python/numpy_rays.h"
#include "apps/runtime/plugins.h"
#include "apps/runtime/trace_rays.h"
#include "framework/config/common_keys.h"
#include "framework/core/error.h"
#include "framework/core/timed_build.h"
#include "framework/report/build_stats_json.h"

#include <fmt/core.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <limits>

namespace py = pybind11;

namespace bvhlab {
namespace {

// The build statistics under the names of the statistics JSON (buildStatsJson); an unset figure
// (std::optional) is None.
py::object statsDict(const BuildStats& b) {
    nlohmann::json j = buildStatsJson(b);
    j["build_ms"] = b.buildMs;
    j["build_cpu_ms"] = b.buildCpuMs;
    j["primitives"] = b.primitives;
    return pythonFromJson(j);
}

void checkThreads(int threads) {
    if (threads < 0) throw InputError(fmt::format("threads {}: expected 0 (all hardware threads) or more", threads));
}

// FNV-1a of the valid primitives' indices.
uint64_t hashOfValid(const Scene& scene) {
    uint64_t hash = 14695981039346656037ull;
    for (const uint32_t prim : scene.validPrimitives) hash = (hash ^ prim) * 1099511628211ull;
    return hash;
}

PythonAccelerator build(std::shared_ptr<PythonScene> scene, const std::string& name, const py::object& envDict,
                        int threads) {
    if (!loadPluginFor(name)) throw InputError(unknownAcceleratorMessage(name));
    const Env env = envWith(*scene, envDict, threads);
    PythonAccelerator built{scene,        createAccelerator(name, env),    {},
                            scene->moves, scene->scene().primitiveCount(), hashOfValid(scene->scene())};
    py::gil_scoped_release release;
    tbb::task_arena(threads > 0 ? threads : tbb::info::default_concurrency()).execute([&] {
        built.stats = timedBuild(*built.accel, scene->scene().primitives());
    });
    return built;
}

// The structure updated to `scene`'s primitives, timed as bvhlab times an update; false (and
// nothing changed) when it has none, or when other primitives are valid at the same count (an
// update keeps the set it was built over).
bool update(PythonAccelerator& self, std::shared_ptr<PythonScene> scene, int threads) {
    checkThreads(threads);
    const uint64_t validHash = hashOfValid(scene->scene());
    if (scene->scene().primitiveCount() == self.primitives && validHash != self.validHash) return false;
    std::optional<BuildStats> stats;
    {
        py::gil_scoped_release release;
        tbb::task_arena(threads > 0 ? threads : tbb::info::default_concurrency()).execute([&] {
            stats = timedUpdate(*self.accel, scene->scene().primitives());
        });
    }
    if (!stats) return false;
    self.sceneMoves = scene->moves;
    self.validHash = validHash;
    self.scene = std::move(scene);  // the structure keeps views of its primitives
    self.stats = *stats;
    return true;
}

// Answers the arrays' rays into a new array of Record, one per ray, as bvhlab raycast answers
// them (forEachRayRange), with the GIL released: each range is read into its thread's buffers,
// answered by the batch call, and written in place by write(answers, costs, records). The
// queries count only when `counters` is asked (a caller timing them asks for none); costs are
// empty unless it is and the structure counts. `coherent`: the batch calls' hint (RayCoherence).
template <typename Record, typename Answer, typename Write>
py::array answerInto(const PythonAccelerator& self, const RayArrays& rays, int threads, bool counters, bool coherent,
                     Write&& write) {
    checkThreads(threads);
    self.currentScene();
    const bool counted = counters && self.accel->hasCounters();
    py::array_t<Record> result(py::ssize_t(rays.size()));
    Record* records = result.mutable_data();
    struct Buffers {
        std::vector<Ray> rays;
        std::vector<Answer> answers;
        std::vector<RayCost> costs;
    };
    tbb::enumerable_thread_specific<Buffers> perThread;
    const RayCoherence coherence = coherent ? RayCoherence::Coherent : RayCoherence::Incoherent;
    {
        py::gil_scoped_release release;  // held again before `result`, a Python object, is returned
        forEachRayRange(rays.size(), threads, counters, [&](size_t begin, size_t end, QueryCounters& queryCounters) {
            Buffers& b = perThread.local();
            b.rays.resize(end - begin);
            b.answers.resize(end - begin);
            b.costs.resize(counted ? end - begin : 0);
            rays.read(begin, b.rays);
            if constexpr (std::is_same_v<Answer, Hit>)
                self.accel->findNearestBatch(b.rays, b.answers, queryCounters, b.costs, coherence);
            else
                self.accel->isOccludedBatch(b.rays, b.answers, queryCounters, b.costs, coherence);
            write(std::span<const Answer>(b.answers), std::span<const RayCost>(b.costs), records + begin);
        });
    }
    return result;
}

py::array intersect(const PythonAccelerator& self, const py::handle& origins, const py::handle& directions,
                    const py::handle& tmin, const py::handle& tmax, int threads, bool counters, bool coherent) {
    const RayArrays rays(origins, directions, tmin, tmax);
    if (counters)
        return answerInto<CountedHitRecord, Hit>(self, rays, threads, true, coherent,
                                                 writeHitRecords<CountedHitRecord>);
    return answerInto<HitRecord, Hit>(self, rays, threads, false, coherent, writeHitRecords<HitRecord>);
}

py::array occluded(const PythonAccelerator& self, const py::handle& origins, const py::handle& directions,
                   const py::handle& tmin, const py::handle& tmax, int threads, bool counters, bool coherent) {
    const RayArrays rays(origins, directions, tmin, tmax);
    if (counters)
        return answerInto<CountedOcclusionRecord, uint8_t>(self, rays, threads, true, coherent,
                                                           [](auto answers, auto costs, CountedOcclusionRecord* out) {
                                                               for (size_t i = 0; i < answers.size(); ++i) {
                                                                   out[i].occluded = answers[i] != 0;
                                                                   writeCounters(costs, i, out[i]);
                                                               }
                                                           });
    return answerInto<bool, uint8_t>(self, rays, threads, false, coherent, [](auto answers, auto, bool* out) {
        for (size_t i = 0; i < answers.size(); ++i) out[i] = answers[i] != 0;
    });
}

}  // namespace

const Scene& PythonAccelerator::currentScene() const {
    if (scene->moves != sceneMoves)
        throw InputError(
            fmt::format("the scene '{}' moved (set_time) since this {} was built or updated: "
                        "accel.update(scene), or bvhlab.build again",
                        scene->scene().name, accel->name()));
    return scene->scene();
}

Env envWith(const PythonScene& scene, const py::object& envDict, int threads) {
    checkThreads(threads);
    Env env = scene.env;
    env.set(keys::SetRayTracing::threads, std::to_string(threads), "threads");
    for (const std::string& assignment : envAssignments(envDict)) env.setOverride(assignment);
    return env;
}

void bindAccelerator(py::module_& m) {
    static const std::string queryArguments =
        "origins and directions: (N, 3) float32 or float64 of any strides, read in place, N >= 0; tmin, tmax: "
        "numbers or (N,) arrays; threads: 0 for all hardware threads; coherent: the rays are a coherent batch (a "
        "camera's rays row by row, shadow rays towards one light), a hint for the structure's traversal that never "
        "changes the answers. Rays with a NaN are misses.";
    // Static: pybind11 keeps the pointer.
    static const std::string intersectDoc =
        "Closest hits: a structured array t (inf on a miss), prim (-1 on a miss), u, v, and with counters n_it, "
        "n_tr per ray (float32; NaN for a structure without counters). " +
        queryArguments;
    static const std::string occludedDoc =
        "Any-hit answers: a bool array, or with counters a structured array occluded, n_it, n_tr (float32; NaN "
        "for a structure without counters). " +
        queryArguments;
    py::class_<PythonAccelerator>(m, "Accelerator", "An acceleration structure built over a scene (bvhlab.build).")
        .def_property_readonly("name", [](const PythonAccelerator& a) { return std::string(a.accel->name()); })
        .def_property_readonly(
            "stats", [](const PythonAccelerator& a) { return statsDict(a.stats); },
            "build_ms, nodes, leaves, sah, epo, bytes, ... and the structure's figures; None "
            "where the structure has no such figure")
        .def_property_readonly(
            "has_counters", [](const PythonAccelerator& a) { return a.accel->hasCounters(); },
            "False for a structure that counts no N_IT and N_TR (Embree): its counters are NaN")
        .def("intersect", &intersect, py::arg("origins"), py::arg("directions"), py::arg("tmin") = 0.0f,
             py::arg("tmax") = std::numeric_limits<float>::infinity(), py::arg("threads") = 0,
             py::arg("counters") = false, py::arg("coherent") = false, intersectDoc.c_str())
        .def("occluded", &occluded, py::arg("origins"), py::arg("directions"), py::arg("tmin") = 0.0f,
             py::arg("tmax") = std::numeric_limits<float>::infinity(), py::arg("threads") = 0,
             py::arg("counters") = false, py::arg("coherent") = false, occludedDoc.c_str())
        .def("update", &update, py::arg("scene"), py::arg("threads") = 0,
             "Updates the structure after the primitives moved: `scene` has the built scene's primitives (the "
             "same counts and valid ones: the same scene after set_time, or the same file at another time) at new "
             "positions. True when it "
             "answers for them now (stats: the updated structure's, build_ms the update's time); False when the "
             "structure has no update or other primitives are valid now (a moving triangle became degenerate or "
             "stopped being so): build it again with bvhlab.build. Other counts: ValueError.")
        .def("__repr__", [](const PythonAccelerator& a) {
            return fmt::format("<bvhlab.Accelerator {} over '{}'>", a.accel->name(), a.scene->scene().name);
        });

    m.def("build", &build, py::arg("scene"), py::arg("accelerator") = "sahbvh8", py::arg("env") = py::none(),
          py::arg("threads") = 0,
          "Builds a structure of the registry (bvhlab.accelerators()) over the scene, env keys as a dict "
          "({\"BVH::bins\": 32}) over the scene's env; the build timed as bvhlab times it.");

    m.def(
        "accelerators",
        [] {
            loadPluginsOfFolders();  // listed as build() would find them by name
            py::list list;
            for (const AcceleratorInfo& info : acceleratorInfos()) {
                py::dict entry;
                entry["name"] = info.name;
                entry["description"] = info.description;
                entry["keys"] = info.envKeys;
                entry["plugin"] = info.plugin;
                list.append(entry);
            }
            return list;
        },
        "Every accelerator, those of the plugins in the plugin folders (BVHLAB_PLUGIN_PATH, bvhlab's own) included: "
        "{name, description, keys, plugin} (plugin: its file, empty for those built into bvhlab).");

    m.def(
        "load_plugin",
        [](const std::filesystem::path& file) {
            const LoadedPlugin& plugin = loadPlugin(file);
            py::dict loaded;
            loaded["file"] = plugin.file;
            loaded["abi"] = plugin.abi;
            loaded["accelerators"] = plugin.accelerators;
            loaded["compiler"] = plugin.compiler;
            loaded["cxx_flags"] = plugin.cxxFlags;
            loaded["optimized"] = plugin.optimized;
            return loaded;
        },
        py::arg("path"), "Loads a plugin's accelerators (docs/plugins.md); again: nothing happens.");
}

}  // namespace bvhlab
