// Tests of the strict OBJ reader (spec/formats.md FMT-OBJ-*, FMT-SIZE-0, FMT-NUM-*, FMT-POLY-1).
#include <string>

#include <catch2/catch.hpp>

#include <fhr/io/read.hpp>
#include "refusal.hpp"

using Catch::Matchers::Contains;
using fhr::io::parse_obj;
using fhr::test::refusal;

namespace {

const std::string tetra_vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n";

fhr::InvalidInput obj_refusal(const std::string& text) {
    return refusal([&] { parse_obj(text, "t.obj"); });
}

/// The refusal of the tetrahedron's vertices followed by one face line (line 5).
fhr::InvalidInput face_refusal(const std::string& face) { return obj_refusal(tetra_vertices + face + "\n"); }

}  // namespace

TEST_CASE("FMT-OBJ-2/3: a tetrahedron is read exactly, 1-based indices become 0-based", "[unit][io]") {
    const fhr::PolygonSoup soup = parse_obj(tetra_vertices + "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n", "t.obj");
    CHECK(soup.source == "t.obj");
    REQUIRE(soup.points.size() == 4);
    CHECK(soup.points[2] == fhr::Vec3(0, 1, 0));
    CHECK(soup.offsets == std::vector<std::uint32_t>{0, 3, 6, 9, 12});
    CHECK(soup.indices == std::vector<std::uint32_t>{0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3});
    CHECK(soup.point_line == std::vector<std::uint64_t>{1, 2, 3, 4});
    CHECK(soup.polygon_line == std::vector<std::uint64_t>{5, 6, 7, 8});
}

TEST_CASE("FMT-OBJ-3: the corner forms i, i/t, i//n and i/t/n", "[unit][io]") {
    const fhr::PolygonSoup soup =
        parse_obj(tetra_vertices +
                      "vt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n"
                      "f 1/1 3/2 2/3\nf 1//1 2//1 4//1\nf 1/1/1 4/2/1 3/3/1\nf 2/-1 3/-2/-1 4\n",
                  "t.obj");
    CHECK(soup.indices == std::vector<std::uint32_t>{0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3});
    CHECK(soup.polygon_line == std::vector<std::uint64_t>{9, 10, 11, 12});
}

TEST_CASE("FMT-OBJ-4: negative indices count back from the last vertex defined so far", "[unit][io]") {
    const fhr::PolygonSoup soup =
        parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 0 0 1\nf -4 -3 -1\nf 1 -1 -2\n", "t.obj");
    CHECK(soup.indices == std::vector<std::uint32_t>{0, 1, 2, 0, 1, 3, 0, 3, 2});
}

TEST_CASE("FMT-OBJ-5: positive indices may refer to vertices defined later", "[unit][io]") {
    const fhr::PolygonSoup soup = parse_obj("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", "t.obj");
    CHECK(soup.indices == std::vector<std::uint32_t>{0, 1, 2});
    CHECK(soup.polygon_line == std::vector<std::uint64_t>{1});
}

TEST_CASE("FMT-OBJ-1/2: ignored statements, w and colours, comments, CRLF, polygons", "[unit][io]") {
    const std::string text =
        "# exported\r\nmtllib m.mtl\r\no thing\r\ng a b\r\ns 1\r\nusemtl red\r\n"
        "v 0 0 0 1\r\nv 1 0 0 0.5 0.5 0.5\r\nv 1 1 0\r\nv 0 1 0 # trailing comment\r\n"
        "vp 0.5\r\nl 1 2\r\np 1\r\ns off\r\nf 1 2 3 4\r\n\r\ncstype bspline\r\nend\r\n";
    const fhr::PolygonSoup soup = parse_obj(text, "t.obj");
    CHECK(soup.points.size() == 4);
    CHECK(soup.points[1] == fhr::Vec3(1, 0, 0));
    CHECK(soup.polygon_size(0) == 4);
    CHECK(soup.polygon_line == std::vector<std::uint64_t>{15});
}

TEST_CASE("FMT-SIZE-0 / FMT-OBJ-6: an empty file or one without faces is refused", "[unit][io]") {
    CHECK(obj_refusal("").problem() == "empty file");
    const fhr::InvalidInput no_faces = obj_refusal(tetra_vertices + "# no faces\n");
    CHECK(no_faces.line() == 0);
    CHECK_THAT(no_faces.problem(), Contains("no faces"));
}

