// FHR core — geometry helpers (see geometry.hpp).
#include "core/geometry.hpp"

#include <algorithm>
#include <cmath>

namespace fhr {

Vec3 edge_vector(const TriMesh& m, HalfedgeId h) { return m.position(m.to(h)) - m.position(m.from(h)); }

double edge_length(const TriMesh& m, EdgeId e) { return edge_vector(m, TriMesh::halfedge(e, 0)).norm(); }

static Vec3 face_cross(const TriMesh& m, FaceId f) {
    const auto v = m.face_vertices(f);
    return (m.position(v[1]) - m.position(v[0])).cross(m.position(v[2]) - m.position(v[0]));
}

double face_area(const TriMesh& m, FaceId f) { return 0.5 * face_cross(m, f).norm(); }

Vec3 face_normal(const TriMesh& m, FaceId f) {
    const Vec3 n = face_cross(m, f);
    const double len = n.norm();
    return len > 0 ? Vec3(n / len) : Vec3::Zero();
}

double corner_angle(const TriMesh& m, HalfedgeId h) {
    const Vec3 a = edge_vector(m, h);
    const Vec3 b = -edge_vector(m, m.prev(h));
    return std::atan2(a.cross(b).norm(), a.dot(b));
}

Vec3 vertex_normal(const TriMesh& m, VertexId v) {
    Vec3 n = Vec3::Zero();
    m.for_each_outgoing(v, [&](HalfedgeId h) {
        if (!m.is_boundary(h)) n += corner_angle(m, h) * face_normal(m, m.face(h));
    });
    const double len = n.norm();
    return len > 0 ? Vec3(n / len) : Vec3::Zero();
}

double angle_sum(const TriMesh& m, VertexId v) {
    double s = 0;
    m.for_each_outgoing(v, [&](HalfedgeId h) {
        if (!m.is_boundary(h)) s += corner_angle(m, h);
    });
    return s;
}

BoundingBox bounding_box(const TriMesh& m) {
    BoundingBox b{Vec3::Constant(INFINITY), Vec3::Constant(-INFINITY)};
    for (const Vec3& p : m.positions()) {
        b.min = b.min.cwiseMin(p);
        b.max = b.max.cwiseMax(p);
    }
    return b;
}

double signed_volume(const TriMesh& m) {
    // Tetrahedra from the box centre: the same volume for a closed surface, less cancellation.
    const BoundingBox box = bounding_box(m);
    const Vec3 c = 0.5 * (box.min + box.max);
    double six_v = 0;
    for (FaceId f : m.faces()) {
        const auto v = m.face_vertices(f);
        six_v += (m.position(v[0]) - c).dot((m.position(v[1]) - c).cross(m.position(v[2]) - c));
    }
    return six_v / 6;
}

EdgeLengthStats edge_length_stats(const TriMesh& m) {
    std::vector<double> len;
    len.reserve(m.n_edges());
    for (EdgeId e : m.edges()) len.push_back(edge_length(m, e));
    EdgeLengthStats s;
    if (len.empty()) return s;
    std::sort(len.begin(), len.end());
    double sum = 0;
    for (double l : len) sum += l;
    s.min = len.front();
    s.max = len.back();
    s.mean = sum / static_cast<double>(len.size());
    const std::size_t n = len.size();
    s.median = n % 2 ? len[n / 2] : 0.5 * (len[n / 2 - 1] + len[n / 2]);
    return s;
}

}  // namespace fhr
