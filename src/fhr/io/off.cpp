// FHR io — strict OFF reader (spec/formats.md FMT-OFF-*). The paper (§1) starts from a given
// triangulation T; this is the most common way it is handed over. Accepted: the Geomview header
// `[ST][C][N]OFF`, the counts `V F [E]` on the header line or the next, one vertex per line
// (`x y z`, plus texture/colour/normal values when the header announces them), one face per line
// (`n i0 … i(n-1)` plus at most 4 colour values), '#' comments, "\n" or "\r\n" line endings.
#include <string>

#include <fhr/io/detail/text_scanner.hpp>
#include <fhr/io/read.hpp>

namespace fhr::io {

namespace {

using detail::Where;

/// FMT-OFF-1: the header keyword. Returns whether vertex lines carry extra values (ST, C, N).
bool parse_header_keyword(std::string_view keyword, detail::TextScanner& in) {
    std::string_view prefix = keyword;
    if (prefix.size() < 3 || prefix.substr(prefix.size() - 3) != "OFF")
        in.fail({"header"}, "missing OFF header: first token is " + detail::quoted(keyword));
    prefix.remove_suffix(3);
    if (prefix.substr(0, 2) == "ST") prefix.remove_prefix(2);
    if (prefix.substr(0, 1) == "C") prefix.remove_prefix(1);
    if (prefix.substr(0, 1) == "N") prefix.remove_prefix(1);
    if (!prefix.empty())
        in.fail({"header"},
                "unsupported OFF variant " + detail::quoted(keyword) + " (accepted: [ST][C][N]OFF in 3 dimensions)");
    return keyword.size() > 3;
}

}  // namespace

PolygonSoup parse_off(std::string_view bytes, const std::string& name) {
    detail::check_input_size(bytes, name);
    detail::TextScanner in(bytes, name);
    if (!in.next_line()) detail::fail(name, 0, {}, "empty file (only blank lines and comments)");
    const bool vertex_extras = parse_header_keyword(in.token(), in);

    // FMT-OFF-2: the counts V F [E], on the header line or on the next one (E is ignored).
    const Where counts{"counts"};
    if (!in.has_token() && !in.next_line())
        detail::fail(name, in.line(), {}, "header only: missing the counts line 'V F E'");
    const std::uint64_t vertex_count = in.count(counts);
    const std::uint64_t face_count = in.count(counts);
    if (in.has_token()) in.count(counts);
    in.expect_end_of_line(counts);
    if (face_count == 0) in.fail(counts, "no faces (the header declares 0)");

    // FMT-SIZE-1: a vertex line needs at least 6 bytes ("0 0 0\n"), a face line at least 8
    // ("3 0 0 0\n"; the last line may lack its newline). Checked before anything is reserved.
    const std::uint64_t need = detail::add_min_bytes(detail::add_min_bytes(0, vertex_count, 6), face_count, 8);
    const std::uint64_t left = in.rest().size() + 1;
    if (need > left)
        in.fail(counts, "the header declares " + std::to_string(vertex_count) + " vertices and " +
                            std::to_string(face_count) + " faces (at least " + std::to_string(need) +
                            " bytes), but only " + std::to_string(left - 1) + " bytes follow (truncated file?)");

    PolygonSoup soup;
    soup.source = name;
    soup.points.reserve(vertex_count);
    soup.point_line.reserve(vertex_count);
    soup.offsets.reserve(face_count + 1);
    soup.polygon_line.reserve(face_count);
    soup.indices.reserve(3 * face_count);

    for (std::uint64_t v = 0; v < vertex_count; ++v) {
        const Where where{"vertex", v};
        if (!in.next_line())
            in.fail({}, "unexpected end of file: expected " + std::to_string(vertex_count) + " vertices, found " +
                            std::to_string(v));
        soup.points.push_back(in.point(where));
        soup.point_line.push_back(in.line());
        // FMT-OFF-3: extra vertex values only when the header announces them (they are skipped).
        if (!vertex_extras) in.expect_end_of_line(where);
    }

    for (std::uint64_t f = 0; f < face_count; ++f) {
        const Where where{"face", f};
        if (!in.next_line())
            in.fail({}, "unexpected end of file: expected " + std::to_string(face_count) + " faces, found " +
                            std::to_string(f));
        const std::uint64_t n = in.count(where);
        detail::check_polygon_size(n, name, in.line(), where);
        for (std::uint64_t k = 0; k < n; ++k) soup.indices.push_back(in.index(where, vertex_count));
        soup.offsets.push_back(static_cast<std::uint32_t>(soup.indices.size()));
        soup.polygon_line.push_back(in.line());
        // FMT-OFF-4: a face may end with a colour: at most 4 numbers.
        for (int c = 0; c < 4 && in.has_token(); ++c) in.real(where);
        if (in.has_token())
            in.fail(where, "unexpected " + detail::quoted(in.token()) + " after " + std::to_string(n) +
                               " indices and 4 colour values");
    }

    // FMT-OFF-5: nothing may follow the declared data.
    if (in.next_line()) in.fail({}, "unexpected data after face " + std::to_string(face_count - 1) + " (the last one)");
    return soup;
}

}  // namespace fhr::io
