// fhr for Python (beyond the paper) — meshes: reading and writing them, their counts, the random
// mesh generator, §2's decimation and §3's exact geodesic between two vertices.
#include "bindings.hpp"

#include <pybind11/stl.h>

#include <cstdint>
#include <string>
#include <vector>

#include <fhr/core/errors.hpp>
#include <fhr/core/surface_point.hpp>
#include <fhr/core/topology.hpp>
#include <fhr/domain/decimate.hpp>
#include <fhr/generate/random_mesh.hpp>
#include <fhr/geodesic/ellipse.hpp>
#include <fhr/io/read.hpp>
#include <fhr/io/write.hpp>

namespace fhr::python {

void bind_meshes(py::module_& m) {
    m.def(
        "read_mesh", [](const std::string& path) { return mesh_arrays(io::read_mesh(path)); }, py::arg("path"),
        "read_mesh(path) -> (V, F): a closed, connected triangle mesh (.off, .obj, .ply, .stl) through every "
        "input rule of spec/mesh.md. V: (n, 3) float64, F: (m, 3) int64.");
    m.def(
        "write_mesh",
        [](const std::string& path, const py::array& V, const py::array& F) {
            const TriMesh mesh = mesh_of(V, F);
            io::write_mesh(path, mesh.positions(), mesh.triangles());
        },
        py::arg("path"), py::arg("V"), py::arg("F"),
        "write_mesh(path, V, F): validates (V, F) and writes it (.off, .obj or .ply) atomically, coordinates "
        "bit-exact.");
    m.def(
        "info",
        [](const py::array& V, const py::array& F) {
            const TriMesh mesh = mesh_of(V, F);
            py::dict d;
            d["vertices"] = mesh.n_vertices();
            d["faces"] = mesh.n_faces();
            d["edges"] = mesh.n_edges();
            d["euler_characteristic"] = euler_characteristic(mesh);
            d["boundary_loops"] = boundary_loops(mesh).size();
            d["components"] = connected_components(mesh).count;
            d["genus"] = genus(mesh);
            return d;
        },
        py::arg("V"), py::arg("F"),
        "info(V, F) -> dict: counts, Euler characteristic, boundary loops, components and genus of a valid "
        "manifold triangle mesh (boundary and several components allowed here).");
    // A recipe from Python's arguments: the family by name and its knobs as keyword arguments
    // (generate::set_knob: the CLI's names with '_' for '-').
    const auto recipe = [](int genus, std::size_t faces, std::uint64_t seed, double noise, int holes, int components,
                           const std::string& family, const py::kwargs& knobs) {
        generate::RandomMeshOptions o{genus, faces, seed, noise, holes, components};
        o.family = generate::parse_family(family);
        for (const auto& [name, value] : knobs)
            generate::set_knob(o.knobs, o.family, py::str(name), value.cast<double>());
        return o;
    };
    m.def(
        "generate",
        [recipe](int genus, std::size_t faces, std::uint64_t seed, double noise, int holes, int components,
                 const std::string& family, const py::kwargs& knobs) {
            return mesh_arrays(
                generate::random_mesh(recipe(genus, faces, seed, noise, holes, components, family, knobs)));
        },
        py::arg("genus"), py::arg("faces"), py::arg("seed") = 0, py::arg("noise") = 0.0, py::arg("holes") = 0,
        py::arg("components") = 1, py::arg("family") = "block",
        "generate(genus, faces, seed=0, noise=0.0, holes=0, components=1, family='block', **knobs) -> (V, F): the "
        "random mesh that `fhr generate` writes for the same options, bit for bit. genus and holes (boundary loops) "
        "are totals over the components; the defaults give a closed connected mesh. family is one of block, smooth, "
        "quality, valence, density, degenerate, immersed; knobs are the family's own options, named as "
        "`fhr generate`'s with '_' for '-' (e.g. smallest_angle=1e-5 for quality).");
    m.def(
        "min_faces",
        [recipe](int genus, int holes, int components, const std::string& family, const py::kwargs& knobs) {
            return generate::min_faces(recipe(genus, 0, 0, 0.0, holes, components, family, knobs));
        },
        py::arg("genus"), py::arg("holes") = 0, py::arg("components") = 1, py::arg("family") = "block",
        "min_faces(genus, holes=0, components=1, family='block', **knobs) -> int: the fewest faces generate() makes "
        "for these totals, family and knobs.");
    m.def(
        "decimate",
        [](const py::array& V, const py::array& F, std::size_t faces) {
            const TriMesh T = mesh_of(V, F);
            domain::Domain D;
            {
                py::gil_scoped_release unlocked;
                D = domain::decimate(T, {.target_faces = faces});
            }
            py::array_t<std::int64_t> t_vertex(static_cast<py::ssize_t>(D.t_vertex.size()));
            auto w = t_vertex.mutable_unchecked<1>();
            for (VertexId j : D.t_vertex.ids()) w(j.idx()) = D.t_vertex[j].idx();
            return py::make_tuple(vertices_array(D.mesh.positions()), faces_array(D.mesh.triangles()), t_vertex);
        },
        py::arg("V"), py::arg("F"), py::arg("faces"),
        "decimate(V, F, faces) -> (DV, DF, t_vertex): §2's half-edge-collapse decimation to exactly `faces` faces; "
        "vertex j of the domain is vertex t_vertex[j] of the input, at the same position.");
    m.def(
        "geodesic",
        [](const py::array& V, const py::array& F, std::int64_t source, std::int64_t target) {
            const TriMesh T = mesh_of(V, F);
            for (const std::int64_t v : {source, target})
                if (v < 0 || static_cast<std::uint64_t>(v) >= T.n_vertices())
                    throw InvalidInput("vertex " + std::to_string(v) + " is out of range (the mesh has " +
                                       std::to_string(T.n_vertices()) + " vertices)");
            geodesic::EllipsePath path;
            {
                py::gil_scoped_release unlocked;
                path = geodesic::ellipse_shortest_path(T, VertexId(static_cast<VertexId::Index>(source)),
                                                       VertexId(static_cast<VertexId::Index>(target)));
            }
            std::vector<Vec3> xyz;
            py::list surface;
            for (const SurfacePoint& p : path.path.points) {
                xyz.push_back(position(T, p));
                if (p.kind == SurfacePoint::Kind::vertex)
                    surface.append(py::make_tuple("vertex", p.vertex.idx()));
                else  // the paths of §3 run through vertices and across edges only
                    surface.append(py::make_tuple("edge", T.from(p.halfedge).idx(), T.to(p.halfedge).idx(), p.t));
            }
            return py::make_tuple(path.path.length, vertices_array(xyz), surface);
        },
        py::arg("V"), py::arg("F"), py::arg("source"), py::arg("target"),
        "geodesic(V, F, source, target) -> (length, points, surface): the exact shortest path on the surface "
        "between two vertices (§3's ellipse search, certified); points: (k, 3) float64 from source to target; "
        "surface: the same k points as ('vertex', v) or ('edge', a, b, t), the point (1 − t)·V[a] + t·V[b].");
}

}  // namespace fhr::python
