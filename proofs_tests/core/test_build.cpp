// Tests of build_trimesh: every input rule INV-IN-1..12 of spec/mesh.md gets a soup that breaks
// it, and the message must name the problem, the element and the line.
#include <catch2/catch.hpp>

#include <fhr/core/build.hpp>
#include <fhr/core/errors.hpp>
#include <fhr/core/geometry.hpp>
#include <fhr/core/topology.hpp>

using namespace fhr;

namespace {

PolygonSoup soup(const std::vector<Vec3>& points, const std::vector<std::vector<std::uint32_t>>& polys) {
    PolygonSoup s;
    s.source = "in.off";
    s.points = points;
    for (std::size_t v = 0; v < points.size(); ++v) s.point_line.push_back(3 + v);
    for (std::size_t p = 0; p < polys.size(); ++p) {
        s.add_polygon(polys[p].data(), static_cast<std::uint32_t>(polys[p].size()));
        s.polygon_line.push_back(3 + points.size() + p);
    }
    return s;
}

const std::vector<Vec3> tet_points{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
const std::vector<std::vector<std::uint32_t>> tet_faces{{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

TriMesh build(const PolygonSoup& s, BuildOptions o = {}) {
    BuildLog log;
    return build_trimesh(s, o, log);
}

// Runs the builder, expects InvalidInput, and returns it for inspection.
InvalidInput refused(const PolygonSoup& s, BuildOptions o = {}) {
    BuildLog log;
    try {
        build_trimesh(s, o, log);
    } catch (const InvalidInput& e) {
        return e;
    }
    FAIL("build_trimesh accepted an invalid soup");
    throw;
}

}  // namespace

TEST_CASE("INV-IN: a valid tetrahedron builds and validates", "[unit][build]") {
    BuildLog log;
    const TriMesh m = build_trimesh(soup(tet_points, tet_faces), {}, log);
    m.validate();
    CHECK(m.n_vertices() == 4);
    CHECK(m.n_faces() == 4);
    CHECK(m.n_edges() == 6);
    CHECK(euler_characteristic(m) == 2);
    CHECK(genus(m) == 0);
    CHECK(log.warnings.empty());
    CHECK(signed_volume(m) == Approx(1.0 / 6));
}

TEST_CASE("INV-IN-1: non-finite and overflowing coordinates are refused", "[unit][build]") {
    auto pts = tet_points;
    pts[2].y() = std::numeric_limits<double>::quiet_NaN();
    auto e = refused(soup(pts, tet_faces));
    CHECK(e.line() == 5);
    CHECK_THAT(e.problem(), Catch::Contains("vertex 2") && Catch::Contains("non-finite"));
    pts[2].y() = -2e150;
    e = refused(soup(pts, tet_faces));
    CHECK_THAT(e.problem(), Catch::Contains("vertex 2") && Catch::Contains("overflow"));
    pts[2].y() = 1e150;  // the largest accepted magnitude
    CHECK_NOTHROW(build(soup(pts, tet_faces)));
}

TEST_CASE("INV-IN-2: faces with fewer than 3 vertices or a repeated vertex are refused", "[unit][build]") {
    auto faces = tet_faces;
    faces.push_back({1, 2});
    auto e = refused(soup(tet_points, faces));
    CHECK(e.line() == 3 + 4 + 4);
    CHECK_THAT(e.problem(), Catch::Contains("face 4 has 2 vertices"));
    faces.back() = {1, 2, 1};
    e = refused(soup(tet_points, faces));
    CHECK_THAT(e.problem(), Catch::Contains("face 4 repeats vertex 1"));
}

TEST_CASE("INV-IN-3: polygons need --triangulate", "[unit][build]") {
    const std::vector<Vec3> cube{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                 {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    const std::vector<std::vector<std::uint32_t>> quads{{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                                        {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
    const auto e = refused(soup(cube, quads));
    CHECK_THAT(e.problem(), Catch::Contains("face 0 has 4 vertices") && Catch::Contains("--triangulate"));
    BuildOptions o;
    o.triangulate = true;
    const TriMesh m = build(soup(cube, quads), o);
    m.validate();
    CHECK(m.n_faces() == 12);
    CHECK(genus(m) == 0);
    CHECK(signed_volume(m) == Approx(1.0));
}

TEST_CASE("INV-IN-4: duplicate faces are refused, whatever their orientation", "[unit][build]") {
    auto faces = tet_faces;
    faces.push_back({3, 2, 1});
    const auto e = refused(soup(tet_points, faces));
    CHECK_THAT(e.problem(), Catch::Contains("faces 3 and 4 are duplicates"));
    CHECK(e.line() == 3 + 4 + 4);
}

TEST_CASE("INV-IN-4: two faces on the same three edges are duplicates too; the message uses the file's numbers",
          "[unit][build]") {
    // The pillow (1, 2, 3), (1, 3, 2): each edge in exactly two faces, consistently oriented, so
    // only the vertex sets tell. Points 0 and 4 are isolated and dropped first (INV-IN-12), so
    // the mesh numbers the vertices 0, 1, 2; the message still names the file's 1, 3, 2.
    std::vector<Vec3> pts{{9, 9, 9}};
    for (const auto& p : tet_points) pts.push_back(p);
    const auto e = refused(soup(pts, {{1, 2, 3}, {1, 3, 2}}));
    CHECK(e.problem() == "faces 0 and 1 are duplicates (vertices 1, 3, 2)");
    CHECK(e.line() == 3 + 5 + 1);
    // Every order of the second face's corners: turned over, or the same orientation started
    // elsewhere (then no corner of one sits where the same vertex sits in the other).
    for (const std::vector<std::uint32_t>& second :
         std::vector<std::vector<std::uint32_t>>{{1, 2, 3}, {2, 3, 1}, {3, 1, 2}, {1, 3, 2}, {3, 2, 1}, {2, 1, 3}}) {
        INFO(second[0] << ", " << second[1] << ", " << second[2]);
        CHECK_THAT(refused(soup(pts, {{1, 2, 3}, second})).problem(),
                   Catch::StartsWith("faces 0 and 1 are duplicates"));
    }
}

TEST_CASE("INV-IN-5: exactly degenerate triangles are refused", "[unit][build]") {
    // A flat double-covered "tetrahedron" whose apex lies on the segment (0,0,0)-(2,0,0).
    auto pts = tet_points;
    pts[3] = {0.5, 0, 0};
    auto e = refused(soup(pts, tet_faces));
    CHECK_THAT(e.problem(), Catch::Contains("face 1 is degenerate"));
    // Two coincident positions also make a degenerate triangle.
    pts = tet_points;
    pts[3] = pts[1];
    e = refused(soup(pts, tet_faces));
    CHECK_THAT(e.problem(), Catch::Contains("degenerate"));
    // Nearly but not exactly collinear is accepted: the predicate is exact.
    pts = tet_points;
    pts[3] = {0.5, 0, 1e-300};
    CHECK_NOTHROW(build(soup(pts, tet_faces)));
}

TEST_CASE("INV-IN-6: an edge in three faces is refused", "[unit][build]") {
    auto pts = tet_points;
    pts.push_back({1, 1, 1});
    auto faces = tet_faces;
    faces.push_back({1, 2, 4});
    const auto e = refused(soup(pts, faces));
    CHECK_THAT(e.problem(), Catch::Contains("non-manifold edge (2, 1) is shared by 3 faces (0, 3, 4)"));
}

TEST_CASE("INV-IN-7: a Moebius strip is not orientable", "[unit][build]") {
    // Strip of 3 quads (6 triangles) closed with a half twist.
    std::vector<Vec3> pts;
    for (int i = 0; i < 3; ++i) {
        const double a = 2 * M_PI * i / 3;
        pts.push_back({std::cos(a), std::sin(a), -0.2 + 0.05 * i});
        pts.push_back({1.3 * std::cos(a), 1.3 * std::sin(a), 0.2 + 0.07 * i});
    }
    const std::vector<std::vector<std::uint32_t>> faces{{0, 2, 1}, {1, 2, 3}, {2, 4, 3},
                                                        {3, 4, 5}, {4, 1, 5}, {5, 1, 0}};
    const auto e = refused(soup(pts, faces));
    CHECK_THAT(e.problem(), Catch::Contains("not orientable"));
}

TEST_CASE("INV-IN-8: inconsistently oriented faces are re-oriented outward, with a warning", "[unit][build]") {
    auto faces = tet_faces;
    std::swap(faces[1][1], faces[1][2]);
    BuildLog log;
    const TriMesh m = build_trimesh(soup(tet_points, faces), {}, log);
    m.validate();
    CHECK(log.reoriented_faces == 1);
    REQUIRE(log.warnings.size() == 1);
    CHECK_THAT(log.warnings[0], Catch::Contains("re-oriented 1 faces") && Catch::Contains("face 1"));
    CHECK(signed_volume(m) > 0);
    // All faces inside out: the whole surface is turned.
    auto inverted = tet_faces;
    for (auto& f : inverted) std::swap(f[0], f[1]);
    BuildLog log2;
    const TriMesh m2 = build_trimesh(soup(tet_points, inverted), {}, log2);
    CHECK(log2.reoriented_faces == 4);
    CHECK(signed_volume(m2) == Approx(1.0 / 6));
}

TEST_CASE("INV-IN-9: a bow-tie vertex is refused", "[unit][build]") {
    // Two tetrahedra sharing vertex 0 only.
    auto pts = tet_points;
    pts.push_back({-1, 0, 0});
    pts.push_back({0, -1, 0});
    pts.push_back({0, 0, -1});
    auto faces = tet_faces;
    for (auto f : tet_faces) {
        for (auto& v : f)
            if (v != 0) v += 3;
        std::swap(f[1], f[2]);  // mirrored copy: swap to stay outward
        faces.push_back(f);
    }
    const auto e = refused(soup(pts, faces));
    CHECK_THAT(e.problem(), Catch::Contains("non-manifold vertex 0"));
    CHECK(e.line() == 3);
}

TEST_CASE("INV-IN-10: boundary is accepted, and refused when a closed surface is required", "[unit][build]") {
    const std::vector<std::vector<std::uint32_t>> open(tet_faces.begin(), tet_faces.begin() + 3);
    const TriMesh m = build(soup(tet_points, open));
    m.validate();
    CHECK(boundary_loops(m).size() == 1);
    CHECK(genus(m) == 0);
    CHECK(euler_characteristic(m) == 1);
    BuildOptions o;
    o.require_closed = true;
    const auto e = refused(soup(tet_points, open), o);
    CHECK_THAT(e.problem(), Catch::Contains("boundary (1 boundary loop") && Catch::Contains("closed surface"));
}

TEST_CASE("INV-IN-10: two boundary loops, counted in the plural", "[unit][build]") {
    // Two separate triangles: each its own loop; the first loop runs against face 0.
    std::vector<Vec3> pts = tet_points;
    pts.push_back({5, 0, 0});
    pts.push_back({6, 0, 0});
    pts.push_back({5, 1, 0});
    BuildOptions o;
    o.require_closed = true;
    const auto e = refused(soup(pts, {{0, 1, 2}, {4, 5, 6}}), o);
    CHECK(e.problem() ==
          "the mesh has boundary (2 boundary loops, the first through edge (1, 0)): the method needs a closed surface");
    CHECK(e.line() == 0);
}

TEST_CASE("INV-IN-10, INV-IN-11: a closed connected surface passes when both are required", "[unit][build]") {
    BuildOptions o;
    o.require_closed = true;
    o.require_connected = true;
    const TriMesh m = build(soup(tet_points, tet_faces), o);
    CHECK_NOTHROW(m.validate());
    CHECK(m.is_closed());
    CHECK(connected_components(m).count == 1);
}

TEST_CASE("INV-IN-11: several components are accepted, and refused when a connected surface is required",
          "[unit][build]") {
    auto pts = tet_points;
    for (const auto& p : tet_points) pts.push_back(p + Vec3(5, 0, 0));
    auto faces = tet_faces;
    for (auto f : tet_faces) {
        for (auto& v : f) v += 4;
        faces.push_back(f);
    }
    const TriMesh m = build(soup(pts, faces));
    CHECK(connected_components(m).count == 2);
    CHECK(euler_characteristic(m) == 4);
    CHECK(genus(m) == 0);
    BuildOptions o;
    o.require_connected = true;
    const auto e = refused(soup(pts, faces), o);
    CHECK_THAT(e.problem(), Catch::Contains("2 connected components"));
}

TEST_CASE("INV-IN-12: isolated vertices are dropped with a warning", "[unit][build]") {
    std::vector<Vec3> pts{{9, 9, 9}};
    for (const auto& p : tet_points) pts.push_back(p);
    auto faces = tet_faces;
    for (auto& f : faces)
        for (auto& v : f) ++v;
    BuildLog log;
    const TriMesh m = build_trimesh(soup(pts, faces), {}, log);
    CHECK(m.n_vertices() == 4);
    CHECK(log.dropped_vertices == 1);
    CHECK(log.vertex_origin.values() == std::vector<std::uint32_t>{1, 2, 3, 4});
    REQUIRE(log.warnings.size() == 1);
    CHECK_THAT(log.warnings[0], Catch::Contains("dropped 1 isolated vertices (first: vertex 0)"));
    CHECK(m.position(VertexId(0)) == tet_points[0]);
}

TEST_CASE("INV-IN: an empty soup is refused", "[unit][build]") {
    const auto e = refused(soup({}, {}));
    CHECK_THAT(e.problem(), Catch::Contains("no faces"));
}

TEST_CASE("INV-IN-13: a flat closed surface (four coplanar points as a tetrahedron) is refused as bad input",
          "[unit][build]") {
    // The apex moved into the plane of face 0, inside its triangle: no triangle is degenerate,
    // but the four faces cover the triangle twice.
    auto pts = tet_points;
    pts[3] = (pts[0] + pts[1] + pts[2]) / 3.0;
    const auto e = refused(soup(pts, tet_faces));
    CHECK_THAT(e.problem(), Catch::Contains("the closed surface is flat"));
    CHECK_THAT(e.problem(), Catch::Contains("all 4 vertices"));
    // Off the plane by the smallest amount the exact predicate sees: accepted.
    pts[3].z() += 1e-300;
    CHECK_NOTHROW(build(soup(pts, tet_faces)));
    // A surface with boundary may be flat (when boundary is allowed).
    BuildOptions o;
    o.require_closed = false;
    const std::vector<std::vector<std::uint32_t>> disk = {{0, 1, 2}};
    CHECK_NOTHROW(build(soup(tet_points, disk), o));
}
