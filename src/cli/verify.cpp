// FHR cli — `fhr verify FILE [--mesh INPUT] [--json] [--kind K]`: the oracle for any producer of a
// parameterization (spec/cli.md CLI-VERIFY-*). The kind of map is decided by the file's content: a
// `fhr-param 1` file (spec/param.md: PARAM-1 by the strict reader, PARAM-2..10, and PARAM-11 with
// the input mesh T) or a UV atlas, PLY or OBJ (spec/atlas.md: ATLAS-1..7, and ATLAS-8 with T); and
// `fhr verify --vertex-map MAP --domain D --mesh T` judges a per-vertex map of T onto D
// (spec/vertex_map.md VMAP-1..9). It prints a verdict and one line per check, or one JSON object
// with the distortion figures (spec/distortion.md). D, T′ and T may have boundary and several
// components.
// Exit codes: 0 valid, 1 invalid (a check failed), 2 unreadable (the file or the mesh).
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include <fhr/core/errors.hpp>
#include <fhr/exchange/atlas.hpp>
#include <fhr/exchange/fhr_param.hpp>
#include <fhr/exchange/verdict.hpp>
#include <fhr/exchange/verify.hpp>
#include <fhr/exchange/vertex_map.hpp>
#include <fhr/io/detail/json.hpp>
#include <fhr/io/read.hpp>
#include "cli/common.hpp"

