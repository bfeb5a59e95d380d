// Tests of the strict STL reader (spec/formats.md FMT-STL-*, FMT-SIZE-0, FMT-NUM-*): ascii and
// binary, size-based detection, welding of equal corners.
#include <array>
#include <bit>
#include <cmath>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include <fhr/io/read.hpp>
#include "refusal.hpp"

using Catch::Matchers::Contains;
using fhr::io::parse_stl;
using fhr::test::refusal;

namespace {

fhr::InvalidInput stl_refusal(const std::string& bytes) {
    return refusal([&] { parse_stl(bytes, "t.stl"); });
}

using Corner = std::array<float, 3>;
using Triangle = std::array<Corner, 3>;

const std::vector<Triangle> tetra = {
    {{{0, 0, 0}, {0, 1, 0}, {1, 0, 0}}},
    {{{0, 0, 0}, {1, 0, 0}, {0, 0, 1}}},
    {{{0, 0, 0}, {0, 0, 1}, {0, 1, 0}}},
    {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}},
};

void put_u32(std::string& out, std::uint32_t v) {
    for (int b = 0; b < 4; ++b) out += static_cast<char>((v >> (8 * b)) & 0xff);
}

/// Binary STL (little endian), with an 80-byte header that starts with `header`.
std::string binary_stl(const std::vector<Triangle>& triangles, const std::string& header = "binary") {
    std::string out = header;
    out.resize(80, ' ');
    put_u32(out, static_cast<std::uint32_t>(triangles.size()));
    for (const Triangle& t : triangles) {
        for (int c = 0; c < 3; ++c) put_u32(out, 0);  // normal
        for (const Corner& corner : t)
            for (float x : corner) put_u32(out, std::bit_cast<std::uint32_t>(x));
        out += std::string(2, '\0');
    }
    return out;
}

const std::string ascii_facet_1 =
    " facet normal 0 0 -1\n  outer loop\n   vertex 0 0 0\n   vertex 0 1 0\n"
    "   vertex 1 0 0\n  endloop\n endfacet\n";
const std::string ascii_rest =
    " facet normal 0 -1 0\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n   vertex 0 0 1\n  endloop\n endfacet\n"
    " facet normal -1 0 0\n  outer loop\n   vertex 0 0 0\n   vertex 0 0 1\n   vertex 0 1 0\n  endloop\n endfacet\n"
    " facet normal 1 1 1\n  outer loop\n   vertex 1 0 0\n   vertex 0 1 0\n   vertex 0 0 1\n  endloop\n endfacet\n";
const std::string ascii_tetra = "solid tetra\n" + ascii_facet_1 + ascii_rest + "endsolid tetra\n";

/// The welded tetrahedron: 4 points in order of first occurrence.
void check_tetra(const fhr::PolygonSoup& soup) {
    REQUIRE(soup.points.size() == 4);
    CHECK(soup.points[0] == fhr::Vec3(0, 0, 0));
    CHECK(soup.points[1] == fhr::Vec3(0, 1, 0));
    CHECK(soup.points[2] == fhr::Vec3(1, 0, 0));
    CHECK(soup.points[3] == fhr::Vec3(0, 0, 1));
    CHECK(soup.offsets == std::vector<std::uint32_t>{0, 3, 6, 9, 12});
    CHECK(soup.indices == std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3, 0, 3, 1, 2, 1, 3});
}

}  // namespace

TEST_CASE("FMT-STL-2/3: an ascii tetrahedron is read and its equal corners welded", "[unit][io]") {
    const fhr::PolygonSoup soup = parse_stl(ascii_tetra, "t.stl");
    check_tetra(soup);
    CHECK(soup.source == "t.stl");
    CHECK(soup.point_line == std::vector<std::uint64_t>{4, 5, 6, 13});
    CHECK(soup.polygon_line == std::vector<std::uint64_t>{2, 9, 16, 23});
}

TEST_CASE("FMT-STL-2: CRLF, several solids, nameless solids, NaN normals", "[unit][io]") {
    std::string text =
        "solid\r\n" + ascii_facet_1 + "endsolid\r\nsolid second part\r\n" + ascii_rest + "endsolid second part";
    text.replace(text.find("normal 0 0 -1"), 13, "normal nan nan nan");
    check_tetra(parse_stl(text, "t.stl"));
}

TEST_CASE("FMT-STL-1/3: a binary tetrahedron is read and welded; no source lines", "[unit][io]") {
    const fhr::PolygonSoup soup = parse_stl(binary_stl(tetra), "t.stl");
    check_tetra(soup);
    CHECK(soup.point_line.empty());
    CHECK(soup.polygon_line.empty());
}

TEST_CASE("FMT-STL-1: a binary file whose header starts with 'solid' is still binary", "[unit][io]") {
    check_tetra(parse_stl(binary_stl(tetra, "solid exported by a CAD program"), "t.stl"));
}

