// The parts of the Python module bvhlab (docs/python.md), each adding its functions and classes.
#pragma once

#include <pybind11/pybind11.h>
#include <nlohmann/json.hpp>

namespace bvhlab {

void bindScene(pybind11::module_& m);        // Scene, load_scene, rays
void bindAccelerator(pybind11::module_& m);  // build, Accelerator, accelerators, load_plugin
void bindRayFiles(pybind11::module_& m);     // read_rays, write_rays, read_hits, write_hits
void bindRender(pybind11::module_& m);       // render

// A JSON value as Python's json module reads it (the statistics dicts).
inline pybind11::object pythonFromJson(const nlohmann::json& value) {
    return pybind11::module_::import("json").attr("loads")(value.dump());
}

}  // namespace bvhlab
