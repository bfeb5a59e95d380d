// §3 the ellipse search: the path found inside T_jk (K = 1.06, grown when the path touches the
// artificial boundary) has the length of the unrestricted exact shortest path (GEO-E1), on random
// meshes of genus 0–3 and on the 171 domain edges of the paper's fandisk domain (§6); GEO-E3: the
// certificate rejects a restricted path that is not a shortest path of T (a shortcut outside
// the ellipse), and every certificate kind agrees with the unrestricted search; GEO-E7: a path
// pressed against T_jk's artificial boundary is never returned, K grows instead.
#include <catch2/catch.hpp>
#include <rapidcheck/catch.h>

#include <cmath>
#include <map>
#include <span>
#include <tuple>

#include <fhr/core/build.hpp>
#include <fhr/core/errors.hpp>
#include <fhr/core/topology.hpp>
#include <fhr/domain/decimate.hpp>
#include <fhr/generate/random_mesh.hpp>
#include <fhr/geodesic/ellipse.hpp>
#include <fhr/geodesic/detail/fast_marching.hpp>
#include <fhr/io/read.hpp>
#include <fhr/testing/rapidcheck.hpp>
#include "geodesic/geodesic_checks.hpp"
#include "support/test_support.hpp"

using namespace fhr;
using geodesic::ellipse_shortest_path;
using geodesic::ExactGeodesic;
using Certificate = geodesic::EllipsePath::Certificate;
using test::paper_ellipse;

namespace {

double unrestricted(const TriMesh& m, VertexId a, VertexId b) {
    ExactGeodesic g(m, a);
    g.propagate(std::span(&b, 1));
    return g.distance(b);
}

bool same_length(double x, double y) { return std::abs(x - y) <= 1e-12 * std::max(1.0, std::abs(y)); }

}  // namespace

TEST_CASE("GEO-E1: the ellipse path is as short as the unrestricted one (random meshes)", "[property][geodesic]") {
    rc::prop("ellipse vs whole mesh", [] {
        const TriMesh m = *fhr::testing::gen_closed_mesh(0, 3, 1200);
        const auto n = static_cast<std::uint32_t>(m.n_vertices());
        const VertexId a(*rc::gen::inRange<std::uint32_t>(0, n)), b(*rc::gen::inRange<std::uint32_t>(0, n));
        RC_PRE(a != b);
        const auto e = ellipse_shortest_path(m, a, b);
        RC_ASSERT(same_length(e.path.length, unrestricted(m, a, b)));
        RC_ASSERT(e.K >= 1.06);
        RC_ASSERT(e.attempts >= 1u);
        RC_ASSERT((e.attempts == 1) == (e.K == 1.06));
        RC_ASSERT(e.path.points.front().vertex == a);
        RC_ASSERT(e.path.points.back().vertex == b);
        RC_ASSERT(e.ellipse_faces <= m.n_faces());
    });
}

TEST_CASE("GEO-E1: the 171 fandisk domain edges (paper §6) by the ellipse search", "[real][geodesic]") {
    const std::string path = test::cgal_mesh("fandisk.off");
    const TriMesh T = test::load_mesh(path);
    domain::DecimateOptions o;
    o.target_faces = 114;
    const domain::Domain D = domain::decimate(T, o);
    // Unrestricted distances: one full tree per domain vertex that starts an edge.
    std::map<std::uint32_t, std::unique_ptr<ExactGeodesic>> trees;
    std::size_t edges = 0, grown = 0, checked = 0;
    for (const auto& [a, b] : domain::edge_endpoints(D)) {
        auto& tree = trees[a.idx()];
        if (!tree) {
            tree = std::make_unique<ExactGeodesic>(T, a);
            tree->propagate();
        }
        const auto r = ellipse_shortest_path(T, a, b);
        ++edges;
        grown += r.attempts > 1;
        checked += same_length(r.path.length, tree->distance(b));
        CAPTURE(a.idx(), b.idx(), r.path.length, tree->distance(b), r.K);
        CHECK(same_length(r.path.length, tree->distance(b)));
    }
    CHECK(edges == 171);
    CHECK(checked == 171);
    CAPTURE(grown);
    CHECK(grown < edges);  // K = 1.06 suffices for some paths; paper_notes/ellipse.md has the counts
}

