// SurfacePoint: positions, and the canonical form that makes one location compare equal however
// it is named (a vertex as an edge end, an edge point from either side, a face point with a zero
// weight) — what §3's path nodes u_p and Fig. 4's inserted points x_j need.
#include <catch2/catch.hpp>

#include <fhr/core/surface_point.hpp>

using namespace fhr;

namespace {

TriMesh tetrahedron() {
    std::vector<Vec3> p{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const std::vector<Triangle> t{{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    return TriMesh::from_triangles(std::move(p), t);
}

}  // namespace

TEST_CASE("SurfacePoint positions interpolate linearly", "[unit][surface_point]") {
    const TriMesh m = tetrahedron();
    CHECK(position(m, SurfacePoint::at_vertex(VertexId(3))) == Vec3(0, 0, 1));
    const HalfedgeId h = m.find_halfedge(VertexId(1), VertexId(3));
    REQUIRE(h.valid());
    CHECK(position(m, SurfacePoint::on_edge(h, 0.25)).isApprox(Vec3(0.75, 0, 0.25)));
    const FaceId f(3);  // (1, 2, 3)
    CHECK(position(m, SurfacePoint::in_face(f, {0.5, 0.25, 0.25})).isApprox(Vec3(0.5, 0.25, 0.25)));
}

TEST_CASE("SurfacePoint canonical form names each location once", "[unit][surface_point]") {
    const TriMesh m = tetrahedron();
    const HalfedgeId h = m.find_halfedge(VertexId(1), VertexId(3));
    // Edge ends are vertices.
    CHECK(same_location(m, SurfacePoint::on_edge(h, 0), SurfacePoint::at_vertex(VertexId(1))));
    CHECK(same_location(m, SurfacePoint::on_edge(h, 1), SurfacePoint::at_vertex(VertexId(3))));
    // An edge point is the same from both halfedges.
    CHECK(same_location(m, SurfacePoint::on_edge(h, 0.25), SurfacePoint::on_edge(TriMesh::twin(h), 0.75)));
    CHECK_FALSE(same_location(m, SurfacePoint::on_edge(h, 0.25), SurfacePoint::on_edge(h, 0.75)));
    // A face point with a zero weight lies on the opposite edge, from either adjacent face.
    for (FaceId f : m.faces()) {
        const auto v = m.face_vertices(f);
        for (int k = 0; k < 3; ++k) {
            std::array<double, 3> b{};
            b[(k + 1) % 3] = 0.75;
            b[(k + 2) % 3] = 0.25;
            const SurfacePoint p = SurfacePoint::in_face(f, b);
            const SurfacePoint c = canonical(m, p);
            REQUIRE(c.kind == SurfacePoint::Kind::edge);
            CHECK(position(m, c).isApprox(position(m, p)));
            const HalfedgeId e = m.find_halfedge(v[(k + 1) % 3], v[(k + 2) % 3]);
            CHECK(same_location(m, p, SurfacePoint::on_edge(e, 0.25)));
        }
        // Two zero weights: a vertex.
        CHECK(same_location(m, SurfacePoint::in_face(f, {0, 1, 0}), SurfacePoint::at_vertex(v[1])));
    }
}

TEST_CASE("SurfacePoint: face points inside a face are the same location only with the same weights",
          "[unit][surface_point]") {
    const TriMesh m = tetrahedron();
    const SurfacePoint p = SurfacePoint::in_face(FaceId(3), {0.5, 0.25, 0.25});
    CHECK(same_location(m, p, SurfacePoint::in_face(FaceId(3), {0.5, 0.25, 0.25})));
    CHECK_FALSE(same_location(m, p, SurfacePoint::in_face(FaceId(3), {0.25, 0.5, 0.25})));
    CHECK_FALSE(same_location(m, p, SurfacePoint::in_face(FaceId(2), {0.5, 0.25, 0.25})));
    // Inside a face is never on an edge or at a vertex.
    CHECK_FALSE(same_location(m, p, SurfacePoint::at_vertex(VertexId(1))));
}
