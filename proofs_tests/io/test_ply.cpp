// Tests of the strict PLY reader (spec/formats.md FMT-PLY-*, FMT-SIZE-*, FMT-NUM-*, FMT-IDX-1,
// FMT-POLY-1): ascii, binary little endian and binary big endian.
#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include <fhr/io/read.hpp>
#include "refusal.hpp"

using Catch::Matchers::Contains;
using fhr::io::parse_ply;
using fhr::test::refusal;

namespace {

fhr::InvalidInput ply_refusal(const std::string& bytes) {
    return refusal([&] { parse_ply(bytes, "t.ply"); });
}

/// Appends `v` as the PLY scalar type `type` (either spelling), little or big endian.
void put(std::string& out, std::string_view type, double v, bool big_endian) {
    const auto bytes = [&](auto x) {
        char b[sizeof x];
        std::memcpy(b, &x, sizeof x);
        if (big_endian == (std::endian::native == std::endian::little)) std::reverse(b, b + sizeof x);
        out.append(b, sizeof x);
    };
    if (type == "char" || type == "int8")
        bytes(static_cast<std::int8_t>(v));
    else if (type == "uchar" || type == "uint8")
        bytes(static_cast<std::uint8_t>(v));
    else if (type == "short" || type == "int16")
        bytes(static_cast<std::int16_t>(v));
    else if (type == "ushort" || type == "uint16")
        bytes(static_cast<std::uint16_t>(v));
    else if (type == "int" || type == "int32")
        bytes(static_cast<std::int32_t>(v));
    else if (type == "uint" || type == "uint32")
        bytes(static_cast<std::uint32_t>(v));
    else if (type == "float" || type == "float32")
        bytes(static_cast<float>(v));
    else if (type == "double" || type == "float64")
        bytes(v);
    else
        FAIL("unknown type in test: " << type);
}

const double tetra_points[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
const int tetra_faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

/// A binary tetrahedron: vertex x y z of `coord` type, face list of `count`/`index` types.
std::string binary_tetra(bool big_endian, std::string_view coord, std::string_view count, std::string_view index) {
    std::string out = std::string("ply\nformat ") + (big_endian ? "binary_big_endian" : "binary_little_endian") +
                      " 1.0\nelement vertex 4\nproperty " + std::string(coord) + " x\nproperty " + std::string(coord) +
                      " y\nproperty " + std::string(coord) + " z\nelement face 4\nproperty list " + std::string(count) +
                      " " + std::string(index) + " vertex_indices\nend_header\n";
    for (const auto& p : tetra_points)
        for (double c : p) put(out, coord, c, big_endian);
    for (const auto& f : tetra_faces) {
        put(out, count, 3, big_endian);
        for (int i : f) put(out, index, i, big_endian);
    }
    return out;
}

const std::string ascii_header =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
    "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n";
// padded beyond the minimum size, so that shortened face lists still pass FMT-SIZE-1
const std::string ascii_vertices = "0.0 0.0 0.0\n1.0 0.0 0.0\n0.0 1.0 0.0\n0.0 0.0 1.0\n";
const std::string ascii_faces = "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

/// The expected tetrahedron.
void check_tetra(const fhr::PolygonSoup& soup) {
    REQUIRE(soup.points.size() == 4);
    for (int v = 0; v < 4; ++v)
        CHECK(soup.points[v] == fhr::Vec3(tetra_points[v][0], tetra_points[v][1], tetra_points[v][2]));
    CHECK(soup.offsets == std::vector<std::uint32_t>{0, 3, 6, 9, 12});
    CHECK(soup.indices == std::vector<std::uint32_t>{0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3});
}

}  // namespace

TEST_CASE("FMT-PLY-1..3: an ascii tetrahedron is read exactly, with its source lines", "[unit][io]") {
    const fhr::PolygonSoup soup = parse_ply(ascii_header + ascii_vertices + ascii_faces, "t.ply");
    check_tetra(soup);
    CHECK(soup.source == "t.ply");
    CHECK(soup.point_line == std::vector<std::uint64_t>{10, 11, 12, 13});
    CHECK(soup.polygon_line == std::vector<std::uint64_t>{14, 15, 16, 17});
}

TEST_CASE("FMT-PLY-2/3: extra properties, extra list properties and extra elements are read past", "[unit][io]") {
    const std::string text =
        "ply\r\nformat ascii 1.0\r\ncomment made by hand\r\nobj_info nothing\r\nelement vertex 4\r\n"
        "property uchar red\r\nproperty double z\r\nproperty list uchar float extra\r\nproperty double y\r\n"
        "property double x\r\nelement face 4\r\nproperty int flags\r\nproperty list ushort uint vertex_index\r\n"
        "property list char short more\r\nelement edge 2\r\nproperty list int int ends\r\nproperty float w\r\n"
        "end_header\r\n"
        "255 0 2 0.5 1.5 0 0\r\n0 0 0 0 1\r\n1 0 1 7 1 0\r\n2 1 3 1 2 3 0 0\r\n"
        "9 3 0 2 1 0\r\n9 3 0 1 3 1 -5\r\n9 3 0 3 2 0\r\n9 3 1 2 3 2 1 2\r\n"
        "2 0 1 0.5\r\n0 1.5\r\n";
    check_tetra(parse_ply(text, "t.ply"));
}

TEST_CASE("FMT-PLY-3: binary little and big endian with every scalar type spelling", "[unit][io]") {
    const std::vector<std::pair<std::string, std::string>> types = {
        {"char", "int8"}, {"uchar", "uint8"}, {"short", "int16"},   {"ushort", "uint16"},
        {"int", "int32"}, {"uint", "uint32"}, {"float", "float32"}, {"double", "float64"}};
    for (bool big_endian : {false, true})
        for (const auto& [name, alias] : types)
            for (const std::string& spelling : {name, alias}) {
                INFO((big_endian ? "big endian " : "little endian ") << spelling);
                check_tetra(parse_ply(binary_tetra(big_endian, spelling, "uchar", "int"), "t.ply"));
                if (name != "float" && name != "double") {
                    const fhr::PolygonSoup soup =
                        parse_ply(binary_tetra(big_endian, "float", spelling, spelling), "t.ply");
                    check_tetra(soup);
                    CHECK(soup.point_line.empty());
                    CHECK(soup.polygon_line.empty());
                }
            }
}

TEST_CASE("FMT-PLY-3: binary float32 coordinates are widened exactly; faces may come first", "[unit][io]") {
    std::string out =
        "ply\nformat binary_little_endian 1.0\nelement face 1\nproperty list uchar uint vertex_indices\n"
        "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "property list uint double normal\nend_header\n";
    put(out, "uchar", 3, false);
    for (int i : {2, 1, 0}) put(out, "uint", i, false);
    for (int v = 0; v < 3; ++v) {
        for (int c = 0; c < 3; ++c) put(out, "float", 0.1 * (v + c), false);
        put(out, "uint", 1, false);
        put(out, "double", 7, false);
    }
    const fhr::PolygonSoup soup = parse_ply(out, "t.ply");
    CHECK(soup.indices == std::vector<std::uint32_t>{2, 1, 0});
    CHECK(soup.points[2].z() == static_cast<double>(static_cast<float>(0.1 * 4)));
}

TEST_CASE("FMT-SIZE-0 / FMT-PLY-1: broken headers are refused with their line", "[unit][io]") {
    CHECK(ply_refusal("").problem() == "empty file");
    const auto header = [](const std::string& lines) { return ply_refusal("ply\n" + lines + "0 0 0\n"); };
    const fhr::InvalidInput magic = ply_refusal("plx\nformat ascii 1.0\n");
    CHECK(magic.line() == 1);
    CHECK(magic.problem() == "header: missing the 'ply' magic line");
    CHECK_THAT(ply_refusal("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n").problem(),
               Contains("no 'end_header'"));
    CHECK_THAT(header("element vertex 1\nproperty float x\nend_header\n").problem(), Contains("no 'format' line"));
    const fhr::InvalidInput encoding = header("format binary 1.0\n");
    CHECK(encoding.line() == 2);
    CHECK(encoding.problem() == "header: unknown encoding 'binary'");
    CHECK_THAT(header("format ascii 2.0\n").problem(), Contains("unsupported PLY version"));
    const fhr::InvalidInput type = header("format ascii 1.0\nelement vertex 1\nproperty int64 x\n");
    CHECK(type.line() == 4);
    CHECK(type.problem() == "header: unknown property type 'int64'");
    CHECK_THAT(header("format ascii 1.0\nproperty float x\n").problem(), Contains("property before any element"));
    CHECK_THAT(header("format ascii 1.0\nelement vertex 1\nelement vertex 1\n").problem(),
               Contains("element 'vertex' declared twice"));
    CHECK_THAT(header("format ascii 1.0\nelement vertex 1\nproperty float x\nproperty double x\n").problem(),
               Contains("property 'x' declared twice"));
    CHECK_THAT(header("format ascii 1.0\nelement vertex 1\nproperty list float int x\n").problem(),
               Contains("list count type must be an integer type"));
    CHECK_THAT(header("format ascii 1.0\nbogus line\n").problem(), Contains("unknown header line 'bogus'"));
    CHECK_THAT(header("format ascii 1.0\nelement vertex -1\n").problem(), Contains("negative count -1"));
    CHECK_THAT(header("format ascii 1.0\nelement vertex 1 2\n").problem(), Contains("unexpected '2' at end of line"));
}

TEST_CASE("FMT-PLY-2: the vertex coordinates and the face list must be declared", "[unit][io]") {
    const auto header = [](const std::string& elements) {
        return ply_refusal("ply\nformat ascii 1.0\n" + elements + "end_header\n0 0 0\n3 0 0 0\n");
    };
    const std::string vertex = "element vertex 1\nproperty float x\nproperty float y\nproperty float z\n";
    const std::string face = "element face 1\nproperty list uchar int vertex_indices\n";
    CHECK_THAT(header(face).problem(), Contains("no 'vertex' element"));
    CHECK_THAT(header(vertex).problem(), Contains("no 'face' element"));
    CHECK_THAT(header("element vertex 1\nproperty float x\nproperty float z\n" + face).problem(),
               Contains("element 'vertex' has no property 'y'"));
    CHECK_THAT(
        header("element vertex 1\nproperty float x\nproperty list uchar float y\nproperty float z\n" + face).problem(),
        Contains("vertex property 'y' is a list"));
    CHECK_THAT(header(vertex + "element face 1\nproperty list uchar int indices\n").problem(),
               Contains("element 'face' has no property 'vertex_indices'"));
    CHECK_THAT(header(vertex + "element face 1\nproperty int vertex_indices\n").problem(),
               Contains("must be a list of integers"));
    CHECK_THAT(header(vertex + "element face 1\nproperty list uchar float vertex_indices\n").problem(),
               Contains("must be a list of integers"));
    CHECK_THAT(header(vertex + "element face 0\nproperty list uchar int vertex_indices\n").problem(),
               Contains("no faces"));
    CHECK_THAT(header(vertex + face + "element empty 0\n").problem(), Contains("element 'empty' has no properties"));
}

TEST_CASE("FMT-SIZE-1: absurd element counts are refused before allocating", "[unit][io]") {
    const auto start = std::chrono::steady_clock::now();
    const fhr::InvalidInput ascii = ply_refusal(
        "ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 4000000000\nproperty list uchar int vertex_indices\nend_header\n" +
        ascii_vertices + ascii_faces);
    CHECK_THAT(ascii.problem(), Contains("need at least") && Contains("truncated file"));
    std::string binary = binary_tetra(false, "double", "uchar", "int");
    binary.replace(binary.find("vertex 4"), 8, "vertex 4000000000");
    CHECK_THAT(ply_refusal(binary).problem(), Contains("need at least 96000000"));
    const std::string other =
        "ply\nformat binary_big_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
        "property float z\nelement face 4\nproperty list uchar int vertex_indices\n"
        "element junk 9223372036854775807\nproperty list uint uint v\nend_header\n";
    CHECK_THAT(ply_refusal(other).problem(), Contains("truncated file"));
    CHECK(std::chrono::steady_clock::now() - start <
          std::chrono::seconds(1));  // CLI-ERR-1: refused at once, not after a huge allocation
}

TEST_CASE("FMT-PLY-3: truncated bodies are refused, naming the element", "[unit][io]") {
    std::string binary = binary_tetra(true, "double", "uchar", "int");
    binary.resize(binary.size() - 5);
    const fhr::InvalidInput short_body = ply_refusal(binary);
    CHECK(short_body.line() == 0);
    CHECK_THAT(short_body.problem(), Contains("need at least 148 bytes, but only 143 bytes follow the header"));
    std::string quad = binary_tetra(true, "double", "uchar", "int");
    quad[quad.size() - 13] = 4;  // the last face announces 4 indices; the data ends after 3
    const fhr::InvalidInput cut = ply_refusal(quad);
    CHECK(cut.line() == 0);
    CHECK(cut.problem() == "face 3: unexpected end of data (truncated file?)");
    std::string skipped = binary_tetra(false, "double", "uchar", "int");
    skipped.insert(skipped.find("end_header"), "element junk 1\nproperty list uint double v\n");
    skipped += std::string("\x10\0\0\0", 4);  // 16 doubles announced, none there
    skipped += std::string(20, '\0');
    CHECK(ply_refusal(skipped).problem() == "junk 0: unexpected end of data (truncated file?)");

    const std::string long_vertices = "0.000000 0.000000 0.000000\n1.000000 0 0\n0 1.000000 0\n0 0 1.000000\n";
    const fhr::InvalidInput text = ply_refusal(ascii_header + long_vertices + "3 0 2 1\n3 0 1 3\n3 0 3 2\n");
    CHECK(text.line() == 16);
    CHECK(text.problem() == "face 3: unexpected end of file (the header declares 4)");
}

TEST_CASE("FMT-IDX-1: negative, out-of-range and overflowing PLY indices are refused", "[unit][io]") {
    const fhr::InvalidInput ascii =
        ply_refusal(ascii_header + ascii_vertices + "3 0 2 1\n3 0 -1 3\n3 0 3 2\n3 1 2 3\n");
    CHECK(ascii.line() == 15);
    CHECK(ascii.problem() == "face 1: negative index -1");
    CHECK(std::string(ascii.what()) == "t.ply:15: face 1: negative index -1");
    CHECK_THAT(ply_refusal(ascii_header + ascii_vertices + "3 0 2 1\n3 0 99999999999999999999 3\n3 0 3 2\n3 1 2 3\n")
                   .problem(),
               Contains("face 1: number '99999999999999999999' is out of 64-bit integer range"));
    CHECK_THAT(ply_refusal(ascii_header + ascii_vertices + "3 0 2 1\n3 0 2147483648 3\n3 0 3 2\n3 1 2 3\n").problem(),
               Contains("face 1: value 2147483648 out of range for int"));

    std::string binary = binary_tetra(false, "float", "uchar", "int");
    const std::size_t face1 = binary.size() - 3 * 13 + 1 + 4;  // second index of face 1
    std::string out_of_range = binary;
    std::string big;
    put(big, "int", 999, false);
    out_of_range.replace(face1, 4, big);
    const fhr::InvalidInput range = ply_refusal(out_of_range);
    CHECK(range.line() == 0);
    CHECK(range.problem() == "face 1: index 999 out of range (0..3)");
    CHECK(std::string(range.what()) == "t.ply: face 1: index 999 out of range (0..3)");
    std::memset(&binary[face1], 0xff, 4);
    CHECK(ply_refusal(binary).problem() == "face 1: negative index -1");
    std::string unsigned_index = binary_tetra(false, "float", "uchar", "uint");
    std::memset(&unsigned_index[unsigned_index.size() - 3 * 13 + 1 + 4], 0xff, 4);
    CHECK(ply_refusal(unsigned_index).problem() == "face 1: index 4294967295 out of range (0..3)");
}

TEST_CASE("FMT-POLY-1: faces with fewer than 3 vertices and negative list lengths are refused", "[unit][io]") {
    const fhr::InvalidInput two = ply_refusal(ascii_header + ascii_vertices + "3 0 2 1\n2 0 1\n3 0 3 2\n3 1 2 3\n");
    CHECK(two.line() == 15);
    CHECK(two.problem() == "face 1: has 2 vertices (a polygon needs at least 3)");
    std::string binary = binary_tetra(false, "float", "char", "int");
    binary[binary.size() - 2 * 13] = '\xff';  // face 2 has -1 indices
    CHECK(ply_refusal(binary).problem() == "face 2: negative list length -1");
    CHECK_THAT(ply_refusal(ascii_header + ascii_vertices + "256 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n").problem(),
               Contains("face 0: value 256 out of range for uchar"));
}

TEST_CASE("FMT-NUM-*: bad ascii numbers and NaN / infinite / huge binary coordinates are refused", "[unit][io]") {
    const auto vertex = [](const std::string& line) {
        return ply_refusal(ascii_header + "0.0 0.0 0.0\n" + line + "\n0.0 1.0 0.0\n0.0 0.0 1.0\n" + ascii_faces);
    };
    const fhr::InvalidInput word = vertex("1 abc 0");
    CHECK(word.line() == 11);
    CHECK(word.problem() == "vertex 1: expected a number, found 'abc'");
    CHECK_THAT(vertex("1 1e400 0").problem(), Contains("vertex 1: number '1e400' is out of double range"));
    CHECK(vertex("1 nan 0").problem() == "vertex 1: coordinate is NaN");
    CHECK(vertex("1 0 inf").problem() == "vertex 1: coordinate is infinite");
    CHECK_THAT(vertex("1 0").problem(), Contains("expected a number, found end of line"));
    CHECK_THAT(vertex("1 0 0 0").problem(), Contains("unexpected '0' at end of line"));

    for (bool big_endian : {false, true}) {
        const std::string base = binary_tetra(big_endian, "double", "uchar", "int");
        const std::size_t body = base.find("end_header\n") + 11;
        const auto with_coordinate = [&](double v) {
            std::string bytes = base;
            std::string value;
            put(value, "double", v, big_endian);
            bytes.replace(body + 3 * 8 * 2 + 8, 8, value);  // vertex 2, y
            return ply_refusal(bytes);
        };
        CHECK(with_coordinate(std::nan("")).problem() == "vertex 2: coordinate is NaN");
        CHECK(with_coordinate(-HUGE_VAL).problem() == "vertex 2: coordinate is infinite");
        CHECK_THAT(with_coordinate(2e150).problem(), Contains("vertex 2: coordinate too large"));
        CHECK(with_coordinate(2e150).line() == 0);
    }
    std::string single = binary_tetra(false, "float", "uchar", "int");
    std::string inf;
    put(inf, "float", HUGE_VAL, false);
    single.replace(single.find("end_header\n") + 11 + 4, 4, inf);  // vertex 0, y
    CHECK(ply_refusal(single).problem() == "vertex 0: coordinate is infinite");
}

TEST_CASE("FMT-PLY-4: data after the last element is refused", "[unit][io]") {
    const fhr::InvalidInput binary = ply_refusal(binary_tetra(false, "float", "uchar", "int") + "abc");
    CHECK(binary.line() == 0);
    CHECK(binary.problem() == "unexpected data after the last element (3 bytes)");
    const fhr::InvalidInput ascii = ply_refusal(ascii_header + ascii_vertices + ascii_faces + "1 2 3\n");
    CHECK(ascii.line() == 18);
    CHECK(ascii.problem() == "unexpected data after the last element");
}
