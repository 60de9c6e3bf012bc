// The parts of the Python module bvhlab (docs/python.md), each adding its functions and classes.
#pragma once

#include <pybind11/pybind11.h>

namespace bvhlab {

void bindScene(pybind11::module_& m);        // Scene, load_scene, rays
void bindAccelerator(pybind11::module_& m);  // build, Accelerator, accelerators, load_plugin
void bindRayFiles(pybind11::module_& m);     // read_rays, write_rays, read_hits, write_hits
void bindRender(pybind11::module_& m);       // render

}  // namespace bvhlab