TEST_CASE("GEO-E1: any K_0, every certificate agrees with the unrestricted length", "[property][geodesic]") {
    rc::prop("ellipse (K_0 in {1.0001, 1.01, 1.06, 1.3}) vs whole mesh", [] {
        const TriMesh m = *fhr::testing::gen_closed_mesh(0, 3, 1200);
        const auto n = static_cast<std::uint32_t>(m.n_vertices());
        const VertexId a(*rc::gen::inRange<std::uint32_t>(0, n)), b(*rc::gen::inRange<std::uint32_t>(0, n));
        RC_PRE(a != b);
        const double K0 = *rc::gen::element(1.0001, 1.01, 1.06, 1.3);
        const auto e = ellipse_shortest_path(m, a, b, {K0});
        RC_TAG(static_cast<int>(e.certificate));
        RC_ASSERT(same_length(e.path.length, unrestricted(m, a, b)));
        RC_ASSERT((e.attempts == 1) == (e.K == K0));
        RC_ASSERT((e.certificate == Certificate::whole_mesh) == (e.ellipse_faces == m.n_faces()));
        RC_ASSERT(e.certificate_windows == 0 || e.certificate == Certificate::search ||
                  e.certificate == Certificate::replaced);
    });
}

// The paper's acceptance test (touches_boundary in ellipse.cpp) is what makes K grow: with a thin
// first ellipse the restricted path often runs through a vertex or along an edge of T_jk's
// artificial boundary, and then it is not returned, even when a certificate could prove it
// shortest (GEO-E7). So a returned path certified by the border or by the search touches no face
// left out of its final T_jk (rebuilt here by the paper's rule at the returned K); only
// "replaced" (the whole-mesh search's own path) and "whole_mesh" (no artificial boundary) are
// exempt. A mutant that broke the paper's test would accept pressed paths at K_0.
TEST_CASE("GEO-E7: a path certified inside T_jk touches none of its artificial boundary; K grows when it would",
          "[property][geodesic]") {
    std::size_t grown = 0, checked = 0;
    rc::prop("thin first ellipses (K_0 in {1.0001, 1.01})", [&] {
        const TriMesh m = *fhr::testing::gen_closed_mesh(0, 3, 1200);
        const auto n = static_cast<std::uint32_t>(m.n_vertices());
        const VertexId a(*rc::gen::inRange<std::uint32_t>(0, n)), b(*rc::gen::inRange<std::uint32_t>(0, n));
        RC_PRE(a != b);
        const double K0 = *rc::gen::element(1.0001, 1.01);
        const auto e = ellipse_shortest_path(m, a, b, {K0});
        RC_TAG(static_cast<int>(e.certificate));
        grown += e.attempts > 1;
        if (e.certificate != Certificate::border && e.certificate != Certificate::search) return;
        const FaceData<std::uint8_t> T_jk = paper_ellipse(m, a, b, e.K);
        for (const SurfacePoint& q : e.path.points)
            for (FaceId f : test::faces_at(m, q)) RC_ASSERT(T_jk[f] != 0);
        ++checked;
    });
    CAPTURE(grown, checked);
    CHECK(grown > 0);
    CHECK(checked > 0);
}

// The rule itself, on many pairs of a few generated meshes with thin first ellipses: whenever the
// restricted path at K_0 (rebuilt here: the paper's T_jk, the exact search inside it) touches T_jk's
// artificial boundary, the search does not stop at K_0, though a certificate might well accept that
// path (the lengths alone could not tell). Paths that touch it at a vertex only, the common case,
// must occur.
TEST_CASE("GEO-E7: a restricted path at K_0 that touches T_jk's artificial boundary makes K grow", "[unit][geodesic]") {
    std::size_t touching = 0, at_vertices_only = 0;
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
        const TriMesh m = generate::random_closed_mesh({static_cast<int>(seed % 3), 400, seed, seed % 2 ? 0.0 : 0.1});
        const auto n = static_cast<std::uint32_t>(m.n_vertices());
        for (std::uint32_t i = 0; i < 30; ++i) {
            const VertexId a((i * 7919u + 3) % n), b((i * 104729u + 11) % n);
            if (a == b) continue;
            for (const double K0 : {1.0001, 1.01}) {
                const FaceData<std::uint8_t> T_jk = paper_ellipse(m, a, b, K0);
                ExactGeodesic inside(m, a, {&T_jk});
                inside.propagate(std::span(&b, 1));
                if (!std::isfinite(inside.distance(b))) continue;  // T_jk does not join a and b: K grows anyway
                bool touches = false, at_an_edge = false;
                for (const SurfacePoint& q : inside.path_to(b).points)
                    for (FaceId f : test::faces_at(m, q))
                        if (!T_jk[f]) touches = true, at_an_edge = at_an_edge || q.kind == SurfacePoint::Kind::edge;
                if (!touches) continue;
                ++touching;
                at_vertices_only += !at_an_edge;
                CAPTURE(seed, a.idx(), b.idx(), K0);
                CHECK(ellipse_shortest_path(m, a, b, {K0}).attempts > 1);
            }
        }
    }
    CAPTURE(touching);
    CHECK(at_vertices_only > 0);
}

