// §3: the geodesic suite's shared checks and helpers (see geodesic_checks.hpp).
#include "geodesic/geodesic_checks.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <utility>
#include <vector>

#include <fhr/core/geometry.hpp>
#include <fhr/core/surface_point.hpp>
#include <fhr/core/topology.hpp>
#include <fhr/geodesic/detail/fast_marching.hpp>

namespace fhr::test {

generate::RandomMeshOptions needle_recipe(int genus, int components, std::size_t faces, std::uint64_t seed) {
    generate::RandomMeshOptions o;
    o.genus = genus;
    o.components = components;
    o.faces = faces;
    o.seed = seed;
    o.family = generate::Family::quality;
    o.knobs.smallest_angle_deg = 1e-9;
    o.knobs.bad_fraction = 0.5;
    return o;
}

using geodesic::GeodesicPath;

double rel_dev(double a, double b) {
    if (a == b) return 0;
    if (std::isinf(a) || std::isinf(b)) return INFINITY;
    return std::abs(a - b) / std::max(std::abs(a), std::abs(b));
}

std::string sci(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3e", x);
    return buf;
}

std::vector<FaceId> faces_at(const TriMesh& m, const SurfacePoint& p) {
    std::vector<FaceId> fs;
    if (p.kind == SurfacePoint::Kind::vertex)
        m.for_each_outgoing(p.vertex, [&](HalfedgeId h) { fs.push_back(m.face(h)); });
    else
        fs = {m.face(p.halfedge), m.face(TriMesh::twin(p.halfedge))};
    return fs;
}

namespace {

bool face_kept(const FaceData<std::uint8_t>* mask, FaceId f) { return f.valid() && (!mask || (*mask)[f]); }

double angle(const Vec3& a, const Vec3& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); }

/// The kept faces around v unfolded into the plane: its edges in clockwise order, edge k at the
/// angle theta[k] from edges[0] (the sum of the kept corner angles at v between them). Closed
/// when the kept faces surround v (total: their angle sum); open when they form one fan from a
/// border edge (edges[0]) to the other (edges.back()).
struct Fan {
    std::vector<HalfedgeId> edges;
    std::vector<double> theta;
    double total = 0;
    bool closed = false;
};

/// nullopt when v has no kept face or its kept faces form several fans (a pinched vertex).
std::optional<Fan> kept_fan(const TriMesh& m, const FaceData<std::uint8_t>* mask, VertexId v) {
    std::vector<HalfedgeId> ring;  // clockwise; face(ring[i]) lies between ring[i − 1] and ring[i]
    m.for_each_outgoing(v, [&](HalfedgeId h) { ring.push_back(h); });
    const std::size_t n = ring.size();
    const auto kept = [&](std::size_t i) { return face_kept(mask, m.face(ring[i % n])); };
    std::size_t runs = 0, start = 0;
    for (std::size_t i = 0; i < n; ++i)
        if (kept(i + 1) && !kept(i)) ++runs, start = i;  // ring[start] is a border edge of a fan
    Fan fan;
    fan.closed = runs == 0 && kept(0);
    if (!fan.closed && runs != 1) return std::nullopt;
    fan.edges.push_back(ring[start]);
    fan.theta.push_back(0);
    for (std::size_t i = start + 1; i < start + n && kept(i); ++i) {
        fan.total += corner_angle(m, ring[i % n]);
        fan.edges.push_back(ring[i % n]);
        fan.theta.push_back(fan.total);
    }
    if (fan.closed) fan.total += corner_angle(m, ring[start]);  // face(ring[0]), between ring[n − 1] and ring[0]
    return fan;
}

/// The angular position in v's fan of a point q that shares a kept face with v (NAN otherwise).
double fan_position(const TriMesh& m, const Fan& fan, VertexId v, const SurfacePoint& q) {
    const Vec3 pv = m.position(v), pq = position(m, q);
    const std::size_t n = fan.edges.size();
    for (std::size_t k = 0; k < n; ++k) {
        const HalfedgeId g = fan.edges[k];
        const bool on_edge =
            q.kind == SurfacePoint::Kind::vertex ? q.vertex == m.to(g) : TriMesh::edge(q.halfedge) == TriMesh::edge(g);
        if (on_edge) return fan.theta[k];
        // face(g), between the edges k − 1 and k (for k = 0 only when the fan is closed).
        if ((k > 0 || fan.closed) && q.kind == SurfacePoint::Kind::edge &&
            TriMesh::edge(q.halfedge) == TriMesh::edge(m.next(g))) {
            const std::size_t before = k > 0 ? k - 1 : n - 1;
            return fan.theta[before] + angle(m.position(m.to(fan.edges[before])) - pv, pq - pv);
        }
    }
    return NAN;
}

/// The angles between a path's segments from `in` to v and from v to `out`, measured through
/// v's kept faces: {the side inside the fan, the other side} for a closed fan, {the side inside
/// the fan, INFINITY (the hole: unconstrained)} for an open one; nullopt for a pinched vertex.
std::optional<std::pair<double, double>> side_angles(const TriMesh& m, const FaceData<std::uint8_t>* mask, VertexId v,
                                                     const SurfacePoint& in, const SurfacePoint& out) {
    const std::optional<Fan> fan = kept_fan(m, mask, v);
    if (!fan) return std::nullopt;
    const double a = fan_position(m, *fan, v, in), b = fan_position(m, *fan, v, out);
    if (!fan->closed) return std::pair{std::abs(b - a), INFINITY};
    const double side = std::fmod(b - a + fan->total, fan->total);
    return std::pair{side, fan->total - side};
}

}  // namespace

