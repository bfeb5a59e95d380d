// §3's searches on the caller's Workspace (geodesic/workspace.hpp). A workspace keeps
// the searches' per-vertex arrays from one search to the next and gets them back clean, so its
// history must never show in a result: GEO-15, one workspace reused across meshes of different
// sizes (larger, then smaller, then larger again) and by searches alive at once gives bitwise the
// results of searches on arrays of their own; GEO-16, a search that ends early, is abandoned, or
// ends by an exception thrown in the middle of it (the ellipse search refusing two vertices of
// different components after its fast marching has swept the whole component) hands its arrays
// back clean. Ids: paper_notes/exact_geodesics.md.
#include <catch2/catch.hpp>
#include <rapidcheck/catch.h>

#include <array>
#include <cmath>
#include <span>
#include <stdexcept>
#include <vector>

#include <fhr/core/errors.hpp>
#include <fhr/core/topology.hpp>
#include <fhr/generate/random_mesh.hpp>
#include <fhr/geodesic/ellipse.hpp>
#include <fhr/geodesic/exact.hpp>
#include <fhr/geodesic/detail/fast_marching.hpp>
#include <fhr/geodesic/workspace.hpp>
#include <fhr/testing/rapidcheck.hpp>

using namespace fhr;
using geodesic::ExactGeodesic;
using geodesic::Workspace;

namespace {

bool same_points(const std::vector<SurfacePoint>& p, const std::vector<SurfacePoint>& q) {
    if (p.size() != q.size()) return false;
    for (std::size_t i = 0; i < p.size(); ++i)
        if (p[i].kind != q[i].kind || p[i].vertex != q[i].vertex || p[i].halfedge != q[i].halfedge || p[i].t != q[i].t)
            return false;
    return true;
}

bool same(const geodesic::EllipsePath& p, const geodesic::EllipsePath& q) {
    return p.path.length == q.path.length && same_points(p.path.points, q.path.points) && p.K == q.K &&
           p.attempts == q.attempts && p.ellipse_faces == q.ellipse_faces && p.windows_created == q.windows_created &&
           p.certificate == q.certificate && p.certificate_windows == q.certificate_windows;
}

bool same(const geodesic::DistanceField& f, const geodesic::DistanceField& g) {
    return f.distance.values() == g.distance.values() && f.finalized == g.finalized;
}

// Every distance and the path to `target` of the full exact search from `source`.
struct ExactResult {
    std::vector<double> distance;
    geodesic::GeodesicPath path;
    bool operator==(const ExactResult& o) const {
        return distance == o.distance && path.length == o.path.length && same_points(path.points, o.path.points);
    }
};

ExactResult exact(const TriMesh& m, VertexId source, VertexId target, Workspace* workspace) {
    ExactGeodesic g(m, source, {.workspace = workspace});
    g.propagate();
    ExactResult r{{}, g.path_to(target)};
    for (VertexId v : m.vertices()) r.distance.push_back(g.distance(v));
    return r;
}

geodesic::DistanceField marching(const TriMesh& m, VertexId source, double max_distance, Workspace* workspace) {
    return geodesic::fast_marching(m, std::span(&source, 1), {.max_distance = max_distance, .workspace = workspace});
}

// The three searches from a to b on `workspace` agree bitwise with the same searches on arrays
// of their own (no workspace: allocated and filled for the call).
void check_reuse(const TriMesh& m, VertexId a, VertexId b, Workspace& workspace) {
    const geodesic::EllipsePath fresh = geodesic::ellipse_shortest_path(m, a, b);
    RC_ASSERT(same(geodesic::ellipse_shortest_path(m, a, b, {.workspace = &workspace}), fresh));
    const double half = fresh.path.length / 2;  // an early-stopped field, and the full one
    RC_ASSERT(same(marching(m, a, half, &workspace), marching(m, a, half, nullptr)));
    RC_ASSERT(same(marching(m, b, INFINITY, &workspace), marching(m, b, INFINITY, nullptr)));
    RC_ASSERT(exact(m, a, b, &workspace) == exact(m, a, b, nullptr));
}

}  // namespace