// A restricted path that the paper's test accepts (it touches no vertex or edge of T_jk's
// artificial boundary) but that is longer than the shortest path of T, which runs outside T_jk:
// fast marching overestimates the distance along the shortcut by more than K − 1 = 6 %. A
// certificate that accepted it would return 2.736…; the search certificate must replace it.
// (The mesh: `fhr generate --genus 2 --faces 230 --seed 685547253639986`, vertices 64 and 43.)
TEST_CASE("GEO-E3: a restricted path that is not a shortest path of T is rejected", "[unit][geodesic]") {
    const TriMesh m = generate::random_closed_mesh({2, 230, 685547253639986ull, 0.0});
    const VertexId a(64), b(43);
    const FaceData<std::uint8_t> mask = paper_ellipse(m, a, b, 1.06);
    ExactGeodesic inside(m, a, {&mask});
    inside.propagate(std::span(&b, 1));
    const double whole = unrestricted(m, a, b);
    CAPTURE(inside.distance(b), whole);
    REQUIRE(inside.distance(b) > whole * (1 + 1e-3));  // the ellipse misses the shortest path
    // The border bound cannot certify it: an exit from T_jk is cheaper than the restricted path.
    CHECK(inside.stats().border_key < inside.distance(b));
    const auto e = ellipse_shortest_path(m, a, b);
    CHECK(e.attempts == 1);  // the paper's test passed at K = 1.06: only the certificate catches it
    CHECK(e.certificate == Certificate::replaced);
    CHECK(same_length(e.path.length, whole));
    CHECK(e.path.points.front().vertex == a);
    CHECK(e.path.points.back().vertex == b);
    // Both directions.
    CHECK(same_length(ellipse_shortest_path(m, b, a).path.length, whole));
}

// Many pairs on a few generated meshes with a thin ellipse (K_0 = 1.01): every kind of
// certificate occurs and every length equals the unrestricted one.
TEST_CASE("GEO-E3: all certificate kinds occur and agree with the unrestricted length", "[unit][geodesic]") {
    std::map<Certificate, std::size_t> seen;
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
        const TriMesh m = generate::random_closed_mesh({static_cast<int>(seed % 3), 400, seed, seed % 2 ? 0.0 : 0.1});
        const auto n = static_cast<std::uint32_t>(m.n_vertices());
        for (std::uint32_t i = 0; i < 30; ++i) {
            const VertexId a((i * 7919u + 3) % n), b((i * 104729u + 11) % n);
            if (a == b) continue;
            const auto e = ellipse_shortest_path(m, a, b, {1.01});
            ++seen[e.certificate];
            CAPTURE(seed, a.idx(), b.idx(), e.K, static_cast<int>(e.certificate));
            CHECK(same_length(e.path.length, unrestricted(m, a, b)));
        }
    }
    CAPTURE(seen[Certificate::border], seen[Certificate::search], seen[Certificate::replaced]);
    CHECK(seen[Certificate::border] > 0);
    CHECK(seen[Certificate::search] > 0);
    CHECK(seen[Certificate::replaced] > 0);  // 3 of the 180 pairs: T_jk missed the shortest path
}

TEST_CASE("GEO-E2: bad requests are refused", "[unit][geodesic]") {
    const TriMesh m = generate::random_closed_mesh({0, 100, 1, 0.0});
    CHECK_THROWS_AS(ellipse_shortest_path(m, VertexId(3), VertexId(3)), InvalidInput);
    CHECK_THROWS_WITH(ellipse_shortest_path(m, VertexId(3), VertexId(9999)), Catch::Contains("out of range"));
    CHECK_THROWS_WITH(ellipse_shortest_path(m, VertexId(3), VertexId(4), {1.0}),
                      Catch::Contains("K must be greater than 1"));
    // A target on another component (the first and last vertex of a 3-component mesh).
    const TriMesh three = generate::random_mesh({1, 300, 7, 0.1, 3, 3});
    const VertexId last(static_cast<std::uint32_t>(three.n_vertices() - 1));
    CHECK_THROWS_WITH(ellipse_shortest_path(three, VertexId(0), last), Catch::Contains("not connected"));
    CHECK_THROWS_AS(ellipse_shortest_path(three, last, VertexId(0)), InvalidInput);
}

