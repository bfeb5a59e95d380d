// FHR exchange — the oracle's verdicts as JSON (verdict.hpp, spec/cli.md CLI-VERIFY-4).
#include <fhr/exchange/verdict.hpp>

#include <fhr/io/detail/json.hpp>

namespace fhr::exchange {

namespace {

void index_or_null(io::JsonWriter& j, const char* key, std::int64_t index) {
    j.key(key);
    if (index < 0)
        j.null();
    else
        j.value(index);
}

void optional_value(io::JsonWriter& j, const char* key, const std::optional<double>& x) {
    j.key(key);
    if (x)
        j.value(*x);
    else
        j.null();
}

}  // namespace

void write_distortion_fields(io::JsonWriter& j, const Distortion& d) {
    optional_value(j, "l2_stretch", d.l2_stretch);
    optional_value(j, "linf_stretch", d.linf_stretch);
    optional_value(j, "symmetric_dirichlet", d.symmetric_dirichlet);
    j.key("anisotropy").begin_object();
    optional_value(j, "p50", d.anisotropy_p50);
    optional_value(j, "p99", d.anisotropy_p99);
    optional_value(j, "p999", d.anisotropy_p999);
    optional_value(j, "max", d.anisotropy_max);
    j.key("above_10").value(d.anisotropy_above_10).end_object();
    j.key("area_distortion").begin_object();
    optional_value(j, "p99", d.area_distortion_p99);
    optional_value(j, "max", d.area_distortion_max);
    j.end_object();
    j.key("degenerate").value(d.degenerate);
}

namespace {

/// The keys every kind shares (CLI-VERIFY-4) before `domain` and `surface`, which the caller writes.
void write_head(io::JsonWriter& j, const std::string& path, const std::optional<std::string>& mesh, const char* kind,
                const std::vector<CheckResult>& checks, const char* rule = nullptr) {
    const CheckResult* first = first_judged_failure(checks);
    j.begin_object().key("file").value(path).key("mesh");
    if (mesh)
        j.value(*mesh);
    else
        j.null();
    j.key("kind").value(kind).key("rule");
    if (rule)
        j.value(rule);
    else
        j.null();
    j.key("readable").value(true).key("valid").value(first == nullptr).key("first_failure");
    if (first)
        j.value(first->id);
    else
        j.null();
}

/// The `checks` array (CLI-VERIFY-4); an atlas check's entry also has `chart`, `u` and `v`.
void write_checks(io::JsonWriter& j, const std::vector<CheckResult>& checks) {
    j.key("checks").begin_array();
    for (const auto& c : checks) {
        j.begin_object().key("id").value(c.id).key("title").value(c.title);
        j.key("result").value(to_string(c.status));
        j.key("checked").value(c.checked).key("failures").value(c.failures);
        j.key("first_failure");
        if (c.first_failure.empty())
            j.null();
        else
            j.value(c.first_failure);
        index_or_null(j, "face", c.face);
        index_or_null(j, "vertex", c.vertex);
        index_or_null(j, "patch", c.patch);
        if (c.id.rfind("ATLAS-", 0) == 0) {
            index_or_null(j, "chart", c.chart);
            optional_value(j, "u", c.uv ? std::optional<double>((*c.uv)[0]) : std::nullopt);
            optional_value(j, "v", c.uv ? std::optional<double>((*c.uv)[1]) : std::nullopt);
        }
        j.end_object();
    }
    j.end_array();
}

void pair_list(io::JsonWriter& j, const char* key, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs) {
    j.key(key).begin_array();
    for (const auto& [f, g] : pairs) j.begin_array().value(f).value(g).end_array();
    j.end_array();
}

}  // namespace

MapKind kind_of_content(std::string_view bytes, std::string_view name) {
    const std::size_t i = bytes.find_first_not_of(" \t\r\n");
    if (i != std::string_view::npos && bytes.substr(i, 9) == "fhr-param") return MapKind::param;
    if (bytes.substr(0, 4) == "ply\n" || bytes.substr(0, 5) == "ply\r\n") return MapKind::atlas;
    return name.size() >= 5 && name.substr(name.size() - 5) == ".fhrp" ? MapKind::param : MapKind::atlas;
}

std::string verdict_json(const std::string& path, const std::optional<std::string>& mesh, const ParamFile& file,
                         const std::vector<CheckResult>& checks, const Distortion& distortion) {
    io::JsonWriter j;
    write_head(j, path, mesh, "param", checks);
    j.key("domain").begin_object().key("vertices").value(file.domain_vertices.size());
    j.key("faces").value(file.domain_faces.size()).end_object();
    j.key("surface").begin_object().key("vertices").value(file.surface_vertices.size());
    j.key("faces").value(file.surface_faces.size()).end_object();
    write_checks(j, checks);
    j.key("distortion").begin_object();
    write_distortion_fields(j, distortion);
    j.end_object();
    j.end_object();
    return j.str();
}

std::string verdict_json(const std::string& path, const std::optional<std::string>& mesh, const Atlas& atlas,
                         const AtlasReport& report, bool lists) {
    io::JsonWriter j;
    write_head(j, path, mesh, "atlas", report.checks);
    j.key("domain").null();
    j.key("surface").begin_object().key("vertices").value(report.vertices);
    j.key("faces").value(atlas.faces.size()).end_object();
    write_checks(j, report.checks);
    j.key("distortion").begin_object();
    write_distortion_fields(j, report.distortion);
    j.end_object();
    j.key("charts").value(report.charts).key("mirrored_charts").value(report.mirrored_charts);
    j.key("folded_faces").value(report.folded.size()).key("overlapping_pairs").value(report.overlapping.size());
    j.key("contacts").value(report.contacts.size());
    optional_value(j, "seam_length", report.seam_length);
    optional_value(j, "packing_unit_square", report.packing_unit_square);
    optional_value(j, "packing_bounding_square", report.packing_bounding_square);
    if (lists) {  // --list: the sets themselves, for comparison with other checkers
        j.key("folded_face_list").begin_array();
        for (std::uint32_t f : report.folded) j.value(f);
        j.end_array();
        pair_list(j, "overlapping_pair_list", report.overlapping);
        pair_list(j, "contact_list", report.contacts);
    }
    j.end_object();
    return j.str();
}

std::string verdict_json(const std::string& path, const std::string& domain, const std::string& mesh,
                         const VertexMapFile& map, const PolygonSoup& D, const PolygonSoup& T,
                         const VertexMapReport& report, bool lists) {
    io::JsonWriter j;
    write_head(j, path, mesh, "vertex_map", report.checks, "adjacent");
    j.key("format").value(to_string(map.format)).key("domain_file").value(domain);
    j.key("domain").begin_object().key("vertices").value(D.points.size());
    j.key("faces").value(D.polygon_count()).end_object();
    j.key("surface").begin_object().key("vertices").value(T.points.size());
    j.key("faces").value(T.polygon_count()).end_object();
    write_checks(j, report.checks);
    j.key("distortion").begin_object();
    write_distortion_fields(j, report.distortion);
    j.end_object();
    j.key("edges_without_image").value(report.edges_without_image.size());
    j.key("crossing_pairs").value(report.crossing_pairs).key("folded_faces").value(report.folded.size());
    if (lists) {
        j.key("folded_face_list").begin_array();
        for (std::uint32_t f : report.folded) j.value(f);
        j.end_array();
        pair_list(j, "edges_without_image_list", report.edges_without_image);
    }
    j.end_object();
    return j.str();
}

}  // namespace fhr::exchange
