// Tests of the strict OFF reader and of read_soup (spec/formats.md FMT-OFF-*, FMT-SIZE-*,
// FMT-NUM-*, FMT-IDX-1, FMT-POLY-1, FMT-EXT-1).
#include <bit>
#include <charconv>
#include <chrono>
#include <filesystem>
#include <string>

#include <catch2/catch.hpp>
#include <rapidcheck/catch.h>

#include <fhr/io/detail/text_scanner.hpp>
#include <fhr/io/read.hpp>
#include "refusal.hpp"
#include "support/test_support.hpp"

using Catch::Matchers::Contains;
using fhr::io::parse_off;
using fhr::test::refusal;

namespace {

// padded beyond the 6-byte minimum of a vertex line, so that files with a shorter face list
// still pass the size check (FMT-SIZE-1) and reach the check under test
const std::string tetra_vertices = "0.0 0.0 0.0\n1.0 0.0 0.0\n0.0 1.0 0.0\n0.0 0.0 1.0\n";
const std::string tetra_faces = "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
const std::string tetra = "OFF\n4 4 6\n" + tetra_vertices + tetra_faces;

/// The refusal of `text` by parse_off, named "t.off".
fhr::InvalidInput off_refusal(const std::string& text) {
    return refusal([&] { parse_off(text, "t.off"); });
}

using fhr::io::detail::NumberStatus;

/// What the number parsers must return: std::from_chars on the whole token, a leading '+'
/// allowed (FMT-NUM-1).
template <class T>
NumberStatus reference_parse(std::string_view token, T& out) {
    if (token.size() > 1 && token[0] == '+' && token[1] != '-' && token[1] != '+') token.remove_prefix(1);
    const char* end = token.data() + token.size();
    const auto [ptr, ec] = std::from_chars(token.data(), end, out);
    if (ec == std::errc::result_out_of_range && ptr == end) return NumberStatus::out_of_range;
    if (ec != std::errc() || ptr != end || token.empty()) return NumberStatus::not_a_number;
    return NumberStatus::ok;
}

/// Number-like tokens: random strings over digits, signs, '.', 'e', and the decimal forms of
/// random doubles and integers.
rc::Gen<std::string> number_token() {
    return rc::gen::oneOf(
        rc::gen::container<std::string>(rc::gen::element('0', '1', '5', '9', '-', '+', '.', 'e', 'E', 'x', 'n')),
        rc::gen::map(rc::gen::arbitrary<std::uint64_t>(),
                     [](std::uint64_t bits) {
                         char b[40];
                         return std::string(b, std::to_chars(b, b + sizeof b, std::bit_cast<double>(bits)).ptr);
                     }),
        rc::gen::map(rc::gen::pair(rc::gen::arbitrary<std::int64_t>(), rc::gen::inRange(0, 20)),
                     [](std::pair<std::int64_t, int> p) {
                         char b[48];
                         const std::string digits(b, std::to_chars(b, b + sizeof b, p.first).ptr);
                         // shift a decimal point into the digits, or append zeros (overflow)
                         const std::size_t at = digits.size() - std::min<std::size_t>(p.second, digits.size() - 1);
                         return p.second % 3 == 0 ? digits + std::string(p.second, '0')
                                                  : digits.substr(0, at) + "." + digits.substr(at);
                     }));
}

}  // namespace

TEST_CASE("FMT-NUM-1: the number parsers agree with std::from_chars", "[property][io]") {
    rc::prop("parse_int64 and parse_double", [] {
        const std::string token = *number_token();
        std::int64_t i = 0, i_ref = 0;
        const NumberStatus si = fhr::io::detail::parse_int64(token, i);
        RC_ASSERT(si == reference_parse(token, i_ref));
        if (si == NumberStatus::ok) RC_ASSERT(i == i_ref);
        double d = 0, d_ref = 0;
        const NumberStatus sd = fhr::io::detail::parse_double(token, d);
        RC_ASSERT(sd == reference_parse(token, d_ref));
        if (sd == NumberStatus::ok) RC_ASSERT(std::bit_cast<std::uint64_t>(d) == std::bit_cast<std::uint64_t>(d_ref));
    });
    for (const char* token : {"-9223372036854775808", "9223372036854775807", "9223372036854775808",
                              "-9223372036854775809", "00000000000000000000000042", "-0", "+0", "+", "-", "+-1"}) {
        INFO(token);
        std::int64_t i = 0, i_ref = 0;
        const NumberStatus status = fhr::io::detail::parse_int64(token, i);
        CHECK(status == reference_parse(std::string_view(token), i_ref));
        if (status == NumberStatus::ok) CHECK(i == i_ref);
    }
    for (const char* token : {"0.1", "-0", "-0.0", ".5", "5.", "-.5", ".", "1.2.3", "9007199254740993",
                              "0.9007199254740993", "123456789012345678.9", "1e22", "4.9e-324", "nan", "-inf"}) {
        INFO(token);
        double d = 0, d_ref = 0;
        const NumberStatus status = fhr::io::detail::parse_double(token, d);
        CHECK(status == reference_parse(std::string_view(token), d_ref));
        if (status == NumberStatus::ok) CHECK(std::bit_cast<std::uint64_t>(d) == std::bit_cast<std::uint64_t>(d_ref));
    }
}

