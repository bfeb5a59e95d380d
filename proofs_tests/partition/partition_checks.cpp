// FHR tests — PART-1..8 of spec/partition.md, independent of how src/fhr/partition computes them.
#include "partition/partition_checks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include <fhr/core/geometry.hpp>
#include <fhr/core/topology.hpp>
#include <fhr/geodesic/ellipse.hpp>
#include <fhr/param/disk.hpp>

namespace fhr::test {

std::vector<geodesic::GeodesicPath> exact_paths(const TriMesh& T, const domain::Domain& D) {
    std::vector<geodesic::GeodesicPath> paths;
    for (const auto& [a, b] : domain::edge_endpoints(D)) paths.push_back(geodesic::ellipse_shortest_path(T, a, b).path);
    return paths;
}

namespace {

// Distance from p to the segment [a, b].
double segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
    const Vec3 e = b - a;
    const double t = std::clamp((p - a).dot(e) / e.squaredNorm(), 0.0, 1.0);
    return (p - (a + t * e)).norm();
}

// The faces of T whose closure holds vertex v of T′ (its own vertex's faces, or its edge's two).
std::set<std::uint32_t> faces_holding(const TriMesh& T, const partition::Origin& o) {
    std::set<std::uint32_t> s;
    auto add = [&](FaceId f) {
        if (f.valid()) s.insert(f.idx());  // a boundary halfedge has no face
    };
    if (o.vertex.valid()) {
        T.for_each_outgoing(VertexId(o.vertex), [&](HalfedgeId h) { add(T.face(h)); });
    } else {
        add(T.face(TriMesh::halfedge(EdgeId(o.edge), 0)));
        add(T.face(TriMesh::halfedge(EdgeId(o.edge), 1)));
    }
    return s;
}

// Components, boundary loops and χ of a mesh (the topology §2–§3 keep).
std::tuple<std::size_t, std::size_t, long> topology(const TriMesh& m) {
    return {connected_components(m).count, boundary_loops(m).size(), euler_characteristic(m)};
}

// PART-13: the faces of T′ in one face F of T, joined across the edges on no curve, are the pieces
// the curves' chords cut F into; each is a convex polygon of points on F's sides, triangulated
// with the largest smallest angle of all its triangulations. The optimum is found here again by
// dynamic programming over the polygon's sub-polygons (Klincsek), with the same measure: a
// triangle's smallest angle (atan2 of |u × w| and u · w, at least the least positive double), or
// −1 for three corners on one side of F.
std::string piece_violation(const TriMesh& T, const partition::Network& net) {
    const TriMesh& M = net.mesh;
    std::vector<std::uint32_t> piece(M.n_faces());
    for (std::uint32_t f = 0; f < M.n_faces(); ++f) piece[f] = f;
    const auto root = [&](std::uint32_t f) {
        while (piece[f] != f) f = piece[f] = piece[piece[f]];
        return f;
    };
    for (HalfedgeId h : M.halfedges()) {
        const HalfedgeId t = TriMesh::twin(h);
        if (M.is_boundary(h) || M.is_boundary(t) || net.d_halfedge[h].valid()) continue;
        const FaceId f = M.face(h), g = M.face(t);
        if (net.t_face[f] == net.t_face[g]) piece[root(f.idx())] = root(g.idx());
    }
    std::vector<std::vector<FaceId>> pieces(M.n_faces());
    for (FaceId f : M.faces()) pieces[root(f.idx())].push_back(f);
    // The sides of F a vertex of T′ lies on, as bits of F's three edges.
    const auto sides = [&](VertexId v, FaceId F) {
        const partition::Origin& o = net.origin[v];
        unsigned bits = 0;
        HalfedgeId h = T.halfedge(F);
        for (unsigned s = 0; s < 3; ++s, h = T.next(h))
            if (o.vertex.valid() ? (T.from(h) == VertexId(o.vertex) || T.to(h) == VertexId(o.vertex))
                                 : TriMesh::edge(h) == EdgeId(o.edge))
                bits |= 1u << s;
        return bits;
    };
    for (const std::vector<FaceId>& faces : pieces) {
        if (faces.size() < 2) continue;  // a triangle has one triangulation
        const FaceId F(net.t_face[faces.front()]);
        std::set<std::uint32_t> in_piece;
        for (FaceId f : faces) in_piece.insert(f.idx());
        std::map<std::uint32_t, std::uint32_t> after;  // the piece's boundary, vertex to next vertex
        for (FaceId f : faces) {
            HalfedgeId h = M.halfedge(f);
            for (int k = 0; k < 3; ++k, h = M.next(h)) {
                const HalfedgeId t = TriMesh::twin(h);
                if (!M.is_boundary(t) && in_piece.count(M.face(t).idx())) continue;
                if (!after.emplace(M.from(h).idx(), M.to(h).idx()).second)
                    return "PART-13: a piece of a face of T is not a disk";
            }
        }
        std::vector<VertexId> polygon{VertexId(after.begin()->first)};
        while (polygon.size() <= after.size()) {
            const auto next = after.find(polygon.back().idx());
            if (next == after.end()) return "PART-13: a piece's boundary is not a loop";
            if (next->second == polygon.front().idx()) break;
            polygon.push_back(VertexId(next->second));
        }
        const std::size_t m = polygon.size();
        if (m != after.size() || faces.size() != m - 2) return "PART-13: a piece of a face of T has vertices inside";
        std::map<std::uint32_t, std::size_t> at;
        std::vector<unsigned> mask(m);
        for (std::size_t i = 0; i < m; ++i) {
            at[polygon[i].idx()] = i;
            mask[i] = sides(polygon[i], F);
        }
        const auto quality = [&](std::size_t a, std::size_t b, std::size_t c) {
            if (mask[a] & mask[b] & mask[c]) return -1.0;
            const Vec3 p[3] = {M.position(polygon[a]), M.position(polygon[b]), M.position(polygon[c])};
            double smallest = INFINITY;
            for (int k = 0; k < 3; ++k) {
                const Vec3 u = p[(k + 1) % 3] - p[k], w = p[(k + 2) % 3] - p[k];
                smallest = std::min(smallest, std::atan2(u.cross(w).norm(), u.dot(w)));
            }
            return std::max(smallest, std::numeric_limits<double>::denorm_min());
        };
        std::vector<double> best(m * m, INFINITY);  // best[i·m + j]: the optimum of sub-polygon i..j
        for (std::size_t len = 2; len < m; ++len)
            for (std::size_t i = 0; i + len < m; ++i) {
                const std::size_t j = i + len;
                best[i * m + j] = -INFINITY;
                for (std::size_t k = i + 1; k < j; ++k)
                    best[i * m + j] =
                        std::max(best[i * m + j], std::min({best[i * m + k], best[k * m + j], quality(i, k, j)}));
            }
        double made = INFINITY;
        for (FaceId f : faces) {
            const auto v = M.face_vertices(f);
            made = std::min(made, quality(at.at(v[0].idx()), at.at(v[1].idx()), at.at(v[2].idx())));
        }
        if (made != best[m - 1]) {
            std::ostringstream why;
            why.precision(17);
            why << "PART-13: a piece of face " << F.idx() << " of T (" << m
                << " corners) is triangulated with smallest angle " << made << ", its best triangulation has "
                << best[m - 1];
            return why.str();
        }
    }
    return "";
}

}  // namespace

