// Beyond the paper (§3): the restricted shortest path (see restricted.hpp for the pseudocode).
#include <fhr/partition/detail/restricted.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <fhr/core/errors.hpp>
#include <fhr/partition/embed.hpp>

namespace fhr::partition {
namespace {

// The mask is not the region the precondition promises (a disk of T′_S whose boundary the path
// may touch only where it runs along it): found deep inside the walk, thrown to restricted_path's
// boundary only, and returned there as the reason (restricted.hpp).
struct NotTheRegion {
    std::string why;
};

class Restrictor {
public:
    // Works on the piece T_S of T around the region and on T′_S (partition/region.hpp).
    Restrictor(const Region& region, const FaceData<std::uint8_t>& mask, geodesic::Workspace* workspace)
        : region_(region), T_(region.sub()), net_(region.cut()), mask_(mask), workspace_(workspace) {}

    // The parameter of vertex x of T′ on T's edge E (along halfedge(E, 0)), when x lies on E.
    std::optional<double> param_on(EdgeId E, VertexId x) const {
        const Origin& o = net_.origin[x];
        const HalfedgeId h = TriMesh::halfedge(E, 0);
        if (o.vertex.valid()) {
            if (VertexId(o.vertex) == T_.from(h)) return 0.0;
            if (VertexId(o.vertex) == T_.to(h)) return 1.0;
            return std::nullopt;
        }
        if (EdgeId(o.edge) == E) return o.t;
        return std::nullopt;
    }

    // The edge of T that T′'s edge (a, b) runs along, if any (otherwise it is a chord of a face).
    std::optional<EdgeId> along(VertexId a, VertexId b) const {
        const Origin &oa = net_.origin[a], &ob = net_.origin[b];
        if (oa.vertex.valid() && ob.vertex.valid()) {
            const HalfedgeId h = T_.find_halfedge(VertexId(oa.vertex), VertexId(ob.vertex));
            if (h.valid()) return TriMesh::edge(h);
            return std::nullopt;
        }
        const EdgeId E(oa.vertex.valid() ? ob.edge : oa.edge);
        if (param_on(E, a) && param_on(E, b)) return E;
        return std::nullopt;
    }

    // Vertex x of T′ as a point of T.
    SurfacePoint place(VertexId x) const {
        const Origin& o = net_.origin[x];
        if (o.vertex.valid()) return SurfacePoint::at_vertex(VertexId(o.vertex));
        return SurfacePoint::on_edge(TriMesh::halfedge(EdgeId(o.edge), 0), o.t);
    }

    // The vertex of T at (or nearest to) vertex u of T′_S, for messages.
    VertexId near_in_t(VertexId u) const {
        const Origin& o = net_.origin[u];
        if (o.vertex.valid()) return region_.in_t(VertexId(o.vertex));
        const HalfedgeId h = TriMesh::halfedge(EdgeId(o.edge), 0);
        return region_.in_t(o.t < 0.5 ? T_.from(h) : T_.to(h));
    }

    bool masked(FaceId f) const { return f.valid() && mask_[f] != 0; }

    bool on_boundary(VertexId u) const {
        bool in = false, outside = false;
        net_.mesh.for_each_outgoing(u, [&](HalfedgeId h) { (masked(net_.mesh.face(h)) ? in : outside) = true; });
        return in && outside;
    }