// T is a surface with holes and several components; the path may run along a hole.
// The certificates' argument only needs that a path leaves T_jk through its artificial border
// (paper_notes/ellipse.md), so every kind must still agree with the unrestricted length.
TEST_CASE("GEO-E5: on meshes with holes and components the ellipse path is a shortest path of T",
          "[property][geodesic]") {
    std::map<Certificate, std::size_t> seen, seen_reaching_hole;
    std::size_t hugging = 0, grown = 0;
    rc::prop("ellipse vs whole mesh, with boundary", [&] {
        const fhr::testing::GeneratedMesh m = *fhr::testing::gen_mesh(
            {.min_genus = 0, .max_genus = 2, .max_faces = 1200, .min_holes = 1, .max_holes = 5, .max_components = 3});
        const auto pairs = test::hugging_pairs(m);
        const Components comp = connected_components(m);
        VertexId a, b;
        if (*rc::gen::arbitrary<bool>()) {
            std::tie(a, b) = pairs[*rc::gen::inRange<std::size_t>(0, pairs.size())];
        } else {  // any two vertices of one component
            const auto n = static_cast<std::uint32_t>(m.n_vertices());
            a = VertexId(*rc::gen::inRange<std::uint32_t>(0, n));
            b = VertexId(*rc::gen::inRange<std::uint32_t>(0, n));
            RC_PRE(comp.vertex_component[a] == comp.vertex_component[b]);
        }
        RC_PRE(a != b);
        const double K0 = *rc::gen::element(1.0001, 1.01, 1.06, 1.3);
        const auto e = ellipse_shortest_path(m, a, b, {K0});
        RC_ASSERT(same_length(e.path.length, unrestricted(m, a, b)));
        RC_ASSERT(test::path_violation(m, e.path, a, b) == "");
        RC_ASSERT((e.certificate == Certificate::whole_mesh) == (e.ellipse_faces == m.n_faces()));
        // Does the final T_jk reach a hole of T (a face of it has an edge on T's boundary)?
        const FaceData<std::uint8_t> T_jk = paper_ellipse(m, a, b, e.K);
        bool reaches_hole = false;
        for (FaceId f : m.faces()) {
            const HalfedgeId h = m.halfedge(f);
            for (HalfedgeId g : {h, m.next(h), m.next(m.next(h))})
                reaches_hole = reaches_hole || (T_jk[f] && m.is_boundary(TriMesh::twin(g)));
        }
        const test::VertexPassages p = test::vertex_passages(m, e.path);
        ++seen[e.certificate];
        seen_reaching_hole[e.certificate] += reaches_hole;
        hugging += p.boundary + p.boundary_edges > 0;
        grown += e.attempts > 1;
    });
    CAPTURE(seen[Certificate::border], seen[Certificate::search], seen[Certificate::replaced],
            seen[Certificate::whole_mesh], seen_reaching_hole[Certificate::border],
            seen_reaching_hole[Certificate::search], hugging, grown);
    CHECK(seen_reaching_hole[Certificate::border] > 0);
    CHECK(seen_reaching_hole[Certificate::search] > 0);
    CHECK(hugging > 0);
}