TEST_CASE("FMT-OFF-1..5: a tetrahedron is read exactly, with its source lines", "[unit][io]") {
    const fhr::PolygonSoup soup = parse_off(tetra, "t.off");
    CHECK(soup.source == "t.off");
    REQUIRE(soup.points.size() == 4);
    CHECK(soup.points[1] == fhr::Vec3(1, 0, 0));
    CHECK(soup.points[3] == fhr::Vec3(0, 0, 1));
    CHECK(soup.offsets == std::vector<std::uint32_t>{0, 3, 6, 9, 12});
    CHECK(soup.indices == std::vector<std::uint32_t>{0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3});
    CHECK(soup.point_line == std::vector<std::uint64_t>{3, 4, 5, 6});
    CHECK(soup.polygon_line == std::vector<std::uint64_t>{7, 8, 9, 10});
}

TEST_CASE("FMT-OFF-1/2: counts on the header line, comments, blank lines, CRLF, no final newline", "[unit][io]") {
    const std::string text =
        "# made by hand\r\nOFF 4 4 6 # counts here\r\n\r\n0 0 0\r\n1 0 0\r\n  # a comment line\r\n0 1 0\r\n"
        "0 0 1\r\n3 0 2 1\r\n3 0 1 3\r\n3 0 3 2\r\n3 1 2 3";
    const fhr::PolygonSoup soup = parse_off(text, "t.off");
    CHECK(soup.points.size() == 4);
    CHECK(soup.polygon_count() == 4);
    CHECK(soup.point_line == std::vector<std::uint64_t>{4, 5, 7, 8});
    CHECK(soup.polygon_line.back() == 12);
}

TEST_CASE("FMT-OFF-2: the edge count is optional and ignored", "[unit][io]") {
    CHECK(parse_off("OFF\n4 4\n" + tetra_vertices + tetra_faces, "t.off").polygon_count() == 4);
    CHECK(parse_off("OFF\n4 4 12345\n" + tetra_vertices + tetra_faces, "t.off").polygon_count() == 4);
}

TEST_CASE("FMT-OFF-1/3/4: COFF, NOFF, STCNOFF vertex extras and face colours are skipped", "[unit][io]") {
    const std::string coff =
        "COFF\n4 4 6\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 0 0 255 255\n0 0 1 9 9 9 9\n"
        "3 0 2 1 0.5 0.5 0.5\n3 0 1 3 1 0 0 1\n3 0 3 2 7\n3 1 2 3\n";
    const fhr::PolygonSoup soup = parse_off(coff, "t.coff");
    CHECK(soup.points[3] == fhr::Vec3(0, 0, 1));
    CHECK(soup.indices.back() == 3);
    const std::string noff = "NOFF\n4 4 6\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n0 0 1 0 0 1\n" + tetra_faces;
    CHECK(parse_off(noff, "t.off").points[2] == fhr::Vec3(0, 1, 0));
    const std::string stcnoff =
        "STCNOFF\n4 4 6\n0 0 0 0 0 1 1 1 1 1 0 0\n1 0 0 0 0 1 1 1 1 1 0 0\n"
        "0 1 0 0 0 1 1 1 1 1 0 0\n0 0 1 0 0 1 1 1 1 1 0 0\n" +
        tetra_faces;
    CHECK(parse_off(stcnoff, "t.off").points.size() == 4);
}

