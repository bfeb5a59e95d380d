// FHR §3 — the ellipse search for Γ(x_j, x_k) (see ellipse.hpp and paper_notes/ellipse.md).
#include "geodesic/ellipse.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/errors.hpp"
#include "geodesic/fast_marching.hpp"

namespace fhr::geodesic {
namespace {

// d_a(a, b): fast marching from a, its bound doubled until b is final. The straight-line
// distance is a lower bound of the geodesic one, so the first bound is never wasted by much.
double approximate_distance(const TriMesh& mesh, VertexId a, VertexId b) {
    double bound = 2 * (mesh.position(a) - mesh.position(b)).norm();
    for (;;) {
        const DistanceField f = fast_marching(mesh, std::span(&a, 1), {bound});
        if (std::isfinite(f.distance[b.idx()])) return f.distance[b.idx()];
        bound *= 2;
    }
}

// A face next to h that the mask leaves out (so h lies on T_jk's artificial boundary).
bool outside(const TriMesh& mesh, const std::vector<std::uint8_t>& mask, HalfedgeId h) {
    return !mesh.is_boundary(h) && !mask[mesh.face(h).idx()];
}

// The paper's test: the path touches a vertex of the artificial boundary, or runs along an edge
// next to a left-out face.
bool touches_boundary(const TriMesh& mesh, const std::vector<std::uint8_t>& mask, const GeodesicPath& path) {
    for (const SurfacePoint& p : path.points) {
        if (p.kind == SurfacePoint::Kind::vertex) {
            bool touches = false;
            mesh.for_each_outgoing(p.vertex, [&](HalfedgeId h) { touches = touches || outside(mesh, mask, h); });
            if (touches) return true;
        } else if (p.kind == SurfacePoint::Kind::edge) {
            if (outside(mesh, mask, p.halfedge) || outside(mesh, mask, TriMesh::twin(p.halfedge))) return true;
        }
    }
    return false;
}

// Distance from p to the segment [u, w].
double segment_distance(const Vec3& p, const Vec3& u, const Vec3& w) {
    const Vec3 e = w - u;
    const double len2 = e.squaredNorm();
    const double t = len2 > 0 ? std::clamp((p - u).dot(e) / len2, 0.0, 1.0) : 0.0;
    return (p - (u + t * e)).norm();
}

// Theorem (paper_notes/ellipse.md): a path from a to b that leaves T_jk first meets its
// artificial boundary at a point x of some boundary edge (u, w) of length ℓ. Its part up to x
// lies in T_jk, so it is at least d_R(a, x) long (d_R: exact distance within T_jk); d_R is
// 1-Lipschitz along the edge, so d_R(a, x) >= max(d_R(a,u) − |ux|, d_R(a,w) − |wx|)
// >= (d_R(a,u) + d_R(a,w) − ℓ) / 2. The rest is at least the straight-line distance from b to the
// edge. When that sum is at least the restricted length L on every boundary edge, no path
// through the outside is shorter, and the restricted path is a shortest path of T.
bool certified(const TriMesh& mesh, const std::vector<std::uint8_t>& mask, const ExactGeodesic& from_a, VertexId b,
               double L) {
    const Vec3& pb = mesh.position(b);
    for (HalfedgeId h : mesh.halfedges()) {
        if (mesh.is_boundary(h) || !mask[mesh.face(h).idx()] || !outside(mesh, mask, TriMesh::twin(h))) continue;
        const VertexId u = mesh.from(h), w = mesh.to(h);
        const Vec3 &pu = mesh.position(u), &pw = mesh.position(w);
        const double to_edge = 0.5 * (from_a.distance(u) + from_a.distance(w) - (pu - pw).norm());
        if (to_edge + segment_distance(pb, pu, pw) < L) return false;
    }
    return true;
}

}  // namespace

EllipsePath ellipse_shortest_path(const TriMesh& mesh, VertexId a, VertexId b, const EllipseOptions& options) {
    const std::size_t nv = mesh.n_vertices();
    if (a.idx() >= nv || b.idx() >= nv)
        throw InvalidInput("", 0, "vertex " + std::to_string(std::max(a.idx(), b.idx())) + " is out of range (the mesh has " +
                                      std::to_string(nv) + " vertices)");
    if (a == b) throw InvalidInput("", 0, "the two vertices are the same (" + std::to_string(a.idx()) + ")");
    if (!(options.K > 1)) throw InvalidInput("", 0, "K must be greater than 1");
    const double d_ab = approximate_distance(mesh, a, b);
    EllipsePath result;
    std::vector<std::uint8_t> mask(mesh.n_faces());
    for (double K = options.K;; K = 1 + 2 * (K - 1)) {
        const double bound = K * d_ab;
        const DistanceField from_a = fast_marching(mesh, std::span(&a, 1), {bound});
        const DistanceField from_b = fast_marching(mesh, std::span(&b, 1), {bound});
        std::fill(mask.begin(), mask.end(), 0);
        std::size_t faces = 0;
        for (VertexId v : from_a.finalized) {
            if (!(from_a.distance[v.idx()] + from_b.distance[v.idx()] <= bound)) continue;
            mesh.for_each_outgoing(v, [&](HalfedgeId h) {
                std::uint8_t& in = mask[mesh.face(h).idx()];
                faces += !in;
                in = 1;
            });
        }
        const bool everything = faces == mesh.n_faces();
        ExactGeodesic exact(mesh, a, {everything ? nullptr : &mask});
        exact.propagate();  // all of T_jk: the certificate needs d_R on its whole boundary
        GeodesicPath path = exact.path_to(b);
        result.attempts += 1;
        result.windows_created += exact.stats().windows_created;
        if (everything || (std::isfinite(path.length) && !touches_boundary(mesh, mask, path) &&
                           certified(mesh, mask, exact, b, path.length))) {
            result.path = std::move(path);
            result.K = K;
            result.ellipse_faces = faces;
            return result;
        }
    }
}

}  // namespace fhr::geodesic
