// The Python module bvhlab (docs/python.md): scenes, every accelerator of the registry, rays and
// hits as NumPy arrays. bvhlab::InputError, the CLI's one-line message, becomes bvhlab.InputError,
// a ValueError.
#include "apps/python/bindings.h"
#include "apps/python/numpy_rays.h"
#include "framework/core/error.h"
#include "framework/core/fatal_signal_report.h"

#include <pybind11/numpy.h>

namespace py = pybind11;

namespace {

// The module's arrays are NumPy's: without it the import fails saying so and how to get it,
// rather than pybind11's "initialization failed".
void requireNumPy() {
    try {
        py::module_::import("numpy");
    } catch (py::error_already_set& missing) {
        const std::string python = py::str(py::module_::import("sys").attr("executable"));
        throw std::runtime_error(
            "bvhlab needs NumPy, which this Python (" + python + ") cannot import (" + missing.what() +
            "): install Debian's python3-numpy and use /usr/bin/python3, or `pip install numpy` for this Python");
    }
}

}  // namespace

PYBIND11_MODULE(bvhlab, m) {
    requireNumPy();
    m.doc() = "bvhlab: load scenes, build any acceleration structure, trace NumPy arrays of rays";
    // A crash inside a plugin names the plugin, the call and its ray before Python dies of it.
    bvhlab::installFatalSignalReport();
    py::register_exception<bvhlab::InputError>(m, "InputError", PyExc_ValueError);
    PYBIND11_NUMPY_DTYPE(bvhlab::HitRecord, t, prim, u, v);
    PYBIND11_NUMPY_DTYPE(bvhlab::CountedHitRecord, t, prim, u, v, n_it, n_tr);
    PYBIND11_NUMPY_DTYPE(bvhlab::CountedOcclusionRecord, occluded, n_it, n_tr);
    bvhlab::bindScene(m);
    bvhlab::bindAccelerator(m);
    bvhlab::bindRayFiles(m);
    bvhlab::bindRender(m);
}
