// FHR exchange — the readers of per-vertex maps (spec/vertex_map.md "Reading", VMAP-1): fhr's own
// `fhr-vertex-map 1`, SHREC'16-style `.corr`, `.vtpm` (a halfedge and two weights per vertex) and
// IJV triplets. The grammar only: indices of D, NaN weights and missing images are kept, for VMAP-2
// to judge and name.
#include <fhr/exchange/vertex_map.hpp>

#include <algorithm>
#include <string>

#include <fhr/core/errors.hpp>
#include <fhr/io/detail/text_scanner.hpp>
#include <fhr/io/read.hpp>

namespace fhr::exchange {

namespace {

using io::detail::TextScanner;
using io::detail::Where;

double weight(TextScanner& s, Where where) {
    const std::string_view t = s.token(where, "a weight");
    double x = 0;
    if (io::detail::parse_double(t, x) != io::detail::NumberStatus::ok)
        s.fail(where, "expected a weight, found " + io::detail::quoted(t));
    return x;
}

std::int64_t integer(TextScanner& s, Where where, std::string_view what) {
    const std::string_view t = s.token(where, what);
    std::int64_t x = 0;
    if (io::detail::parse_int64(t, x) != io::detail::NumberStatus::ok)
        s.fail(where, "expected " + std::string(what) + ", found " + io::detail::quoted(t));
    return x;
}

/// A record `FACE w0 w1 w2` (plain: 0-based; corr: 1-based), a negative face meaning none.
VertexImageRecord face_record(TextScanner& s, Where where, std::int64_t base) {
    VertexImageRecord r;
    r.line = s.line();
    const std::int64_t f = integer(s, where, "a face index");
    for (double& w : r.weights) w = weight(s, where);
    if (f >= 0) {
        if (f < base) s.fail(where, "face index 0 in a file whose faces count from 1");
        r.ref = VertexImageRecord::Ref::face;
        r.a = f - base;
    } else if (f != -1) {
        s.fail(where, "face index " + std::to_string(f) + " (-1 means no image)");
    }
    s.expect_end_of_line(where);
    return r;
}

void expect_records(const TextScanner& s, std::size_t have, std::size_t want) {
    if (have != want)
        s.fail(Where{"file"}, std::to_string(have) + " records for the " + std::to_string(want) + " vertices of T");
}

std::vector<VertexImageRecord> read_plain(TextScanner& s, std::size_t n) {
    if (!s.next_line() || s.token() != "fhr-vertex-map") s.fail(Where{"header"}, "expected 'fhr-vertex-map 1'");
    if (s.token() != "1") s.fail(Where{"header"}, "expected version 1 after 'fhr-vertex-map'");
    s.expect_end_of_line(Where{"header"});
    if (!s.next_line()) s.fail(Where{"header"}, "expected the number of vertices");
    const std::uint64_t count = s.count(Where{"header"});
    s.expect_end_of_line(Where{"header"});
    if (count != n)
        s.fail(Where{"header"}, "the map has " + std::to_string(count) + " vertices but T has " + std::to_string(n));
    std::vector<VertexImageRecord> records;
    records.reserve(n);
    while (records.size() < n && s.next_line()) records.push_back(face_record(s, Where{"vertex", records.size()}, 0));
    if (s.next_line()) s.fail(Where{"file"}, "text after the last vertex");
    expect_records(s, records.size(), n);
    return records;
}

std::vector<VertexImageRecord> read_corr(TextScanner& s, std::size_t n) {
    std::vector<VertexImageRecord> records;
    records.reserve(n);
    while (s.next_line()) {
        if (records.size() == n)
            s.fail(Where{"vertex", records.size()}, "more records than the " + std::to_string(n) + " vertices of T");
        records.push_back(face_record(s, Where{"vertex", records.size()}, 1));
    }
    expect_records(s, records.size(), n);
    return records;
}

std::vector<VertexImageRecord> read_vtpm(TextScanner& s, std::size_t n, std::size_t m) {
    if (!s.next_line()) s.fail(Where{"header"}, "expected the numbers of vertices of T and D");
    const std::uint64_t nt = s.count(Where{"header"});
    if (!s.has_token() && !s.next_line()) s.fail(Where{"header"}, "expected the number of vertices of D");
    const std::uint64_t nd = s.count(Where{"header"});
    s.expect_end_of_line(Where{"header"});
    if (nt != n || nd != m)
        s.fail(Where{"header"}, "the map is of " + std::to_string(nt) + " onto " + std::to_string(nd) +
                                    " vertices, but T has " + std::to_string(n) + " and D " + std::to_string(m));
    std::vector<VertexImageRecord> records;
    records.reserve(n);
    while (records.size() < n && s.next_line()) {
        const Where where{"vertex", records.size()};
        VertexImageRecord r;
        r.line = s.line();
        r.a = integer(s, where, "a vertex of D");
        r.b = integer(s, where, "a vertex of D");
        const double alpha = weight(s, where), beta = weight(s, where);
        s.expect_end_of_line(where);
        if (r.a == -1 && r.b == -1) {
            records.push_back(r);
            continue;
        }
        if (r.a < 0 || r.b < 0)
            s.fail(where, "halfedge " + std::to_string(r.a) + " -> " + std::to_string(r.b) + " (-1 -1 means no image)");
        r.ref = VertexImageRecord::Ref::halfedge;
        r.weights = {1 - alpha - beta, alpha, beta};
        records.push_back(r);
    }
    if (s.next_line()) s.fail(Where{"file"}, "text after the last vertex");
    expect_records(s, records.size(), n);
    return records;
}

std::vector<VertexImageRecord> read_ijv(TextScanner& s, std::size_t n) {
    std::vector<VertexImageRecord> records(n);
    while (s.next_line()) {
        const Where where{"line"};
        const std::int64_t i = integer(s, where, "a vertex of T");
        const std::int64_t j = integer(s, where, "a vertex of D");
        const double w = weight(s, where);
        s.expect_end_of_line(where);
        if (i < 1 || static_cast<std::uint64_t>(i) > n)
            s.fail(where, "vertex " + std::to_string(i) + " of T out of range 1.." + std::to_string(n));
        VertexImageRecord& r = records[static_cast<std::size_t>(i - 1)];
        const Where vertex{"vertex", static_cast<std::uint64_t>(i - 1)};
        const auto used = static_cast<std::size_t>(
            std::count_if(r.corners.begin(), r.corners.end(), [](std::int64_t c) { return c >= 0; }));
        if (std::find(r.corners.begin(), r.corners.end(), j - 1) != r.corners.end() && j >= 1)
            s.fail(vertex, "vertex " + std::to_string(j) + " of D named twice");
        if (used == 3) s.fail(vertex, "more than three weights");
        if (j < 1) s.fail(where, "vertex " + std::to_string(j) + " of D (indices count from 1)");
        if (used == 0) r.line = s.line();
        r.ref = VertexImageRecord::Ref::vertices;
        r.corners[used] = j - 1;
        r.weights[used] = w;
    }
    return records;
}

}  // namespace

const char* to_string(VertexMapFormat format) {
    switch (format) {
        case VertexMapFormat::plain: return "plain";
        case VertexMapFormat::corr: return "corr";
        case VertexMapFormat::vtpm: return "vtpm";
        case VertexMapFormat::ijv: return "ijv";
    }
    return "?";
}

std::optional<VertexMapFormat> vertex_map_format_named(std::string_view name) {
    for (VertexMapFormat f :
         {VertexMapFormat::plain, VertexMapFormat::corr, VertexMapFormat::vtpm, VertexMapFormat::ijv})
        if (name == to_string(f)) return f;
    return std::nullopt;
}

std::optional<VertexMapFormat> vertex_map_format_of(std::string_view path) {
    const auto ends = [&](std::string_view ext) {
        return path.size() >= ext.size() && std::equal(ext.rbegin(), ext.rend(), path.rbegin(), [](char a, char b) {
                   return a == (b >= 'A' && b <= 'Z' ? static_cast<char>(b - 'A' + 'a') : b);
               });
    };
    if (ends(".vmap")) return VertexMapFormat::plain;
    if (ends(".corr")) return VertexMapFormat::corr;
    if (ends(".vtpm")) return VertexMapFormat::vtpm;
    if (ends(".ijv")) return VertexMapFormat::ijv;
    return std::nullopt;
}

VertexMapFile parse_vertex_map(std::string_view bytes, const std::string& name, VertexMapFormat format,
                               std::size_t t_vertices, std::size_t d_vertices) {
    io::detail::check_input_size(bytes, name);
    TextScanner s(bytes, name, format == VertexMapFormat::plain ? '#' : '\0');
    VertexMapFile file{name, format, {}};
    switch (format) {
        case VertexMapFormat::plain: file.records = read_plain(s, t_vertices); break;
        case VertexMapFormat::corr: file.records = read_corr(s, t_vertices); break;
        case VertexMapFormat::vtpm: file.records = read_vtpm(s, t_vertices, d_vertices); break;
        case VertexMapFormat::ijv: file.records = read_ijv(s, t_vertices); break;
    }
    return file;
}

VertexMapFile read_vertex_map(const std::string& path, std::optional<VertexMapFormat> format, std::size_t t_vertices,
                              std::size_t d_vertices) {
    if (!format) format = vertex_map_format_of(path);
    if (!format)
        throw InvalidInput(
            path, 0, "cannot tell the map's format from its name (.vmap, .corr, .vtpm, .ijv); name it with --format");
    return parse_vertex_map(io::read_bytes(path), path, *format, t_vertices, d_vertices);
}

}  // namespace fhr::exchange
