// numpy arrays (and VTK's arrays, as numpy views) -> zsweep's scene data:
// tet meshes, sphere sets, triangle surfaces. Every check raises ValueError
// (pybind11::value_error) with one line naming the entry and the array.
#pragma once

#include <string>

#include <pybind11/pybind11.h>

#include "scene/scene_input.h"

namespace zs::python {

// {"points": (N,3), "tets": (M,4) int, "scalar": (N,) or (M,)} (scalar
// optional; one value per tet is cell data); or VTK's cells of an
// unstructured grid as arrays: {"points", "offsets", "connectivity",
// "types", "scalar" or "cell_scalar"}, split into tets as the .vtu reader
// splits them. "association" (optional): as a scene's mesh.association.
TetMesh tet_mesh_from(const pybind11::dict& d, const std::string& where);
// {"centers": (N,3), "radii": (N,), "colors": (N,3|4) in [0,1], "scalar": (N,)}
// (colors and scalar optional; "centres" is accepted too).
SphereSet sphere_set_from(const pybind11::dict& d, const std::string& where);
// {"points": (N,3), "triangles": (M,3) int}.
TriangleMesh triangle_mesh_from(const pybind11::dict& d, const std::string& where);

// The `data` argument of render: {"mesh": {path: dict}, "spheres": ...,
// "surfaces": ...} as the Python layer builds it.
SceneData scene_data_from(const pybind11::dict& data);

}  // namespace zs::python