TEST_CASE("FMT-OBJ-1: an unknown statement is refused", "[unit][io]") {
    const fhr::InvalidInput e = obj_refusal(tetra_vertices + "vx 1 2 3\nf 1 2 3\n");
    CHECK(e.line() == 5);
    CHECK(e.problem() == "unknown OBJ statement 'vx'");
}

TEST_CASE("FMT-OBJ-5: index 0 is refused (OBJ indices are 1-based)", "[unit][io]") {
    const fhr::InvalidInput e = face_refusal("f 1 0 2");
    CHECK(e.line() == 5);
    CHECK(e.problem() == "face 0: index 0 (OBJ indices are 1-based)");
    CHECK(std::string(e.what()) == "t.obj:5: face 0: index 0 (OBJ indices are 1-based)");
}

TEST_CASE("FMT-OBJ-4/5: out-of-range and overflowing indices are refused", "[unit][io]") {
    // a positive index is checked once all vertices are known, and still names its face's line
    const fhr::InvalidInput positive = obj_refusal(tetra_vertices + "f 1 2 3\nf 1 2 5\nv 9 9 9\nf 1 2 7\n");
    CHECK(positive.line() == 8);
    CHECK(positive.problem() == "face 2: index 7 out of range (1..5)");
    const fhr::InvalidInput relative = face_refusal("f 1 2 -5");
    CHECK(relative.line() == 5);
    CHECK(relative.problem() == "face 0: relative index -5 out of range (only 4 vertices defined so far)");
    CHECK_THAT(face_refusal("f 1 2 99999999999999999999").problem(),
               Contains("face 0: index '99999999999999999999' out of range"));
    CHECK_THAT(face_refusal("f 1 2 -99999999999999999999").problem(), Contains("out of range"));
    CHECK_THAT(face_refusal("f 1 2 4294967297").problem(), Contains("index '4294967297' out of range"));
    CHECK_THAT(face_refusal("f 1 2 -9223372036854775808").problem(), Contains("relative index"));
}

TEST_CASE("FMT-OBJ-3: malformed corners are refused", "[unit][io]") {
    for (const char* corner : {"3/", "3//", "3/1/", "3/x", "3//0", "3/0", "3/1/1/1", "/1", "x"}) {
        INFO(corner);
        const fhr::InvalidInput e = face_refusal(std::string("f 1 2 ") + corner);
        CHECK(e.line() == 5);
        CHECK_THAT(e.problem(),
                   Contains("face 0:") && (Contains("malformed corner") || Contains("expected a vertex index")));
    }
}

TEST_CASE("FMT-POLY-1: a face with fewer than 3 vertices is refused", "[unit][io]") {
    CHECK(face_refusal("f 1 2").problem() == "face 0: has 2 vertices (a polygon needs at least 3)");
    CHECK(face_refusal("f").problem() == "face 0: has 0 vertices (a polygon needs at least 3)");
}

TEST_CASE("FMT-OBJ-2 / FMT-NUM-*: bad vertex lines are refused", "[unit][io]") {
    const auto vertex = [](const std::string& line) { return obj_refusal("v 0 0 0\n" + line + "\nf 1 1 1\n"); };
    const fhr::InvalidInput word = vertex("v 1 two 3");
    CHECK(word.line() == 2);
    CHECK(word.problem() == "vertex 1: expected a number, found 'two'");
    CHECK_THAT(vertex("v 1 2").problem(), Contains("vertex 1: expected a number, found end of line"));
    CHECK_THAT(vertex("v 1 2 3 4 5").problem(), Contains("expected x y z, x y z w or x y z r g b"));
    CHECK_THAT(vertex("v 1 2 3 4 5 6 7").problem(), Contains("unexpected '7' at end of line"));
    CHECK_THAT(vertex("v 1 2 1e400").problem(), Contains("'1e400' is out of double range"));
    CHECK(vertex("v nan 2 3").problem() == "vertex 1: coordinate is NaN");
    CHECK(vertex("v 1 -inf 3").problem() == "vertex 1: coordinate is infinite");
    CHECK_THAT(vertex("v 1 2 -2e150").problem(), Contains("coordinate too large"));
}
