#pragma once
// The module's functions, one group per file; module.cpp adds them all.

#include <pybind11/pybind11.h>

namespace geodual::python {

void add_mesh_io(pybind11::module_& module);    // read_mesh, write_mesh
void add_geodesics(pybind11::module_& module);  // geodesic, voronoi
void add_remesh(pybind11::module_& module);     // remesh, RemeshResult

}  // namespace geodual::python