std::string partition_violation(const TriMesh& T, const partition::Partition& P) {
    std::ostringstream why;
    const TriMesh& M = P.network.mesh;
    const domain::Domain& D = P.domain;
    // PART-1: T′ is a valid triangulation with T's Euler characteristic, boundary loops and components.
    try {
        M.validate();
    } catch (const std::logic_error& e) {
        return std::string("PART-1: ") + e.what();
    }
    if (topology(M) != topology(T)) return "PART-1: T′ does not have T's components, boundary loops and χ";
    // PART-2: Ω_T′ = Ω_T — T's vertices kept in place, new vertices on T's edges, every face of
    // T′ inside a face of T, the same area.
    if (M.n_vertices() < T.n_vertices() || P.network.origin.size() != M.n_vertices()) return "PART-2: vertex count";
    for (VertexId v : T.vertices())
        if (M.position(v) != T.position(v) || P.network.origin[v].vertex != TVertexId(v)) {
            why << "PART-2: vertex " << v.idx() << " of T moved";
            return why.str();
        }
    for (std::size_t i = T.n_vertices(); i < M.n_vertices(); ++i) {
        const partition::Origin& o = P.network.origin[VertexId(static_cast<VertexId::Index>(i))];
        if (o.vertex.valid() || !(o.t > 0 && o.t < 1)) return "PART-2: a new vertex is not inside an edge of T";
        const HalfedgeId h = TriMesh::halfedge(EdgeId(o.edge), 0);
        const Vec3 &a = T.position(T.from(h)), &b = T.position(T.to(h));
        if (segment_distance(M.position(VertexId(static_cast<VertexId::Index>(i))), a, b) > 1e-12 * (b - a).norm()) {
            why << "PART-2: vertex " << i << " of T′ is off its edge " << o.edge.idx() << " of T";
            return why.str();
        }
    }
    for (FaceId f : M.faces()) {
        const auto v = M.face_vertices(f);
        std::set<std::uint32_t> common = faces_holding(T, P.network.origin[v[0]]);
        for (int k = 1; k < 3; ++k) {
            const auto s = faces_holding(T, P.network.origin[v[static_cast<std::size_t>(k)]]);
            std::set<std::uint32_t> both;
            std::set_intersection(common.begin(), common.end(), s.begin(), s.end(), std::inserter(both, both.begin()));
            common = both;
        }
        if (common.empty()) {
            why << "PART-2: face " << f.idx() << " of T′ lies in no face of T";
            return why.str();
        }
    }
    double area_t = 0, area_m = 0;
    for (FaceId f : T.faces()) area_t += face_area(T, f);
    for (FaceId f : M.faces()) area_m += face_area(M, f);
    // Rounding: each of the ~#F area terms is exact to a few ulps, so the sums agree to ~1e−13.
    if (std::abs(area_t - area_m) > 1e-12 * area_t) return "PART-2: the area of T′ differs from T's";
    // PART-3: one path per D edge, from x_j to x_k, its segments edges of T′ carrying its D halfedge.
    if (P.network.path.size() != D.mesh.n_edges() || P.paths.size() != D.mesh.n_edges()) return "PART-3: path count";
    std::vector<int> on_path(M.n_vertices(), -1);
    for (EdgeId e : D.mesh.edges()) {
        const auto& path = P.network.path[DEdgeId(e)];
        const DHalfedgeId dh(TriMesh::halfedge(e, 0));
        if (path.size() < 2 || path.front() != D.t_vertex[D.mesh.from(HalfedgeId(dh))] ||
            path.back() != D.t_vertex[D.mesh.to(HalfedgeId(dh))])
            return "PART-3: a path does not join its corners";
        double length = 0;
        for (std::size_t i = 0; i + 1 < path.size(); ++i) {
            const HalfedgeId h = M.find_halfedge(path[i], path[i + 1]);
            if (!h.valid() || P.network.d_halfedge[h] != dh ||
                P.network.d_halfedge[TriMesh::twin(h)] != TriMesh::twin(dh))
                return "PART-3: a path segment is not a labelled edge of T′";
            length += (M.position(path[i + 1]) - M.position(path[i])).norm();
        }
        // Snapping moves each node by at most max_snap_distance: the embedded curve is at most
        // 2·(#nodes)·max_snap longer than the exact geodesic, and never shorter than it by more than rounding.
        const double L = P.paths[e].path.length;
        if (length < L * (1 - 1e-12) ||
            length > L * (1 + 1e-12) + 2 * static_cast<double>(path.size()) * P.network.max_snap_distance) {
            why << "PART-3: the curve of domain edge " << e.idx() << " is " << length << " long, its geodesic " << L;
            return why.str();
        }
        // PART-4: condition (1) — the curves' interiors are disjoint and hold no corner.
        for (std::size_t i = 1; i + 1 < path.size(); ++i) {
            if (P.network.corner[path[i]].valid() || on_path[path[i].idx()] >= 0) {
                why << "PART-4: the curve of domain edge " << e.idx() << " meets another curve or a corner at vertex "
                    << path[i].idx();
                return why.str();
            }
            on_path[path[i].idx()] = static_cast<int>(e.idx());
        }
    }
    std::size_t labelled = 0;
    for (DHalfedgeId d : P.network.d_halfedge) labelled += d.valid();
    std::size_t segments = 0;
    for (const auto& path : P.network.path) segments += path.size() - 1;
    if (labelled != 2 * segments) return "PART-3: edges of T′ carry labels of no path";
    // PART-5: condition (2) — around x_j the curves leave in the order of D's edges around v_j.
    for (VertexId vj : D.mesh.vertices()) {
        std::vector<DHalfedgeId> d_order, t_order;
        D.mesh.for_each_outgoing(vj, [&](HalfedgeId h) { d_order.push_back(DHalfedgeId(h)); });
        M.for_each_outgoing(D.t_vertex[vj], [&](HalfedgeId h) {
            if (P.network.d_halfedge[h].valid()) t_order.push_back(P.network.d_halfedge[h]);
        });
        const auto it = std::find(t_order.begin(), t_order.end(), d_order.front());
        if (it == t_order.end() || t_order.size() != d_order.size())
            return "PART-5: the curves at a corner are not D's edges";
        std::rotate(t_order.begin(), it, t_order.end());
        if (t_order != d_order) {
            why << "PART-5: the cyclic order at domain vertex " << vj.idx() << " differs from D's";
            return why.str();
        }
    }
    // PART-6: every face of T′ in exactly one patch, one patch per face of D.
    const auto& patches = P.patches;
    if (patches.patch.size() != D.mesh.n_faces() || patches.patch_of_face.size() != M.n_faces())
        return "PART-6: patch count";
    std::vector<int> seen(M.n_faces(), 0);
    for (FaceId df : D.mesh.faces())
        for (FaceId f : patches.patch[df].faces) {
            if (patches.patch_of_face[f] != df) return "PART-6: patch_of_face disagrees with the patch's faces";
            ++seen[f.idx()];
        }
    if (std::any_of(seen.begin(), seen.end(), [](int s) { return s != 1; }))
        return "PART-6: a face of T′ is not in exactly one patch";
    // PART-7: patch adjacency is D's — across every curve edge, the patches of D's two faces.
    for (HalfedgeId h : M.halfedges()) {
        const HalfedgeId dh(P.network.d_halfedge[h]);
        if (M.is_boundary(h)) {
            // PART-12: T′'s boundary lies on the curves of D's boundary edges.
            if (!dh.valid() || !D.mesh.is_boundary(dh))
                return "PART-12: a boundary edge of T′ is on no boundary curve of D";
            continue;
        }
        if (dh.valid() && patches.patch_of_face[M.face(h)] != D.mesh.face(dh))
            return "PART-7: a patch borders a curve of a domain face it does not belong to";
        if (!dh.valid() && !M.is_boundary(TriMesh::twin(h)) &&
            patches.patch_of_face[M.face(h)] != patches.patch_of_face[M.face(TriMesh::twin(h))])
            return "PART-7: two patches meet along an edge that is on no curve";
    }
    // PART-8: each patch is a disk bounded by the three curves of its face, corners at x_j, x_k, x_l.
    for (FaceId df : D.mesh.faces()) {
        const partition::Patch& p = patches.patch[df];
        if (const auto broken = param::disk_violation(p.disk)) {
            why << "PART-8: patch " << df.idx() << ": " << broken->what;
            return why.str();
        }
        const auto corners = D.mesh.face_vertices(df);
        for (std::size_t c = 0; c < 3; ++c)
            if (p.vertices[p.disk.boundary[p.disk.corners[c]]] != D.t_vertex[corners[c]])
                return "PART-8: a corner is misplaced";
        for (std::size_t i = 0; i < p.vertices.size(); ++i)
            if (p.disk.positions[i] != M.position(p.vertices[i]))
                return "PART-8: a patch vertex's position differs from T′'s";
    }
    return piece_violation(T, P.network);
}

