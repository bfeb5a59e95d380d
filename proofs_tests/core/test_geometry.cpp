// Geometry helpers on meshes with known answers: a regular octahedron (all quantities closed
// form) and a unit cube.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <vector>

#include <fhr/core/geometry.hpp>
#include <fhr/core/topology.hpp>

using namespace fhr;

namespace {

TriMesh octahedron(double r) {
    std::vector<Vec3> p{{r, 0, 0}, {-r, 0, 0}, {0, r, 0}, {0, -r, 0}, {0, 0, r}, {0, 0, -r}};
    const std::vector<Triangle> t{{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                  {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    return TriMesh::from_triangles(std::move(p), t);
}

}  // namespace

TEST_CASE("geometry of a regular octahedron matches closed forms", "[unit][geometry]") {
    const double r = 2.0;
    const TriMesh m = octahedron(r);
    m.validate();
    const double edge = r * std::sqrt(2.0);
    for (EdgeId e : m.edges()) CHECK(edge_length(m, e) == Approx(edge));
    for (FaceId f : m.faces()) {
        CHECK(face_area(m, f) == Approx(std::sqrt(3.0) / 4 * edge * edge));
        const auto v = m.face_vertices(f);
        const Vec3 centroid = (m.position(v[0]) + m.position(v[1]) + m.position(v[2])) / 3;
        CHECK(face_normal(m, f).dot(centroid.normalized()) == Approx(1.0));  // outward, unit
    }
    for (HalfedgeId h : m.halfedges()) CHECK(corner_angle(m, h) == Approx(M_PI / 3));
    for (VertexId v : m.vertices()) {
        CHECK(angle_sum(m, v) == Approx(4 * M_PI / 3));
        CHECK(vertex_normal(m, v).dot(m.position(v).normalized()) == Approx(1.0));
    }
    CHECK(signed_volume(m) == Approx(4.0 / 3 * r * r * r));
    const BoundingBox b = bounding_box(m);
    CHECK(b.min == Vec3(-r, -r, -r));
    CHECK(b.max == Vec3(r, r, r));
    CHECK(b.diagonal() == Approx(2 * r * std::sqrt(3.0)));
    const EdgeLengthStats s = edge_length_stats(m);
    CHECK(s.min == Approx(edge));
    CHECK(s.max == Approx(edge));
    CHECK(s.median == Approx(edge));
    CHECK(euler_characteristic(m) == 2);
    CHECK(genus(m) == 0);
    // Gauss–Bonnet: the angle defects of a closed surface sum to 2πχ.
    double defect = 0;
    for (VertexId v : m.vertices()) defect += 2 * M_PI - angle_sum(m, v);
    CHECK(defect == Approx(2 * M_PI * euler_characteristic(m)));
}

TEST_CASE("corner_angle is accurate for needle triangles", "[unit][geometry]") {
    // A triangle with a 1e-12 rad angle: acos of a dot product would lose it, atan2 does not.
    const double eps = 1e-12;
    std::vector<Vec3> p{{0, 0, 0}, {1, 0, 0}, {1, eps, 0}, {0.5, 0.5, 1}};
    const std::vector<Triangle> t{{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}};
    const TriMesh m = TriMesh::from_triangles(std::move(p), t);
    const HalfedgeId h = m.find_halfedge(VertexId(0), VertexId(1));
    REQUIRE(m.face(h) == FaceId(0));
    CHECK(corner_angle(m, h) == Approx(std::atan(eps)).epsilon(1e-12));
}

TEST_CASE("closest_point_on_triangle: degenerate triangles give the nearest point of their edges", "[unit][geometry]") {
    // Whatever the order of the corners: a segment with a doubled end, a segment through three
    // distinct collinear corners, a single point.
    struct Case {
        Vec3 a, b, c, p, expected;
    };
    const std::vector<Case> cases{
        {{0, 0, 0}, {0, 0, 0}, {2, 0, 0}, {1, 1, 0}, {1, 0, 0}},       // a = b: the segment a–c
        {{0, 0, 0}, {2, 0, 0}, {2, 0, 0}, {1, 0, 3}, {1, 0, 0}},       // b = c
        {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {1.5, 1, 0}, {1.5, 0, 0}},   // three on a line
        {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 1, 0}, {2, 0, 0}},       // beyond the far end
        {{1, 1, 1}, {1, 1, 1}, {1, 1, 1}, {0, 0, 0}, {1, 1, 1}},       // one point
    };
    for (const Case& k : cases) {
        const Vec3 corners[3] = {k.a, k.b, k.c};
        for (const auto& [i, j, l] : std::vector<std::array<int, 3>>{{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}}) {
            INFO("corners " << i << j << l << ", p = " << k.p.transpose());
            CHECK((closest_point_on_triangle(k.p, corners[i], corners[j], corners[l]) - k.expected).norm() < 1e-15);
        }
    }
}

TEST_CASE("normals of degenerate faces are zero; a flat disk's boundary vertex has the disk's normal", "[unit][geometry]") {
    // The triangle (0, 1, 2) on the x axis has no normal; nor has any of its vertices.
    const std::vector<Triangle> line{{0, 1, 2}};
    const TriMesh flat = TriMesh::from_triangles({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(3, 0, 0)}, line);
    CHECK(face_normal(flat, FaceId(0)) == Vec3::Zero());
    for (VertexId v : flat.vertices()) CHECK(vertex_normal(flat, v) == Vec3::Zero());
    // Two triangles of the plane z = 0 around boundary vertex 0: only the faces count, not the
    // boundary halfedge, and both say +z.
    const std::vector<Triangle> fan{{0, 1, 2}, {0, 2, 3}};
    const TriMesh disk = TriMesh::from_triangles({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)}, fan);
    REQUIRE(disk.is_boundary(VertexId(0)));
    CHECK(vertex_normal(disk, VertexId(0)) == Vec3(0, 0, 1));
    CHECK(angle_sum(disk, VertexId(0)) == Approx(M_PI / 2));
}

TEST_CASE("edge and shape statistics of a mesh without elements are all zero", "[unit][geometry]") {
    const TriMesh empty;
    const EdgeLengthStats e = edge_length_stats(empty);
    CHECK((e.min == 0 && e.max == 0 && e.mean == 0 && e.median == 0));
    const ShapeStats s = shape_stats(empty);
    CHECK((s.min_angle == 0 && s.max_angle == 0 && s.min_valence == 0 && s.max_valence == 0));
}
