// The Python module geodual: remeshing of triangle-mesh scans through the dual
// of the exact geodesic Voronoi diagram, on numpy arrays.

#include "bindings.hpp"
#include "errors.hpp"

#include "geodual/pipeline/heap.hpp"
#include "geodual/pipeline/version.hpp"

#include <string>

PYBIND11_MODULE(geodual, module) {
  module.doc() = R"(geodual: remeshing of dense triangle-mesh scans through the dual of the exact
geodesic Voronoi diagram.

Meshes are numpy arrays: V, float64 n x 3 vertex positions, and F, int32 m x 3
triangles (indices into V).

    import geodual
    V, F = geodual.read_mesh("scan.ply")
    result = geodual.remesh(V, F, sites=2000)
    geodual.write_mesh("remeshed.ply", result.vertices, result.faces)
    print(result.stats["q_avg"], result.stats["hausdorff_pct"])

Functions: read_mesh, write_mesh, remesh, geodesic, voronoi, keep_freed_memory_in_heap.
Errors: geodual.Error (a RuntimeError) for bad input data or impossible
requests; geodual.UsageError (also a ValueError) for bad option values;
geodual.Cancelled when a progress callback returns False; ValueError and
TypeError for arrays of the wrong shape or type. Ctrl-C raises
KeyboardInterrupt, also in the middle of a computation.)";
  module.attr("__version__") = std::string(geodual::version());
  module.attr("build_version") = std::string(geodual::build_version());
  geodual::python::add_exceptions(module);
  geodual::python::add_mesh_io(module);
  geodual::python::add_geodesics(module);
  geodual::python::add_remesh(module);
  module.def("keep_freed_memory_in_heap", &geodual::pipeline::keep_freed_memory_in_heap,
             R"(Lets glibc's malloc keep freed blocks of up to 256 MB for reuse (process-wide; a no-op
elsewhere): each geodesic diagram allocates and frees arrays of tens of MB, whose pages otherwise
fault in again for the next. Remeshing is then faster, with the same results. For a process
whose work is mostly geodual's, as the geodual command line tool is.)");
}