std::string recovery_violation(const TriMesh& T, const domain::Domain& D0, const partition::Partition& P) {
    const domain::Domain& D = P.domain;
    try {
        D.mesh.validate();
    } catch (const std::logic_error& e) {
        return std::string("PART-9: ") + e.what();
    }
    if (topology(D.mesh) != topology(T)) return "PART-9: D lost T's topology";
    if (D.t_vertex.size() != D.mesh.n_vertices()) return "PART-9: correspondence size";
    std::vector<int> in_d(T.n_vertices(), 0);
    for (VertexId j : D.t_vertex.ids()) {
        if (D.mesh.position(j) != T.position(D.t_vertex[j])) return "PART-9: a vertex of D is not at its x_j";
        ++in_d[D.t_vertex[j].idx()];
    }
    for (VertexId v : P.kept)
        if (in_d[v.idx()] != 1) return "PART-9: a kept vertex is not a vertex of D";
    if (P.vertices_added != D.mesh.n_vertices() - D0.mesh.n_vertices()) return "PART-9: vertices_added is wrong";
    if (P.retries == 0 && D.mesh.triangles() != D0.mesh.triangles()) return "PART-9: D changed without a retry";
    return "";
}

std::string keep_violation(const TriMesh& T, const domain::Domain& D0, const partition::Partition& P) {
    if (P.domain.mesh.triangles() != D0.mesh.triangles() || P.domain.t_vertex != D0.t_vertex)
        return "PART-10: D was changed";
    if (P.retries != 0 || P.curves.size() != D0.mesh.n_edges()) return "PART-10: retries or curve count";
    const auto ends = domain::edge_endpoints(D0);
    for (EdgeId e : P.curves.ids()) {
        const partition::CurveInfo& c = P.curves[e];
        const double g = geodesic::ellipse_shortest_path(T, ends[e.idx()].first, ends[e.idx()].second).path.length;
        const double L = P.paths[e].path.length;
        std::ostringstream why;
        why << "PART-10: domain edge " << e.idx() << " (L " << L << ", geodesic " << g << ", restricted shortest "
            << c.shortest << ", bound " << c.separation_bound << "): ";
        if (c.kind == partition::CurveKind::boundary) {
            // PART-12: the arc of T's boundary between the ends, T's faces on its left.
            const auto& pts = P.paths[e].path.points;
            if (!D0.mesh.is_boundary(e)) return why.str() + "an interior edge of D has a boundary curve";
            for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
                if (pts[i].kind != SurfacePoint::Kind::vertex || pts[i + 1].kind != SurfacePoint::Kind::vertex)
                    return why.str() + "a boundary curve leaves T's vertices";
                const HalfedgeId h = T.find_halfedge(pts[i].vertex, pts[i + 1].vertex);
                const bool d_face_left = !D0.mesh.is_boundary(TriMesh::halfedge(e, 0));
                if (!h.valid() || T.is_boundary(h) == d_face_left || !T.is_boundary(TriMesh::twin(h)) == d_face_left)
                    return why.str() + "a boundary curve is not along T's boundary with D's face on T's side";
                if (i > 0 && std::binary_search(D0.t_vertex.begin(), D0.t_vertex.end(), pts[i].vertex))
                    return why.str() + "a boundary curve passes a corner of D";
            }
            continue;
        }
        if (D0.mesh.is_boundary(e)) return why.str() + "a boundary edge of D without its boundary curve";
        if (std::abs(c.geodesic_length - g) > 1e-12 * g) return why.str() + "the reported geodesic length is wrong";
        if (c.kind == partition::CurveKind::geodesic) {
            if (std::abs(L - g) > 1e-9 * g) return why.str() + "a curve called geodesic is not a shortest path";
            continue;
        }
        if (c.reason.empty()) return why.str() + "a restricted curve without its reason";
        if (c.shortest < g * (1 - 1e-12)) return why.str() + "the restricted shortest length is below the geodesic's";
        if (L < c.shortest * (1 - 1e-9))
            return why.str() + "the separated curve is shorter than the restricted shortest";
        if (L > c.shortest + c.separation_bound + 1e-12 * L)
            return why.str() + "the separation added more than its bound";
    }
    return "";
}

}  // namespace fhr::test
