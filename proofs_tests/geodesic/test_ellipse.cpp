// §3 the ellipse search: the path found inside T_jk (K = 1.06, grown when the path touches the
// artificial boundary) has the length of the unrestricted exact shortest path (GEO-E1), on random
// meshes of genus 0–3 and on the 171 domain edges of the paper's fandisk domain (§6); GEO-E3: the
// certificate rejects a restricted path that is not a shortest path of T (a shortcut outside
// the ellipse), and every certificate kind agrees with the unrestricted search.
#include <catch2/catch.hpp>
#include <rapidcheck/catch.h>

#include <cmath>
#include <map>

#include <fhr/core/build.hpp>
#include <fhr/core/errors.hpp>
#include <fhr/domain/decimate.hpp>
#include <fhr/generate/random_mesh.hpp>
#include <fhr/geodesic/ellipse.hpp>
#include <fhr/geodesic/fast_marching.hpp>
#include <fhr/io/read.hpp>
#include <fhr/testing/rapidcheck.hpp>
#include "support/test_support.hpp"

using namespace fhr;
using geodesic::ellipse_shortest_path;
using geodesic::ExactGeodesic;
using Certificate = geodesic::EllipsePath::Certificate;

namespace {

double unrestricted(const TriMesh& m, VertexId a, VertexId b) {
    ExactGeodesic g(m, a);
    g.propagate(std::span(&b, 1));
    return g.distance(b);
}

bool same_length(double x, double y) { return std::abs(x - y) <= 1e-12 * std::max(1.0, std::abs(y)); }

// The paper's T_jk for one K, built here from its definition (independently of ellipse.cpp):
// the faces with a vertex v such that d_a(v, a) + d_a(v, b) <= K d_a(a, b), d_a by fast marching.
FaceData<std::uint8_t> paper_ellipse(const TriMesh& m, VertexId a, VertexId b, double K) {
    const geodesic::DistanceField fa = geodesic::fast_marching(m, std::span(&a, 1));
    const geodesic::DistanceField fb = geodesic::fast_marching(m, std::span(&b, 1));
    const double bound = K * fa.distance[b];
    FaceData<std::uint8_t> mask(m.n_faces(), 0);
    for (VertexId v : m.vertices())
        if (fa.distance[v] + fb.distance[v] <= bound)
            m.for_each_outgoing(v, [&](HalfedgeId h) {
                if (!m.is_boundary(h)) mask[m.face(h)] = 1;
            });
    return mask;
}

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
    const auto path = test::cgal_mesh("fandisk.off");
    if (!path) FAIL("fandisk.off is missing: ./run extracts libcgal-demo's meshes into out/");
    const TriMesh T = test::load_mesh(*path);
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
    CHECK_THROWS_WITH(ellipse_shortest_path(m, VertexId(3), VertexId(4), {1.0}), Catch::Contains("K must be greater than 1"));
}