TEST_CASE("FMT-STL-3: -0 and +0 weld; corners differing in the last bit do not", "[unit][io]") {
    std::vector<Triangle> t = tetra;
    t[3][0] = {1, -0.0f, 0};
    t[3][2] = {std::nextafter(0.0f, 1.0f), 0, 1};
    const fhr::PolygonSoup soup = parse_stl(binary_stl(t), "t.stl");
    CHECK(soup.points.size() == 5);
    CHECK(soup.indices[9] == 2);
    CHECK(soup.indices[11] == 4);
    CHECK(std::signbit(soup.points[2].y()) == false);  // the first occurrence is kept
}

TEST_CASE("FMT-SIZE-0 / FMT-STL-1: empty, unrecognised and truncated binary files are refused", "[unit][io]") {
    CHECK(stl_refusal("").problem() == "empty file");
    const fhr::InvalidInput tiny = stl_refusal("hello");
    CHECK(tiny.line() == 0);
    CHECK_THAT(tiny.problem(), Contains("not an ascii STL") && Contains("too short for a binary STL (5 bytes < 84)"));
    std::string cut = binary_stl(tetra);
    cut.resize(cut.size() - 7);
    const fhr::InvalidInput truncated = stl_refusal(cut);
    CHECK(truncated.line() == 0);
    CHECK_THAT(truncated.problem(),
               Contains("declares 4 triangles (284 bytes) but the file has 277 bytes (truncated file?)"));
    CHECK(stl_refusal(binary_stl({})).problem() == "binary STL with no triangles");
}

TEST_CASE("FMT-SIZE-1: an absurd binary triangle count is refused without allocating", "[unit][io]") {
    std::string bytes = binary_stl(tetra);
    bytes.replace(80, 4, std::string("\xff\xff\xff\xff", 4));
    CHECK_THAT(stl_refusal(bytes).problem(), Contains("declares 4294967295 triangles"));
}

TEST_CASE("FMT-NUM-2/3: NaN, infinite and huge binary corners are refused, naming the triangle", "[unit][io]") {
    for (const float bad : {std::nanf(""), HUGE_VALF, -HUGE_VALF}) {
        std::vector<Triangle> t = tetra;
        t[2][1][2] = bad;
        const fhr::InvalidInput e = stl_refusal(binary_stl(t));
        CHECK(e.line() == 0);
        CHECK_THAT(e.problem(), Contains("triangle 2: coordinate is") && (Contains("NaN") || Contains("infinite")));
    }
    const std::string huge = "solid\n" + ascii_facet_1 + "endsolid\n";
    const fhr::InvalidInput e =
        stl_refusal(std::string(huge).replace(huge.find("vertex 0 1 0"), 12, "vertex 0 1e151 0"));
    CHECK(e.line() == 5);
    CHECK_THAT(e.problem(), Contains("facet 0: coordinate too large"));
}

TEST_CASE("FMT-STL-2: broken ascii files are refused with their line", "[unit][io]") {
    const auto broken = [](const std::string& from, const std::string& to) {
        std::string text = ascii_tetra;
        text.replace(text.find(from), from.size(), to);
        return stl_refusal(text);
    };
    const fhr::InvalidInput word = broken("vertex 0 1 0", "vertex 0 one 0");
    CHECK(word.line() == 5);
    CHECK(word.problem() == "facet 0: expected a number, found 'one'");
    CHECK_THAT(broken("vertex 0 1 0", "vertex 0 1e400 0").problem(), Contains("'1e400' is out of double range"));
    CHECK(broken("vertex 0 1 0", "vertex 0 nan 0").problem() == "facet 0: coordinate is NaN");
    CHECK(broken("vertex 0 1 0", "vertex 0 -inf 0").problem() == "facet 0: coordinate is infinite");
    CHECK_THAT(broken("vertex 0 1 0", "vertex 0 1 0 0").problem(), Contains("unexpected '0' at end of line"));
    const fhr::InvalidInput four = broken("   vertex 1 0 0\n  endloop", "   vertex 1 0 0\n   vertex 1 1 1\n  endloop");
    CHECK(four.line() == 7);
    CHECK(four.problem() == "facet 0: expected 'endloop', found 'vertex'");
    CHECK_THAT(broken(" facet normal 0 0 -1", " facet 0 0 -1").problem(), Contains("expected 'normal', found '0'"));
    CHECK_THAT(broken("outer loop", "outer").problem(), Contains("expected 'loop', found end of line"));
    CHECK_THAT(broken("endsolid tetra\n", "").problem(),
               Contains("unexpected end of file: expected 'facet' or 'endsolid'"));
    CHECK_THAT(broken("endsolid tetra\n", "endsolid tetra\nextra\n").problem(),
               Contains("expected 'solid', found 'extra'"));
    CHECK_THAT(broken(" facet normal 1 1 1", " facet normal 1 1").problem(), Contains("facet 3: expected a number"));
    CHECK_THAT(stl_refusal("solid x\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n").problem(),
               Contains("unexpected end of file: expected 'vertex'"));
    CHECK_THAT(stl_refusal("solid empty\nendsolid empty\n").problem(), Contains("no facets"));
    CHECK_THAT(stl_refusal("solid x\nsomething\n").problem(),
               Contains("expected 'facet' or 'endsolid', found 'something'"));
}
