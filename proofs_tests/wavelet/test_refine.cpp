// FHR §5 — dyadic refinement (Fig. 5) and where the vertices of D^J lie in D (spec/wavelet.md
// WAV-1, WAV-2, WAV-11): counts and Euler characteristic, the numbering, exact dyadic coordinates,
// and every vertex on an edge or vertex of D denoting one point from all its faces; on closed
// domains and on domains with boundary and several components (beyond the paper).
#include <catch2/catch.hpp>
#include <rapidcheck/catch.h>

#include <atomic>
#include <cmath>
#include <map>

#include <fhr/core/errors.hpp>
#include <fhr/core/executor.hpp>
#include <fhr/core/topology.hpp>
#include <fhr/wavelet/refine.hpp>
#include "wavelet_support.hpp"

using namespace fhr;
using wavelet::DomainPoint;
using wavelet::Refinement;

namespace {

long euler(const TriMesh& m) {
    return static_cast<long>(m.n_vertices()) - static_cast<long>(m.n_edges()) + static_cast<long>(m.n_faces());
}

// A point of Ω_D as the D vertices with non-zero weight and their weights (exact).
std::map<std::uint32_t, double> as_point(const TriMesh& D, FaceId f, const std::array<double, 3>& beta) {
    std::map<std::uint32_t, double> p;
    const auto v = D.face_vertices(f);
    for (int c = 0; c < 3; ++c)
        if (beta[c] != 0) p[v[c].idx()] = beta[c];
    return p;
}

void check_counts(const TriMesh& D, const Refinement& r, int J) {
    RC_ASSERT(r.depth() == J);
    for (int j = 1; j <= J; ++j) {
        const TriMesh &c = r.levels[j - 1], &f = r.levels[j];
        f.validate();
        RC_ASSERT(f.n_vertices() == c.n_vertices() + c.n_edges());
        RC_ASSERT(f.n_faces() == 4 * c.n_faces());
        RC_ASSERT(f.n_edges() == 2 * c.n_edges() + 3 * c.n_faces());
        RC_ASSERT(euler(f) == euler(D));
        // The same topology: boundary loops, components, and so genus.
        RC_ASSERT(boundary_loops(f).size() == boundary_loops(D).size());
        RC_ASSERT(connected_components(f).count == connected_components(D).count);
        // The old vertices keep their ids and their kind; new vertex #V(D^{j−1}) + e sits at the
        // middle of edge e, of valence 6, or 4 on a boundary edge, which it splits into two
        // boundary edges (faces of D^j are children 4f..4f+3 of face f of D^{j−1}).
        for (VertexId v : c.vertices()) {
            RC_ASSERT(f.valence(v) == c.valence(v));
            RC_ASSERT(f.is_boundary(v) == c.is_boundary(v));
        }
        std::size_t boundary_edges = 0;
        for (EdgeId e : c.edges()) {
            const HalfedgeId h = TriMesh::halfedge(e, 0);
            const VertexId u(static_cast<std::uint32_t>(c.n_vertices()) + e.idx());
            const bool open = c.is_boundary(e);
            boundary_edges += open;
            RC_ASSERT(f.valence(u) == (open ? 4u : 6u));
            RC_ASSERT(f.is_boundary(u) == open);
            for (VertexId end : {c.from(h), c.to(h)}) {
                const HalfedgeId half = f.find_halfedge(u, end);
                RC_ASSERT(half.valid());
                RC_ASSERT(f.is_boundary(TriMesh::edge(half)) == open);
            }
        }
        std::size_t fine_boundary_edges = 0;
        for (EdgeId e : f.edges()) fine_boundary_edges += f.is_boundary(e);
        RC_ASSERT(fine_boundary_edges == 2 * boundary_edges);
        for (FaceId g : c.faces()) {
            const auto parent = c.face_vertices(g);
            for (std::uint32_t k = 0; k < 3; ++k) RC_ASSERT(f.face_vertices(FaceId(4 * g.idx() + k))[k] == parent[k]);
        }
    }
}

void check_locations(const TriMesh& D, const Refinement& r) {
    const int J = r.depth();
    const TriMesh& fine = r.finest();
    const double grid = std::ldexp(1.0, J);
    RC_ASSERT(r.location.size() == fine.n_vertices());
    RC_ASSERT(r.corner_beta.size() == fine.n_faces());
    auto dyadic = [&](const std::array<double, 3>& b) {
        for (double x : b)
            if (!(x >= 0 && x <= 1 && std::floor(x * grid) == x * grid)) return false;
        return b[0] + b[1] + b[2] == 1 && b[2] + b[1] + b[0] == 1;
    };
    for (const DomainPoint& p : r.location) RC_ASSERT(dyadic(p.beta));
    // D's own vertices sit exactly at a corner.
    for (VertexId v : D.vertices()) {
        const auto pt = as_point(D, r.location[v.idx()].face, r.location[v.idx()].beta);
        RC_ASSERT(pt.size() == 1u);
        RC_ASSERT(pt.begin()->first == v.idx());
    }
    // Every occurrence of a vertex as a corner of a face of D^J (possibly in another face of D)
    // denotes the same point as its location, and the geometric D^J agrees with Σ β x.
    std::vector<double> area(D.n_faces(), 0.0);
    for (FaceId g : fine.faces()) {
        const FaceId root(g.idx() >> (2 * J));
        const auto v = fine.face_vertices(g);
        const auto& B = r.corner_beta[g.idx()];
        for (int c = 0; c < 3; ++c) {
            RC_ASSERT(dyadic(B[c]));
            const DomainPoint& loc = r.location[v[c].idx()];
            RC_ASSERT(as_point(D, root, B[c]) == as_point(D, loc.face, loc.beta));
        }
        // Orientation and area of the child in the reference plane (β1, β2): exact for dyadics.
        const double a2 = (B[1][1] - B[0][1]) * (B[2][2] - B[0][2]) - (B[2][1] - B[0][1]) * (B[1][2] - B[0][2]);
        RC_ASSERT(a2 > 0);
        area[root.idx()] += a2;
    }
    for (double a : area) RC_ASSERT(a == 1.0);  // the children tile their root face (twice the area 1/2)
    for (VertexId v : fine.vertices()) {
        const DomainPoint& loc = r.location[v.idx()];
        const auto c = D.face_vertices(loc.face);
        const Vec3 x = loc.beta[0] * D.position(c[0]) + loc.beta[1] * D.position(c[1]) + loc.beta[2] * D.position(c[2]);
        RC_ASSERT((fine.position(v) - x).norm() <= 1e-14 * (1 + x.norm()));
    }
    // Nested: D^j's vertices are the first #V(D^j) of D^J.
    for (int j = 0; j < J; ++j)
        for (VertexId v : r.levels[j].vertices()) RC_ASSERT(r.levels[j].position(v) == fine.position(v));
}

}  // namespace