namespace fhr::cli {
namespace {

/// PARAM-1 (ATLAS-1) is decided by the reader: a file that is read satisfies it. `sizes` is the
/// line under the verdict.
std::string print_human(const std::string& path, const std::string& sizes,
                        const std::vector<exchange::CheckResult>& checks) {
    const exchange::CheckResult* first = exchange::first_judged_failure(checks);
    std::string s = path + ": " + (first ? "INVALID: " + first->id + ": " + first->first_failure : "valid") + "\n";
    s += "  " + sizes + "\n";
    for (const auto& c : checks) {
        char head[64];
        std::snprintf(head, sizeof head, "  %-9s %-8s ", c.id.c_str(), exchange::to_string(c.status));
        s += head + c.title;
        if (c.status == exchange::CheckStatus::info)  // reported, not judged (PARAM-10, ATLAS-7)
            s += ": " + std::to_string(c.failures) + " of " + std::to_string(c.checked) +
                 " (reported, not judged); first: " + c.first_failure;
        else if (c.status == exchange::CheckStatus::pass)
            s += " (" + std::to_string(c.checked) + " checked)";
        else if (c.status == exchange::CheckStatus::fail)
            s += ": " + std::to_string(c.failures) + " of " + std::to_string(c.checked) +
                 " fail; first: " + c.first_failure;
        else
            s += ": " + c.first_failure;
        s += "\n";
    }
    return s;
}

std::string atlas_sizes(const exchange::Atlas& atlas, const exchange::AtlasReport& report) {
    return "atlas: " + std::to_string(report.vertices) + " vertices, " + std::to_string(atlas.faces.size()) +
           " faces, " + std::to_string(report.charts) + " charts (" + std::to_string(report.mirrored_charts) +
           " mirrored), " + std::to_string(report.textures) + (report.textures == 1 ? " texture" : " textures");
}

/// `--json`'s verdict on a file (or mesh) that cannot be read (CLI-VERIFY-4); exit 2 follows.
void print_unreadable(const std::string& path, const InvalidInput& e) {
    io::JsonWriter j;
    j.begin_object().key("file").value(path).key("readable").value(false).key("valid").value(false);
    j.key("error").value(e.what()).end_object();
    std::fputs(j.str().c_str(), stdout);
}

/// The kind of FILE: `--kind` when given, else by content (exchange::kind_of_content).
std::string kind_of(const std::string& path, const std::optional<std::string>& kind) {
    if (kind) {
        if (*kind != "param" && *kind != "atlas") usage_error("--kind must be param or atlas, not '" + *kind + "'");
        return *kind;
    }
    return exchange::kind_of_content(io::read_bytes(path), path) == exchange::MapKind::param ? "param" : "atlas";
}

/// `fhr verify --vertex-map MAP --domain D --mesh T [--rule adjacent] [--format F]`.
int run_verify_vertex_map(const Args& args) {
    const std::string path = *args.get("vertex-map");
    if (!args.positional().empty()) usage_error("--vertex-map takes no FILE: the map is its value");
    const std::string& domain_path = args.require("domain");
    const std::string& mesh_path = args.require("mesh");
    if (const auto rule = args.get("rule"); rule && *rule != "adjacent")
        usage_error(*rule == "geodesic"
                        ? std::string("--rule geodesic is not implemented (spec/vertex_map.md); use adjacent")
                        : "--rule must be adjacent, not '" + *rule + "'");
    std::optional<exchange::VertexMapFormat> format;
    if (const auto name = args.get("format")) {
        format = exchange::vertex_map_format_named(*name);
        if (!format) usage_error("--format must be plain, corr, vtpm or ijv, not '" + *name + "'");
    }
    const bool json = args.flag("json");
    PolygonSoup T, D;
    exchange::VertexMapFile map;
    try {
        D = io::read_soup(domain_path);
        T = io::read_soup(mesh_path);
        map = exchange::read_vertex_map(path, format, T.points.size(), D.points.size());
    } catch (const InvalidInput& e) {
        if (json) print_unreadable(path, e);
        throw;
    }
    const exchange::VertexMapReport report = exchange::verify_vertex_map(map, T, D);
    const std::string out =
        json ? exchange::verdict_json(path, domain_path, mesh_path, map, D, T, report, args.flag("list"))
             : print_human(path,
                           std::string("vertex map (") + exchange::to_string(map.format) +
                               ", rule adjacent) of T: " + std::to_string(T.points.size()) + " vertices, " +
                               std::to_string(T.polygon_count()) + " faces onto D: " + std::to_string(D.points.size()) +
                               " vertices, " + std::to_string(D.polygon_count()) + " faces",
                           report.checks);
    std::fputs(out.c_str(), stdout);
    return report.valid() ? 0 : 1;
}

}  // namespace

int run_verify(const std::vector<std::string>& argv) {
    const Args args(argv, {"json", "no-mirror", "strict", "list", "paper"},
                    {"mesh", "kind", "vertex-map", "domain", "rule", "format"});
    if (args.get("vertex-map")) return run_verify_vertex_map(args);
    for (const char* option : {"domain", "rule", "format"})
        if (args.get(option)) usage_error(std::string("--") + option + " is for --vertex-map");
    const std::string& path = args.single_positional("FILE");
    const std::optional<std::string> mesh_path = args.get("mesh");
    const bool json = args.flag("json");
    std::string kind;
    exchange::ParamFile file;
    exchange::Atlas atlas;
    std::optional<TriMesh> mesh;
    try {
        kind = kind_of(path, args.get("kind"));
        if (kind == "param")
            file = exchange::read_param(path);
        else
            atlas = exchange::read_atlas(path);
        // T may have boundary and several components, like D and T′ (spec/param.md PARAM-11).
        if (mesh_path) mesh = load_mesh(*mesh_path, {});
    } catch (const InvalidInput& e) {  // unreadable: exit 2 through main, with the one-line error
        if (json) print_unreadable(path, e);
        throw;
    }
    std::string out;
    bool valid = false;
    if (kind == "param") {
        std::vector<exchange::CheckResult> checks{exchange::grammar_check(file)};
        exchange::VerifyReport report = exchange::verify(file, mesh ? &*mesh : nullptr, nullptr, args.flag("paper"));
        valid = report.valid();
        for (auto& c : report.checks) checks.push_back(std::move(c));
        out = json ? exchange::verdict_json(path, mesh_path, file, checks, report.distortion)
                   : print_human(path,
                                 "D: " + std::to_string(file.domain_vertices.size()) + " vertices, " +
                                     std::to_string(file.domain_faces.size()) +
                                     " faces; T': " + std::to_string(file.surface_vertices.size()) + " vertices, " +
                                     std::to_string(file.surface_faces.size()) + " faces",
                                 checks);
    } else {
        const exchange::AtlasOptions options{.no_mirror = args.flag("no-mirror"), .strict = args.flag("strict")};
        const exchange::AtlasReport report = exchange::verify_atlas(atlas, mesh ? &*mesh : nullptr, options);
        valid = report.valid();
        out = json ? exchange::verdict_json(path, mesh_path, atlas, report, args.flag("list"))
                   : print_human(path, atlas_sizes(atlas, report), report.checks);
    }
    std::fputs(out.c_str(), stdout);
    return valid ? 0 : 1;
}

}  // namespace fhr::cli
