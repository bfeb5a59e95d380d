// fhr for Python (beyond the paper) — numpy arrays as meshes and back (bindings.hpp).
#include "bindings.hpp"

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <fhr/core/errors.hpp>

namespace fhr::python {

void require_shape(const py::array& a, py::ssize_t cols, const char* what) {
    if (a.ndim() != 2 || a.shape(1) != cols) {
        std::string shape = "(";
        for (py::ssize_t i = 0; i < a.ndim(); ++i) shape += (i ? ", " : "") + std::to_string(a.shape(i));
        throw InvalidInput(std::string(what) + " must have shape (n, " + std::to_string(cols) + "), not " + shape +
                           (a.ndim() == 1 ? ",)" : ")"));
    }
}

std::vector<Vec3> points_of(const py::array& V) {
    require_shape(V, 3, "V");
    const char kind = V.dtype().kind();
    if (kind != 'f' && kind != 'i' && kind != 'u')
        throw InvalidInput("V must hold numbers (its dtype is " + std::string(py::str(V.dtype())) + ")");
    if (kind == 'f' && V.dtype().itemsize() > 8)
        throw InvalidInput("V's dtype " + std::string(py::str(V.dtype())) + " does not fit float64 without loss");
    const auto v = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(V);
    const auto r = v.unchecked<2>();
    std::vector<Vec3> points(static_cast<std::size_t>(r.shape(0)));
    for (py::ssize_t i = 0; i < r.shape(0); ++i) {
        for (py::ssize_t k = 0; k < 3; ++k) {
            const double x = r(i, k);
            if (!std::isfinite(x))
                throw InvalidInput("V[" + std::to_string(i) + "] is not finite (vertex " + std::to_string(i) + ")");
            if (kind != 'f' && std::abs(x) > 9007199254740992.0)
                throw InvalidInput("V[" + std::to_string(i) + "] does not fit float64 without loss");
        }
        points[static_cast<std::size_t>(i)] = Vec3(r(i, 0), r(i, 1), r(i, 2));
    }
    return points;
}

std::vector<Triangle> triangles_of(const py::array& F, std::size_t n) {
    require_shape(F, 3, "F");
    const char kind = F.dtype().kind();
    if (kind != 'i' && kind != 'u')
        throw InvalidInput("F must hold integers (its dtype is " + std::string(py::str(F.dtype())) + ")");
    std::vector<Triangle> faces(static_cast<std::size_t>(F.shape(0)));
    auto fill = [&](auto typed) {
        const auto r = typed.template unchecked<2>();
        for (py::ssize_t i = 0; i < r.shape(0); ++i)
            for (py::ssize_t k = 0; k < 3; ++k) {
                const auto x = r(i, k);
                if (x < 0 || static_cast<std::uint64_t>(x) >= n)
                    throw InvalidInput("face " + std::to_string(i) + " has vertex index " + std::to_string(x) +
                                       ", outside [0, " + std::to_string(n) + ")");
                faces[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(x);
            }
    };
    if (kind == 'u')
        fill(py::array_t<std::uint64_t, py::array::c_style | py::array::forcecast>::ensure(F));
    else
        fill(py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(F));
    return faces;
}

PolygonSoup soup_of(const py::array& V, const py::array& F) {
    PolygonSoup soup;
    soup.points = points_of(V);
    for (const Triangle& t : triangles_of(F, soup.points.size())) soup.add_polygon(t.data(), 3);
    return soup;
}

TriMesh mesh_of(const py::array& V, const py::array& F, const BuildOptions& options) {
    const PolygonSoup soup = soup_of(V, F);
    BuildLog log;
    return build_trimesh(soup, options, log);
}

Vertices vertices_array(std::span<const Vec3> points) {
    Vertices V({static_cast<py::ssize_t>(points.size()), py::ssize_t{3}});
    auto w = V.mutable_unchecked<2>();
    for (std::size_t i = 0; i < points.size(); ++i)
        for (int k = 0; k < 3; ++k) w(static_cast<py::ssize_t>(i), k) = points[i][k];
    return V;
}

Faces faces_array(std::span<const Triangle> triangles) {
    Faces F({static_cast<py::ssize_t>(triangles.size()), py::ssize_t{3}});
    auto w = F.mutable_unchecked<2>();
    for (std::size_t i = 0; i < triangles.size(); ++i)
        for (int k = 0; k < 3; ++k) w(static_cast<py::ssize_t>(i), k) = triangles[i][static_cast<std::size_t>(k)];
    return F;
}

py::tuple mesh_arrays(const TriMesh& m) {
    return py::make_tuple(vertices_array(m.positions()), faces_array(m.triangles()));
}

}  // namespace fhr::python