std::string path_violation(const TriMesh& m, const GeodesicPath& p, VertexId s, VertexId t,
                           const FaceData<std::uint8_t>* mask, double conditioning) {
    if (p.points.empty()) return "empty path";
    const auto is_vertex = [](const SurfacePoint& q, VertexId v) {
        return q.kind == SurfacePoint::Kind::vertex && q.vertex == v;
    };
    if (!is_vertex(p.points.front(), s) || !is_vertex(p.points.back(), t)) return "does not run from source to target";
    const BoundingBox box = bounding_box(m);
    const double diag = box.diagonal();
    const double node_error = 1e-12 * diag * conditioning;
    double longest_edge = 0;
    for (EdgeId e : m.edges()) longest_edge = std::max(longest_edge, edge_length(m, e));
    double sum = 0;
    std::vector<Vec3> x;
    std::vector<double> err;
    for (const SurfacePoint& q : p.points) {
        x.push_back(position(m, q));
        err.push_back(node_error);
    }
    for (std::size_t i = 0; i + 1 < p.points.size(); ++i) {
        const auto a = faces_at(m, p.points[i]), b = faces_at(m, p.points[i + 1]);
        const bool share = std::any_of(a.begin(), a.end(), [&](FaceId f) {
            return face_kept(mask, f) && std::find(b.begin(), b.end(), f) != b.end();
        });
        if (!share) return "points " + std::to_string(i) + " and " + std::to_string(i + 1) + " share no kept face";
        sum += (x[i + 1] - x[i]).norm();
        // A vertex node may be a snapped crossing (the line passes it within snap_tolerance·ℓ_v,
        // ℓ_v its longest edge), or a vertex that a ray passed on the wrong side when the next
        // node was reached within cover_tolerance·|edge| of a window (exact.hpp): ≤ ℓ_max·that.
        if (p.points[i].kind == SurfacePoint::Kind::vertex) {
            double longest = 0;
            m.for_each_outgoing(p.points[i].vertex,
                                [&](HalfedgeId h) { longest = std::max(longest, edge_length(m, TriMesh::edge(h))); });
            err[i] += geodesic::snap_tolerance * longest + geodesic::cover_tolerance * longest_edge;
        }
    }
    // 1e-12 relative, plus the rounding of the nodes' coordinates (about 4 ulps of the largest
    // coordinate per node, whatever the path's length: it matters for paths of ~10⁻⁴·diag).
    const double coordinate = std::max(box.min.cwiseAbs().maxCoeff(), box.max.cwiseAbs().maxCoeff());
    const double length_tol =
        (1e-12 * p.length + 4 * DBL_EPSILON * coordinate * static_cast<double>(p.points.size())) * conditioning;
    if (std::abs(sum - p.length) > length_tol)
        return "length " + std::to_string(p.length) + " != segment sum, off by " + sci(rel_dev(sum, p.length));
    for (std::size_t i = 1; i + 1 < p.points.size(); ++i) {
        const SurfacePoint& q = p.points[i];
        const double shortest = std::min((x[i] - x[i - 1]).norm(), (x[i + 1] - x[i]).norm());
        const double tol = (err[i - 1] + 2 * err[i] + err[i + 1]) / shortest;
        if (q.kind == SurfacePoint::Kind::edge) {
            const Vec3 a = m.position(m.from(q.halfedge));
            const double unfolded = angle(x[i - 1] - x[i], a - x[i]) + angle(a - x[i], x[i + 1] - x[i]);
            if (std::abs(unfolded - std::numbers::pi) > tol)
                return "bends by " + sci(unfolded - std::numbers::pi) + " (tolerance " + sci(tol) + ") at edge point " +
                       std::to_string(i);
            continue;
        }
        const auto sides = side_angles(m, mask, q.vertex, p.points[i - 1], p.points[i + 1]);
        if (!sides) continue;  // pinched
        // Bending by ε at a vertex between segments a, b saves only ab·ε²/(2(a + b)) against
        // the straight way past it: a tie below node_error makes either way a shortest path.
        const double a = (x[i] - x[i - 1]).norm(), b = (x[i + 1] - x[i]).norm();
        const double tie = std::sqrt(2 * node_error * (a + b) / (a * b));
        const double least = std::min(sides->first, sides->second);
        if (!(least >= std::numbers::pi - tol - tie))
            return std::string("a side angle is π − ") + sci(std::numbers::pi - least) + " (tolerance " +
                   sci(tol + tie) + ") at " + (std::isinf(sides->second) ? "boundary " : "") + "vertex " +
                   std::to_string(q.vertex.idx()) + " (node " + std::to_string(i) + ")";
    }
    return "";
}