    RestrictedPath run(VertexId from, VertexId to) {
        geodesic::ExactOptions options;
        options.face_mask = &mask_;
        options.workspace = workspace_;
        geodesic::ExactGeodesic search(net_.mesh, from, options);
        const VertexId targets[] = {to};
        search.propagate(targets);
        RestrictedPath out;
        out.shortest = search.distance(to);
        if (!std::isfinite(out.shortest))
            throw PartitionFailure("restricted path: vertex " + std::to_string(region_.in_t(to).idx()) +
                                   " cannot be reached from vertex " + std::to_string(region_.in_t(from).idx()) +
                                   " inside the region the other curves leave free");
        const std::vector<SurfacePoint> pts = snapped(search.path_to(to).points, out.separation_bound);
        std::vector<SurfacePoint>& nodes = out.path.points;
        auto push = [&](const SurfacePoint& p) {
            if (nodes.empty() || !same_location(T_, nodes.back(), p)) nodes.push_back(p);
        };
        for (std::size_t i = 0; i < pts.size(); ++i) {
            const SurfacePoint& p = pts[i];
            if (i == 0 || i + 1 == pts.size()) {
                push(SurfacePoint::at_vertex(p.vertex));
            } else if (p.kind == SurfacePoint::Kind::edge) {
                const VertexId a = net_.mesh.from(p.halfedge), b = net_.mesh.to(p.halfedge);
                if (const auto E = along(a, b)) {
                    const double s = (1 - p.t) * *param_on(*E, a) + p.t * *param_on(*E, b);
                    push(SurfacePoint::on_edge(TriMesh::halfedge(*E, 0), s));
                }  // else: across a chord inside a face of T, where the curve is straight: dropped
            } else if (p.kind == SurfacePoint::Kind::vertex) {
                if (!on_boundary(p.vertex)) {
                    push(place(p.vertex));
                } else {
                    // Two touched vertices joined by an edge of T′ inside the region that runs along an
                    // edge of T: their separation points may lie on its two sides, so the curve crosses
                    // it at its middle (no other curve is on it: both its faces are in the region).
                    const SurfacePoint& q = pts[i - 1];
                    if (i >= 2 && q.kind == SurfacePoint::Kind::vertex && on_boundary(q.vertex)) {
                        const HalfedgeId h = net_.mesh.find_halfedge(q.vertex, p.vertex);
                        const auto E = h.valid() ? along(q.vertex, p.vertex) : std::nullopt;
                        if (E && masked(net_.mesh.face(h)) && masked(net_.mesh.face(TriMesh::twin(h))))
                            push(SurfacePoint::on_edge(TriMesh::halfedge(*E, 0),
                                                       (*param_on(*E, q.vertex) + *param_on(*E, p.vertex)) / 2));
                    }
                    ++out.touches;
                    out.separation_bound += separate(p.vertex, pts[i - 1], pts[i + 1], push);
                }
            } else {
                throw NotTheRegion{"a node inside a face of T′"};
            }
        }
        nodes.front() = SurfacePoint::at_vertex(from);
        nodes.back() = SurfacePoint::at_vertex(to);
        for (std::size_t i = 1; i < nodes.size(); ++i)
            out.path.length += (position(T_, nodes[i]) - position(T_, nodes[i - 1])).norm();
        return out;
    }

private:
    // Γ*'s nodes within snap_fraction of an end of their edge of T′_S moved to that end, as embed
    // snaps every geodesic (a path through a vertex reaches it as an edge point a rounding error
    // away: 1e-12 of an edge beside a saddle of the block family, which then left the next curve no
    // room to separate). Each move of at most snap_fraction·|edge| lengthens the curve by at most
    // twice that, added to `bound`. A vertex reached twice (near a vertex whose edges differ in
    // length by more than 1/snap_fraction, the crossings of the long ones snap and those of a short
    // one between them do not: the quality family's needles) closes a loop, which is cut out: the
    // curve only gets shorter.
    std::vector<SurfacePoint> snapped(const std::vector<SurfacePoint>& star, double& bound) const {
        const TriMesh& m = net_.mesh;
        std::vector<SurfacePoint> pts;
        for (std::size_t i = 0; i < star.size(); ++i) {
            SurfacePoint p = star[i];
            if (i > 0 && i + 1 < star.size() && p.kind == SurfacePoint::Kind::edge &&
                (p.t <= snap_fraction || p.t >= 1 - snap_fraction)) {
                const VertexId a = m.from(p.halfedge), b = m.to(p.halfedge);
                bound += 2 * std::min(p.t, 1 - p.t) * (m.position(b) - m.position(a)).norm();
                p = SurfacePoint::at_vertex(p.t <= snap_fraction ? a : b);
            }
            if (p.kind == SurfacePoint::Kind::vertex) {
                const auto again = std::find_if(pts.begin(), pts.end(), [&](const SurfacePoint& q) {
                    return q.kind == SurfacePoint::Kind::vertex && q.vertex == p.vertex;
                });
                if (again != pts.end()) {
                    pts.erase(again + 1, pts.end());
                    continue;
                }
            }
            if (pts.empty() || !same_location(m, pts.back(), p)) pts.push_back(p);
        }
        return pts;
    }

    const Region& region_;
    const TriMesh& T_;
    const Network& net_;
    const FaceData<std::uint8_t>& mask_;
    geodesic::Workspace* workspace_;

    // Where neighbour point p of vertex u lies in u's fan of outgoing halfedges `fan` (clockwise):
    // 2k for the edge of fan[k], 2k − 1 for the face between fan[k − 1] and fan[k] (face(fan[k])).
    long fan_position(const std::vector<HalfedgeId>& fan, VertexId u, const SurfacePoint& p) const {
        const TriMesh& m = net_.mesh;
        auto edge_to = [&](VertexId w) -> long {
            for (std::size_t k = 0; k < fan.size(); ++k)
                if (m.to(fan[k]) == w) return static_cast<long>(2 * k);
            throw NotTheRegion{"a neighbour point is not beside its vertex"};
        };
        if (p.kind == SurfacePoint::Kind::vertex) return edge_to(p.vertex);
        if (p.kind != SurfacePoint::Kind::edge) throw NotTheRegion{"a node inside a face of T′"};
        const VertexId a = m.from(p.halfedge), b = m.to(p.halfedge);
        if (a == u) return edge_to(b);
        if (b == u) return edge_to(a);
        for (std::size_t k = 0; k < fan.size(); ++k) {
            const FaceId f = m.face(fan[k]);
            if (f == m.face(p.halfedge) || f == m.face(TriMesh::twin(p.halfedge))) return static_cast<long>(2 * k) - 1;
        }
        throw NotTheRegion{"a neighbour point is not in a face at its vertex"};
    }

