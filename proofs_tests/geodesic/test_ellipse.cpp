// §3 the ellipse search: the path found inside T_jk (K = 1.06, grown when the path touches the
// artificial boundary) has the length of the unrestricted exact shortest path (GEO-E1), on random
// meshes of genus 0–3 and on the 171 domain edges of the paper's fandisk domain (§6).
#include <catch2/catch.hpp>
#include <rapidcheck/catch.h>

#include <cmath>
#include <map>

#include "core/build.hpp"
#include "core/errors.hpp"
#include "domain/decimate.hpp"
#include "geodesic/ellipse.hpp"
#include "io/read.hpp"
#include "support/gen_mesh.hpp"
#include "support/test_support.hpp"

using namespace fhr;
using geodesic::ellipse_shortest_path;
using geodesic::ExactGeodesic;

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
        const TriMesh m = *test::gen_closed_mesh(0, 3, 1200);
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
    if (!path) {
        WARN("fandisk.off is not present (./run extracts libcgal-demo's meshes into out/); skipped");
        return;
    }
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

TEST_CASE("GEO-E2: bad requests are refused", "[unit][geodesic]") {
    const TriMesh m = generate::random_closed_mesh({0, 100, 1, 0.0});
    CHECK_THROWS_AS(ellipse_shortest_path(m, VertexId(3), VertexId(3)), InvalidInput);
    CHECK_THROWS_WITH(ellipse_shortest_path(m, VertexId(3), VertexId(9999)), Catch::Contains("out of range"));
    CHECK_THROWS_WITH(ellipse_shortest_path(m, VertexId(3), VertexId(4), {1.0}), Catch::Contains("K must be greater than 1"));
}
