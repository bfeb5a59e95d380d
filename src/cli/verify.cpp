// FHR cli — `fhr verify PARAM.fhrp [--mesh INPUT] [--json]`: the oracle for any producer of a
// parameterization (spec/cli.md CLI-VERIFY-*, spec/param.md). It reads the file with the strict
// reader (PARAM-1), checks PARAM-2..10 and, with the input mesh T, PARAM-11 (src/fhr/exchange/verify.hpp),
// and prints a verdict and one line per check, or one JSON object. D, T′ and T may have boundary
// and several components (issue 19).
// Exit codes: 0 valid, 1 invalid (a check failed), 2 unreadable (the file or the mesh).
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include <fhr/core/errors.hpp>
#include <fhr/exchange/fhr_param.hpp>
#include <fhr/exchange/verify.hpp>
#include <fhr/io/detail/json.hpp>
#include "cli/common.hpp"

namespace fhr::cli {
namespace {

/// PARAM-1 is decided by the reader: a file that is read satisfies it.
std::string print_human(const std::string& path, const exchange::ParamFile& file,
                        const std::vector<exchange::CheckResult>& checks) {
    const exchange::CheckResult* first = nullptr;
    for (const auto& c : checks)
        if (!first && c.status != exchange::CheckStatus::pass) first = &c;
    std::string s = path + ": " + (first ? "INVALID: " + first->id + ": " + first->first_failure : "valid") + "\n";
    s += "  D: " + std::to_string(file.domain_vertices.size()) + " vertices, " + std::to_string(file.domain_faces.size()) +
         " faces; T': " + std::to_string(file.surface_vertices.size()) + " vertices, " +
         std::to_string(file.surface_faces.size()) + " faces\n";
    for (const auto& c : checks) {
        char head[64];
        std::snprintf(head, sizeof head, "  %-9s %-8s ", c.id.c_str(), exchange::to_string(c.status));
        s += head + c.title;
        if (c.status == exchange::CheckStatus::pass) s += " (" + std::to_string(c.checked) + " checked)";
        else if (c.status == exchange::CheckStatus::fail)
            s += ": " + std::to_string(c.failures) + " of " + std::to_string(c.checked) + " fail; first: " + c.first_failure;
        else s += ": " + c.first_failure;
        s += "\n";
    }
    return s;
}

void index_or_null(io::JsonWriter& j, const char* key, std::int64_t index) {
    j.key(key);
    if (index < 0) j.null();
    else j.value(index);
}

std::string print_json(const std::string& path, const std::optional<std::string>& mesh,
                       const exchange::ParamFile& file, const std::vector<exchange::CheckResult>& checks) {
    const exchange::CheckResult* first = nullptr;
    for (const auto& c : checks)
        if (!first && c.status != exchange::CheckStatus::pass) first = &c;
    io::JsonWriter j;
    j.begin_object().key("file").value(path).key("mesh");
    if (mesh) j.value(*mesh);
    else j.null();
    j.key("readable").value(true).key("valid").value(first == nullptr).key("first_failure");
    if (first) j.value(first->id);
    else j.null();
    j.key("domain").begin_object().key("vertices").value(file.domain_vertices.size());
    j.key("faces").value(file.domain_faces.size()).end_object();
    j.key("surface").begin_object().key("vertices").value(file.surface_vertices.size());
    j.key("faces").value(file.surface_faces.size()).end_object();
    j.key("checks").begin_array();
    for (const auto& c : checks) {
        j.begin_object().key("id").value(c.id).key("title").value(c.title);
        j.key("result").value(exchange::to_string(c.status));
        j.key("checked").value(c.checked).key("failures").value(c.failures);
        j.key("first_failure");
        if (c.first_failure.empty()) j.null();
        else j.value(c.first_failure);
        index_or_null(j, "face", c.face);
        index_or_null(j, "vertex", c.vertex);
        index_or_null(j, "patch", c.patch);
        j.end_object();
    }
    j.end_array().end_object();
    return j.str();
}

}  // namespace

int run_verify(const std::vector<std::string>& argv) {
    const Args args(argv, {"json"}, {"mesh"});
    const std::string& path = args.single_positional("PARAM.fhrp");
    const std::optional<std::string> mesh_path = args.get("mesh");
    exchange::ParamFile file;
    std::optional<TriMesh> mesh;
    try {
        file = exchange::read_param(path);
        // T may have boundary and several components, like D and T′ (spec/param.md PARAM-11).
        if (mesh_path) mesh = load_mesh(*mesh_path, {});
    } catch (const InvalidInput& e) {  // unreadable: exit 2 through main, with the one-line error
        if (args.flag("json")) {
            io::JsonWriter j;
            j.begin_object().key("file").value(path).key("readable").value(false).key("valid").value(false);
            j.key("error").value(e.what()).end_object();
            std::fputs(j.str().c_str(), stdout);
        }
        throw;
    }
    std::vector<exchange::CheckResult> checks{exchange::grammar_check(file)};
    exchange::VerifyReport report = exchange::verify(file, mesh ? &*mesh : nullptr);
    const bool valid = report.valid();
    for (auto& c : report.checks) checks.push_back(std::move(c));
    const std::string out = args.flag("json") ? print_json(path, mesh_path, file, checks) : print_human(path, file, checks);
    std::fputs(out.c_str(), stdout);
    return valid ? 0 : 1;
}

}  // namespace fhr::cli
