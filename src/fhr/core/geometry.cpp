// FHR core — geometry helpers (see geometry.hpp).
#include <fhr/core/geometry.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

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

double box_distance2(const Vec3& p, const Vec3& lo, const Vec3& hi) {
    double d2 = 0;
    for (int i = 0; i < 3; ++i) {
        const double d = std::max(std::max(lo[i] - p[i], p[i] - hi[i]), 0.0);
        d2 += d * d;
    }
    return d2;
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

/// The cross product a × b, each component a difference of two products computed with Kahan's
/// fma algorithm (within 2 ulp of the exact difference).
Vec3 cross_accurate(const Vec3& a, const Vec3& b) {
    auto difference_of_products = [](double w, double x, double y, double z) {  // w·x − y·z
        const double yz = y * z;
        return std::fma(w, x, -yz) + std::fma(-y, z, yz);
    };
    return Vec3(difference_of_products(a[1], b[2], a[2], b[1]), difference_of_products(a[2], b[0], a[0], b[2]),
                difference_of_products(a[0], b[1], a[1], b[0]));
}

/// b − a exactly, as its rounded value plus the rounding error (Knuth's TwoSum per coordinate).
Vec3 difference_error(const Vec3& b, const Vec3& a, const Vec3& rounded) {
    Vec3 error;
    for (int k = 0; k < 3; ++k) {
        const double from_b = rounded[k] - b[k];
        error[k] = (b[k] - (rounded[k] - from_b)) - (a[k] + from_b);
    }
    return error;
}

}  // namespace

// Not obtuse: the circumradius abc / (4·area), the circumcentre lying in the triangle (a point
// inside is nearest to some corner, and the farthest such point is where all three are equally
// far). Obtuse at the corner opposite side c: the circumcentre lies beyond c, and the farthest
// points lie on c, where the perpendicular bisectors of the two other sides meet it, at
// b²c / (b² + c² − a²) from c's end on side b's corner and a²c / (a² + c² − b²) from the other. At
// most ℓ/√3 (at a point p inside, one of the angles the sides subtend at p is ≥ 120°, so
// ℓ² ≥ 3 min|p − x_k|²): much less for a long flat triangle. Raised by 10⁻¹² relative against
// rounding.
double corner_cover_radius(const Vec3& p0, const Vec3& p1, const Vec3& p2) {
    const Vec3* x[3] = {&p0, &p1, &p2};
    double s2[3];  // squared side opposite corner k
    for (int k = 0; k < 3; ++k) s2[k] = (*x[(k + 1) % 3] - *x[(k + 2) % 3]).squaredNorm();
    const int c = static_cast<int>(std::max_element(s2, s2 + 3) - s2), a = (c + 1) % 3, b = (c + 2) % 3;
    double r;
    if (s2[a] + s2[b] >= s2[c]) {
        const double area2 = (p1 - p0).cross(p2 - p0).norm();  // twice the area
        r = area2 > 0 ? std::sqrt(s2[0] * s2[1] * s2[2]) / (2 * area2) : std::sqrt(s2[c]) / 2;
    } else {
        const double side = std::sqrt(s2[c]);
        r = std::max(s2[b] * side / (s2[b] + s2[c] - s2[a]), s2[a] * side / (s2[a] + s2[c] - s2[b]));
    }
    return std::min(r, std::sqrt(s2[c] / 3)) * (1 + 1e-12);
}

/// p projected onto the plane of abc when that projection is in the triangle, else the nearest
/// point of its sides; a zero-area triangle is the union of its sides. Well conditioned for
/// needles (spec/param.md, PARAM-11), in two cases:
/// - every angle's sine is at least 1/4: rounded arithmetic turns the normal n by a few ulp
///   (u/sin α at corner a: b moved by u·|ab| off the plane turns it by u/sin α about ac, and the
///   products' rounding is u·|ab|·|ac| against |n| = |ab|·|ac|·sin α), so the projection errs by
///   about u·|p − a|; a side test (n × side)·(p − corner) errs only where the projection is within
///   about u·|p − a| of the side's line, and then the nearest point is on the sides the projection
///   lies beyond (one, or the two at a corner), within that error over the sine at their corner;
/// - else (a needle, or a cap: two sides almost one line) n from the exact differences (TwoSum)
///   and fma products — for a needle of width h and length L, the rounded differences alone turn
///   its plane by u·L/h about its long axis — and all three sides when the projection is outside:
///   which sides it lies beyond is ill-conditioned at a corner between two almost collinear sides
///   (a wrong sign there put the answer 50 ulp of the diameter off).
/// Ericson's Voronoi-region formulas (products of dot products) cancel to a relative error
/// u·(L/h)² on a needle of length L and width h: 1.7·10⁻⁹ off for a point on the edge of a
/// needle of L/h ≈ 10⁵.
/// The result is clamped to the triangle's bounding box (which holds the exact closest point, so
/// the clamp only brings it nearer): its rounded distance to p is then never below the box's, and
/// a search that skips boxes no nearer than its best so far finds the same minimum as brute force.
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 ab = b - a, ac = c - a, bc = c - b, ap = p - a;
    Vec3 n = ab.cross(ac);
    const double ab2 = ab.squaredNorm(), ac2 = ac.squaredNorm(), bc2 = bc.squaredNorm();
    const bool shaped = 16 * n.squaredNorm() >= std::max({ab2 * ac2, ab2 * bc2, ac2 * bc2});  // every sine ≥ 1/4
    if (!shaped)
        n = cross_accurate(ab, ac) + (ab.cross(difference_error(c, a, ac)) + difference_error(b, a, ab).cross(ac));
    const double nn = n.squaredNorm();
    Vec3 q;
    if (!(nn > 0)) {
        q = closest_on_edges(p, a, b, c);
    } else {
        // |n|·|side|·(signed distance of the projection from the side's line), positive inside.
        const double s_ab = n.cross(ab).dot(ap), s_bc = n.cross(bc).dot(p - b), s_ca = -n.cross(ac).dot(ap);
        if (s_ab >= 0 && s_bc >= 0 && s_ca >= 0) {
            q = p - (ap.dot(n) / nn) * n;
        } else if (!shaped) {
            q = closest_on_edges(p, a, b, c);
        } else {
            double best = std::numeric_limits<double>::infinity();
            const auto beyond = [&](double side, const Vec3& from, const Vec3& to) {
                if (!(side < 0)) return;
                const Vec3 x = closest_on_segment(p, from, to);
                if (const double d = (x - p).squaredNorm(); d < best) best = d, q = x;
            };
            beyond(s_ab, a, b);
            beyond(s_bc, b, c);
            beyond(s_ca, c, a);
        }
    }
    return q.cwiseMax(a.cwiseMin(b).cwiseMin(c)).cwiseMin(a.cwiseMax(b).cwiseMax(c));
}

}  // namespace fhr