TEST_CASE("GEO-15: one workspace reused on a larger, a smaller, then the larger mesh gives bitwise fresh results",
          "[property][geodesic]") {
    rc::prop("reuse across meshes", [] {
        const TriMesh large = *fhr::testing::gen_closed_mesh(0, 3, 1200);
        const TriMesh small = *fhr::testing::gen_closed_mesh(0, 2, 200);
        RC_PRE(large.n_vertices() > small.n_vertices());
        Workspace workspace;
        for (const TriMesh* m : {&large, &small, &large}) {
            const auto n = static_cast<std::uint32_t>(m->n_vertices());
            const VertexId a(*rc::gen::inRange<std::uint32_t>(0, n)), b(*rc::gen::inRange<std::uint32_t>(0, n));
            RC_PRE(a != b);
            check_reuse(*m, a, b, workspace);
        }
    });
}

// Searches alive at once share one workspace (as the ellipse search's two fast-marching runs and
// its restricted and certificate searches do): each borrows arrays of its own from it.
TEST_CASE("GEO-15: searches alive at once on one workspace, then more of them than it keeps, give fresh results",
          "[unit][geodesic]") {
    const TriMesh m = generate::random_mesh({.genus = 2, .faces = 900, .seed = 3});
    const VertexId a(0), b(static_cast<VertexId::Index>(m.n_vertices() / 2));
    Workspace workspace;
    // More of each kind alive at once than the workspace keeps (Workspace::max_kept): the extra
    // ones are freed when handed back, the rest kept, and later searches still start clean.
    std::vector<std::unique_ptr<ExactGeodesic>> exacts;
    std::vector<std::unique_ptr<geodesic::FastMarching>> runs;
    for (std::size_t i = 0; i < Workspace::max_kept + 2; ++i) {
        const VertexId s(static_cast<VertexId::Index>(i * 7));
        exacts.push_back(std::make_unique<ExactGeodesic>(m, s, geodesic::ExactOptions{.workspace = &workspace}));
        runs.push_back(std::make_unique<geodesic::FastMarching>(m, std::span(&s, 1), true, &workspace));
    }
    for (std::size_t i = 0; i < exacts.size(); ++i) {
        const VertexId s(static_cast<VertexId::Index>(i * 7));
        exacts[i]->propagate();
        runs[i]->advance(INFINITY);
        ExactGeodesic fresh(m, s);
        fresh.propagate();
        const geodesic::DistanceField field = marching(m, s, INFINITY, nullptr);
        for (VertexId v : m.vertices()) {
            CHECK(exacts[i]->distance(v) == fresh.distance(v));
            CHECK(runs[i]->distance(v) == field.distance[v]);
        }
    }
    exacts.clear();
    runs.clear();
    CHECK(exact(m, a, b, &workspace) == exact(m, a, b, nullptr));
    CHECK(same(marching(m, b, INFINITY, &workspace), marching(m, b, INFINITY, nullptr)));
    CHECK(same(geodesic::ellipse_shortest_path(m, a, b, {.workspace = &workspace}),
               geodesic::ellipse_shortest_path(m, a, b)));
}

TEST_CASE("GEO-16: a search that stops early, is abandoned or ends by an exception hands its arrays back clean",
          "[unit][geodesic]") {
    // Three components with holes: the ellipse search between two of them throws after its
    // fast marching from a has swept a's whole component.
    const TriMesh m = generate::random_mesh({1, 300, 7, 0.1, 3, 3});
    const Components comp = connected_components(m);
    REQUIRE(comp.count == 3);
    const VertexId a(0);
    VertexId same_component, other_component;
    for (VertexId v : m.vertices()) {
        if (v == a) continue;
        (comp.vertex_component[v] == comp.vertex_component[a] ? same_component : other_component) = v;
    }
    REQUIRE(same_component.valid());
    REQUIRE(other_component.valid());
    const auto check_clean = [&](Workspace& workspace) {
        CHECK(exact(m, a, same_component, &workspace) == exact(m, a, same_component, nullptr));
        CHECK(same(marching(m, a, INFINITY, &workspace), marching(m, a, INFINITY, nullptr)));
        CHECK(same(geodesic::ellipse_shortest_path(m, a, same_component, {.workspace = &workspace}),
                   geodesic::ellipse_shortest_path(m, a, same_component)));
    };
    SECTION("the ellipse search throws in the middle of its searches") {
        Workspace workspace;
        CHECK_THROWS_AS(geodesic::ellipse_shortest_path(m, a, other_component, {.workspace = &workspace}),
                        InvalidInput);
        check_clean(workspace);
    }
    SECTION("a fast-marching run throws when continued with a NaN bound") {
        Workspace workspace;
        {
            geodesic::FastMarching run(m, std::span(&a, 1), true, &workspace);
            run.advance_to(same_component);
            CHECK_THROWS_AS(run.advance(NAN), InvalidInput);
        }
        check_clean(workspace);
    }
    SECTION("searches stopped early, then abandoned by an exception of their caller") {
        Workspace workspace;
        CHECK_THROWS_AS(([&] {
                            geodesic::FastMarching run(m, std::span(&a, 1), true, &workspace);
                            run.advance_to(same_component);
                            ExactGeodesic g(m, a, {.workspace = &workspace});
                            g.propagate(std::span(&same_component, 1));
                            throw std::runtime_error("abandoned");
                        }()),
                        std::runtime_error);
        check_clean(workspace);
    }
}

