#include "apps/python/python_scene.h"

#include "apps/python/bindings.h"
#include "apps/python/numpy_rays.h"
#include "apps/runtime/env_options.h"
#include "apps/runtime/ray_sets.h"
#include "apps/runtime/scene_choice.h"
#include "apps/runtime/scene_loading.h"
#include "framework/core/error.h"
#include "framework/scene/scene_loader.h"

#include <fmt/core.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <optional>

namespace py = pybind11;

namespace bvhlab {
namespace {

// A getter of a read-only (rows, 3) view of one of the scene's arrays of 3-vectors (positions,
// indices), which keeps the Python Scene alive.
template <typename Vector>
auto readOnlyView(std::vector<Vector> Scene::*member) {
    return [member](const py::object& self) {
        using T = typename Vector::value_type;
        const std::vector<Vector>& rows = self.cast<const PythonScene&>().scene().*member;
        py::array view(py::dtype::of<T>(), {rows.size(), size_t(3)}, {3 * sizeof(T), sizeof(T)}, &rows.data()->x, self);
        view.attr("setflags")(py::arg("write") = false);
        return view;
    };
}

// (N, 3) float vertices and (T, 3) integer indices into them, as a finalized scene.
Scene sceneFromArrays(const py::handle& vertices, const py::handle& indices) {
    const auto v = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(vertices);
    const auto i = py::array_t<int64_t, py::array::c_style | py::array::forcecast>::ensure(indices);
    if (!v || v.ndim() != 2 || v.shape(1) != 3 || v.shape(0) == 0)
        throw InputError("vertices: expected a non-empty array of shape (N, 3)");
    if (!i || i.ndim() != 2 || i.shape(1) != 3 || i.shape(0) == 0)
        throw InputError("indices: expected a non-empty integer array of shape (T, 3)");
    Scene scene;
    scene.name = "arrays";
    scene.positions.resize(size_t(v.shape(0)));
    for (size_t k = 0; k < scene.positions.size(); ++k)
        scene.positions[k] = {v.at(py::ssize_t(k), 0), v.at(py::ssize_t(k), 1), v.at(py::ssize_t(k), 2)};
    scene.indices.resize(size_t(i.shape(0)));
    for (size_t t = 0; t < scene.indices.size(); ++t)
        for (int c = 0; c < 3; ++c) {
            const int64_t index = i.at(py::ssize_t(t), c);
            if (index < 0 || index >= v.shape(0))
                throw InputError(fmt::format("indices[{}]: vertex {} out of range (0..{})", t, index, v.shape(0) - 1));
            scene.indices[t][c] = uint32_t(index);
        }
    scene.finalize();
    requireSomethingToRender(scene);
    return scene;
}

EnvOptions optionsWith(const py::object& env) {
    EnvOptions options;
    options.overrides = envAssignments(env);
    return options;
}

// A still scene as Python holds it: one frame in which nothing moves.
std::shared_ptr<PythonScene> stillScene(Scene scene, Env env) {
    auto still = std::make_shared<PythonScene>(PythonScene{{}, std::move(env)});
    still->animated.scene = std::move(scene);
    still->animated.prepare();
    return still;
}

float frameTime(const PythonScene& s, int frame) {
    const int count = s.animated.frameCount;
    if (frame < 0 || frame >= count)
        throw InputError(fmt::format("frame {}: the scene '{}' has {} frame{}, 0 to {}", frame, s.scene().name, count,
                                     count == 1 ? "" : "s", count - 1));
    return s.animated.frameTime(frame);
}

// Moves the scene's primitives, camera and lights to `time`; the structures over it are stale
// until updated if any primitive can move.
void setTime(PythonScene& s, float time) {
    if (!std::isfinite(time)) throw InputError(fmt::format("time {}: expected a finite number", time));
    s.animated.setTime(time);
    if (!s.animated.movingPrimitives().empty()) ++s.moves;
}

// What --scene names (a file or a scene's name), with env's keys over its layers, at the frame
// Scene::frame names, or `frame` or `time` when given.
std::shared_ptr<PythonScene> loadNamedScene(const std::string& scene, const py::object& env,
                                            const std::optional<int>& frame, const std::optional<float>& time) {
    if (frame && time) throw InputError("load_scene: give a frame or a time, not both");
    const EnvOptions options = optionsWith(env);
    Env resolved = chooseScene(scene, "", options).load(options);
    auto loaded = std::make_shared<PythonScene>(PythonScene{loadAnimatedSceneFor(resolved), std::move(resolved)});
    if (frame) setTime(*loaded, frameTime(*loaded, *frame));
    if (time) setTime(*loaded, *time);
    loaded->moves = 0;  // nothing was built over it yet
    return loaded;
}

}  // namespace

std::vector<std::string> envAssignments(const py::object& env) {
    std::vector<std::string> assignments;
    if (env.is_none()) return assignments;
    if (!py::isinstance<py::dict>(env)) throw InputError("env: expected a dict {\"Section::key\": value}");
    for (const auto& [key, value] : py::reinterpret_borrow<py::dict>(env)) {
        if (!py::isinstance<py::str>(key)) throw InputError("env: keys are strings, \"Section::key\"");
        const std::string text = py::isinstance<py::bool_>(value) ? (value.cast<bool>() ? "true" : "false")
                                                                  : py::str(value).cast<std::string>();
        assignments.push_back(key.cast<std::string>() + "=" + text);
    }
    return assignments;
}

void bindScene(py::module_& m) {
    py::class_<PythonScene, std::shared_ptr<PythonScene>>(m, "Scene", "A loaded scene: triangles (and NFF's quadrics).")
        .def_static(
            "from_arrays",
            [](const py::handle& vertices, const py::handle& indices, const py::object& env) {
                return stillScene(sceneFromArrays(vertices, indices), optionsWith(env).load());
            },
            py::arg("vertices"), py::arg("indices"), py::arg("env") = py::none(),
            "A scene of triangles indices[t] over vertices, (N, 3) and (T, 3) arrays.")
        .def_property_readonly("name", [](const PythonScene& s) { return s.scene().name; })
        .def_property_readonly("triangle_count", [](const PythonScene& s) { return s.scene().triangleCount(); })
        .def_property_readonly("primitive_count", [](const PythonScene& s) { return s.scene().primitiveCount(); })
        .def_property_readonly(
            "bounds",
            [](const PythonScene& s) {
                const Bounds3& b = s.scene().bounds;
                return py::make_tuple(py::make_tuple(b.lower.x, b.lower.y, b.lower.z),
                                      py::make_tuple(b.upper.x, b.upper.y, b.upper.z));
            },
            "((xmin, ymin, zmin), (xmax, ymax, zmax)) of the primitives built over")
        .def_property_readonly("vertices", readOnlyView(&Scene::positions), "(N, 3) float32, a read-only view")
        .def_property_readonly("indices", readOnlyView(&Scene::indices),
                               "(T, 3) uint32 into vertices, a read-only view")
        .def_property_readonly(
            "frame_count", [](const PythonScene& s) { return s.animated.frameCount; },
            "the animation's frames (an .aff's `a` line); 1 for a still scene")
        .def_property_readonly(
            "start_time", [](const PythonScene& s) { return s.animated.startTime; },
            "the time of frame 0 (0 for a still scene)")
        .def_property_readonly(
            "end_time", [](const PythonScene& s) { return s.animated.endTime; },
            "the time of the last frame (0 for a still scene)")
        .def_property_readonly(
            "time", [](const PythonScene& s) { return s.animated.time(); }, "the time the scene is at")
        .def("frame_time", &frameTime, py::arg("frame"),
             "The time of a frame, 0 to frame_count - 1: start_time + frame (end_time - start_time) / (frame_count - "
             "1).")
        .def("set_time", &setTime, py::arg("time"),
             "Moves the scene to `time` (any finite time; the animation spans start_time to end_time): its moving "
             "primitives (vertices and indices show them), camera and lights. A structure built over the scene "
             "answers again after accel.update(scene) or a new build; until then its queries raise ValueError. A "
             "still scene does not move.")
        .def("__repr__", [](const PythonScene& s) {
            return fmt::format("<bvhlab.Scene '{}': {} triangles>", s.scene().name, s.scene().triangleCount());
        });

    m.def("load_scene", &loadNamedScene, py::arg("scene") = "", py::arg("env") = py::none(),
          py::arg("frame") = py::none(), py::arg("time") = py::none(),
          "A scene file (.obj .ply .off .nff .aff, optionally .gz) or a scene's name (env/scenes/NAME.env), as "
          "bvhlab --scene reads it, with env/global.env, the scene's env file and `env` layered; empty: "
          "Scene::file, else the embedded scene. An animated scene at `frame` (0 to frame_count - 1) or `time` "
          "when given, else at the frame Scene::frame names.");

    m.def(
        "rays",
        [](const PythonScene& scene, const std::string& kind, const py::object& env) {
            Env resolved = scene.env;
            for (const std::string& assignment : envAssignments(env)) resolved.setOverride(assignment);
            return raysToArrays(benchRays(scene.scene(), resolved, kind));
        },
        py::arg("scene"), py::arg("kind") = "primary", py::arg("env") = py::none(),
        "The bench's rays of the scene's camera and lights (primary, shadow or incoherent), env keys as a dict "
        "over the scene's ({\"Camera::width\": 400}), as bvhlab rays writes them: {origins, directions, tmin, tmax}.");
    m.def(
        "rays",
        [](const std::string& scene, const std::string& kind, const py::object& env) {
            const std::shared_ptr<PythonScene> loaded = loadNamedScene(scene, env, {}, {});
            return raysToArrays(benchRays(loaded->scene(), loaded->env, kind));
        },
        py::arg("scene"), py::arg("kind") = "primary", py::arg("env") = py::none(),
        "The same of a scene file or a scene's name, loaded as load_scene(scene, env) loads it.");
}

}  // namespace bvhlab