TEST_CASE("WAV-1, WAV-2: refinement counts, numbering and exact locations on random domains, J = 0..3",
          "[property][wavelet]") {
    rc::prop("random closed D (genus 0..2)", [] {
        const fhr::testing::GeneratedMesh D = *test::gen_domain(200);
        const int J = *rc::gen::inRange(0, 4);
        const Refinement r = wavelet::refine(D, J);
        check_counts(D, r, J);
        check_locations(D, r);
    });
}

TEST_CASE("WAV-11: refinement counts, numbering and exact locations with boundary and several components, J = 0..3",
          "[property][wavelet]") {
    rc::prop("random D: 1..5 boundary loops, 1..3 components of genus 0..2", [] {
        const test::OpenDomain D = *test::gen_open_domain(160);
        RC_ASSERT(boundary_loops(D).size() == D.hole_count());
        RC_ASSERT(connected_components(D).count == D.components.size());
        RC_TAG(D.components.size(), D.hole_count());
        const int J = *rc::gen::inRange(0, 4);
        const Refinement r = wavelet::refine(D, J);
        check_counts(D, r, J);
        check_locations(D, r);
    });
}

TEST_CASE("WAV-11: one triangle gives D² with 15 vertices, 16 faces and a boundary loop of 12 edges",
          "[unit][wavelet]") {
    // (V, E, F) = (3, 3, 1) → (6, 9, 4) → (15, 30, 16); the boundary's 3 edges → 6 → 12.
    const TriMesh D = TriMesh::from_triangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, std::vector<Triangle>{{0, 1, 2}});
    const Refinement r = wavelet::refine(D, 2);
    CHECK(r.finest().n_vertices() == 15);
    CHECK(r.finest().n_edges() == 30);
    CHECK(r.finest().n_faces() == 16);
    const std::vector<HalfedgeId> loops = boundary_loops(r.finest());
    REQUIRE(loops.size() == 1);
    std::size_t length = 0;
    HalfedgeId h = loops[0];
    do {
        ++length;
        h = r.finest().next(h);
    } while (h != loops[0]);
    CHECK(length == 12);
}

