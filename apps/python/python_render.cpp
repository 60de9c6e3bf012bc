// bvhlab.render: the image `bvhlab render` draws, with its per-pixel outputs as arrays and its
// statistics as the JSON's dict, for one accelerator over its scene.
#include "apps/python/bindings.h"
#include "apps/python/python_accelerator.h"
#include "framework/render/camera.h"
#include "framework/render/renderer.h"
#include "framework/report/statistics.h"

#include <pybind11/numpy.h>

#include <algorithm>
#include <limits>

namespace py = pybind11;

namespace bvhlab {
namespace {

// A (height, width, channels) array of `values` (channels 0: (height, width)); a primitive
// index is -1 on a miss.
template <typename T, typename Value>
py::array_t<T> imageArray(const std::vector<Value>& values, int width, int height, int channels) {
    std::vector<py::ssize_t> shape = {height, width};
    if (channels) shape.push_back(channels);
    py::array_t<T> image(shape);
    T* out = image.mutable_data();
    for (size_t i = 0; i < values.size(); ++i) {
        if constexpr (std::is_same_v<Value, Vec3>)
            for (int c = 0; c < 3; ++c) out[3 * i + c] = values[i][c];
        else if constexpr (std::is_same_v<Value, uint32_t>)
            out[i] = values[i] == kInvalidPrimitive ? T(-1) : T(values[i]);
        else
            out[i] = T(values[i]);
    }
    return image;
}

// A per-pixel counter (N_TR, N_IT) as an (height, width) image: NaN for a structure that counts
// nothing, whose framebuffer holds zeros.
py::array_t<float> counterImage(const std::vector<float>& values, int width, int height, bool counted) {
    py::array_t<float> image = imageArray<float>(values, width, height, 0);
    if (!counted) std::fill_n(image.mutable_data(), image.size(), std::numeric_limits<float>::quiet_NaN());
    return image;
}

// The statistics JSON of the render as a dict. A structure without counters has NaN for the
// per-query counters where the JSON has null, as in every counter Python returns.
py::object renderStatsDict(const StatsRow& row) {
    py::object stats = pythonFromJson(statsJson(row));
    if (row.hasCounters) return stats;
    for (const char* query : {"primary", "shadow"})
        for (const QueryCounter& c : kQueryCounters) stats[query][c.key] = std::numeric_limits<double>::quiet_NaN();
    return stats;
}

py::dict renderAccelerator(const PythonAccelerator& accel, const py::object& envDict, int threads) {
    const Env env = envWith(*accel.scene, envDict, threads);
    const Scene& scene = accel.currentScene();
    const Camera camera(resolveCamera(scene, env));
    const RenderSettings settings = RenderSettings::fromEnv(env, scene, camera.spec());
    Framebuffer fb(camera.width(), camera.height());
    RenderStats stats;
    {
        py::gil_scoped_release release;
        stats = render(scene, *accel.accel, camera, settings, fb);
    }
    const StatsRow row{scene.name,   std::string(accel.accel->name()), scene.primitiveCount(),
                       scene.report, accel.accel->hasCounters(),       accel.stats,
                       stats};
    py::dict result;
    result["image"] = imageArray<float>(fb.color, fb.width, fb.height, 3);
    result["depth"] = imageArray<float>(fb.depth, fb.width, fb.height, 0);
    result["prim"] = imageArray<int64_t>(fb.primitive, fb.width, fb.height, 0);
    result["normal"] = imageArray<float>(fb.normal, fb.width, fb.height, 3);
    result["heatmap"] = counterImage(fb.traversalSteps, fb.width, fb.height, row.hasCounters);
    result["n_it"] = counterImage(fb.intersectionTests, fb.width, fb.height, row.hasCounters);
    result["stats"] = renderStatsDict(row);
    return result;
}

}  // namespace

void bindRender(py::module_& m) {
    m.def("render", &renderAccelerator, py::arg("accel"), py::arg("env") = py::none(), py::arg("threads") = 0,
          "Renders the accelerator's scene as bvhlab render does (its camera and lights, env keys as a dict over "
          "them): {image (H, W, 3) linear colour, depth, prim (-1 on a miss), normal, heatmap (N_TR per pixel), "
          "n_it, stats (the statistics JSON: nodes, sah, build_ms, render_ms, primary, shadow, ...)}; the counters "
          "NaN for a structure without counters.");
}

}  // namespace bvhlab