// GEO-17: the fields of both foci, made once for all paths at a vertex (focus_field),
// give the ellipse search bitwise the result of its own fast-marching runs, whether they reach
// every ellipse, only the first (K grows past them), or none (too short: the call runs its own).
TEST_CASE("GEO-17: focus fields give the ellipse search bitwise its own result, also when they fall short",
          "[property][geodesic]") {
    rc::prop("random foci, partners, K_0 and field radii", [] {
        const TriMesh m = *fhr::testing::gen_closed_mesh(0, 3, 1200);
        const auto n = static_cast<std::uint32_t>(m.n_vertices());
        auto vertex = [&] { return VertexId(*rc::gen::inRange<std::uint32_t>(0, n)); };
        const VertexId a = vertex(), b = vertex();
        RC_PRE(a != b);
        const double K = *rc::gen::element(1.0001, 1.01, 1.06, 1.3);
        std::vector<VertexId> partners_a{b}, partners_b{a};
        for (int i = *rc::gen::inRange(0, 4); i > 0; --i) partners_a.push_back(vertex());
        for (int i = *rc::gen::inRange(0, 4); i > 0; --i) partners_b.push_back(vertex());
        Workspace workspace;
        geodesic::FocusField fa = geodesic::focus_field(m, a, partners_a, K, 1.05, &workspace);
        geodesic::FocusField fb = geodesic::focus_field(m, b, partners_b, K, 1.0, &workspace);
        // The field of a is its radius's: every vertex within it, nothing beyond, values of a fresh run.
        const geodesic::DistanceField full = marching(m, a, INFINITY, nullptr);
        std::size_t within = 0;
        for (VertexId v : m.vertices()) within += full.distance[v] <= fa.radius;
        RC_ASSERT(fa.vertices.size() == within);
        for (std::size_t i = 0; i < fa.vertices.size(); ++i) RC_ASSERT(fa.distance[i] == full.distance[fa.vertices[i]]);
        // Sometimes one field cut short: the vertices within a fraction of its radius.
        if (*rc::gen::element(0, 1)) {
            geodesic::FocusField& cut = *rc::gen::element(0, 1) ? fa : fb;
            cut.radius *= *rc::gen::inRange(1, 100) / 100.0;
            std::size_t keep = 0;
            while (keep < cut.vertices.size() && cut.distance[keep] <= cut.radius) ++keep;
            cut.vertices.resize(keep);
            cut.distance.resize(keep);
        }
        const geodesic::EllipsePath own = geodesic::ellipse_shortest_path(m, a, b, {.K = K});
        RC_ASSERT(same(
            geodesic::ellipse_shortest_path(m, a, b, {.K = K, .workspace = &workspace, .field_a = &fa, .field_b = &fb}),
            own));
        // Fields of other foci are not used.
        RC_ASSERT(same(geodesic::ellipse_shortest_path(m, b, a, {.K = K, .field_a = &fa, .field_b = &fb}),
                       geodesic::ellipse_shortest_path(m, b, a, {.K = K})));
    });
}

TEST_CASE("GEO-17: advance_to a vertex that is final already accepts nothing more", "[unit][geodesic]") {
    // focus_field advances to each partner in turn: one accepted on the way to another must not
    // send the run on to the end of the mesh.
    const TriMesh m = generate::random_mesh({.genus = 2, .faces = 900, .seed = 3});
    const VertexId source(0);
    geodesic::FastMarching run(m, std::span(&source, 1));
    const VertexId far(static_cast<VertexId::Index>(m.n_vertices() / 2)),
        near_(run.advance_to(far) < INFINITY ? run.finalized()[1] : far);
    const std::size_t accepted = run.finalized().size();
    CHECK(accepted < m.n_vertices());
    CHECK(run.advance_to(near_) == run.distance(near_));
    CHECK(run.advance_to(far) == run.distance(far));
    CHECK(run.finalized().size() == accepted);
}
