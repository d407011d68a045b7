#pragma once
// The binding functions of each part of the package (one source each), called by the module's init (module.cpp).
#include <pybind11/pybind11.h>

namespace tessera::python {

void bind_images(pybind11::module_& m);     ///< images.cpp: image files, colors, textures
void bind_meshes(pybind11::module_& m);     ///< meshes.cpp: mesh files, primitives, topology, subdivision
void bind_volumes(pybind11::module_& m);    ///< volumes.cpp: isosurfaces, contours, volume files and rendering
void bind_rendering(pybind11::module_& m);  ///< rendering.cpp: the rasterizer, the ray tracer, ray casting
void bind_sketches(pybind11::module_& m);   ///< sketches.cpp: the canvas and sketches
void bind_curves(pybind11::module_& m);     ///< curves.cpp: Bezier curves and patches
void bind_fractals(pybind11::module_& m);   ///< fractals.cpp: escape-time sets, self-similar sets, terrain

}  // namespace tessera::python
