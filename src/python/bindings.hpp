// fhr for Python (beyond the paper) — what the topics of the `fhr._fhr` extension share: meshes
// as numpy arrays in libigl's convention (V: n × 3 float64, F: m × 3 integers), validated exactly
// as the readers validate files (spec/mesh.md), and the oracle's verdict as a dict. The topics:
// meshes.cpp (reading, writing, the generator, §2's decimation, §3's exact geodesics), run.cpp (the
// whole method and its result), oracle.cpp (the independent oracle on files and arrays); module.cpp
// puts them into one module.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <fhr/core/build.hpp>
#include <fhr/core/polygon_soup.hpp>
#include <fhr/core/trimesh.hpp>
#include <fhr/exchange/fhr_param.hpp>

namespace fhr::python {

namespace py = pybind11;

using Vertices = py::array_t<double>;
using Faces = py::array_t<std::int64_t>;

/// `what`'s rows × cols shape, or InvalidInput naming the array and the shape it has.
void require_shape(const py::array& a, py::ssize_t cols, const char* what);
/// V as points: float or integer dtypes (converted when lossless), finite.
std::vector<Vec3> points_of(const py::array& V);
/// F as triangles: any integer dtype, every index in [0, n).
std::vector<Triangle> triangles_of(const py::array& F, std::size_t n);
/// (V, F) as a soup, in the arrays' numbering.
PolygonSoup soup_of(const py::array& V, const py::array& F);
/// (V, F) through every input rule of spec/mesh.md, as a file would go through them.
TriMesh mesh_of(const py::array& V, const py::array& F, const BuildOptions& options = {});
Vertices vertices_array(std::span<const Vec3> points);
Faces faces_array(std::span<const Triangle> triangles);
/// (V, F) of a mesh.
py::tuple mesh_arrays(const TriMesh& m);

/// The oracle's verdict on a `fhr-param 1` file: PARAM-1 (the file was read) and PARAM-2..11, as
/// `fhr verify --json`'s keys and values without file names; paper: PARAM-10 (chord length) judged.
py::dict verdict(const exchange::ParamFile& file, const TriMesh* mesh, bool paper);

/// The topics' functions and classes, added to the module (in this order: overloads of `verify`
/// are tried in the order they were added).
void bind_meshes(py::module_& m);
void bind_run(py::module_& m);
void bind_oracle(py::module_& m);

}  // namespace fhr::python
