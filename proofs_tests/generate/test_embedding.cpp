// Tests of the exact embedding check and guard (src/fhr/generate/embedding.hpp; spec/generator.md
// GEN-E1..E3): every case of the argument in the header — no common vertex, one, an edge — once
// meeting improperly and once not, decided exactly at the edge of the tolerance no float test has;
// the guard against an independent brute-force oracle over random edits.
#include <catch2/catch.hpp>
#include <rapidcheck/catch.h>

#include <cmath>
#include <vector>

#include <fhr/generate/embedding.hpp>
#include <fhr/generate/random_mesh.hpp>
#include <fhr/testing/rapidcheck.hpp>

using fhr::FaceId;
using fhr::TriMesh;
using fhr::Vec3;
using fhr::VertexId;
using fhr::generate::meet_improperly;
using fhr::generate::TriangleAt;

namespace {

TriangleAt tri(std::array<unsigned, 3> ids, std::array<Vec3, 3> p) {
    return {{VertexId(ids[0]), VertexId(ids[1]), VertexId(ids[2])}, p};
}

/// The smallest double above x.
double up(double x) { return std::nextafter(x, INFINITY); }

}  // namespace

TEST_CASE("GEN-E1: two triangles without a common vertex", "[unit]") {
    const auto a = tri({0, 1, 2}, {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0)});
    // Through each other; coplanar and overlapping; touching at a point of an edge; apart by an ulp.
    CHECK(meet_improperly(a, tri({3, 4, 5}, {Vec3(0.5, 0.5, -1), Vec3(0.5, 0.5, 1), Vec3(3, 3, 0.5)})));
    CHECK(meet_improperly(a, tri({3, 4, 5}, {Vec3(1, 1, 0), Vec3(3, 1, 0), Vec3(1, 3, 0)})));
    CHECK(meet_improperly(a, tri({3, 4, 5}, {Vec3(1, 0, 0), Vec3(1, -1, 1), Vec3(1, -1, -1)})));
    CHECK_FALSE(meet_improperly(a, tri({3, 4, 5}, {Vec3(up(1), 1, 0), Vec3(3, 1, 0), Vec3(1, 3, 0)})));
    CHECK_FALSE(meet_improperly(a, tri({3, 4, 5}, {Vec3(0, 0, 1), Vec3(2, 0, 1), Vec3(0, 2, 1)})));
}

TEST_CASE("GEN-E1: two triangles with one common vertex", "[unit]") {
    const auto a = tri({0, 1, 2}, {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0)});
    // A fan neighbour meeting only at the vertex; one crossing a through its interior (from the
    // common vertex, so no edge without it crosses a... but its far edge does); coplanar overlap.
    CHECK_FALSE(meet_improperly(a, tri({0, 3, 4}, {Vec3(0, 0, 0), Vec3(-1, 0, 1), Vec3(-1, 0, -1)})));
    CHECK(meet_improperly(a, tri({0, 3, 4}, {Vec3(0, 0, 0), Vec3(1, 1, -1), Vec3(1, 1, 1)})));
    CHECK(meet_improperly(a, tri({0, 3, 4}, {Vec3(0, 0, 0), Vec3(1, 0.5, 0), Vec3(3, 3, 0)})));
    // Coplanar, sharing the vertex and touching a's edge from outside along a ray: improper.
    CHECK(meet_improperly(a, tri({0, 3, 4}, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, -1, 0)})));
    CHECK_FALSE(meet_improperly(a, tri({0, 3, 4}, {Vec3(0, 0, 0), Vec3(1, -1e-300, 0), Vec3(1, -1, 0)})));
}

TEST_CASE("GEN-E1: two triangles with a common edge", "[unit]") {
    const auto a = tri({0, 1, 2}, {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0)});
    CHECK_FALSE(
        meet_improperly(a, tri({1, 0, 3}, {Vec3(2, 0, 0), Vec3(0, 0, 0), Vec3(1, -1, 0)})));  // flat, opposite sides
    CHECK_FALSE(meet_improperly(
        a, tri({1, 0, 3}, {Vec3(2, 0, 0), Vec3(0, 0, 0), Vec3(1, 1, 1e-300)})));               // a hair off the plane
    CHECK(meet_improperly(a, tri({1, 0, 3}, {Vec3(2, 0, 0), Vec3(0, 0, 0), Vec3(1, 1, 0)})));  // folded flat onto a
    CHECK(
        meet_improperly(a, tri({1, 0, 3}, {Vec3(2, 0, 0), Vec3(0, 0, 0), Vec3(5, 5, 0)})));  // folded, reaching past a
}

TEST_CASE("GEN-E2: find_self_intersection names a degenerate face and the first pair that meets", "[unit]") {
    const std::vector<Vec3> p{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, -1}, {0.5, 0.5, 1}, {3, 3, 0.5}};
    const TriMesh crossing = TriMesh::from_triangles(p, std::vector<fhr::Triangle>{{0, 1, 2}, {3, 4, 5}});
    const auto pair = fhr::generate::find_self_intersection(crossing);
    REQUIRE(pair);
    CHECK((*pair)[0] == FaceId(0));
    CHECK((*pair)[1] == FaceId(1));
    const std::vector<Vec3> q{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};  // collinear: zero area
    const auto flat =
        fhr::generate::find_self_intersection(TriMesh::from_triangles(q, std::vector<fhr::Triangle>{{0, 1, 2}}));
    REQUIRE(flat);
    CHECK((*flat)[0] == (*flat)[1]);
}

TEST_CASE("GEN-E3: the guard accepts an edit exactly when the edited mesh is embedded", "[property]") {
    // Random vertex moves on generated meshes: the guard's verdict against the whole-mesh check of
    // the moved mesh (an independent, brute-force-free path: every pair from scratch).
    rc::prop("guard == find_self_intersection after the move", [] {
        const fhr::testing::GeneratedMesh g =
            *fhr::testing::gen_mesh({.max_genus = 1, .max_faces = 300, .max_holes = 2});
        TriMesh m = g;
        fhr::generate::EmbeddingGuard guard(m, 0);
        const int moves = *rc::gen::inRange(1, 20);
        for (int i = 0; i < moves; ++i) {
            const VertexId v(*rc::gen::inRange<unsigned>(0, static_cast<unsigned>(m.n_vertices())));
            const double scale = *rc::gen::element(0.01, 0.2, 0.6);
            const Vec3 moved =
                m.position(v) +
                scale * Vec3(*rc::gen::inRange(-100, 101), *rc::gen::inRange(-100, 101), *rc::gen::inRange(-100, 101)) /
                    100.0;
            std::vector<FaceId> star;
            std::vector<TriangleAt> added;
            m.for_each_outgoing(v, [&](fhr::HalfedgeId h) {
                if (m.is_boundary(h)) return;
                star.push_back(m.face(h));
                TriangleAt t = fhr::generate::triangle_at(m, m.face(h));
                for (int k = 0; k < 3; ++k)
                    if (t.v[k] == v) t.p[k] = moved;
                added.push_back(t);
            });
            const bool accepted = guard.accepts(m, star, added);
            const Vec3 old = m.position(v);
            for (FaceId f : star) guard.remove(m, f);
            m.position(v) = moved;
            const bool embedded = !fhr::generate::find_self_intersection(m);
            RC_ASSERT(accepted == embedded);
            if (!accepted) m.position(v) = old;
            for (FaceId f : star) guard.insert(m, f);
        }
    });
}