TEST_CASE("WAV-1: a closed genus-0 domain with 114 faces (the fandisk's D) gives D³ with 3,650 vertices, 7,296 faces",
          "[unit][wavelet]") {
    // The counts depend on D's V, E, F only: V − E + F = 2 and 3F = 2E give 59 vertices and 171
    // edges; then (V, E, F) → (V + E, 2E + 3F, 4F): (230, 684, 456), (914, 2736, 1824), (3650, 10944, 7296).
    const TriMesh D = generate::random_closed_mesh({.genus = 0, .faces = 114, .seed = 7});
    REQUIRE(D.n_vertices() == 59);
    REQUIRE(D.n_edges() == 171);
    const Refinement r = wavelet::refine(D, 3);
    CHECK(r.finest().n_vertices() == 3650);
    CHECK(r.finest().n_faces() == 7296);
    CHECK(r.finest().n_vertices() - D.n_vertices() == 3591);
}

TEST_CASE("WAV-2: sample() evaluates φ at each vertex's location; the first #V(D^j) samples are f^j",
          "[unit][wavelet]") {
    const TriMesh D = test::bipyramid(5);
    const Refinement r = wavelet::refine(D, 2);
    std::atomic<std::size_t> calls = 0;
    const std::vector<Vec3> f = wavelet::sample(r, [&](FaceId face, const std::array<double, 3>& b) {
        ++calls;
        return Vec3(face.idx(), b[1], b[2]);
    });
    REQUIRE(calls == r.finest().n_vertices());
    for (std::size_t v = 0; v < f.size(); ++v) {
        CHECK(f[v] == Vec3(r.location[v].face.idx(), r.location[v].beta[1], r.location[v].beta[2]));
    }
}

TEST_CASE("WAV-2: sample() on several threads calls φ once per vertex and gives the one-thread samples",
          "[unit][wavelet]") {
    const Refinement r = wavelet::refine(test::bipyramid(5), 5);  // 5,122 vertices: two blocks of 4,096 and more
    REQUIRE(r.finest().n_vertices() > 4096);
    std::atomic<std::size_t> calls = 0;
    auto phi = [&](FaceId face, const std::array<double, 3>& b) {
        ++calls;
        return Vec3(face.idx() + b[0], b[1] * b[2], b[2] - b[0]);
    };
    ThreadPool one(1), three(3);
    const std::vector<Vec3> a = wavelet::sample(r, phi, &one);
    REQUIRE(calls == r.finest().n_vertices());
    const std::vector<Vec3> b = wavelet::sample(r, phi, &three);
    CHECK(calls == 2 * r.finest().n_vertices());
    CHECK(a == b);  // a vertex missed on three threads would keep (0, 0, 0)
    for (std::size_t v = 0; v < a.size(); ++v) REQUIRE(a[v] == phi(r.location[v].face, r.location[v].beta));
}

TEST_CASE("WAV-1, WAV-11: refusals: empty or garbage domains, negative or too deep levels", "[unit][wavelet]") {
    const TriMesh D = test::bipyramid(4);
    CHECK_THROWS_AS(wavelet::refine(D, -1), InvalidInput);
    CHECK_THROWS_AS(wavelet::refine(D, 12), InvalidInput);  // 8·4^12 > 2^26 faces
    CHECK_THROWS_AS(wavelet::refine(TriMesh{}, 1), InvalidInput);
    TriMesh collapsed = test::bipyramid(6);
    const HalfedgeId h = collapsed.find_halfedge(VertexId(0), VertexId(1));
    REQUIRE(collapsed.is_collapse_ok(h));
    collapsed.collapse(h);
    REQUIRE(collapsed.has_garbage());
    CHECK_THROWS_AS(wavelet::refine(collapsed, 1), InvalidInput);
    // Boundary and several components are accepted (WAV-11): two disjoint triangles.
    const std::vector<Vec3> p{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {3, 0, 0}, {4, 0, 0}, {3, 1, 0}};
    const std::vector<Triangle> t{{0, 1, 2}, {3, 4, 5}};
    CHECK(wavelet::refine(TriMesh::from_triangles(p, t), 1).finest().n_faces() == 8);
}