    // Replaces the touched vertex u, between the path's points `in` and `out`, by points on the
    // edges of T crossed when walking around u inside the region from `in` to `out`. Returns the
    // bound 2·k·r of the length this adds (k points, each within r of u).
    template <class Push>
    double separate(VertexId u, const SurfacePoint& in, const SurfacePoint& out, Push&& push) {
        const TriMesh& m = net_.mesh;
        // u's fan, rotated to start just after a face outside the region: a walk from `in` to
        // `out` inside the region then never wraps around.
        std::vector<HalfedgeId> fan;
        m.for_each_outgoing(u, [&](HalfedgeId h) { fan.push_back(h); });
        const std::size_t n = fan.size();
        std::size_t start = 0;
        for (std::size_t k = 0; k < n; ++k)
            if (!masked(m.face(fan[k])) && masked(m.face(fan[(k + 1) % n]))) start = k;
        std::rotate(fan.begin(), fan.begin() + static_cast<std::ptrdiff_t>(start), fan.end());
        long a = fan_position(fan, u, in), b = fan_position(fan, u, out);
        if (a < 0) a += static_cast<long>(2 * n);
        if (b < 0) b += static_cast<long>(2 * n);
        const bool forward = a <= b;
        const long lo = std::min(a, b), hi = std::max(a, b);
        // The walk must stay in the region (it does for a path of the region: checked).
        for (long q = lo + 1; q < hi; q += 1)
            if (q % 2 == 1 && !masked(m.face(fan[static_cast<std::size_t>((q + 1) / 2) % n])))
                throw NotTheRegion{"the walk around a touched vertex leaves the region"};
        std::vector<SurfacePoint> points;
        double r = 0;
        for (long q = lo + 1; q < hi; ++q) {
            if (q % 2 != 0) continue;
            const HalfedgeId h = fan[static_cast<std::size_t>(q / 2)];
            const VertexId w = m.to(h);
            const auto E = along(u, w);
            if (!E) continue;  // a chord of a face of T: the points on either side are in that face
            const double su = *param_on(*E, u);
            // The next vertex of T′ on E: the replaced curve is not in T′_S, so it is another curve's
            // node or the far end of E.
            const double gap = std::abs(*param_on(*E, w) - su);
            // A third of the gap: a curve on the other side of the gap, separated towards u, stays apart.
            const double delta = std::min(separation_fraction, gap / 3);
            const double s = su + (*param_on(*E, w) > su ? delta : -delta);
            if (!(s > 0 && s < 1) || s == su || delta < min_separation) {
                char what[200];  // %g: the gap is below 3e-12 here, which std::to_string prints as 0.000000
                std::snprintf(
                    what, sizeof what,
                    "restricted path: no room to separate the curve from the curve near vertex %u (gap %g of an edge)",
                    static_cast<unsigned>(near_in_t(u).idx()), gap);
                throw PartitionFailure(what);
            }
            points.push_back(SurfacePoint::on_edge(TriMesh::halfedge(*E, 0), s));
            const HalfedgeId eh = TriMesh::halfedge(*E, 0);
            r = std::max(r, delta * (T_.position(T_.to(eh)) - T_.position(T_.from(eh))).norm());
        }
        if (!forward) std::reverse(points.begin(), points.end());
        for (const SurfacePoint& p : points) push(p);
        return 2.0 * static_cast<double>(points.size()) * r;
    }
};

}  // namespace

Outcome<RestrictedPath> restricted_path(const Region& region, const FaceData<std::uint8_t>& mask, VertexId from,
                                        VertexId to, geodesic::Workspace* workspace) {
    try {
        RestrictedPath r = Restrictor(region, mask, workspace).run(region.in_sub(from), region.in_sub(to));
        for (SurfacePoint& p : r.path.points) p = region.in_t(p);
        return r;
    } catch (const NotTheRegion& refused) {  // thrown only by the Restrictor above, never escapes
        return Outcome<RestrictedPath>::failure("restricted path: " + refused.why);
    }
}

}  // namespace fhr::partition
