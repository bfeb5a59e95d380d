// fhr for Python (beyond the paper) — the `fhr._fhr` extension under the `fhr` package
// (src/python/fhr/__init__.py): meshes as numpy arrays in libigl's convention (V: n × 3 float64,
// F: m × 3 integers), validated exactly as the readers validate files (spec/mesh.md), and the
// library's calls on them (spec/library.md): the generator, §2's decimation, §3's exact geodesics,
// the whole method (pipeline::run) and the independent oracle. Errors keep the library's
// taxonomy: the `fhr` package defines the Python classes (InvalidInput is a ValueError) and the
// translator below raises them with the library's one-line messages. Long calls release the GIL.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <fhr/fhr.hpp>

namespace py = pybind11;

namespace fhr::python {
namespace {

using Vertices = py::array_t<double>;
using Faces = py::array_t<std::int64_t>;

/// `what`'s rows × cols shape, or InvalidInput naming the array and the shape it has.
void require_shape(const py::array& a, py::ssize_t cols, const char* what) {
    if (a.ndim() != 2 || a.shape(1) != cols) {
        std::string shape = "(";
        for (py::ssize_t i = 0; i < a.ndim(); ++i) shape += (i ? ", " : "") + std::to_string(a.shape(i));
        throw InvalidInput(std::string(what) + " must have shape (n, " + std::to_string(cols) + "), not " + shape +
                           (a.ndim() == 1 ? ",)" : ")"));
    }
}

/// V as points: float or integer dtypes (converted when lossless), finite.
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

/// F as triangles: any integer dtype, every index in [0, n).
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

/// (V, F) through every input rule of spec/mesh.md, as a file would go through them.
/// (V, F) as a soup, in the arrays' numbering.
PolygonSoup soup_of(const py::array& V, const py::array& F) {
    PolygonSoup soup;
    soup.points = points_of(V);
    for (const Triangle& t : triangles_of(F, soup.points.size())) soup.add_polygon(t.data(), 3);
    return soup;
}

TriMesh mesh_of(const py::array& V, const py::array& F, const BuildOptions& options = {}) {
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

/// A verdict of `fhr verify --json` (exchange::verdict_json) as a dict, without the file names
/// (`file`, `mesh`) the command adds.
py::dict verdict_dict(const std::string& json) {
    py::dict d = py::module_::import("json").attr("loads")(json);
    d.attr("pop")("file");
    d.attr("pop")("mesh");
    if (d.contains("domain_file")) d.attr("pop")("domain_file");
    return d;
}

/// The verdict on a `fhr-param 1` file: PARAM-1 (the file was read) and PARAM-2..11.
py::dict verdict(const exchange::ParamFile& file, const TriMesh* mesh, bool paper) {
    exchange::VerifyReport report;
    {
        py::gil_scoped_release unlocked;
        report = exchange::verify(file, mesh, nullptr, paper);
    }
    std::vector<exchange::CheckResult> checks{exchange::grammar_check(file)};
    checks.insert(checks.end(), report.checks.begin(), report.checks.end());
    return verdict_dict(exchange::verdict_json("", std::nullopt, file, checks, report.distortion));
}

/// The verdict on an atlas: ATLAS-1 (it was read) and ATLAS-2..8.
py::dict verdict(const exchange::Atlas& atlas, const TriMesh* mesh, const exchange::AtlasOptions& options, bool lists) {
    exchange::AtlasReport report;
    {
        py::gil_scoped_release unlocked;
        report = exchange::verify_atlas(atlas, mesh, options);
    }
    return verdict_dict(exchange::verdict_json(atlas.source, std::nullopt, atlas, report, lists));
}

/// The verdict on a per-vertex map of T onto D (spec/vertex_map.md VMAP-2..9).
py::dict verdict(const exchange::VertexMapFile& map, const PolygonSoup& T, const PolygonSoup& D, bool lists) {
    exchange::VertexMapReport report;
    {
        py::gil_scoped_release unlocked;
        report = exchange::verify_vertex_map(map, T, D);
    }
    return verdict_dict(exchange::verdict_json(map.source, "", "", map, D, T, report, lists));
}

/// UV as (k, 2) finite numbers.
std::vector<exchange::UV> uv_of(const py::array& UV) {
    require_shape(UV, 2, "UV");
    const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(UV);
    if (!a) throw InvalidInput("UV must hold numbers");
    std::vector<exchange::UV> uv(static_cast<std::size_t>(a.shape(0)));
    const auto r = a.unchecked<2>();
    for (py::ssize_t i = 0; i < r.shape(0); ++i) {
        if (!std::isfinite(r(i, 0)) || !std::isfinite(r(i, 1)))
            throw InvalidInput("UV row " + std::to_string(i) + " is not finite");
        uv[static_cast<std::size_t>(i)] = {r(i, 0), r(i, 1)};
    }
    return uv;
}

/// Points given as faces (k,) and coordinates (k, 3), for phi and psi: each face checked against
/// n_faces, InvalidInput naming the call and the array otherwise.
std::vector<std::pair<std::size_t, std::array<double, 3>>> points_in_faces(const py::array& faces,
                                                                           const py::array& coords, std::size_t n_faces,
                                                                           const std::string& call,
                                                                           const std::string& coords_name,
                                                                           const std::string& face_kind) {
    const auto f = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(faces);
    const auto c = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(coords);
    if (!f || f.ndim() != 1 || !c || c.ndim() != 2 || c.shape(1) != 3 || c.shape(0) != f.shape(0))
        throw InvalidInput(call + " needs faces of shape (k,) and " + coords_name + " of shape (k, 3)");
    std::vector<std::pair<std::size_t, std::array<double, 3>>> points;
    for (py::ssize_t i = 0; i < f.shape(0); ++i) {
        if (f.at(i) < 0 || static_cast<std::size_t>(f.at(i)) >= n_faces)
            throw InvalidInput(face_kind + " " + std::to_string(f.at(i)) + " is out of range");
        points.emplace_back(static_cast<std::size_t>(f.at(i)),
                            std::array<double, 3>{c.at(i, 0), c.at(i, 1), c.at(i, 2)});
    }
    return points;
}

/// Between the steps of a long call (with the GIL released): Ctrl-C raises KeyboardInterrupt
/// there (the call unwinds; nothing has been written), and the caller's progress callback, if any,
/// gets each progress line. Both run on the calling thread (spec/library.md: callbacks never run
/// on the executor's threads).
struct Interruptible final : pipeline::StageObserver {
    explicit Interruptible(py::object progress) : callback(std::move(progress)) {}
    py::object callback;
    pipeline::Timings timings;  ///< for the outputs' timings.json
    void check() const {
        py::gil_scoped_acquire locked;
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    }
    void line(const std::string& text) const {
        check();
        if (!callback.is_none()) {
            py::gil_scoped_acquire locked;
            callback(text);
        }
    }
    void stage(std::string_view name, double seconds, bool in_total) override {
        timings.stage(name, seconds, in_total);
        check();
    }
};

/// A result of fhr.parameterize: the input T, the method's result and the global maps.
class Result {
public:
    Result(TriMesh T, pipeline::RunResult r, pipeline::Timings t, pipeline::Options o)
        : timings(std::move(t)), options(std::move(o)), T_(std::move(T)), r_(std::move(r)) {}
    pipeline::Timings timings;  ///< the stages' seconds, for timings.json
    pipeline::Options options;  ///< the method's options, for report.json (no callbacks)
    const pipeline::Parameterization& p() const { return r_.parameterization; }
    const pipeline::RunResult& run() const { return r_; }
    const TriMesh& T() const { return T_; }
    exchange::ParamFile file() const { return pipeline::to_param_file(p()); }
    const pipeline::GlobalMap& global() {
        if (!global_) {
            if (!p().certified()) throw NumericalFailure("φ and ψ are only defined for a certified parameterization");
            global_.emplace(p());
        }
        return *global_;
    }

private:
    TriMesh T_;
    pipeline::RunResult r_;
    std::optional<pipeline::GlobalMap> global_;
};

void translate(std::exception_ptr error) {
    // The Python classes live in the pure-Python part of the package (fhr/__init__.py).
    auto raise = [](const char* name, const std::exception& e) {
        const py::object cls = py::module_::import("fhr").attr(name);
        PyErr_SetString(cls.ptr(), e.what());
    };
    try {
        if (error) std::rethrow_exception(error);
    } catch (const InvalidInput& e) {
        raise("InvalidInput", e);
    } catch (const PartitionFailure& e) {
        raise("PartitionFailure", e);
    } catch (const NumericalFailure& e) {
        raise("NumericalFailure", e);
    } catch (const InternalError& e) {
        raise("InternalError", e);
    }
}

// What report.json says of the input of a run made from arrays.
pipeline::InputInfo input_info(const Result& r) {
    return {.path = "(arrays)",
            .vertices = r.T().n_vertices(),
            .faces = r.T().n_faces(),
            .genus = genus(r.T()),
            .boundary_loops = boundary_loops(r.T()).size(),
            .components = connected_components(r.T()).count,
            .domain_faces_asked = r.run().domain_faces_asked,
            .domain_faces_requested = r.run().domain_faces_requested};
}

}  // namespace
}  // namespace fhr::python

PYBIND11_MODULE(_fhr, m) {
    using namespace fhr;
    using namespace fhr::python;
    m.doc() = "fhr's C++ library for Python (see the fhr package).";
    m.attr("__version__") = std::string(fhr::version);
    py::register_exception_translator(&translate);

    m.def("page_available", &pipeline::page_available,
          "page_available() -> bool: whether this build holds the run's page (Parameterization.write_html; meson "
          "option page).");
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

    py::class_<Result>(m, "Parameterization", "The result of fhr.parameterize.")
        .def_property_readonly(
            "certified", [](const Result& r) { return r.run().certified(); },
            "Every patch certified one-to-one (Prop. 1) and the independent oracle says valid.")
        .def_property_readonly(
            "domain", [](const Result& r) { return mesh_arrays(r.p().partition.domain.mesh); },
            "(DV, DF): the domain D (after §3, equal to the requested one when D was kept).")
        .def_property_readonly(
            "refined",
            [](const Result& r) {
                return py::make_tuple(vertices_array(r.p().refined_positions), faces_array(r.p().refined_faces));
            },
            "(V', F'): the final T′; its first #V(T) vertices are T's, in T's order.")
        .def_property_readonly(
            "face_patch",
            [](const Result& r) {
                py::array_t<std::int64_t> a(static_cast<py::ssize_t>(r.p().face_patch.size()));
                auto w = a.mutable_unchecked<1>();
                for (std::size_t f = 0; f < r.p().face_patch.size(); ++f)
                    w(static_cast<py::ssize_t>(f)) = r.p().face_patch[f];
                return a;
            },
            "(m',) int64: for each face of T′, the domain face whose patch holds it.")
        .def_property_readonly(
            "face_beta",
            [](const Result& r) {
                const auto& beta = r.p().face_beta;
                py::array_t<double> a({static_cast<py::ssize_t>(beta.size()), py::ssize_t{3}, py::ssize_t{3}});
                auto w = a.mutable_unchecked<3>();
                for (std::size_t f = 0; f < beta.size(); ++f)
                    for (int k = 0; k < 3; ++k)
                        for (int c = 0; c < 3; ++c)
                            w(static_cast<py::ssize_t>(f), k, c) =
                                beta[f][static_cast<std::size_t>(k)][static_cast<std::size_t>(c)];
                return a;
            },
            "(m', 3, 3) float64: for each face of T′ and each of its corners, the barycentric coordinates of ψ "
            "at the corner in its domain face (corner order of DF).")
        .def_property_readonly(
            "oracle",
            [](const Result& r) {
                const exchange::ParamFile file = r.file();
                return verdict(file, &r.T(), true);
            },
            "The independent oracle's verdict on this parameterization against T (as fhr.verify with paper=True: "
            "fhr's map is the paper's).")
        .def(
            "phi",
            [](Result& r, const py::array& faces, const py::array& beta) {
                const pipeline::GlobalMap& g = r.global();
                std::vector<Vec3> out;
                for (const auto& [d, b] :
                     points_in_faces(faces, beta, r.p().partition.domain.mesh.n_faces(), "phi", "beta", "domain face"))
                    out.push_back(g.phi(FaceId(static_cast<FaceId::Index>(d)), b));
                return vertices_array(out);
            },
            py::arg("faces"), py::arg("beta"),
            "phi(faces, beta) -> (k, 3) float64: the points φ(d, β) of the surface for domain faces d and barycentric "
            "coordinates β (corner order of DF).")
        .def(
            "psi",
            [](Result& r, const py::array& faces, const py::array& weights) {
                const pipeline::GlobalMap& g = r.global();
                const auto points =
                    points_in_faces(faces, weights, r.p().refined_faces.size(), "psi", "weights", "face of T′");
                const auto k = static_cast<py::ssize_t>(points.size());
                py::array_t<std::int64_t> d(k);
                py::array_t<double> beta({k, py::ssize_t{3}});
                auto dw = d.mutable_unchecked<1>();
                auto bw = beta.mutable_unchecked<2>();
                for (py::ssize_t i = 0; i < k; ++i) {
                    const auto [face, b] =
                        g.psi(points[static_cast<std::size_t>(i)].first, points[static_cast<std::size_t>(i)].second);
                    dw(i) = face.idx();
                    for (int c = 0; c < 3; ++c) bw(i, c) = b[static_cast<std::size_t>(c)];
                }
                return py::make_tuple(d, beta);
            },
            py::arg("faces"), py::arg("weights"),
            "psi(faces, weights) -> (domain_faces, beta): ψ of the points Σ weights[:, k]·(corner k of face f of T′): "
            "(k,) int64 domain faces and (k, 3) float64 barycentric coordinates in them.")
        .def_property_readonly(
            "wavelets",
            [](const Result& r) -> py::object {
                if (!r.run().wavelets) return py::none();
                const wavelet::WaveletResult& w = *r.run().wavelets;
                py::dict d;
                d["levels"] = w.levels;
                d["remesh"] = py::make_tuple(vertices_array(w.remesh_positions), faces_array(w.remesh_faces));
                d["coefficients"] = w.coefficients;
                d["hausdorff"] = py::make_tuple(w.remesh_hausdorff.lower(), w.remesh_hausdorff.upper());
                d["reconstruction_max_error"] = w.reconstruction_max_error;
                py::list kept;
                for (const wavelet::KeptResult& k : w.kept) {
                    py::dict e;
                    e["percent"] = k.percent;
                    e["count"] = k.count;
                    e["V"] = vertices_array(k.positions);
                    e["l2_error"] = k.l2_error;
                    e["hausdorff"] = py::make_tuple(k.hausdorff.lower(), k.hausdorff.upper());
                    kept.append(e);
                }
                d["kept"] = kept;
                return d;
            },
            "§5 with levels ≥ 1, else None: the remesh (V, F) of D^J sampled through φ, the number of prewavelet "
            "coefficients, its Hausdorff bracket to T, the round trip's largest error, and per kept percentage the "
            "reconstruction V (faces: the remesh's), its L2 error and Hausdorff bracket.")
        .def(
            "write_param", [](const Result& r, const std::string& path) { exchange::write_param(path, r.file()); },
            py::arg("path"), "write_param(path): the `fhr-param 1` file (spec/param.md), as `fhr run` writes it.")
        .def(
            "write",
            [](const Result& r, const std::string& dir, bool figures) {
                const pipeline::InputInfo input = input_info(r);
                const wavelet::WaveletResult* wavelets = r.run().wavelets ? &*r.run().wavelets : nullptr;
                py::gil_scoped_release unlocked;
                pipeline::write_outputs(dir, input, r.p(), r.run().oracle, r.timings, r.options, wavelets);
                if (figures) pipeline::write_figures(dir, r.T(), r.p(), 2, wavelets);
            },
            py::arg("dir"), py::arg("figures") = false,
            "write(dir, figures=False): all of `fhr run`'s outputs into dir (spec/cli.md CLI-RUN-*): domain.off, "
            "geodesics.obj, refined.ply, param.fhrp, textured.obj, report.json, timings.json, §5's meshes; with "
            "figures, figures/ as `fhr run --figures` (z up).")
        .def(
            "write_html",
            [](const Result& r, const std::string& path, const std::string& up, std::size_t page_faces) {
                if (up != "x" && up != "y" && up != "z")
                    throw InvalidInput("up must be 'x', 'y' or 'z', not '" + up + "'");
                const pipeline::InputInfo input = input_info(r);
                const wavelet::WaveletResult* wavelets = r.run().wavelets ? &*r.run().wavelets : nullptr;
                py::gil_scoped_release unlocked;
                pipeline::PageContent content{
                    .title = std::filesystem::path(path).stem().string(),
                    .report_json = pipeline::report_json(input, r.p(), r.run().oracle, r.options, wavelets),
                    .timings_json = pipeline::timings_json(r.timings),
                    .up_axis = up[0] - 'x',
                    .wavelets = wavelets,
                    .rate = {},
                    .display_faces = page_faces};
                if (wavelets) content.rate = pipeline::rate_steps(r.T(), r.p().partition.domain.mesh, *wavelets);
                pipeline::write_page(path, r.T(), r.p(), content);
            },
            py::arg("path"), py::arg("up") = "y", py::arg("page_faces") = pipeline::page_display_faces,
            "write_html(path, up='y', page_faces=2000000): the run's interactive page, as `fhr run --html` writes it "
            "(spec/page.md), into the file path; T′ drawn as is up to page_faces faces, beyond a display copy. "
            "ValueError when this build holds no page (meson option page).");

    m.def(
        "parameterize",
        [](const py::array& V, const py::array& F, std::size_t faces, std::optional<py::tuple> domain,
           const std::string& weights, int levels, const std::vector<double>& keep, py::object progress) {
            TriMesh T = mesh_of(V, F);
            Interruptible interruptible(std::move(progress));
            pipeline::RunOptions options;
            options.faces = faces;
            if ((faces > 0) == domain.has_value()) throw InvalidInput("give exactly one of faces and domain");
            if (domain) {  // (DV, DF, t_vertex): domain vertex j at vertex t_vertex[j] of T
                if (domain->size() != 3) throw InvalidInput("domain must be (DV, DF, t_vertex)");
                const py::array x = py::array::ensure((*domain)[2]);
                if (!x || x.ndim() != 1 || (x.dtype().kind() != 'i' && x.dtype().kind() != 'u'))
                    throw InvalidInput("t_vertex must be a 1-D array of vertex indices of T");
                const auto xs = py::array_t<std::int64_t, py::array::forcecast>::ensure(x);
                std::vector<io::CorrespondenceEntry> entries;
                for (py::ssize_t j = 0; j < xs.shape(0); ++j) {
                    if (xs.at(j) < 0 || static_cast<std::uint64_t>(xs.at(j)) >= T.n_vertices())
                        throw InvalidInput("t_vertex[" + std::to_string(j) + "] = " + std::to_string(xs.at(j)) +
                                           " is not a vertex of T");
                    entries.push_back({SurfacePoint::at_vertex(VertexId(static_cast<VertexId::Index>(xs.at(j)))),
                                       static_cast<std::uint64_t>(j + 1)});
                }
                options.domain =
                    domain::attach_domain(T, mesh_of(py::array::ensure((*domain)[0]), py::array::ensure((*domain)[1])),
                                          entries, {"domain", "t_vertex"});
            }
            options.method.map.weights = param::parse_weights(weights);
            options.method.progress = [&](const std::string& text) { interruptible.line(text); };
            options.method.observer = &interruptible;
            options.levels = levels;
            options.keep = keep;
            pipeline::RunResult result;
            {
                py::gil_scoped_release unlocked;
                result = pipeline::run(T, options);
            }
            pipeline::Options kept = options.method;
            kept.progress = nullptr;
            kept.observer = nullptr;
            return Result(std::move(T), std::move(result), std::move(interruptible.timings), std::move(kept));
        },
        py::arg("V"), py::arg("F"), py::arg("faces") = 0, py::arg("domain") = py::none(),
        py::arg("weights") = "shape-preserving", py::arg("levels") = 0, py::arg("keep") = std::vector<double>{},
        py::arg("progress") = py::none(),
        "parameterize(V, F, faces=0, domain=None, weights='shape-preserving', levels=0, keep=[], progress=None) -> "
        "Parameterization: the paper's method (§2 decimation to `faces`, or a given domain=(DV, DF, t_vertex) with "
        "domain "
        "vertex j at vertex t_vertex[j] of T; §3 partition keeping D; §4 certified patch maps; the oracle; §5 with "
        "levels ≥ 1). progress(line) is called with each progress line; Ctrl-C interrupts between steps "
        "(KeyboardInterrupt).");
    m.def(
        "verify",
        [](const Result& r, std::optional<std::pair<py::array, py::array>> mesh, bool paper) {
            const exchange::ParamFile file = r.file();
            if (!mesh) return verdict(file, &r.T(), paper);
            const TriMesh T = mesh_of(mesh->first, mesh->second);
            return verdict(file, &T, paper);
        },
        py::arg("parameterization"), py::arg("mesh") = py::none(), py::arg("paper") = false,
        "verify(parameterization, mesh=None, paper=False) -> dict: the oracle on what write_param would write, against "
        "its own T or the given (V, F); paper=True judges chord length (PARAM-10) too.");
    m.def(
        "verify",
        [](const std::string& path, std::optional<std::pair<py::array, py::array>> mesh, bool no_mirror, bool strict,
           bool paper) {
            std::optional<TriMesh> T;
            if (mesh) T = mesh_of(mesh->first, mesh->second);
            const std::string bytes = io::read_bytes(path);
            if (exchange::kind_of_content(bytes, path) == exchange::MapKind::param)
                return verdict(exchange::parse_param(bytes, path), T ? &*T : nullptr, paper);
            return verdict(exchange::parse_atlas(bytes, path), T ? &*T : nullptr,
                           {.no_mirror = no_mirror, .strict = strict}, false);
        },
        py::arg("path"), py::arg("mesh") = py::none(), py::arg("no_mirror") = false, py::arg("strict") = false,
        py::arg("paper") = false,
        "verify(path, mesh=None, no_mirror=False, strict=False, paper=False) -> dict: the oracle's checks of a "
        "`fhr-param 1` file "
        "(PARAM-1..11) or a UV atlas, OBJ or PLY (ATLAS-1..8; the kind by content, as `fhr verify`), against the "
        "surface (V, F) when given: the keys and values of `fhr verify --json` without file names (kind, valid, "
        "first_failure: the first check id that did not pass, counts, checks: id, title, result, checked, failures, "
        "first_failure, face, vertex, patch; distortion; an atlas's charts, folds, overlaps, contacts, seams, "
        "packing).");
    m.def(
        "verify_atlas",
        [](const py::array& V, const py::array& F, const py::array& UV, std::optional<py::array> FUV,
           std::optional<py::array> textures, std::optional<std::pair<py::array, py::array>> mesh, bool no_mirror,
           bool strict, bool lists) {
            exchange::Atlas a;
            a.source = "atlas";
            a.points = points_of(V);
            a.faces = triangles_of(F, a.points.size());
            a.uv = uv_of(UV);
            a.face_uv = FUV ? triangles_of(*FUV, a.uv.size()) : triangles_of(F, a.uv.size());
            if (a.face_uv.size() != a.faces.size())
                throw InvalidInput("FUV has " + std::to_string(a.face_uv.size()) + " rows but F has " +
                                   std::to_string(a.faces.size()));
            a.face_texture.assign(a.faces.size(), 0);
            if (textures) {
                const auto t = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(*textures);
                if (!t || t.ndim() != 1 || static_cast<std::size_t>(t.shape(0)) != a.faces.size())
                    throw InvalidInput("textures must have shape (" + std::to_string(a.faces.size()) + ",)");
                for (py::ssize_t i = 0; i < t.shape(0); ++i) {
                    if (t.at(i) < 0 || t.at(i) > 0xffffffffLL)
                        throw InvalidInput("texture " + std::to_string(t.at(i)) + " is out of range");
                    a.face_texture[static_cast<std::size_t>(i)] = static_cast<std::uint32_t>(t.at(i));
                }
            }
            std::optional<TriMesh> T;
            if (mesh) T = mesh_of(mesh->first, mesh->second);
            return verdict(a, T ? &*T : nullptr, {.no_mirror = no_mirror, .strict = strict}, lists);
        },
        py::arg("V"), py::arg("F"), py::arg("UV"), py::arg("FUV") = py::none(), py::arg("textures") = py::none(),
        py::arg("mesh") = py::none(), py::arg("no_mirror") = false, py::arg("strict") = false, py::arg("lists") = false,
        "verify_atlas(V, F, UV, FUV=None, textures=None, mesh=None, no_mirror=False, strict=False, lists=False) -> "
        "dict: "
        "the atlas oracle (spec/atlas.md) on arrays: positions V (n, 3), triangles F (m, 3), texture coordinates UV "
        "(k, 2) indexed per corner by FUV (m, 3), or per vertex like F when FUV is None (then k = n); textures (m,) a "
        "texture number per face. The dict of `fhr verify --json` without file names; with lists, the folded faces, "
        "overlapping pairs and contacts themselves.");
    m.def(
        "verify_vertex_map",
        [](const py::array& V, const py::array& F, const py::array& DV, const py::array& DF, const py::array& faces,
           const py::array& weights, bool lists) {
            const PolygonSoup T = soup_of(V, F), D = soup_of(DV, DF);
            const auto f = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(faces);
            const auto w = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(weights);
            const auto n = static_cast<py::ssize_t>(T.points.size());
            if (!f || f.ndim() != 1 || f.shape(0) != n)
                throw InvalidInput("faces must have shape (" + std::to_string(n) + ",)");
            if (!w || w.ndim() != 2 || w.shape(0) != n || w.shape(1) != 3)
                throw InvalidInput("weights must have shape (" + std::to_string(n) + ", 3)");
            exchange::VertexMapFile map;
            map.source = "vertex map";
            map.records.resize(static_cast<std::size_t>(n));
            for (py::ssize_t i = 0; i < n; ++i) {
                auto& r = map.records[static_cast<std::size_t>(i)];
                if (f.at(i) >= 0) {
                    r.ref = exchange::VertexImageRecord::Ref::face;
                    r.a = f.at(i);
                }
                r.weights = {w.at(i, 0), w.at(i, 1), w.at(i, 2)};
            }
            return verdict(map, T, D, lists);
        },
        py::arg("V"), py::arg("F"), py::arg("DV"), py::arg("DF"), py::arg("faces"), py::arg("weights"),
        py::arg("lists") = false,
        "verify_vertex_map(V, F, DV, DF, faces, weights, lists=False) -> dict: the per-vertex map oracle "
        "(spec/vertex_map.md, "
        "rule adjacent) on arrays: T = (V, F), D = (DV, DF), and per vertex of T a face of D (faces (n,), -1 for none) "
        "and the weights of its corners (weights (n, 3)). The dict of `fhr verify --vertex-map --json` without file "
        "names; with lists, the folded faces and the edges without an image.");
    m.def(
        "verify_vertex_map",
        [](const std::string& path, const std::pair<py::array, py::array>& mesh,
           const std::pair<py::array, py::array>& domain, std::optional<std::string> format, bool lists) {
            const PolygonSoup T = soup_of(mesh.first, mesh.second), D = soup_of(domain.first, domain.second);
            std::optional<exchange::VertexMapFormat> f;
            if (format) {
                f = exchange::vertex_map_format_named(*format);
                if (!f) throw InvalidInput(path, 0, "format must be plain, corr, vtpm or ijv, not '" + *format + "'");
            }
            return verdict(exchange::read_vertex_map(path, f, T.points.size(), D.points.size()), T, D, lists);
        },
        py::arg("path"), py::arg("mesh"), py::arg("domain"), py::arg("format") = py::none(), py::arg("lists") = false,
        "verify_vertex_map(path, mesh, domain, format=None, lists=False) -> dict: the same on a map file (.vmap, "
        ".corr, "
        ".vtpm, .ijv, or format=) of T = mesh (V, F) onto D = domain (DV, DF).");
}