// touches_boundary (ellipse.cpp) must not take a hole of T for T_jk's artificial border: when the
// restricted path at K_0 runs along or around a hole and touches no left-out face, the paper's test
// passes and the search stops at K_0. (A mutant whose touches_boundary counted holes as border
// grows K for every such path, and never stops on a mesh of several components: T_jk cannot grow
// beyond a's component, so "T_jk is all of T" never ends the loop.)
TEST_CASE("GEO-E6: a path that hugs a hole inside T_jk is accepted at K_0", "[property][geodesic]") {
    std::size_t checked = 0;
    rc::prop("hugging pairs at K_0 = 1.06", [&] {
        const fhr::testing::GeneratedMesh m = *fhr::testing::gen_mesh(
            {.min_genus = 0, .max_genus = 2, .max_faces = 1200, .min_holes = 1, .max_holes = 5, .max_components = 3});
        const auto pairs = test::hugging_pairs(m);
        const auto [a, b] = pairs[*rc::gen::inRange<std::size_t>(0, pairs.size())];
        const double K0 = 1.06;
        const FaceData<std::uint8_t> T_jk = paper_ellipse(m, a, b, K0);
        ExactGeodesic inside(m, a, {&T_jk});
        inside.propagate(std::span(&b, 1));
        const geodesic::GeodesicPath path = inside.path_to(b);
        const test::VertexPassages p = test::vertex_passages(m, path);
        RC_PRE(p.boundary + p.boundary_edges > 0);  // it hugs a hole of T
        // ... and touches no left-out face (parenthesised: RC_PRE's expression captor would not
        // short-circuit ||, and T_jk[invalid face] is out of range)
        for (const SurfacePoint& q : path.points)
            for (FaceId f : test::faces_at(m, q)) RC_PRE((!f.valid() || T_jk[f] != 0));
        const auto e = ellipse_shortest_path(m, a, b, {K0});
        RC_TAG(static_cast<int>(e.certificate));
        RC_ASSERT(e.attempts == 1u);
        RC_ASSERT(same_length(e.path.length, unrestricted(m, a, b)));
        ++checked;
    });
    CAPTURE(checked);
    CHECK(checked > 0);
}

// With several components T_jk can grow at most to a's component, never to all of T: the search
// then has no artificial border left and the border certificate must hold (ellipse.md).
TEST_CASE("GEO-E5: a T_jk that covers its whole component (of several) is certified by the border",
          "[unit][geodesic]") {
    std::map<Certificate, std::size_t> seen;
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
        const TriMesh m = generate::random_mesh({0, 60, seed, 0.1, 2, 2});
        const Components comp = connected_components(m);
        std::size_t faces0 = 0;
        for (FaceId f : m.faces()) faces0 += comp.vertex_component[m.face_vertices(f)[0]] == 0;
        for (VertexId a : m.vertices())
            for (VertexId b : m.vertices()) {
                if (!(a < b) || comp.vertex_component[a] != 0 || comp.vertex_component[b] != 0) continue;
                const auto e = ellipse_shortest_path(m, a, b, {3.0});  // a wide first ellipse
                CHECK(same_length(e.path.length, unrestricted(m, a, b)));
                if (e.ellipse_faces == faces0) ++seen[e.certificate];
            }
    }
    CAPTURE(seen[Certificate::border], seen[Certificate::search], seen[Certificate::replaced],
            seen[Certificate::whole_mesh]);
    CHECK(seen[Certificate::border] > 0);
    CHECK(seen[Certificate::search] + seen[Certificate::replaced] + seen[Certificate::whole_mesh] == 0);
}

// When the exact search exhausts a's component without reaching b, b was lost to rounding (a and
// b are connected: fast marching joins them). Growing K cannot help once T_jk is the whole
// component; on a mesh of several components it never becomes all of T, and the search grew K
// for ever (an hour-long `fhr run` on the quality family's 10⁻⁹° needles). It now ends with no
// path. The pairs are losses the exact algorithm still has on such needles (exact_geodesics.md,
// "Needles", open); should it stop losing them, they need replacing by other such pairs.
TEST_CASE("GEO-E9: a target the exact search loses on its whole component gives no path, without growing K for ever",
          "[unit][geodesic]") {
    struct Case {
        int genus, components;
        std::size_t faces;
        std::uint64_t seed;
        std::uint32_t a, b;
    };
    for (const Case c : {Case{0, 1, 200, 2, 9, 87}, Case{2, 2, 1558, 478695528567056040ull, 20, 252}}) {
        const generate::RandomMeshOptions o = test::needle_recipe(c.genus, c.components, c.faces, c.seed);
        const TriMesh m = generate::random_mesh(o);
        CAPTURE(generate::generate_command(o));
        const VertexId a(c.a), b(c.b);
        ExactGeodesic whole(m, a);
        whole.propagate(std::span(&b, 1));
        REQUIRE(!(whole.distance(b) < INFINITY));  // the loss this case is about
        const auto e = ellipse_shortest_path(m, a, b);
        CHECK(e.path.length == INFINITY);
        CHECK(e.path.points.empty());
        CHECK(e.attempts <= 10u);
        const Components comp = connected_components(m);
        std::size_t faces = 0;
        for (FaceId f : m.faces()) faces += comp.vertex_component[m.face_vertices(f)[0]] == comp.vertex_component[a];
        CHECK(e.ellipse_faces == faces);
    }
}
