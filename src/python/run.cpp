// fhr for Python (beyond the paper) — the whole method (pipeline::run) on arrays, and its result:
// D, T′, each face's patch and β, the global maps φ and ψ, §5's meshes, and the run's files and
// page as `fhr run` writes them (src/fhr/app). Long calls release the GIL; Ctrl-C interrupts
// between steps.
#include "bindings.hpp"

#include <pybind11/stl.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <fhr/app/outputs.hpp>
#include <fhr/app/page.hpp>
#include <fhr/core/errors.hpp>
#include <fhr/core/topology.hpp>
#include <fhr/domain/user_domain.hpp>
#include <fhr/io/correspondence.hpp>
#include <fhr/pipeline/run.hpp>

namespace fhr::python {
namespace {

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
    app::Timings timings;  ///< for the outputs' timings.json
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
    Result(TriMesh T, pipeline::RunResult r, app::Timings t, pipeline::Options o)
        : timings(std::move(t)), options(std::move(o)), T_(std::move(T)), r_(std::move(r)) {}
    app::Timings timings;       ///< the stages' seconds, for timings.json
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

// What report.json says of the input of a run made from arrays.
app::InputInfo input_info(const Result& r) {
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

void bind_run(py::module_& m) {
    m.def("page_available", &app::page_available,
          "page_available() -> bool: whether this build holds the run's page (Parameterization.write_html; meson "
          "option page).");
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
                for (RefinedFaceId f : r.p().face_patch.ids())
                    w(static_cast<py::ssize_t>(f.idx())) = r.p().face_patch[f].idx();
                return a;
            },
            "(m',) int64: for each face of T′, the domain face whose patch holds it.")
        .def_property_readonly(
            "face_beta",
            [](const Result& r) {
                const auto& beta = r.p().face_beta;
                py::array_t<double> a({static_cast<py::ssize_t>(beta.size()), py::ssize_t{3}, py::ssize_t{3}});
                auto w = a.mutable_unchecked<3>();
                for (RefinedFaceId f : beta.ids())
                    for (int k = 0; k < 3; ++k)
                        for (int c = 0; c < 3; ++c)
                            w(static_cast<py::ssize_t>(f.idx()), k, c) =
                                beta[f][static_cast<std::size_t>(k)][static_cast<std::size_t>(c)];
                return a;
            },
            "(m', 3, 3) float64: for each face of T′ and each of its corners, the barycentric coordinates of ψ "
            "at the corner in its domain face (corner order of DF).")
        .def_property_readonly(
            "oracle",
            [](const Result& r) {
                const exchange::ParamFile file = r.file();
                return verdict(file, &r.T(), !r.options.relax);
            },
            "The independent oracle's verdict on this parameterization against T (as fhr.verify with paper=True "
            "when the map is the paper's, map=\"paper\": chord length judged).")
        .def(
            "phi",
            [](Result& r, const py::array& faces, const py::array& beta) {
                const pipeline::GlobalMap& g = r.global();
                std::vector<Vec3> out;
                for (const auto& [d, b] :
                     points_in_faces(faces, beta, r.p().partition.domain.mesh.n_faces(), "phi", "beta", "domain face"))
                    out.push_back(g.phi(DFaceId(static_cast<DFaceId::Index>(d)), b));
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
                    const auto [face, b] = g.psi(
                        RefinedFaceId(static_cast<RefinedFaceId::Index>(points[static_cast<std::size_t>(i)].first)),
                        points[static_cast<std::size_t>(i)].second);
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
                const app::InputInfo input = input_info(r);
                const wavelet::WaveletResult* wavelets = r.run().wavelets ? &*r.run().wavelets : nullptr;
                py::gil_scoped_release unlocked;
                app::write_outputs(dir, input, r.p(), r.run().oracle, r.timings, r.options, wavelets);
                if (figures) app::write_figures(dir, r.T(), r.p(), 2, wavelets);
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
                const app::InputInfo input = input_info(r);
                const wavelet::WaveletResult* wavelets = r.run().wavelets ? &*r.run().wavelets : nullptr;
                py::gil_scoped_release unlocked;
                app::PageContent content{
                    .title = std::filesystem::path(path).stem().string(),
                    .report_json = app::report_json(input, r.p(), r.run().oracle, r.options, wavelets),
                    .timings_json = app::timings_json(r.timings),
                    .up_axis = up[0] - 'x',
                    .wavelets = wavelets,
                    .rate = {},
                    .display_faces = page_faces};
                if (wavelets) content.rate = app::rate_steps(r.T(), r.p().partition.domain.mesh, *wavelets);
                app::write_page(path, r.T(), r.p(), content);
            },
            py::arg("path"), py::arg("up") = "y", py::arg("page_faces") = app::page_display_faces,
            "write_html(path, up='y', page_faces=2000000): the run's interactive page, as `fhr run --html` writes it "
            "(spec/page.md), into the file path; T′ drawn as is up to page_faces faces, beyond a display copy. "
            "ValueError when this build holds no page (meson option page).");

    m.def(
        "parameterize",
        [](const py::array& V, const py::array& F, std::size_t faces, std::optional<py::tuple> domain,
           const std::string& weights, const std::string& map, int levels, const std::vector<double>& keep,
           py::object progress) {
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
            if (map != "relaxed" && map != "paper")
                throw InvalidInput("map must be 'relaxed' or 'paper', not '" + map + "'");
            options.method.relax = map == "relaxed";
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
        py::arg("weights") = "shape-preserving", py::arg("map") = "relaxed", py::arg("levels") = 0,
        py::arg("keep") = std::vector<double>{}, py::arg("progress") = py::none(),
        "parameterize(V, F, faces=0, domain=None, weights='shape-preserving', map='relaxed', levels=0, keep=[], "
        "progress=None) -> Parameterization: the paper's method (§2 decimation to `faces`, or a given domain=(DV, DF, "
        "t_vertex) with domain vertex j at vertex t_vertex[j] of T; §3 partition keeping D; §4 certified patch maps, "
        "relaxed where that lowers their distortion, or map='paper' for the paper's own; the oracle; §5 with "
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
}

}  // namespace fhr::python