TEST_CASE("FMT-POLY-1: quads and larger polygons pass through; numbers take '+' and exponents", "[unit][io]") {
    const fhr::PolygonSoup soup =
        parse_off("OFF\n5 2 0\n+0 0e0 0\n1 0 0\n1 1.0E+00 0\n0 1 -0\n5e-1 .5 2.\n4 0 1 2 3\n3 0 1 4\n", "t.off");
    CHECK(soup.polygon_size(0) == 4);
    CHECK(soup.polygon_size(1) == 3);
    CHECK(soup.points[4] == fhr::Vec3(0.5, 0.5, 2));
}

TEST_CASE("FMT-SIZE-0: an empty file, or one of comments only, is refused", "[unit][io]") {
    const fhr::InvalidInput empty = off_refusal("");
    CHECK(empty.line() == 0);
    CHECK(empty.problem() == "empty file");
    CHECK(std::string(empty.what()) == "t.off: empty file");
    CHECK_THAT(off_refusal("# nothing\n\n   \n").problem(), Contains("empty file"));
}

TEST_CASE("FMT-OFF-1: a missing or unsupported header keyword is refused", "[unit][io]") {
    const fhr::InvalidInput missing = off_refusal("4 4 6\n" + tetra_vertices + tetra_faces);
    CHECK(missing.line() == 1);
    CHECK_THAT(missing.problem(), Contains("missing OFF header") && Contains("'4'"));
    CHECK_THAT(off_refusal("4OFF\n4 4 6\n").problem(), Contains("unsupported OFF variant '4OFF'"));
    CHECK_THAT(off_refusal("nOFF\n4\n4 4 6\n").problem(), Contains("unsupported OFF variant"));
}

TEST_CASE("FMT-OFF-2: a header-only file is refused", "[unit][io]") {
    CHECK_THAT(off_refusal("OFF\n").problem(), Contains("missing the counts line"));
    const fhr::InvalidInput zero = off_refusal("OFF\n0 0 0\n");
    CHECK(zero.line() == 2);
    CHECK_THAT(zero.problem(), Contains("no faces"));
    const fhr::InvalidInput no_data = off_refusal("OFF\n4 4 6\n");
    CHECK(no_data.line() == 2);
    CHECK_THAT(no_data.problem(), Contains("4 vertices and 4 faces") && Contains("only 0 bytes follow"));
    CHECK_THAT(off_refusal("OFF\n4 x 6\n").problem(), Contains("counts: expected a number, found 'x'"));
    CHECK_THAT(off_refusal("OFF\n-4 4 6\n").problem(), Contains("negative count -4"));
}

TEST_CASE("FMT-SIZE-1: absurd counts are refused before allocating", "[unit][io]") {
    std::string text = "OFF\n1000000000 1000000000 0\n" + tetra_vertices + tetra_faces;
    text.resize(100, '\n');
    const auto start = std::chrono::steady_clock::now();
    const fhr::InvalidInput e = off_refusal(text);
    CHECK(std::chrono::steady_clock::now() - start <
          std::chrono::seconds(1));  // CLI-ERR-1: refused at once, not after a huge allocation
    CHECK(e.line() == 2);
    CHECK_THAT(e.problem(), Contains("1000000000 vertices and 1000000000 faces") && Contains("truncated file"));
    // counts whose byte need overflows 64 bits saturate instead of wrapping around
    CHECK_THAT(off_refusal("OFF\n9223372036854775807 9223372036854775807 0\n0 0 0\n").problem(),
               Contains("truncated file"));
    CHECK_THAT(off_refusal("OFF\n99999999999999999999 1 0\n0 0 0\n").problem(),
               Contains("'99999999999999999999' is out of 64-bit integer range"));
}

TEST_CASE("FMT-OFF-3/4: truncated vertex and face lists are refused", "[unit][io]") {
    // long coordinates make the file big enough for the size check, so the scan meets its end
    const std::string long_vertices =
        "0.0000000000 0.0000000000 0.0000000000\n1.0000000000 0 0\n"
        "0 1.0000000000 0\n0 0 1.0000000000\n";
    const fhr::InvalidInput faces = off_refusal("OFF\n4 5 0\n" + long_vertices + tetra_faces);
    CHECK(faces.line() == 10);
    CHECK_THAT(faces.problem(), Contains("unexpected end of file: expected 5 faces, found 4"));
    const fhr::InvalidInput vertices = off_refusal("OFF\n5 1 0\n" + long_vertices + "\n\n\n\n\n\n\n\n\n\n");
    CHECK_THAT(vertices.problem(), Contains("expected 5 vertices, found 4"));
}

