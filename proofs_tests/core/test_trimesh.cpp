// FHR tests — TriMesh (src/fhr/core/trimesh.hpp), the halfedge triangulation T of the paper (§1):
// construction, navigation, boundary, the edits the decimation of §2 is built from (flip,
// split, half-edge collapse with the link condition), compaction, and the invariant checker
// (spec/mesh.md INV-MESH-0..8), fed broken structures through TriMesh::from_arrays. Property
// tests run random edit sequences on random meshes of genus 0..4 (support/gen_mesh.hpp).
#include <catch2/catch.hpp>
#include <rapidcheck/catch.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <fhr/core/detail/cones.hpp>
#include <fhr/core/geometry.hpp>
#include <fhr/core/topology.hpp>
#include <fhr/core/trimesh.hpp>
#include <fhr/testing/rapidcheck.hpp>

using Catch::Matchers::Contains;
using fhr::Coned;
using fhr::EdgeId;
using fhr::FaceId;
using fhr::HalfedgeId;
using fhr::Triangle;
using fhr::TriMesh;
using fhr::Vec3;
using fhr::VertexId;

namespace {

TriMesh tetrahedron() {
    const std::vector<Triangle> t{{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    return TriMesh::from_triangles({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)}, t);
}

// Vertices +x, −x, +y, −y, +z, −z.
const std::vector<Triangle> octahedron_triangles{{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                                 {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
std::vector<Vec3> octahedron_positions() {
    return {Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0), Vec3(0, 0, 1), Vec3(0, 0, -1)};
}
TriMesh octahedron() { return TriMesh::from_triangles(octahedron_positions(), octahedron_triangles); }

// Unit cube, vertex x + 2y + 4z, each square (a, b, c, d) counter-clockwise from outside.
TriMesh cube() {
    std::vector<Vec3> p;
    for (int i = 0; i < 8; ++i) p.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
    const std::uint32_t squares[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                         {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    std::vector<Triangle> t;
    for (const auto& s : squares) {
        t.push_back({s[0], s[1], s[2]});
        t.push_back({s[0], s[2], s[3]});
    }
    return TriMesh::from_triangles(std::move(p), t);
}

// Hexagonal disk: centre 0, ring 1..6.
TriMesh hexagon() {
    std::vector<Vec3> p{Vec3(0, 0, 0)};
    const double c = 0.5, s = 0.8660254037844386;
    for (const auto& [x, y] :
         std::vector<std::pair<double, double>>{{1, 0}, {c, s}, {-c, s}, {-1, 0}, {-c, -s}, {c, -s}})
        p.emplace_back(x, y, 0);
    std::vector<Triangle> t;
    for (std::uint32_t i = 1; i <= 6; ++i) t.push_back({0, i, i % 6 + 1});
    return TriMesh::from_triangles(std::move(p), t);
}

// The octahedron with face (0, 2, 4) replaced by a tetrahedral cap over new vertex 6 (valence 3).
TriMesh capped_octahedron() {
    std::vector<Vec3> p = octahedron_positions();
    p.emplace_back(0.6, 0.6, 0.6);
    std::vector<Triangle> t(octahedron_triangles.begin() + 1, octahedron_triangles.end());
    t.push_back({0, 2, 6});
    t.push_back({2, 4, 6});
    t.push_back({4, 0, 6});
    return TriMesh::from_triangles(std::move(p), t);
}

/// The oriented triangles, each rotated to start at its smallest vertex, sorted: equal iff the
/// two meshes have the same faces with the same orientations.
std::vector<Triangle> canonical(std::vector<Triangle> t) {
    for (Triangle& f : t) std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());
    std::sort(t.begin(), t.end());
    return t;
}

std::set<std::uint32_t> neighbours(const TriMesh& m, VertexId v) {
    std::set<std::uint32_t> n;
    m.for_each_outgoing(v, [&](HalfedgeId h) { n.insert(m.to(h).idx()); });
    return n;
}

/// Neighbour sets computed from the triangle list alone (independent of the halfedge links).
std::vector<std::set<std::uint32_t>> neighbours_from_triangles(const TriMesh& m) {
    std::vector<std::set<std::uint32_t>> n(m.n_vertices());
    for (const Triangle& t : m.triangles())
        for (int k = 0; k < 3; ++k) {
            n[t[k]].insert(t[(k + 1) % 3]);
            n[t[(k + 1) % 3]].insert(t[k]);
        }
    return n;
}

void check_counts(const TriMesh& m, std::size_t v, std::size_t e, std::size_t f) {
    CHECK(m.n_vertices() == v);
    CHECK(m.n_edges() == e);
    CHECK(m.n_faces() == f);
}

}  // namespace

// --- construction ---------------------------------------------------------------------------

TEST_CASE("closed polyhedra: counts, Euler characteristic, orientation (INV-MESH-1..8)", "[unit]") {
    const TriMesh tet = tetrahedron(), oct = octahedron(), box = cube();
    check_counts(tet, 4, 6, 4);
    check_counts(oct, 6, 12, 8);
    check_counts(box, 8, 18, 12);
    for (const TriMesh* m : {&tet, &oct, &box}) {
        CHECK_NOTHROW(m->validate());
        CHECK(m->is_closed());
        CHECK(fhr::euler_characteristic(*m) == 2);
        CHECK(fhr::genus(*m) == 0);
        CHECK(fhr::boundary_loops(*m).empty());
    }
    CHECK(fhr::signed_volume(tet) == Approx(1.0 / 6));
    CHECK(fhr::signed_volume(oct) == Approx(4.0 / 3));
    CHECK(fhr::signed_volume(box) == Approx(1.0));
}

TEST_CASE("triangles() returns the input faces in order and orientation", "[unit]") {
    const TriMesh m = octahedron();
    CHECK(m.triangles() == octahedron_triangles);
    for (FaceId f : m.faces()) {
        const auto v = m.face_vertices(f);
        const Triangle& t = octahedron_triangles[f.idx()];
        CHECK((v[0].idx() == t[0] && v[1].idx() == t[1] && v[2].idx() == t[2]));
    }
}

// --- navigation -----------------------------------------------------------------------------

TEST_CASE("halfedge navigation identities (INV-MESH-3, 4, 6)", "[unit]") {
    for (const TriMesh& m : {tetrahedron(), octahedron(), cube()}) {
        for (HalfedgeId h : m.halfedges()) {
            CHECK(TriMesh::twin(TriMesh::twin(h)) == h);
            CHECK(TriMesh::edge(h) == TriMesh::edge(TriMesh::twin(h)));
            CHECK(m.from(TriMesh::twin(h)) == m.to(h));
            CHECK(m.from(m.next(h)) == m.to(h));
            CHECK(m.next(m.next(m.next(h))) == h);
            CHECK(m.prev(m.next(h)) == h);
            CHECK(m.face(m.next(h)) == m.face(h));
            CHECK(m.ccw_rotated(m.cw_rotated(h)) == h);
            CHECK(m.from(m.cw_rotated(h)) == m.from(h));
            CHECK(m.find_halfedge(m.from(h), m.to(h)) == h);
        }
        for (VertexId v : m.vertices()) CHECK(m.from(m.out(v)) == v);
        for (FaceId f : m.faces()) CHECK(m.face(m.halfedge(f)) == f);
    }
}

TEST_CASE("valences", "[unit]") {
    const TriMesh tet = tetrahedron(), oct = octahedron(), box = cube();
    for (VertexId v : tet.vertices()) CHECK(tet.valence(v) == 3);
    for (VertexId v : oct.vertices()) CHECK(oct.valence(v) == 4);
    std::size_t sum = 0;  // handshake: Σ valence = 2E
    for (VertexId v : box.vertices()) {
        CHECK(box.valence(v) >= 3);
        CHECK(box.valence(v) <= 6);
        sum += box.valence(v);
    }
    CHECK(sum == 2 * box.n_edges());
}

TEST_CASE("find_halfedge returns an invalid id for non-adjacent vertices", "[unit]") {
    const TriMesh oct = octahedron();
    CHECK_FALSE(oct.find_halfedge(VertexId(0), VertexId(1)).valid());  // +x, −x
    CHECK_FALSE(oct.find_halfedge(VertexId(4), VertexId(5)).valid());  // +z, −z
    const HalfedgeId h = oct.find_halfedge(VertexId(0), VertexId(2));
    REQUIRE(h.valid());
    CHECK(oct.from(h) == VertexId(0));
    CHECK(oct.to(h) == VertexId(2));
}

TEST_CASE("for_each_outgoing turns clockwise seen from outside, starting at out(v)", "[unit]") {
    const TriMesh oct = octahedron();
    // Seen from above (+z) the neighbours of +z (vertex 4) are +x, +y, −x, −y counter-clockwise,
    // so clockwise they come as 0, 3, 1, 2 (cyclically).
    std::vector<std::uint32_t> order;
    oct.for_each_outgoing(VertexId(4), [&](HalfedgeId h) { order.push_back(oct.to(h).idx()); });
    REQUIRE(order.size() == 4);
    CHECK(oct.from(oct.out(VertexId(4))) == VertexId(4));
    CHECK(order.front() == oct.to(oct.out(VertexId(4))).idx());
    std::rotate(order.begin(), std::find(order.begin(), order.end(), 0u), order.end());
    CHECK(order == std::vector<std::uint32_t>{0, 3, 1, 2});
}

// --- boundary -------------------------------------------------------------------------------

TEST_CASE("a single triangle: one boundary loop of three halfedges", "[unit]") {
    const std::vector<Triangle> t{{0, 1, 2}};
    const TriMesh m = TriMesh::from_triangles({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, t);
    CHECK_NOTHROW(m.validate());
    check_counts(m, 3, 3, 1);
    CHECK_FALSE(m.is_closed());
    CHECK(fhr::euler_characteristic(m) == 1);
    CHECK(fhr::genus(m) == 0);
    const auto loops = fhr::boundary_loops(m);
    REQUIRE(loops.size() == 1);
    std::size_t length = 0;
    HalfedgeId h = loops.front();
    do {
        CHECK(m.is_boundary(h));
        CHECK_FALSE(m.is_boundary(TriMesh::twin(h)));
        CHECK(m.prev(m.next(h)) == h);  // prev walks the boundary loop
        h = m.next(h);
        ++length;
    } while (h != loops.front() && length <= 3);
    CHECK(length == 3);
    for (VertexId v : m.vertices()) {
        CHECK(m.is_boundary(v));
        CHECK(m.is_boundary(m.out(v)));  // INV-MESH-7: out() of a boundary vertex is its boundary halfedge
        CHECK(m.valence(v) == 2);
    }
    for (EdgeId e : m.edges()) {
        CHECK(m.is_boundary(e));
        CHECK_FALSE(m.is_flip_ok(e));
        CHECK_FALSE(m.is_collapse_ok(TriMesh::halfedge(e, 0)));
        // A boundary edge splits too: its one triangle becomes two, the loop gains a vertex.
        TriMesh split = m;
        const VertexId added = split.split_edge(
            e, 0.5 * (m.position(m.from(TriMesh::halfedge(e, 0))) + m.position(m.to(TriMesh::halfedge(e, 0)))));
        split.validate();
        CHECK(split.n_faces() == m.n_faces() + 1);
        CHECK(split.is_boundary(added));
        CHECK(split.valence(added) == 3);
        CHECK(split.to(TriMesh::halfedge(e, 0)) == added);
        CHECK(fhr::boundary_loops(split).size() == 1);
    }
}

TEST_CASE("a hexagonal disk: interior centre, boundary ring", "[unit]") {
    const TriMesh m = hexagon();
    CHECK_NOTHROW(m.validate());
    check_counts(m, 7, 12, 6);
    CHECK(fhr::euler_characteristic(m) == 1);
    CHECK(fhr::genus(m) == 0);
    REQUIRE(fhr::boundary_loops(m).size() == 1);
    CHECK_FALSE(m.is_boundary(VertexId(0)));
    CHECK(m.valence(VertexId(0)) == 6);
    CHECK(fhr::angle_sum(m, VertexId(0)) == Approx(2 * 3.141592653589793));
    for (std::uint32_t i = 1; i <= 6; ++i) {
        CHECK(m.is_boundary(VertexId(i)));
        CHECK(m.valence(VertexId(i)) == 3);
        // The boundary loop runs ring vertex i -> i−1 (the faces' inner side is counter-clockwise).
        const HalfedgeId b = m.out(VertexId(i));
        CHECK(m.is_boundary(b));
        CHECK(m.to(b).idx() == (i + 4) % 6 + 1);
    }
    for (EdgeId e : m.edges()) {  // the rim edges are exactly those not touching the centre
        const HalfedgeId h = TriMesh::halfedge(e, 0);
        CHECK(m.is_boundary(e) == (m.from(h) != VertexId(0) && m.to(h) != VertexId(0)));
        // Rim edges are boundary; a spoke ends at a ring vertex of valence 3, which must keep 3.
        CHECK_FALSE(m.is_flip_ok(e));
    }
}

TEST_CASE("an annulus has two boundary loops and χ = 0", "[unit]") {
    std::vector<Vec3> p;
    for (double r : {1.0, 2.0})
        for (const auto& [x, y] : std::vector<std::pair<double, double>>{{1, 0}, {0, 1}, {-1, 0}, {0, -1}})
            p.emplace_back(r * x, r * y, 0);
    std::vector<Triangle> t;
    for (std::uint32_t i = 0; i < 4; ++i) {
        const std::uint32_t j = (i + 1) % 4;
        t.push_back({i, i + 4, j + 4});
        t.push_back({i, j + 4, j});
    }
    const TriMesh m = TriMesh::from_triangles(std::move(p), t);
    CHECK_NOTHROW(m.validate());
    CHECK(fhr::boundary_loops(m).size() == 2);
    CHECK(fhr::euler_characteristic(m) == 0);
    CHECK(fhr::genus(m) == 0);
}

// --- edits ----------------------------------------------------------------------------------

TEST_CASE("flip on the octahedron replaces edge (+x, +y) by (+z, −z)", "[unit]") {
    TriMesh m = octahedron();
    const HalfedgeId h = m.find_halfedge(VertexId(0), VertexId(2));  // in face (0, 2, 4); twin in (2, 0, 5)
    const EdgeId e = TriMesh::edge(h);
    REQUIRE(m.is_flip_ok(e));
    m.flip(e);
    CHECK_NOTHROW(m.validate());
    check_counts(m, 6, 12, 8);
    CHECK_FALSE(m.find_halfedge(VertexId(0), VertexId(2)).valid());
    CHECK(m.find_halfedge(VertexId(4), VertexId(5)).valid());
    // (a, b, c) = (0, 2, 4) and (b, a, d) = (2, 0, 5) became (a, d, c) = (0, 5, 4) and (d, b, c) = (5, 2, 4).
    std::vector<Triangle> expected(octahedron_triangles.begin() + 1, octahedron_triangles.end());
    expected.erase(expected.begin() + 3);  // (2, 0, 5)
    expected.push_back({0, 5, 4});
    expected.push_back({5, 2, 4});
    CHECK(canonical(m.triangles()) == canonical(expected));
    CHECK(m.valence(VertexId(0)) == 3);
    CHECK(m.valence(VertexId(2)) == 3);
    CHECK(m.valence(VertexId(4)) == 5);
    CHECK(m.valence(VertexId(5)) == 5);
    // A vertex of valence 3 cannot lose an edge.
    CHECK_FALSE(m.is_flip_ok(TriMesh::edge(m.find_halfedge(VertexId(0), VertexId(4)))));
    // Flipping the same edge again restores the octahedron.
    REQUIRE(m.is_flip_ok(e));
    m.flip(e);
    CHECK(canonical(m.triangles()) == canonical(octahedron_triangles));
}

TEST_CASE("no flip is possible on a tetrahedron", "[unit]") {
    const TriMesh m = tetrahedron();
    for (EdgeId e : m.edges()) CHECK_FALSE(m.is_flip_ok(e));
}

// LIB-2: a documented precondition broken by the caller is a std::logic_error naming it, in every
// build with the tests (meson option dchecks), instead of a corrupted mesh.
TEST_CASE("broken preconditions of the mesh edits throw std::logic_error in test builds (LIB-2)", "[unit]") {
#if !defined(FHR_DCHECKS)
    FAIL("the tests are built without FHR_DCHECKS: meson.build turns dchecks on wherever the tests are built");
#endif
    TriMesh tetra = tetrahedron();
    CHECK_THROWS_AS(tetra.flip(EdgeId(0)), std::logic_error);
    CHECK_THROWS_WITH(tetra.flip(EdgeId(0)), Contains("precondition violated: is_flip_ok(e)"));
    TriMesh octa = octahedron();
    octa.collapse(octa.find_halfedge(VertexId(4), VertexId(0)));
    CHECK_THROWS_AS(fhr::euler_characteristic(octa), std::logic_error);
    CHECK_THROWS_WITH(fhr::euler_characteristic(octa), Contains("precondition violated: !m.has_garbage()"));
    TriMesh tetra2 = tetrahedron();  // every collapse of a tetrahedron breaks the link condition
    const HalfedgeId h = tetra2.find_halfedge(VertexId(0), VertexId(1));
    CHECK_THROWS_AS(tetra2.collapse(h), std::logic_error);
    CHECK_THROWS_WITH(tetra2.collapse(h), Contains("precondition violated: is_collapse_ok(h)"));
    CHECK_NOTHROW(tetra2.validate());  // refused before anything changed
    // fill_hole needs a boundary halfedge: an invalid id, one past the end, an interior one.
    for (const HalfedgeId g : {HalfedgeId(), HalfedgeId(12), HalfedgeId(0)})
        CHECK_THROWS_WITH(tetra2.fill_hole(g, Vec3(0, 0, 0)),
                          Contains("precondition violated: h.valid() && h.idx() < n_halfedges() && is_boundary(h)"));
    check_counts(tetra2, 4, 6, 4);  // no apex was added
}

TEST_CASE("split_edge on the tetrahedron", "[unit]") {
    TriMesh m = tetrahedron();
    const HalfedgeId h = m.find_halfedge(VertexId(0), VertexId(1));
    const EdgeId e = TriMesh::edge(h);
    const VertexId b = m.to(TriMesh::halfedge(e, 0));
    const VertexId n = m.split_edge(e, Vec3(0.5, 0, 0));
    CHECK(n == VertexId(4));
    CHECK_NOTHROW(m.validate());
    check_counts(m, 5, 9, 6);
    CHECK(m.position(n) == Vec3(0.5, 0, 0));
    CHECK(m.to(m.out(n)) == b);
    CHECK(neighbours(m, n) == std::set<std::uint32_t>{0, 1, 2, 3});
    CHECK_FALSE(m.find_halfedge(VertexId(0), VertexId(1)).valid());
    CHECK(canonical(m.triangles()) == canonical({{0, 2, 4}, {4, 2, 1}, {0, 4, 3}, {4, 1, 3}, {0, 3, 2}, {1, 2, 3}}));
    CHECK(fhr::signed_volume(m) == Approx(1.0 / 6));
}

TEST_CASE("collapse on the octahedron, then compact", "[unit]") {
    TriMesh m = octahedron();
    const HalfedgeId h = m.find_halfedge(VertexId(4), VertexId(0));  // +z onto +x
    REQUIRE(m.is_collapse_ok(h));
    m.collapse(h);
    CHECK(m.has_garbage());
    CHECK(m.is_deleted(VertexId(4)));
    CHECK_FALSE(m.is_deleted(VertexId(5)));
    // INV-MESH-0: garbage is reported until compact().
    CHECK_THROWS_WITH(m.validate(), Contains("INV-MESH-0"));
    m.compact();
    CHECK_FALSE(m.has_garbage());
    CHECK_NOTHROW(m.validate());
    check_counts(m, 5, 9, 6);
    CHECK(fhr::euler_characteristic(m) == 2);
    // Survivors keep their relative order: old 5 (−z) is now 4.
    CHECK(m.position(VertexId(4)) == Vec3(0, 0, -1));
    CHECK(m.position(VertexId(3)) == Vec3(0, -1, 0));
    // The faces (0, 2, 4), (3, 0, 4) at the collapsed edge vanish, 4 becomes 0 elsewhere.
    CHECK(canonical(m.triangles()) == canonical({{2, 1, 0}, {1, 3, 0}, {2, 0, 4}, {1, 2, 4}, {3, 1, 4}, {0, 3, 4}}));
}

TEST_CASE("before compact(), triangles() and is_closed() skip the collapse's garbage", "[unit]") {
    TriMesh m = octahedron();
    m.collapse(m.find_halfedge(VertexId(4), VertexId(0)));  // faces (0, 2, 4) and (3, 0, 4) go
    const std::vector<Triangle> live = m.triangles();
    CHECK(live.size() == 6);
    CHECK(m.is_closed());  // the removed halfedges have no face, but they are no boundary
    m.compact();
    CHECK(canonical(live) == canonical({{2, 1, 0}, {1, 3, 0}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}}));
    CHECK(m.is_closed());
}

TEST_CASE("the two-triangle pillow: no flip, no collapse (the opposite vertices coincide)", "[unit]") {
    // (0, 1, 2) and (0, 2, 1): a closed surface, valid for TriMesh (build_trimesh refuses it as
    // INV-IN-4 duplicates). Both faces at every edge have the same third vertex.
    const std::vector<Triangle> t{{0, 1, 2}, {0, 2, 1}};
    const TriMesh m = TriMesh::from_triangles({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, t);
    REQUIRE_NOTHROW(m.validate());
    REQUIRE(m.is_closed());
    for (EdgeId e : m.edges()) CHECK_FALSE(m.is_flip_ok(e));
    for (HalfedgeId h : m.halfedges()) CHECK_FALSE(m.is_collapse_ok(h));
}

TEST_CASE("compact without garbage changes nothing", "[unit]") {
    TriMesh m = cube();
    const auto before = m.triangles();
    m.compact();
    CHECK(m.triangles() == before);
    CHECK_NOTHROW(m.validate());
}

TEST_CASE("is_collapse_ok refuses link-condition violations", "[unit]") {
    SECTION("a tetrahedron cannot lose a vertex") {
        const TriMesh m = tetrahedron();
        for (HalfedgeId h : m.halfedges()) CHECK_FALSE(m.is_collapse_ok(h));
    }
    SECTION("a valence-3 neighbour of both ends (it would be left with valence 2)") {
        const TriMesh m = capped_octahedron();
        REQUIRE_NOTHROW(m.validate());
        REQUIRE(m.valence(VertexId(6)) == 3);
        // 0 and 2 share 4, 5 and 6: 4 is a third common neighbour, the link condition fails.
        CHECK_FALSE(m.is_collapse_ok(m.find_halfedge(VertexId(0), VertexId(2))));
        CHECK_FALSE(m.is_collapse_ok(m.find_halfedge(VertexId(2), VertexId(0))));
        CHECK_FALSE(m.is_collapse_ok(m.find_halfedge(VertexId(0), VertexId(4))));
    }
    SECTION("removing the valence-3 vertex itself is allowed and restores the octahedron") {
        TriMesh m = capped_octahedron();
        const HalfedgeId h = m.find_halfedge(VertexId(6), VertexId(0));
        REQUIRE(m.is_collapse_ok(h));
        m.collapse(h);
        m.compact();
        CHECK_NOTHROW(m.validate());
        CHECK(canonical(m.triangles()) == canonical(octahedron_triangles));
    }
    SECTION("an end of valence above is_collapse_ok's stack buffer (64 neighbours) is decided alike") {
        // A bipyramid over 70 equator vertices 2..71 (poles 0 and 1, valence 70), its edge from the
        // south pole to vertex 2 flipped: 3 and 71 become neighbours, both also neighbours of 0.
        const std::size_t n = 70;
        std::vector<Vec3> p{Vec3(0, 0, 1), Vec3(0, 0, -1)};
        std::vector<Triangle> t;
        for (std::size_t i = 0; i < n; ++i) {
            const double a = 2 * 3.141592653589793 * static_cast<double>(i) / static_cast<double>(n);
            p.emplace_back(std::cos(a), std::sin(a), 0);
            const auto e = static_cast<std::uint32_t>(2 + i), f = static_cast<std::uint32_t>(2 + (i + 1) % n);
            t.push_back({0, e, f});
            t.push_back({1, f, e});
        }
        TriMesh m = TriMesh::from_triangles(p, t);
        const EdgeId south = TriMesh::edge(m.find_halfedge(VertexId(1), VertexId(2)));
        REQUIRE(m.is_flip_ok(south));
        m.flip(south);
        REQUIRE(m.valence(VertexId(0)) == n);
        // 3 -> 0 and 0 -> 3: 71 is a third common neighbour (the lookup in 0's ring of 70, then in
        // 3's ring of 5); 7 -> 0 and 0 -> 7 have only the two neighbours of their faces in common.
        CHECK_FALSE(m.is_collapse_ok(m.find_halfedge(VertexId(3), VertexId(0))));
        CHECK_FALSE(m.is_collapse_ok(m.find_halfedge(VertexId(0), VertexId(3))));
        CHECK(m.is_collapse_ok(m.find_halfedge(VertexId(7), VertexId(0))));
        CHECK(m.is_collapse_ok(m.find_halfedge(VertexId(0), VertexId(7))));
    }
}

// --- refused construction: from_triangles (from_arrays below) -----------------------------

TEST_CASE("from_triangles refuses input that would break the invariants", "[unit]") {
    std::vector<Vec3> p{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(1, 1, 0)};
    auto refused = [&](const std::vector<Triangle>& t, const std::string& part) {
        try {
            TriMesh::from_triangles(p, t);
            FAIL("accepted " << t.size() << " triangles");
        } catch (const std::logic_error& e) {
            CHECK_THAT(e.what(), Contains(part));
        }
    };
    refused({{0, 1, 5}}, "face 0 has index out of range");                         // INV-MESH-1
    refused({{0, 1, 2}, {2, 1, 1}}, "face 1 repeats a vertex");                    // INV-MESH-2
    refused({{3, 3, 1}}, "face 0 repeats a vertex");                               // INV-MESH-2
    refused({{0, 1, 2}, {1, 0, 3}, {4, 2, 4}}, "face 2 repeats a vertex");         // INV-MESH-2
    refused({{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}, "edge in more than two faces");     // INV-MESH-4
    refused({{0, 1, 2}, {0, 1, 3}}, "faces 0 and 1 are inconsistently oriented");  // INV-MESH-4
    refused({{0, 1, 2}, {0, 3, 4}}, "vertex 0 has more than one fan");             // INV-MESH-7 (bow-tie)
    p.emplace_back(1, 0, 1);
    refused({{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {0, 4, 5}},
            "vertex 0 has more than one fan");  // a closed fan and an open one
    refused({{0, 1, 2}, {1, 3, 4}, {1, 4, 5}},
            "vertex 1 has more than one fan");  // the first such vertex, not vertex 0
    refused({{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 3, 2}}, "vertex 4 is in no face");  // INV-MESH-6
}

// --- arrays in and out: from_arrays and the invariant checker --------------------------------
//
// from_arrays is the one way to hand TriMesh a structure it did not build itself, so every check
// of validate() (spec/mesh.md INV-MESH-1..8) can be met from outside. Each broken structure below
// breaks one invariant of an otherwise valid one, and the message must name that invariant and
// the element where it breaks, no earlier one.

namespace {

/// Halfedge arrays made by hand, for the checker: edge e joins edges[e] = {a, b} (halfedge 2e
/// runs a -> b, 2e + 1 back), and each listed loop of halfedges is linked by `next`: the loops of
/// `faces` are faces 0, 1, ..., those of `holes` boundary loops. Parallel edges, loops of any
/// length and halfedges on no loop are all allowed: nothing here checks what validate() checks.
/// out(v) is v's first boundary halfedge, else its first halfedge; positions are arbitrary.
TriMesh::Arrays hand_made(std::uint32_t n_vertices, const std::vector<std::array<std::uint32_t, 2>>& edges,
                          const std::vector<std::vector<std::uint32_t>>& faces,
                          const std::vector<std::vector<std::uint32_t>>& holes) {
    TriMesh::Arrays a;
    for (const auto& [from, to] : edges) {
        a.to.push_back(VertexId(to));
        a.to.push_back(VertexId(from));
    }
    a.next.resize(a.to.size());
    a.face.resize(a.to.size());
    auto link = [&](const std::vector<std::uint32_t>& loop, FaceId f) {
        for (std::size_t i = 0; i < loop.size(); ++i) {
            a.next[loop[i]] = HalfedgeId(loop[(i + 1) % loop.size()]);
            a.face[loop[i]] = f;
        }
    };
    for (std::uint32_t f = 0; f < faces.size(); ++f) {
        link(faces[f], FaceId(f));
        a.face_halfedge.push_back(HalfedgeId(faces[f][0]));
    }
    for (const auto& loop : holes) link(loop, FaceId());
    a.out.resize(n_vertices);
    for (std::uint32_t h = 0; h < a.to.size(); ++h) {
        HalfedgeId& out = a.out[a.to[h ^ 1u].idx()];
        if (!out.valid() || (a.face[out.idx()].valid() && !a.face[h].valid())) out = HalfedgeId(h);
    }
    for (std::uint32_t v = 0; v < n_vertices; ++v) a.positions.emplace_back(v, v * v, 1);
    return a;
}

/// One n-gon as a single face: halfedge 2i runs i -> i+1 inside face 0, 2i + 1 back along the
/// boundary loop ..., 5, 3, 1 (0 -> n−1 -> ... -> 1 -> 0). For n = 3 the triangle (0, 1, 2):
/// out(0) = 5, out(1) = 1, out(2) = 3.
TriMesh::Arrays polygon_arrays(std::uint32_t n) {
    std::vector<std::array<std::uint32_t, 2>> edges;
    std::vector<std::uint32_t> inside, outside;
    for (std::uint32_t i = 0; i < n; ++i) {
        edges.push_back({i, (i + 1) % n});
        inside.push_back(2 * i);
        outside.push_back(2 * (n - 1 - i) + 1);
    }
    return hand_made(n, edges, {inside}, {outside});
}

/// Two triangles (0, 1, 2) and (0, 3, 4) sharing only vertex 0: halfedges 0, 2, 4 and 6, 8, 10
/// inside, the boundary loops 5 -> 3 -> 1 (0 -> 2 -> 1 -> 0) and 11 -> 9 -> 7 (0 -> 4 -> 3 -> 0).
/// Vertex 0 has degree 4: halfedges 0 and 6 inside, 5 and 11 on the boundary; out(0) = 5.
TriMesh::Arrays bow_tie_arrays() {
    return hand_made(5, {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {3, 4}, {4, 0}}, {{0, 2, 4}, {6, 8, 10}},
                     {{5, 3, 1}, {11, 9, 7}});
}

/// The message from_arrays throws, or "" when it accepts the arrays.
std::string refusal(TriMesh::Arrays a) {
    try {
        TriMesh::from_arrays(std::move(a));
    } catch (const std::logic_error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("from_arrays(m.arrays()) is m, with every id, also after edits", "[unit]") {
    TriMesh m = octahedron();
    CHECK(TriMesh::from_arrays(m.arrays()).arrays() == m.arrays());
    m.flip(TriMesh::edge(m.find_halfedge(VertexId(0), VertexId(2))));
    const VertexId c = m.split_face(FaceId(3), Vec3(0.3, -0.3, 0.4));
    CHECK_FALSE(m.arrays() == octahedron().arrays());  // the comparison sees the edits
    const TriMesh copy = TriMesh::from_arrays(m.arrays());
    CHECK(copy.arrays() == m.arrays());
    CHECK(copy.triangles() == m.triangles());
    CHECK(copy.out(c) == m.out(c));
    // The hand-made triangle of the tests below is a valid mesh: the triangle (0, 1, 2).
    const TriMesh tri = TriMesh::from_arrays(polygon_arrays(3));
    CHECK(tri.triangles() == std::vector<Triangle>{{0, 1, 2}});
    CHECK(fhr::boundary_loops(tri).size() == 1);
}

TEST_CASE("from_arrays refuses garbage: a collapsed mesh's arrays before compact() (INV-MESH-1)", "[unit]") {
    TriMesh m = octahedron();
    m.collapse(m.find_halfedge(VertexId(4), VertexId(0)));
    HalfedgeId first_gone;  // the lowest halfedge the collapse removed
    for (HalfedgeId h : m.halfedges())
        if (!first_gone.valid() && m.is_deleted(TriMesh::edge(h))) first_gone = h;
    REQUIRE(first_gone.valid());
    CHECK(refusal(m.arrays()) ==
          "INV-MESH-1: halfedge " + std::to_string(first_gone.idx()) + " has an out-of-range reference");
    m.compact();
    CHECK(refusal(m.arrays()).empty());
}

TEST_CASE("INV-MESH-1: array sizes and out-of-range references", "[unit]") {
    CHECK(refusal(polygon_arrays(3)).empty());
    const std::string sizes = "INV-MESH-1: array sizes disagree";
    SECTION("a position too many") {
        TriMesh::Arrays a = polygon_arrays(3);
        a.positions.emplace_back(0, 0, 0);
        CHECK(refusal(a) == sizes);
    }
    SECTION("a next too many") {
        TriMesh::Arrays a = polygon_arrays(3);
        a.next.push_back(HalfedgeId(0));
        CHECK(refusal(a) == sizes);
    }
    SECTION("a face too many") {
        TriMesh::Arrays a = polygon_arrays(3);
        a.face.push_back(FaceId());
        CHECK(refusal(a) == sizes);
    }
    SECTION("an odd number of halfedges") {
        TriMesh::Arrays a = polygon_arrays(3);
        a.to.push_back(VertexId(0));
        a.next.push_back(HalfedgeId(0));
        a.face.push_back(FaceId());
        CHECK(refusal(a) == sizes);
    }
    const std::string reference = "INV-MESH-1: halfedge 0 has an out-of-range reference";
    SECTION("to(0) invalid or past the last vertex") {
        TriMesh::Arrays a = polygon_arrays(3);
        a.to[0] = VertexId();
        CHECK(refusal(a) == reference);
        a.to[0] = VertexId(3);
        CHECK(refusal(a) == reference);
    }
    SECTION("next(0) invalid or past the last halfedge") {
        TriMesh::Arrays a = polygon_arrays(3);
        a.next[0] = HalfedgeId();
        CHECK(refusal(a) == reference);
        a.next[0] = HalfedgeId(6);
        CHECK(refusal(a) == reference);
    }
    SECTION("face(0) past the last face") {
        TriMesh::Arrays a = polygon_arrays(3);
        a.face[0] = FaceId(1);
        CHECK(refusal(a) == "INV-MESH-1: halfedge 0 has an out-of-range face");
    }
}

TEST_CASE("INV-MESH-2..5: loops, next, faces, edges without a face", "[unit]") {
    TriMesh::Arrays a = polygon_arrays(3);
    SECTION("INV-MESH-2: halfedge 0 turned into a loop at its tail") {
        a.to[0] = VertexId(0);
        CHECK(refusal(a) == "INV-MESH-2: halfedge 0 is a loop at vertex 0");
    }
    SECTION("INV-MESH-3: next(0) = 0 starts at vertex 0, not at to(0) = 1") {
        a.next[0] = HalfedgeId(0);
        CHECK(refusal(a) == "INV-MESH-3: next of halfedge 0 does not start where it ends");
    }
    SECTION("INV-MESH-4: next(0) = 1 leaves vertex 1, but on the boundary, not in face 0") {
        a.next[0] = HalfedgeId(1);
        CHECK(refusal(a) == "INV-MESH-4: next of halfedge 0 lies in another face");
    }
    SECTION("INV-MESH-4: face 0's halfedge invalid, past the end, or on the boundary") {
        for (const HalfedgeId h : {HalfedgeId(), HalfedgeId(6), HalfedgeId(1)}) {
            a.face_halfedge[0] = h;
            CHECK(refusal(a) == "INV-MESH-4: face 0 does not own its halfedge");
        }
    }
    SECTION("INV-MESH-4: a quadrilateral face") {
        CHECK(refusal(polygon_arrays(4)) == "INV-MESH-4: face 0 is not a triangle");
    }
    SECTION("INV-MESH-5: the triangle without its face: both loops are boundary") {
        a.face.assign(a.face.size(), FaceId());
        a.face_halfedge.clear();
        CHECK(refusal(a) == "INV-MESH-5: edge 0 has no face on either side");
    }
}

TEST_CASE("INV-MESH-6..8: out(), fans, parallel edges", "[unit]") {
    SECTION("INV-MESH-6: out(0) invalid, past the end, or leaving vertex 1") {
        TriMesh::Arrays a = polygon_arrays(3);
        for (const HalfedgeId h : {HalfedgeId(), HalfedgeId(6), HalfedgeId(1)}) {
            a.out[0] = h;
            CHECK(refusal(a) == "INV-MESH-6: out of vertex 0 does not leave it");
        }
    }
    const std::string boundary_fans =
        "INV-MESH-7: vertex 0 has several boundary fans, or out() is not its boundary halfedge";
    SECTION("INV-MESH-7: out(0) is the interior halfedge 0 of a boundary vertex") {
        TriMesh::Arrays a = polygon_arrays(3);
        a.out[0] = HalfedgeId(0);
        CHECK(refusal(a) == boundary_fans);
    }
    SECTION("INV-MESH-7: a bow-tie: the fan from out(0) has 2 of vertex 0's 4 halfedges") {
        CHECK(refusal(bow_tie_arrays()) == "INV-MESH-7: vertex 0 is not a single fan (non-manifold vertex)");
    }
    SECTION("INV-MESH-7: a next that is no permutation: the walk 11, 6, 5, 0, 5, ... never returns to out(0)") {
        TriMesh::Arrays a = bow_tie_arrays();
        a.next[7] = HalfedgeId(5);  // 3 -> 0 now goes on to 0 -> 2, as 1 -> 0 does
        a.out[0] = HalfedgeId(11);
        CHECK(refusal(a) == "INV-MESH-7: vertex 0 is not a single fan (non-manifold vertex)");
    }
    SECTION("INV-MESH-7: the bow-tie's two boundary loops joined at vertex 0 into a figure eight") {
        TriMesh::Arrays a = bow_tie_arrays();
        a.next[1] = HalfedgeId(11);  // 1 -> 0 -> 4
        a.next[7] = HalfedgeId(5);   // 3 -> 0 -> 2: one fan 5, 0, 11, 6 with two boundary halfedges
        CHECK(refusal(a) == boundary_fans);
    }
    SECTION("INV-MESH-8: a closed surface with two edges between vertices 0 and 1") {
        // Edges 0 and 1 both join 0 and 1; vertex 2 lies between them on one side, 3 on the other.
        // Every vertex is a single closed fan, so only INV-MESH-8 can see it.
        const TriMesh::Arrays a = hand_made(4, {{0, 1}, {1, 0}, {0, 2}, {1, 2}, {0, 3}, {1, 3}},
                                            {{0, 6, 5}, {2, 4, 7}, {1, 8, 11}, {3, 10, 9}}, {});
        CHECK(refusal(a) == "INV-MESH-8: two edges join vertex 0 and vertex 1");
    }
}

TEST_CASE("split_edge on a boundary edge whose halfedge 0 is the boundary side", "[unit]") {
    // from_triangles and the edits always put a face on halfedge 0 of a boundary edge; arrays
    // from outside need not. The triangle (0, 1, 2) with every edge the other way round: edge 0
    // is 1 -> 0 (halfedge 0, on the boundary loop 4 -> 2 -> 0: 0 -> 2 -> 1 -> 0) and 0 -> 1
    // (halfedge 1, in the face 1 -> 3 -> 5).
    TriMesh m = TriMesh::from_arrays(hand_made(3, {{1, 0}, {2, 1}, {0, 2}}, {{1, 3, 5}}, {{4, 2, 0}}));
    REQUIRE(m.is_boundary(HalfedgeId(0)));
    const VertexId c = m.split_edge(EdgeId(0), Vec3(0.5, 0.5, 1));
    CHECK(c == VertexId(3));
    CHECK_NOTHROW(m.validate());
    check_counts(m, 4, 5, 2);
    // Halfedge 0 keeps its tail and now ends at the new vertex, still on the boundary, followed
    // by the new edge's halfedge 6 (3 -> 0); on the boundary out(3) is that boundary halfedge.
    CHECK(m.from(HalfedgeId(0)) == VertexId(1));
    CHECK(m.to(HalfedgeId(0)) == c);
    CHECK(m.next(HalfedgeId(0)) == HalfedgeId(6));
    CHECK(m.out(c) == HalfedgeId(6));
    CHECK(m.is_boundary(HalfedgeId(6)));
    CHECK(m.triangles() == std::vector<Triangle>{{0, 3, 2}, {3, 1, 2}});
    std::vector<std::uint32_t> loop;
    for (HalfedgeId g = m.out(VertexId(0)); loop.empty() || g != m.out(VertexId(0)); g = m.next(g))
        loop.push_back(m.from(g).idx());
    CHECK(loop == std::vector<std::uint32_t>{0, 2, 1, 3});
}

// --- properties on random meshes -----------------------------------------------------------

TEST_CASE("random edit sequences keep every invariant, χ and the genus", "[property]") {
    rc::prop("flip / split / collapse", [] {
        TriMesh m = *fhr::testing::gen_closed_mesh(0, 4, 600);
        const long chi = fhr::euler_characteristic(m), g = fhr::genus(m);
        std::size_t faces = m.n_faces();
        const int steps = *rc::gen::inRange(1, 60);
        for (int s = 0; s < steps; ++s) {
            const auto kind = *rc::gen::inRange(0, 3);
            const HalfedgeId h(*rc::gen::inRange<std::uint32_t>(0, static_cast<std::uint32_t>(m.n_halfedges())));
            const EdgeId e = TriMesh::edge(h);
            if (kind == 0 && m.is_flip_ok(e)) {
                m.flip(e);
            } else if (kind == 1) {
                const Vec3 mid = 0.5 * (m.position(m.from(h)) + m.position(m.to(h)));
                m.split_edge(e, mid);
                faces += 2;
            } else if (kind == 2 && m.is_collapse_ok(h)) {
                m.collapse(h);
                m.compact();
                faces -= 2;
            }
            m.validate();
            RC_ASSERT(m.n_faces() == faces);
            RC_ASSERT(fhr::euler_characteristic(m) == chi);
        }
        RC_ASSERT(fhr::genus(m) == g);
        RC_ASSERT(fhr::connected_components(m).count == 1u);
        RC_ASSERT(m.is_closed());
    });
}

TEST_CASE("is_collapse_ok is exactly the link condition", "[property]") {
    rc::prop("against neighbour sets of the triangle list", [] {
        const TriMesh m = *fhr::testing::gen_closed_mesh(0, 3, 400);
        const auto n = neighbours_from_triangles(m);
        for (HalfedgeId h : m.halfedges()) {
            const std::uint32_t v0 = m.from(h).idx(), v1 = m.to(h).idx();
            const std::set<std::uint32_t> opposite{m.to(m.next(h)).idx(), m.to(m.next(TriMesh::twin(h))).idx()};
            std::set<std::uint32_t> common;
            std::set_intersection(n[v0].begin(), n[v0].end(), n[v1].begin(), n[v1].end(),
                                  std::inserter(common, common.begin()));
            RC_ASSERT(m.is_collapse_ok(h) == (common == opposite && opposite.size() == 2 && m.n_vertices() > 4));
        }
    });
}

TEST_CASE("is_flip_ok: new diagonal absent and both ends keep valence >= 3", "[property]") {
    rc::prop("against neighbour sets of the triangle list", [] {
        const TriMesh m = *fhr::testing::gen_closed_mesh(0, 3, 400);
        const auto n = neighbours_from_triangles(m);
        for (EdgeId e : m.edges()) {
            const HalfedgeId h = TriMesh::halfedge(e, 0);
            const std::uint32_t a = m.from(h).idx(), b = m.to(h).idx();
            const std::uint32_t c = m.to(m.next(h)).idx(), d = m.to(m.next(TriMesh::twin(h))).idx();
            const bool expected = c != d && !n[c].count(d) && n[a].size() > 3 && n[b].size() > 3;
            RC_ASSERT(m.is_flip_ok(e) == expected);
        }
    });
}

TEST_CASE("a flip done twice, and a split undone by collapsing the new vertex, restore the faces", "[property]") {
    rc::prop("edit inverses", [] {
        TriMesh m = *fhr::testing::gen_closed_mesh(0, 3, 400);
        const auto original = canonical(m.triangles());
        const EdgeId e(*rc::gen::inRange<std::uint32_t>(0, static_cast<std::uint32_t>(m.n_edges())));
        if (m.is_flip_ok(e)) {
            m.flip(e);
            RC_ASSERT(canonical(m.triangles()) != original);
            RC_ASSERT(m.is_flip_ok(e));
            m.flip(e);
            RC_ASSERT(canonical(m.triangles()) == original);
        }
        // The generator's fallback (src/fhr/generate): collapsing the new vertex onto to(out(new)).
        const HalfedgeId h = TriMesh::halfedge(e, 0);
        const VertexId added = m.split_edge(e, 0.5 * (m.position(m.from(h)) + m.position(m.to(h))));
        RC_ASSERT(m.is_collapse_ok(m.out(added)));
        m.collapse(m.out(added));
        m.compact();
        m.validate();
        RC_ASSERT(canonical(m.triangles()) == original);
    });
}

TEST_CASE("split_vertex undoes collapse exactly (the vertex split of §2's history)", "[property]") {
    rc::prop("collapse then split_vertex restores the faces, with the removed vertex renumbered last", [] {
        TriMesh m = *fhr::testing::gen_closed_mesh(0, 4, 600);
        const auto original = canonical(m.triangles());
        const HalfedgeId h(*rc::gen::inRange<std::uint32_t>(0, static_cast<std::uint32_t>(m.n_halfedges())));
        RC_PRE(m.is_collapse_ok(h));
        const VertexId v0 = m.from(h), v1 = m.to(h), va = m.to(m.next(h)), vb = m.to(m.next(TriMesh::twin(h)));
        const Vec3 p0 = m.position(v0);
        m.collapse(h);
        m.compact();  // v0 disappears; vertices above it move down by one
        auto renumbered = [&](VertexId v) { return VertexId(v.idx() - (v.idx() > v0.idx() ? 1 : 0)); };
        const VertexId added = m.split_vertex(renumbered(v1), renumbered(va), renumbered(vb), p0);
        m.validate();
        RC_ASSERT(added.idx() == m.n_vertices() - 1);
        RC_ASSERT(m.position(added) == p0);
        // Map back: the new vertex is v0, the others return to their old numbers.
        auto old_number = [&](std::uint32_t v) {
            if (v == added.idx()) return v0.idx();
            return v + (v >= v0.idx() ? 1u : 0u);
        };
        std::vector<Triangle> back = m.triangles();
        for (auto& t : back)
            for (auto& v : t) v = old_number(v);
        RC_ASSERT(canonical(back) == original);
    });
}

TEST_CASE("split_face inserts a vertex of valence 3 inside a face (paper Fig. 4)", "[property]") {
    rc::prop("split_face keeps the invariants and adds two faces", [] {
        TriMesh m = *fhr::testing::gen_closed_mesh(0, 4, 600);
        const long chi = fhr::euler_characteristic(m);
        const FaceId f(*rc::gen::inRange<std::uint32_t>(0, static_cast<std::uint32_t>(m.n_faces())));
        const auto corners = m.face_vertices(f);
        const Vec3 centroid = (m.position(corners[0]) + m.position(corners[1]) + m.position(corners[2])) / 3;
        const std::size_t faces = m.n_faces();
        const VertexId c = m.split_face(f, centroid);
        m.validate();
        RC_ASSERT(m.n_faces() == faces + 2);
        RC_ASSERT(fhr::euler_characteristic(m) == chi);
        RC_ASSERT(m.valence(c) == 3u);
        std::set<std::uint32_t> ring;
        m.for_each_outgoing(c, [&](HalfedgeId g) { ring.insert(m.to(g).idx()); });
        const std::set<std::uint32_t> expected{corners[0].idx(), corners[1].idx(), corners[2].idx()};
        RC_ASSERT(ring == expected);
        // The three new faces keep the old face's orientation: their normals agree with it.
        const Vec3 n =
            (m.position(corners[1]) - m.position(corners[0])).cross(m.position(corners[2]) - m.position(corners[0]));
        m.for_each_outgoing(c, [&](HalfedgeId g) { RC_ASSERT(fhr::face_normal(m, m.face(g)).dot(n) > 0); });
    });
}

// ---- Cones over boundary loops (core/detail/cones.hpp; spec/mesh.md CONE-1, CONE-2) ----

using fhr::add_cones;
using fhr::boundary_arc;
using fhr::boundary_loops;
using fhr::euler_characteristic;
using fhr::genus;

TEST_CASE("CONE-1: fill_hole closes a loop by a cone and keeps every existing id", "[unit][trimesh][boundary]") {
    rc::prop("random surfaces with holes", [] {
        const fhr::testing::GeneratedMesh T = *fhr::testing::gen_mesh({.min_genus = 0,
                                                                       .max_genus = 2,
                                                                       .max_faces = 600,
                                                                       .min_holes = 1,
                                                                       .max_holes = 5,
                                                                       .min_components = 1,
                                                                       .max_components = 3});
        const Coned C = add_cones(T);
        C.mesh.validate();
        RC_ASSERT(C.mesh.is_closed());
        const std::size_t loops = boundary_loops(T).size();
        RC_ASSERT(C.mesh.n_vertices() == T.n_vertices() + loops);
        RC_ASSERT(C.real_vertices == T.n_vertices());
        RC_ASSERT(C.real_faces == T.n_faces());
        // Each loop of b edges adds one vertex, b edges and b faces: χ grows by one per loop.
        RC_ASSERT(euler_characteristic(C.mesh) == euler_characteristic(T) + static_cast<long>(loops));
        RC_ASSERT(genus(C.mesh) == genus(T));
        // T's elements keep their ids: every halfedge its head, and every face its corners.
        for (HalfedgeId h : T.halfedges()) RC_ASSERT(C.mesh.to(h) == T.to(h));
        for (FaceId f : T.faces()) RC_ASSERT(C.mesh.face_vertices(f) == T.face_vertices(f));
        // Each apex is joined to exactly the vertices of its loop.
        const std::vector<HalfedgeId> hs = boundary_loops(T);
        for (std::size_t i = 0; i < hs.size(); ++i) {
            std::size_t n = 0;
            for (HalfedgeId g = hs[i]; n == 0 || g != hs[i]; g = T.next(g)) {
                ++n;
                RC_ASSERT(C.mesh.find_halfedge(T.from(g), VertexId(static_cast<VertexId::Index>(T.n_vertices() + i)))
                              .valid());
            }
            RC_ASSERT(C.mesh.valence(VertexId(static_cast<VertexId::Index>(T.n_vertices() + i))) == n);
        }
    });
}

TEST_CASE("CONE-2: boundary_arc walks T's boundary with T's faces on its left", "[unit][trimesh][boundary]") {
    // A 3 x 1 strip of squares: boundary 0-1-2-3-7-6-5-4 (faces counter-clockwise seen from +z).
    std::vector<Vec3> p;
    for (int y = 0; y <= 1; ++y)
        for (int x = 0; x <= 3; ++x) p.emplace_back(x, y, 0);
    std::vector<Triangle> t;
    for (std::uint32_t x = 0; x < 3; ++x) {
        t.push_back({x, x + 1, x + 5});
        t.push_back({x, x + 5, x + 4});
    }
    const TriMesh T = TriMesh::from_triangles(p, t);
    const Coned C = add_cones(T);
    auto ids = [](const std::vector<VertexId>& a) {
        std::vector<std::uint32_t> out;
        for (VertexId v : a) out.push_back(v.idx());
        return out;
    };
    CHECK(ids(boundary_arc(C.mesh, C.real_vertices, VertexId(0), VertexId(3))) ==
          std::vector<std::uint32_t>{0, 1, 2, 3});
    CHECK(ids(boundary_arc(C.mesh, C.real_vertices, VertexId(3), VertexId(0))) ==
          std::vector<std::uint32_t>{3, 7, 6, 5, 4, 0});
    CHECK(ids(boundary_arc(C.mesh, C.real_vertices, VertexId(6), VertexId(1))) ==
          std::vector<std::uint32_t>{6, 5, 4, 0, 1});
    // Each step has a face of T on its left.
    const auto arc = boundary_arc(C.mesh, C.real_vertices, VertexId(2), VertexId(1));
    for (std::size_t i = 0; i + 1 < arc.size(); ++i) {
        const HalfedgeId h = T.find_halfedge(arc[i], arc[i + 1]);
        REQUIRE(h.valid());
        CHECK(!T.is_boundary(h));
        CHECK(T.is_boundary(TriMesh::twin(h)));
    }
}

TEST_CASE("CONE-2: boundary_arc refuses a, b that are not two vertices of one loop (LIB-2)",
          "[unit][trimesh][boundary]") {
    // The hexagonal disk: boundary loop 1..6 around the interior vertex 0; the apex is vertex 7.
    const TriMesh T = hexagon();
    const Coned C = add_cones(T);
    REQUIRE(C.real_vertices == 7);
    const std::string range = "precondition violated: a != b && a.idx() < real_vertices && b.idx() < real_vertices";
    CHECK_THROWS_WITH(boundary_arc(C.mesh, C.real_vertices, VertexId(1), VertexId(1)), Contains(range));
    CHECK_THROWS_WITH(boundary_arc(C.mesh, C.real_vertices, VertexId(7), VertexId(1)), Contains(range));
    CHECK_THROWS_WITH(boundary_arc(C.mesh, C.real_vertices, VertexId(1), VertexId(7)), Contains(range));
    const std::string step = "precondition violated: step.valid() && arc.size() <= real_vertices";
    // From the interior vertex no edge has T's face on one side and a cone face on the other.
    CHECK_THROWS_WITH(boundary_arc(C.mesh, C.real_vertices, VertexId(0), VertexId(1)), Contains(step));
    // To the interior vertex the walk goes round the loop without end: it stops after #V(T) steps.
    CHECK_THROWS_WITH(boundary_arc(C.mesh, C.real_vertices, VertexId(1), VertexId(0)), Contains(step));
    // The valid arcs around the loop: 1 -> 2 -> 3 (the disk lies to the left).
    CHECK((boundary_arc(C.mesh, C.real_vertices, VertexId(1), VertexId(3)) ==
           std::vector<VertexId>{VertexId(1), VertexId(2), VertexId(3)}));
}
