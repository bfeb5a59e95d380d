// FHR io — strict STL reader (spec/formats.md FMT-STL-*), ascii and binary. STL stores each
// triangle with its own three corners; the paper's triangulation T (§1) shares vertices between
// triangles, so corners with equal coordinates are welded into one point (FMT-STL-3).
#include <array>
#include <bit>
#include <string>
#include <unordered_map>

#include <fhr/io/detail/text_scanner.hpp>
#include <fhr/io/read.hpp>

namespace fhr::io {

namespace {

using detail::TextScanner;
using detail::Where;

/// FMT-STL-3: welds corners whose coordinates compare equal (−0 and +0 are the same point);
/// points are numbered in order of first occurrence, so the result is deterministic.
class Welder {
public:
    explicit Welder(PolygonSoup& soup) : soup_(soup) {}
    std::uint32_t add(const Vec3& p, std::uint64_t line, bool text) {
        // x + 0.0 turns −0 into +0, so that the bit patterns of equal coordinates are equal.
        const Key key = {std::bit_cast<std::uint64_t>(p.x() + 0.0), std::bit_cast<std::uint64_t>(p.y() + 0.0),
                         std::bit_cast<std::uint64_t>(p.z() + 0.0)};
        const auto [it, inserted] = index_.try_emplace(key, static_cast<std::uint32_t>(soup_.points.size()));
        if (inserted) {
            soup_.points.push_back(p);
            if (text) soup_.point_line.push_back(line);
        }
        return it->second;
    }

private:
    using Key = std::array<std::uint64_t, 3>;
    struct KeyHash {
        std::size_t operator()(const Key& k) const {
            std::uint64_t h = 0x9e3779b97f4a7c15ULL;
            for (std::uint64_t v : k) h = (h ^ v) * 0xff51afd7ed558ccdULL, h ^= h >> 32;
            return static_cast<std::size_t>(h);
        }
    };
    PolygonSoup& soup_;
    std::unordered_map<Key, std::uint32_t, KeyHash> index_;
};

/// FMT-STL-1: 80-byte header, uint32 triangle count n, n records of 50 bytes (normal, 3 corners as
/// little-endian float32, 2 attribute bytes). The caller has checked the size is 84 + 50 n.
PolygonSoup parse_binary(std::string_view bytes, std::uint32_t n, const std::string& name) {
    if (n == 0) detail::fail(name, 0, {}, "binary STL with no triangles");
    PolygonSoup soup;
    soup.source = name;
    soup.offsets.reserve(std::size_t{n} + 1);
    soup.indices.reserve(3 * std::size_t{n});
    Welder welder(soup);
    const auto float_at = [&](std::size_t offset) {
        std::uint32_t r = 0;
        for (int b = 3; b >= 0; --b) r = (r << 8) | static_cast<unsigned char>(bytes[offset + b]);
        return static_cast<double>(std::bit_cast<float>(r));
    };
    for (std::uint32_t t = 0; t < n; ++t) {
        const std::size_t record = 84 + 50 * std::size_t{t};
        for (std::size_t c = 0; c < 3; ++c) {
            const std::size_t at = record + 12 + 12 * c;
            const Vec3 p(float_at(at), float_at(at + 4), float_at(at + 8));
            detail::check_point(p, name, 0, {"triangle", t});
            soup.indices.push_back(welder.add(p, 0, false));
        }
        soup.offsets.push_back(static_cast<std::uint32_t>(soup.indices.size()));
    }
    return soup;
}

/// Fails unless the current line starts with `keyword`.
void expect_keyword(TextScanner& in, std::string_view keyword, Where where) {
    const std::string_view t = in.token();
    if (t != keyword)
        in.fail(where, "expected '" + std::string(keyword) + "', found " +
                           (t.empty() ? std::string("end of line") : detail::quoted(t)));
}

/// Moves to the next line and checks it starts with `keyword`.
void expect_line(TextScanner& in, std::string_view keyword, Where where) {
    if (!in.next_line()) in.fail(where, "unexpected end of file: expected '" + std::string(keyword) + "'");
    expect_keyword(in, keyword, where);
}

/// FMT-STL-2: one or more `solid [name] … endsolid [name]`, each facet
/// `facet normal nx ny nz / outer loop / vertex x y z (3×) / endloop / endfacet`, one per line.
PolygonSoup parse_ascii(std::string_view bytes, const std::string& name) {
    TextScanner in(bytes, name, '\0');
    PolygonSoup soup;
    soup.source = name;
    Welder welder(soup);
    in.next_line();
    expect_keyword(in, "solid", {});
    while (true) {
        const Where where{"facet", soup.polygon_count()};
        if (!in.next_line()) in.fail({}, "unexpected end of file: expected 'facet' or 'endsolid'");
        const std::string_view keyword = in.token();
        if (keyword == "endsolid") {
            if (!in.next_line()) break;
            expect_keyword(in, "solid", {});  // another solid follows
            continue;
        }
        if (keyword != "facet") in.fail(where, "expected 'facet' or 'endsolid', found " + detail::quoted(keyword));
        const std::uint64_t facet_line = in.line();
        expect_keyword(in, "normal", where);
        for (int c = 0; c < 3; ++c) in.real(where);  // the normal is ignored (any number, even NaN)
        in.expect_end_of_line(where);
        expect_line(in, "outer", where);
        expect_keyword(in, "loop", where);
        in.expect_end_of_line(where);
        for (int c = 0; c < 3; ++c) {
            expect_line(in, "vertex", where);
            const Vec3 p = in.point(where);
            in.expect_end_of_line(where);
            soup.indices.push_back(welder.add(p, in.line(), true));
        }
        expect_line(in, "endloop", where);
        in.expect_end_of_line(where);
        expect_line(in, "endfacet", where);
        in.expect_end_of_line(where);
        soup.offsets.push_back(static_cast<std::uint32_t>(soup.indices.size()));
        soup.polygon_line.push_back(facet_line);
    }
    if (soup.polygon_count() == 0) detail::fail(name, 0, {}, "no facets");
    return soup;
}

}  // namespace

PolygonSoup parse_stl(std::string_view bytes, const std::string& name) {
    detail::check_input_size(bytes, name);
    // FMT-STL-1: binary exactly when the size is 84 + 50 n for the count n at offset 80, even when
    // the 80-byte header starts with "solid" (as many binary exporters write).
    if (bytes.size() >= 84) {
        std::uint32_t n = 0;
        for (int b = 83; b >= 80; --b) n = (n << 8) | static_cast<unsigned char>(bytes[b]);
        if (bytes.size() == 84 + 50 * std::uint64_t{n}) return parse_binary(bytes, n, name);
        if (bytes.substr(0, 5) != "solid")
            detail::fail(name, 0, {},
                         "not an ascii STL (no 'solid' at the start) and not a binary STL: the header declares " +
                             std::to_string(n) + " triangles (" + std::to_string(84 + 50 * std::uint64_t{n}) +
                             " bytes) but the file has " + std::to_string(bytes.size()) + " bytes (truncated file?)");
    } else if (bytes.substr(0, 5) != "solid") {
        detail::fail(name, 0, {},
                     "not an ascii STL (no 'solid' at the start) and too short for a binary STL (" +
                         std::to_string(bytes.size()) + " bytes < 84)");
    }
    return parse_ascii(bytes, name);
}

}  // namespace fhr::io