TEST_CASE("FMT-IDX-1: negative, out-of-range and overflowing OFF indices are refused", "[unit][io]") {
    const auto with_face = [](const std::string& face) {
        return off_refusal("OFF\n4 4 6\n" + tetra_vertices + "3 0 2 1\n3 0 1 3\n" + face + "\n3 1 2 3\n");
    };
    const fhr::InvalidInput negative = with_face("3 0 -1 2");
    CHECK(negative.line() == 9);
    CHECK(negative.problem() == "face 2: negative index -1");
    CHECK(std::string(negative.what()) == "t.off:9: face 2: negative index -1");
    CHECK(with_face("3 0 4 2").problem() == "face 2: index 4 out of range (0..3)");
    CHECK_THAT(with_face("3 0 99999999999999999999 2").problem(),
               Contains("face 2: index '99999999999999999999' out of range (0..3)"));
    CHECK_THAT(with_face("3 0 -99999999999999999999 2").problem(), Contains("negative index"));
    CHECK_THAT(with_face("3 0 1.5 2").problem(), Contains("face 2: expected a vertex index, found '1.5'"));
}

TEST_CASE("FMT-POLY-1: faces with fewer than 3 vertices or too few indices are refused", "[unit][io]") {
    const std::string head = "OFF\n4 4 6\n" + tetra_vertices;
    const fhr::InvalidInput two = off_refusal(head + "2 0 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
    CHECK(two.line() == 7);
    CHECK_THAT(two.problem(), Contains("face 0: has 2 vertices"));
    CHECK_THAT(off_refusal(head + "0\n3 0 1 3\n3 0 3 2\n3 1 2 3\n").problem(), Contains("has 0 vertices"));
    CHECK_THAT(off_refusal(head + "4 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n").problem(),
               Contains("face 0: expected a vertex index, found end of line"));
}

TEST_CASE("FMT-NUM-1: non-numeric tokens and numbers outside double range are refused", "[unit][io]") {
    const auto with_vertex = [](const std::string& vertex) {
        return off_refusal("OFF\n4 4 6\n0.0 0.0 0.0\n" + vertex + "\n0.0 1.0 0.0\n0.0 0.0 1.0\n" + tetra_faces);
    };
    const fhr::InvalidInput word = with_vertex("1 abc 0");
    CHECK(word.line() == 4);
    CHECK(word.problem() == "vertex 1: expected a number, found 'abc'");
    CHECK_THAT(with_vertex("1 0x10 0").problem(), Contains("found '0x10'"));
    CHECK_THAT(with_vertex("1 1,5 0").problem(), Contains("found '1,5'"));
    CHECK_THAT(with_vertex("1 0 1e400").problem(), Contains("vertex 1: number '1e400' is out of double range"));
    CHECK_THAT(with_vertex("1 0 1e-400").problem(), Contains("out of double range"));
    CHECK_THAT(with_vertex("1 0").problem(), Contains("vertex 1: expected a number, found end of line"));
    CHECK_THAT(with_vertex(std::string("1 \x01\xff 0", 6)).problem(), Contains("found '\\x01\\xff'"));
}

TEST_CASE("FMT-NUM-2/3: NaN, infinite and too large coordinates are refused", "[unit][io]") {
    const auto with_vertex = [](const std::string& vertex) {
        return off_refusal("OFF\n4 4 6\n0 0 0\n1 0 0\n" + vertex + "\n0 0 1\n" + tetra_faces);
    };
    const fhr::InvalidInput nan = with_vertex("nan 1 0");
    CHECK(nan.line() == 5);
    CHECK(nan.problem() == "vertex 2: coordinate is NaN");
    CHECK(with_vertex("0 inf 0").problem() == "vertex 2: coordinate is infinite");
    CHECK(with_vertex("0 1 -Infinity").problem() == "vertex 2: coordinate is infinite");
    CHECK_THAT(with_vertex("0 1 1.0000001e150").problem(), Contains("coordinate too large: lengths would overflow"));
    CHECK(parse_off("OFF\n4 4 6\n0 0 0\n1 0 0\n0 1e150 -1e150\n0 0 1\n" + tetra_faces, "t.off").points[2].y() == 1e150);
}

TEST_CASE("FMT-OFF-3: extra values on a plain OFF vertex line are refused", "[unit][io]") {
    const fhr::InvalidInput e = off_refusal("OFF\n4 4 6\n0 0 0\n1 0 0 1\n0 1 0\n0 0 1\n" + tetra_faces);
    CHECK(e.line() == 4);
    CHECK(e.problem() == "vertex 1: unexpected '1' at end of line");
}

TEST_CASE("FMT-OFF-4: a face colour has at most 4 values", "[unit][io]") {
    const fhr::InvalidInput e =
        off_refusal("OFF\n4 4 6\n" + tetra_vertices + "3 0 2 1 1 1 1 1 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
    CHECK(e.line() == 7);
    CHECK_THAT(e.problem(), Contains("face 0: unexpected '1' after 3 indices and 4 colour values"));
    CHECK_THAT(off_refusal("OFF\n4 4 6\n" + tetra_vertices + "3 0 2 1 red\n3 0 1 3\n3 0 3 2\n3 1 2 3\n").problem(),
               Contains("face 0: expected a number, found 'red'"));
}

TEST_CASE("FMT-OFF-5: data after the declared faces is refused", "[unit][io]") {
    const fhr::InvalidInput e = off_refusal(tetra + "3 0 1 2\n");
    CHECK(e.line() == 11);
    CHECK(e.problem() == "unexpected data after face 3 (the last one)");
    CHECK(parse_off(tetra + "# trailing comment\n\n", "t.off").polygon_count() == 4);
}

TEST_CASE("FMT-EXT-1: the extension picks the reader, case-insensitively", "[unit][io]") {
    using fhr::io::Format;
    using fhr::io::format_from_extension;
    CHECK(format_from_extension("a/b.off") == Format::off);
    CHECK(format_from_extension("B.COFF") == Format::off);
    CHECK(format_from_extension("x.Obj") == Format::obj);
    CHECK(format_from_extension("x.tar.ply") == Format::ply);
    CHECK(format_from_extension("x.STL") == Format::stl);
    const fhr::InvalidInput e = refusal([] { format_from_extension("mesh.xyz"); });
    CHECK(e.line() == 0);
    CHECK(e.file() == "mesh.xyz");
    CHECK_THAT(e.problem(), Contains("unknown format") && Contains("'.xyz'"));
    CHECK_THAT(refusal([] { format_from_extension("dir.off/mesh"); }).problem(), Contains("extension missing"));
}

TEST_CASE("FMT-EXT-1: read_soup reads a real file and refuses unreadable or unknown ones", "[unit][io]") {
    const std::string path = fhr::test::write_temp("tetra.OFF", tetra);
    const fhr::PolygonSoup soup = fhr::io::read_soup(path);
    CHECK(soup.source == path);
    CHECK(soup.polygon_count() == 4);

    const fhr::InvalidInput unknown = refusal([] { fhr::io::read_soup(fhr::test::write_temp("tetra.txt", tetra)); });
    CHECK_THAT(unknown.problem(), Contains("unknown format"));
    const std::string missing = fhr::test::temp_path("does-not-exist.off");
    const fhr::InvalidInput unreadable = refusal([&] { fhr::io::read_soup(missing); });
    CHECK(unreadable.file() == missing);
    CHECK(unreadable.line() == 0);
    CHECK(unreadable.problem() == "cannot open: No such file or directory");
    const std::string dir = fhr::test::temp_path("folder.off");
    std::filesystem::create_directories(dir);
    CHECK(refusal([&] { fhr::io::read_soup(dir); }).problem() == "cannot open: Is a directory");
    CHECK(refusal([] { fhr::io::read_soup(fhr::test::write_temp("empty.off", "")); }).problem() == "empty file");
}

TEST_CASE("FMT-OFF: the horse (48,485 vertices, 96,966 faces) reads completely", "[unit][io][shared]") {
    FHR_SHARED_MESH_OR_SKIP(horse, "horse.off");
    const fhr::PolygonSoup soup = fhr::io::read_soup(horse);
    CHECK(soup.points.size() == 48485);
    CHECK(soup.polygon_count() == 96966);
    CHECK(soup.indices.size() == 3 * 96966);
    CHECK(soup.polygon_line.back() == 2 + 48485 + 96966);
}
