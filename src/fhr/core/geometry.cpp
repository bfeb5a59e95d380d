// FHR core — geometry helpers (see geometry.hpp).
#include <fhr/core/geometry.hpp>

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

Vec3 triangle_normal(const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 n = (b - a).cross(c - a);
    const double len = n.norm();
    return len > 0 ? Vec3(n / len) : Vec3::Zero();
}

Vec3 face_normal(const TriMesh& m, FaceId f) {
    const auto v = m.face_vertices(f);
    return triangle_normal(m.position(v[0]), m.position(v[1]), m.position(v[2]));
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

ShapeStats shape_stats(const TriMesh& m) {
    ShapeStats s;
    if (m.n_faces() == 0) return s;
    s.min_angle = INFINITY;
    for (HalfedgeId h : m.halfedges()) {
        if (m.is_boundary(h)) continue;
        const double a = corner_angle(m, h);
        s.min_angle = std::min(s.min_angle, a);
        s.max_angle = std::max(s.max_angle, a);
    }
    s.min_valence = SIZE_MAX;
    for (VertexId v : m.vertices()) {
        const std::size_t k = m.valence(v);
        s.min_valence = std::min(s.min_valence, k);
        s.max_valence = std::max(s.max_valence, k);
    }
    return s;
}

namespace {

Vec3 closest_on_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
    const Vec3 ab = b - a;
    const double len2 = ab.squaredNorm();
    if (!(len2 > 0)) return a;
    const double t = std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
    return a + t * ab;
}

/// A degenerate (zero-area) triangle is the union of its edges: the nearest of their closest points.
Vec3 closest_on_edges(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 q[3] = {closest_on_segment(p, a, b), closest_on_segment(p, b, c), closest_on_segment(p, c, a)};
    const Vec3* best = &q[0];
    for (const Vec3& x : q)
        if ((x - p).squaredNorm() < (*best - p).squaredNorm()) best = &x;
    return *best;
}

}  // namespace

/// Degenerate triangles included: Ericson's Voronoi regions hold for a proper triangle only (with
/// two equal corners the region of the zero-length edge between them would take in every p that
/// projects into the triangle, and return that corner), so a zero-area triangle is settled first.
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    if (!(ab.cross(ac).squaredNorm() > 0)) return closest_on_edges(p, a, b, c);
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return a;
    const Vec3 bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return b;
    const Vec3 cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return c;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return closest_on_segment(p, a, b);
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return closest_on_segment(p, a, c);
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) return closest_on_segment(p, b, c);
    const double sum = va + vb + vc;  // = |ab × ac|² > 0 in exact arithmetic
    if (!(sum > 0)) return closest_on_edges(p, a, b, c);  // a needle whose sum rounding has eaten
    return a + (vb / sum) * ab + (vc / sum) * ac;
}

}  // namespace fhr
