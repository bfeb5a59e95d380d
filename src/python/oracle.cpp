// fhr for Python (beyond the paper) — the independent oracle (src/fhr/exchange) on `fhr-param 1`
// files, UV atlases and per-vertex maps, from files or arrays: the verdicts of `fhr verify --json`
// as dicts.
#include "bindings.hpp"

#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <fhr/core/errors.hpp>
#include <fhr/exchange/atlas.hpp>
#include <fhr/exchange/verdict.hpp>
#include <fhr/exchange/verify.hpp>
#include <fhr/exchange/vertex_map.hpp>
#include <fhr/io/read.hpp>

namespace fhr::python {
namespace {

/// A verdict of `fhr verify --json` (exchange::verdict_json) as a dict, without the file names
/// (`file`, `mesh`) the command adds.
py::dict verdict_dict(const std::string& json) {
    py::dict d = py::module_::import("json").attr("loads")(json);
    d.attr("pop")("file");
    d.attr("pop")("mesh");
    if (d.contains("domain_file")) d.attr("pop")("domain_file");
    return d;
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

}  // namespace

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

void bind_oracle(py::module_& m) {
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

}  // namespace fhr::python