VertexPassages vertex_passages(const TriMesh& m, const GeodesicPath& p) {
    VertexPassages count;
    const auto& pts = p.points;
    for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
        const bool vv = pts[i].kind == SurfacePoint::Kind::vertex && pts[i + 1].kind == SurfacePoint::Kind::vertex;
        if (vv && m.is_boundary(TriMesh::edge(m.find_halfedge(pts[i].vertex, pts[i + 1].vertex))))
            ++count.boundary_edges;
        if (i == 0 || pts[i].kind != SurfacePoint::Kind::vertex) continue;
        const VertexId v = pts[i].vertex;
        if (!m.is_boundary(v)) {
            ++count.interior;
            continue;
        }
        ++count.boundary;
        const auto sides = side_angles(m, nullptr, v, pts[i - 1], pts[i + 1]);
        count.boundary_bends += sides && sides->first > std::numbers::pi + 1e-6;
    }
    return count;
}

double needle_ratio(const TriMesh& m) {
    double worst = 1;
    for (FaceId f : m.faces()) {
        const auto v = m.face_vertices(f);
        const Vec3 &a = m.position(v[0]), &b = m.position(v[1]), &c = m.position(v[2]);
        const double longest2 = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
        worst = std::max(worst, longest2 / (b - a).cross(c - a).norm());  // ℓ² / (2·area) = ℓ / height
    }
    return worst;
}

bool passes_a_vertex(const GeodesicPath& p) {
    return std::any_of(p.points.begin() + 1, p.points.end() - 1,
                       [](const SurfacePoint& q) { return q.kind == SurfacePoint::Kind::vertex; });
}

std::vector<std::vector<VertexId>> boundary_loop_vertices(const TriMesh& m) {
    std::vector<std::vector<VertexId>> result;
    for (HalfedgeId start : boundary_loops(m)) {
        std::vector<VertexId>& loop = result.emplace_back();
        HalfedgeId h = start;
        do {
            loop.push_back(m.from(h));
            h = m.next(h);
        } while (h != start);
    }
    return result;
}

std::vector<std::pair<VertexId, VertexId>> hugging_pairs(const TriMesh& m) {
    std::vector<std::pair<VertexId, VertexId>> pairs;
    for (const std::vector<VertexId>& loop : boundary_loop_vertices(m)) {
        const std::size_t n = loop.size();
        const auto reflex = std::max_element(loop.begin(), loop.end(),
                                             [&](VertexId a, VertexId b) { return angle_sum(m, a) < angle_sum(m, b); });
        const auto r = static_cast<std::size_t>(reflex - loop.begin());
        for (std::size_t k = 1; k <= 3 && 2 * k < n; ++k) pairs.emplace_back(loop[(r + n - k) % n], loop[(r + k) % n]);
        if (n >= 4) pairs.emplace_back(loop[r], loop[(r + n / 2) % n]);
    }
    return pairs;
}

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

}  // namespace fhr::test
