// FHR §3 — embedding the geodesic network into T (eq. 1, Fig. 3); conditions (1) and (2).
// See embed.hpp for the pseudocode and paper_notes/partition.md for the decisions.
#include <fhr/partition/embed.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fhr/core/errors.hpp>

namespace fhr::partition {
namespace {

using Kind = Conflict::Kind;

// A node of a path on T: a vertex, or the point at parameter t of T's halfedge(edge, 0).
struct Node {
    VertexId vertex;
    EdgeId edge;
    double t = 0;
};

// A chord: a segment of path `d_edge` across face `face` of T between two vertices of T′.
struct Chord {
    FaceId face;
    VertexId a, b;
    std::uint32_t d_edge;
};

// A piece of path `d_edge` along T's edge `edge`, between parameters t0 < t1.
struct Run {
    EdgeId edge;
    double t0, t1;
    std::uint32_t d_edge;
};

// Bit s is set when a point of a face's boundary lies on the face's side s (side s runs from
// corner s to corner s + 1); corners lie on two sides.
using SideMask = std::uint8_t;

class Embedder {
public:
    // With D: paths[e] runs between the corners x_j, x_k of D's halfedge (e, 0), and (2) is checked.
    // Without: the corners are the paths' ends (numbered in order of first appearance).
    Embedder(const TriMesh& T, const domain::Domain* D, std::span<const geodesic::GeodesicPath> paths,
             std::span<const std::uint8_t> unsnapped, Executor& executor)
        : T_(T), D_(D), paths_(paths), unsnapped_(unsnapped), executor_(executor) {
        Network& n = out_.network;
        n.corner.assign(T.n_vertices(), DVertexId());
        if (D) {
            for (VertexId j : D->t_vertex.ids()) n.corner[D->t_vertex[j]] = DVertexId(j);
            ends_ = domain::edge_endpoints(*D);
        } else {
            DVertexId::Index corners = 0;
            for (const geodesic::GeodesicPath& p : paths) {
                if (p.points.size() < 2 || p.points.front().kind != SurfacePoint::Kind::vertex ||
                    p.points.back().kind != SurfacePoint::Kind::vertex)
                    throw ContractViolation("embed: a curve does not run between two vertices");
                ends_.emplace_back(p.points.front().vertex, p.points.back().vertex);
                for (VertexId x : {p.points.front().vertex, p.points.back().vertex})
                    if (!n.corner[x].valid()) n.corner[x] = DVertexId(corners++);
            }
        }
        n.on_path.assign(T.n_vertices(), PathPosition{});
        n.origin.resize(T.n_vertices());
        for (VertexId v : T.vertices()) n.origin[v].vertex = TVertexId(v);
        positions_.assign(T.positions().begin(), T.positions().end());
        slot_.assign(T.n_edges(), none);
    }

    Embedding run() {
        if (D_ && paths_.size() != D_->mesh.n_edges())
            throw ContractViolation("embed: one path per edge of D is needed");
        for (std::uint32_t e = 0; e < paths_.size(); ++e) add_path(e);
        check_runs();
        std::vector<Triangle> triangles;
        triangles.reserve(T_.n_faces() + 2 * chords_.size());
        triangulate_faces(triangles);
        if (!out_.conflicts.empty()) return std::move(out_);
        Network& n = out_.network;
        n.mesh = TriMesh::from_triangles(std::move(positions_), triangles);
        label_paths();
        if (D_) check_order();
        return std::move(out_);
    }

private:
    const TriMesh& T_;
    const domain::Domain* D_;
    std::vector<std::pair<VertexId, VertexId>> ends_;  // per path: x_j, x_k
    std::span<const geodesic::GeodesicPath> paths_;
    std::span<const std::uint8_t> unsnapped_;
    Executor& executor_;
    Embedding out_;
    std::vector<Vec3> positions_;
    // Per edge of T: its nodes as (t, vertex of T′), in order of registration: on_edge_[slot_[e]],
    // where slot_[e] is `none` for the edges no path crosses or runs along (most of them: a
    // direct array rather than a hash map, since every face of T asks for its three edges).
    static constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> slot_;
    std::vector<std::vector<std::pair<double, VertexId>>> on_edge_;
    std::vector<Chord> chords_;
    std::vector<Run> runs_;

    static Conflict make_conflict(Kind kind, std::uint32_t a, std::uint32_t b, std::array<VertexId, 3> near,
                                  DVertexId d_vertex = {}) {
        return Conflict{kind,
                        DEdgeId(std::min(a, b)),
                        DEdgeId(std::max(a, b)),
                        d_vertex,
                        {TVertexId(near[0]), TVertexId(near[1]), TVertexId(near[2])}};
    }
    void conflict(Kind kind, std::uint32_t a, std::uint32_t b, std::array<VertexId, 3> near, DVertexId d_vertex = {}) {
        out_.conflicts.push_back(make_conflict(kind, a, b, near, d_vertex));
    }

    // The vertex of T nearest to vertex v of T′: itself, or the nearer end of its edge of T.
    VertexId nearest(VertexId v) const {
        const Origin& o = out_.network.origin[v];
        if (o.vertex.valid()) return VertexId(o.vertex);
        const HalfedgeId h = TriMesh::halfedge(EdgeId(o.edge), 0);
        return o.t < 0.5 ? T_.from(h) : T_.to(h);
    }

    // The path's node as a vertex or an edge point of T (canonical edge direction), snapped.
    Node node_of(const SurfacePoint& p, bool snap) {
        if (p.kind == SurfacePoint::Kind::vertex) return Node{p.vertex, {}, 0};
        if (p.kind != SurfacePoint::Kind::edge) throw ContractViolation("embed: a path node inside a face");
        const EdgeId e = TriMesh::edge(p.halfedge);
        const double t = (p.halfedge.idx() & 1u) ? 1 - p.t : p.t;
        const HalfedgeId h = TriMesh::halfedge(e, 0);
        if (snap && (t <= snap_fraction || t >= 1 - snap_fraction)) {
            const VertexId v = t <= snap_fraction ? T_.from(h) : T_.to(h);
            const double moved = (T_.position(v) - position(T_, p)).norm();
            out_.network.max_snap_distance = std::max(out_.network.max_snap_distance, moved);
            return Node{v, {}, 0};
        }
        return Node{{}, e, t};
    }

    // The vertex of T′ at a node, created on first use. Two nodes on one edge are one point when
    // their parameters differ by at most same_point_t or give the same position: a node given on
    // the edge's other halfedge has t = 1 − t′, exact only to half an ulp of 1, and two windows of
    // the exact algorithm meet an edge at parameters a few ulps apart. Two vertices of T′ there
    // would leave a piece of the face with no proper triangle (a regression: two paths through
    // one point of an edge, found by the pipeline property over several components).
    static constexpr double same_point_t = 0x1p-50;
    VertexId vertex_of(const Node& n) {
        if (n.vertex.valid()) return n.vertex;
        std::uint32_t& slot = slot_[n.edge.idx()];
        if (slot == none) {
            slot = static_cast<std::uint32_t>(on_edge_.size());
            on_edge_.emplace_back();
        }
        auto& list = on_edge_[slot];
        const HalfedgeId h = TriMesh::halfedge(n.edge, 0);
        const Vec3 at = (1 - n.t) * T_.position(T_.from(h)) + n.t * T_.position(T_.to(h));
        for (const auto& [t, v] : list)
            if (std::abs(t - n.t) <= same_point_t || positions_[v.idx()] == at) return v;
        const VertexId v(static_cast<VertexId::Index>(positions_.size()));
        positions_.push_back(at);
        Network& net = out_.network;
        net.origin.push_back(Origin{{}, TEdgeId(n.edge), n.t});
        net.on_path.push_back(PathPosition{});
        net.corner.push_back(DVertexId());
        list.emplace_back(n.t, v);
        return v;
    }

    void add_path(std::uint32_t e) {
        const auto [xj, xk] = ends_[e];
        const auto& points = paths_[e].points;
        if (points.size() < 2 || points.front().kind != SurfacePoint::Kind::vertex || points.front().vertex != xj ||
            points.back().kind != SurfacePoint::Kind::vertex || points.back().vertex != xk)
            throw ContractViolation("embed: the path of D edge " + std::to_string(e) + " does not run from x_j to x_k");
        std::vector<Node> nodes;
        for (const SurfacePoint& p : points) {
            const Node n = node_of(p, unsnapped_.empty() || !unsnapped_[e]);
            if (nodes.empty() || !same(nodes.back(), n)) nodes.push_back(n);
        }
        Network& net = out_.network;
        std::vector<VertexId>& path = net.path.emplace_back();
        for (const Node& n : nodes) path.push_back(vertex_of(n));
        for (std::size_t i = 1; i + 1 < nodes.size(); ++i) {
            const VertexId v = path[i];
            if (net.corner[v].valid()) {
                // Γ(x_j, x_k) runs over x_m: D needs vertices beside x_m on it (paper_notes/partition.md).
                conflict(Kind::through_corner, e, e, {nearest(path[i - 1]), nearest(path[i + 1]), {}}, net.corner[v]);
            } else if (net.on_path[v].d_edge.valid()) {
                conflict(Kind::shared_node, net.on_path[v].d_edge.idx(), e, {nearest(v), {}, {}});
            } else {
                net.on_path[v] = PathPosition{DEdgeId(e), static_cast<std::uint32_t>(i)};
            }
        }
        for (std::size_t i = 0; i + 1 < nodes.size(); ++i) add_segment(nodes[i], nodes[i + 1], path[i], path[i + 1], e);
    }

    static bool same(const Node& a, const Node& b) {
        return a.vertex.valid() ? a.vertex == b.vertex : (!b.vertex.valid() && a.edge == b.edge && a.t == b.t);
    }

    // Parameter of vertex v of T along T's halfedge(e, 0), or NaN when v is not an end of e.
    double end_parameter(EdgeId e, VertexId v) const {
        const HalfedgeId h = TriMesh::halfedge(e, 0);
        if (T_.from(h) == v) return 0;
        if (T_.to(h) == v) return 1;
        return std::numeric_limits<double>::quiet_NaN();
    }

    // Segment [a, b] of path e: a run along an edge of T or a chord of a face of T.
    void add_segment(const Node& a, const Node& b, VertexId va, VertexId vb, std::uint32_t e) {
        auto run = [&](EdgeId edge, double ta, double tb) {
            runs_.push_back(Run{edge, std::min(ta, tb), std::max(ta, tb), e});
        };
        if (a.vertex.valid() && b.vertex.valid()) {
            const HalfedgeId h = T_.find_halfedge(a.vertex, b.vertex);
            if (!h.valid())
                throw ContractViolation("embed: consecutive path vertices are not adjacent (D edge " +
                                        std::to_string(e) + ")");
            const EdgeId edge = TriMesh::edge(h);
            return run(edge, end_parameter(edge, a.vertex), end_parameter(edge, b.vertex));
        }
        if (!a.vertex.valid() && !b.vertex.valid() && a.edge == b.edge) return run(a.edge, a.t, b.t);
        const Node& p = a.vertex.valid() ? b : a;  // an edge node
        const Node& q = a.vertex.valid() ? a : b;  // a vertex, or another edge node
        if (q.vertex.valid() && !std::isnan(end_parameter(p.edge, q.vertex)))
            return run(p.edge, p.t, end_parameter(p.edge, q.vertex));
        for (unsigned side = 0; side < 2; ++side) {
            const HalfedgeId h = TriMesh::halfedge(p.edge, side);
            const HalfedgeId h1 = T_.next(h), h2 = T_.next(h1);
            const bool holds =
                q.vertex.valid() ? T_.to(h1) == q.vertex : (TriMesh::edge(h1) == q.edge || TriMesh::edge(h2) == q.edge);
            if (holds) return chords_.push_back(Chord{T_.face(h), va, vb, e});
        }
        throw ContractViolation("embed: consecutive path nodes share no face (D edge " + std::to_string(e) + ")");
    }

    // (1) along edges: a path running along a piece of an edge of T must not contain another
    // path's node (which would be a crossing or an overlap).
    void check_runs() {
        const Network& net = out_.network;
        for (const Run& r : runs_) {
            if (slot_[r.edge.idx()] == none) continue;
            for (const auto& [t, v] : on_edge_[slot_[r.edge.idx()]]) {
                if (t > r.t0 && t < r.t1)
                    conflict(Kind::shared_node, r.d_edge, net.on_path[v].d_edge.idx(), {nearest(v), {}, {}});
            }
        }
    }

    // The arrays of one face's triangulation, reused from face to face within a block
    // (allocated per face, a full embedding of the horse's network took 79–93 ms on one thread,
    // 64–66 ms with them reused).
    struct FaceScratch {
        std::vector<VertexId> poly;  // the face's boundary polygon: corners and nodes in order
        std::vector<SideMask> mask;  // per polygon vertex, the sides it lies on
        std::vector<std::pair<double, VertexId>> along;
        std::vector<std::pair<std::size_t, std::size_t>> cuts;
        std::vector<std::vector<std::size_t>> pieces;
        std::vector<double> best;
        std::vector<std::size_t> apex;
        std::vector<std::pair<std::size_t, std::size_t>> stack;
    };

    // Appends the nodes on T's halfedge h, in the direction of h, to the polygon, on side s.
    void append_nodes_along(HalfedgeId h, unsigned s, FaceScratch& x) const {
        const std::uint32_t slot = slot_[TriMesh::edge(h).idx()];
        if (slot == none) return;
        x.along.assign(on_edge_[slot].begin(), on_edge_[slot].end());
        std::sort(x.along.begin(), x.along.end());
        if (h.idx() & 1u) std::reverse(x.along.begin(), x.along.end());
        for (const auto& [t, v] : x.along) {
            x.poly.push_back(v);
            x.mask.push_back(static_cast<SideMask>(1u << s));
        }
    }

    // The faces in blocks, in parallel: each block's triangles, their faces of T and
    // its crossings, joined in face order, so the result is the sequential one. Once (1) fails no
    // face is triangulated (the caller needs only the conflicts): the earlier conflicts stop every
    // block, a block's own stop it.
    void triangulate_faces(std::vector<Triangle>& triangles) {
        std::sort(chords_.begin(), chords_.end(),
                  [](const Chord& x, const Chord& y) { return x.face.idx() < y.face.idx(); });
        struct Block {
            std::vector<Triangle> triangles;
            std::vector<FaceId> t_face;
            std::vector<Conflict> conflicts;
        };
        constexpr std::size_t block = std::size_t{1} << 14;
        const std::size_t nf = T_.n_faces(), nb = (nf + block - 1) / block;
        const bool failed = !out_.conflicts.empty();
        std::vector<Block> blocks(nb);
        executor_.for_each(nb, 2, [&](std::size_t b) {
            Block& out = blocks[b];
            const auto first_face = static_cast<FaceId::Index>(b * block),
                       end = static_cast<FaceId::Index>(std::min(nf, (b + 1) * block));
            out.triangles.reserve(end - first_face);
            auto chord = std::lower_bound(chords_.begin(), chords_.end(), first_face,
                                          [](const Chord& c, FaceId::Index f) { return c.face.idx() < f; });
            FaceScratch scratch;
            for (FaceId::Index i = first_face; i < end; ++i) {
                const FaceId f(i);
                const auto first = chord;
                while (chord != chords_.end() && chord->face == f) ++chord;
                triangulate_face(f, std::span<const Chord>(first, chord), out.triangles, out.conflicts, failed,
                                 scratch);
                out.t_face.resize(out.triangles.size(), f);
            }
        });
        out_.network.t_face.reserve(nf);
        for (Block& b : blocks) {
            triangles.insert(triangles.end(), b.triangles.begin(), b.triangles.end());
            for (FaceId f : b.t_face) out_.network.t_face.push_back(TFaceId(f));
            out_.conflicts.insert(out_.conflicts.end(), b.conflicts.begin(), b.conflicts.end());
        }
    }

    // Face f of T cut along its chords (Fig. 3), triangulated.
    void triangulate_face(FaceId f, std::span<const Chord> chords, std::vector<Triangle>& triangles,
                          std::vector<Conflict>& conflicts, bool failed, FaceScratch& x) const {
        const HalfedgeId h0 = T_.halfedge(f), h1 = T_.next(h0), h2 = T_.next(h1);
        if (chords.empty() && slot_[TriMesh::edge(h0).idx()] == none && slot_[TriMesh::edge(h1).idx()] == none &&
            slot_[TriMesh::edge(h2).idx()] == none) {  // untouched by the network: the face itself
            triangles.push_back({T_.from(h0).idx(), T_.from(h1).idx(), T_.from(h2).idx()});
            return;
        }
        std::vector<VertexId>& poly = x.poly;
        poly.clear();
        x.mask.clear();
        HalfedgeId h = T_.halfedge(f);
        for (unsigned s = 0; s < 3; ++s, h = T_.next(h)) {
            poly.push_back(T_.from(h));
            x.mask.push_back(static_cast<SideMask>((1u << s) | (1u << ((s + 2) % 3))));
            append_nodes_along(h, s, x);
        }
        auto index_of = [&](VertexId v) {
            return static_cast<std::size_t>(std::find(poly.begin(), poly.end(), v) - poly.begin());
        };
        std::vector<std::pair<std::size_t, std::size_t>>& cuts = x.cuts;
        cuts.clear();
        for (const Chord& c : chords) {
            std::size_t a = index_of(c.a), b = index_of(c.b);
            if (a == poly.size() || b == poly.size()) throw InternalError("embed: a chord's end is not on its face");
            cuts.emplace_back(std::min(a, b), std::max(a, b));
        }
        // Theorem: two chords of a convex polygon cross iff their ends interleave along its boundary.
        for (std::size_t i = 0; i < cuts.size(); ++i)
            for (std::size_t k = i + 1; k < cuts.size(); ++k) {
                const auto [a, b] = cuts[i];
                const auto [c, d] = cuts[k];
                if ((a < c && c < b && b < d) || (c < a && a < d && d < b))
                    conflicts.push_back(
                        make_conflict(Kind::crossing, chords[i].d_edge, chords[k].d_edge, T_.face_vertices(f)));
            }
        if (failed || !conflicts.empty()) return;
        // The chords cut the polygon into convex pieces: split the piece holding each chord.
        std::vector<std::vector<std::size_t>>& pieces = x.pieces;
        pieces.resize(1);
        pieces[0].clear();
        for (std::size_t i = 0; i < poly.size(); ++i) pieces[0].push_back(i);
        for (const auto& [a, b] : cuts) {
            for (std::size_t p = 0; p < pieces.size(); ++p) {
                std::vector<std::size_t>& piece = pieces[p];
                auto ia = std::find(piece.begin(), piece.end(), a), ib = std::find(piece.begin(), piece.end(), b);
                if (ia == piece.end() || ib == piece.end()) continue;
                if (ib < ia) std::swap(ia, ib);  // a piece is a cyclic sequence: either end may come first
                const std::size_t d = static_cast<std::size_t>(ib - ia);
                if (d == 1 || d == piece.size() - 1) break;  // already a side of this piece
                std::vector<std::size_t> inner(ia, ib + 1), outer(ib, piece.end());
                outer.insert(outer.end(), piece.begin(), ia + 1);
                piece = std::move(inner);
                pieces.push_back(std::move(outer));
                break;
            }
        }
        for (const auto& piece : pieces) triangulate_convex(x, piece, triangles);
    }

    // Smallest angle of triangle (a, b, c) of T′, or −1 when its corners lie on one side of the
    // face of T (collinear: a triangle of zero area). Properness is decided by the sides alone:
    // corners on two or three sides of the face are in convex position, so the triangle is proper
    // in exact arithmetic even when its angle rounds to 0 (two points 2·10⁻¹⁷ apart beside a
    // 10⁻⁹° corner of the quality family): such an angle counts as the least positive double.
    // The caller only asks whether it exceeds `floor`: once one angle shows it does not, that
    // angle is returned (a value ≤ floor, as the smallest would be) and the others are not computed.
    double quality(const std::vector<VertexId>& poly, const std::vector<SideMask>& mask, std::size_t a, std::size_t b,
                   std::size_t c, double floor) const {
        if (mask[a] & mask[b] & mask[c]) return -1;
        const Vec3 &pa = positions_[poly[a].idx()], &pb = positions_[poly[b].idx()], &pc = positions_[poly[c].idx()];
        auto angle = [](const Vec3& o, const Vec3& x, const Vec3& y) {
            const Vec3 u = x - o, w = y - o;
            return std::max(std::atan2(u.cross(w).norm(), u.dot(w)), std::numeric_limits<double>::denorm_min());
        };
        const double first = angle(pa, pb, pc);
        if (first <= floor) return first;
        const double second = std::min(first, angle(pb, pc, pa));
        if (second <= floor) return second;
        return std::min(second, angle(pc, pa, pb));
    }

    // The triangulation of a convex piece (indices into poly, in boundary order) that maximizes
    // the smallest angle (Klincsek's dynamic programme over sub-polygons, O(m³)); the Fig. 3
    // "either diagonal" choice, made for shape.
    void triangulate_convex(FaceScratch& x, const std::vector<std::size_t>& piece,
                            std::vector<Triangle>& triangles) const {
        const std::vector<VertexId>& poly = x.poly;
        const std::size_t m = piece.size();
        constexpr double inf = std::numeric_limits<double>::infinity();
        std::vector<double>& best = x.best;
        std::vector<std::size_t>& apex = x.apex;
        best.assign(m * m, inf);
        apex.assign(m * m, 0);
        for (std::size_t len = 2; len < m; ++len)
            for (std::size_t i = 0; i + len < m; ++i) {
                const std::size_t j = i + len;
                double& b = best[i * m + j];
                b = -inf;
                for (std::size_t k = i + 1; k < j; ++k) {
                    // Only a q above b changes anything: the triangle's angles are computed only
                    // when the two sub-polygons' optima leave it room to.
                    const double sides = std::min(best[i * m + k], best[k * m + j]);
                    if (!(sides > b)) continue;
                    const double q = std::min(sides, quality(poly, x.mask, piece[i], piece[k], piece[j], b));
                    if (q > b) {
                        b = q;
                        apex[i * m + j] = k;
                    }
                }
            }
        // Theorem (paper_notes/partition.md): a convex piece always has a triangulation without
        // collinear triangles, so the optimum is positive.
        if (!(best[m - 1] > 0)) throw InternalError("embed: a piece of a face has no proper triangulation");
        std::vector<std::pair<std::size_t, std::size_t>>& stack = x.stack;
        stack.assign(1, {0, m - 1});
        while (!stack.empty()) {
            const auto [i, j] = stack.back();
            stack.pop_back();
            if (j < i + 2) continue;
            const std::size_t k = apex[i * m + j];
            triangles.push_back({poly[piece[i]].idx(), poly[piece[k]].idx(), poly[piece[j]].idx()});
            stack.emplace_back(i, k);
            stack.emplace_back(k, j);
        }
    }

    // Every segment is an edge of T′: label it with its D halfedge.
    void label_paths() {
        Network& net = out_.network;
        net.d_halfedge = HalfedgeData<DHalfedgeId>(net.mesh, DHalfedgeId());
        for (DEdgeId e : net.path.ids()) {
            const auto& path = net.path[e];
            for (std::size_t i = 0; i + 1 < path.size(); ++i) {
                const HalfedgeId h = net.mesh.find_halfedge(path[i], path[i + 1]);
                if (!h.valid() || net.d_halfedge[h].valid())
                    throw InternalError("embed: a path segment is not an edge of T′");
                net.d_halfedge[h] = TriMesh::halfedge(e, 0);
                net.d_halfedge[TriMesh::twin(h)] = TriMesh::halfedge(e, 1);
            }
        }
    }

    // (2): around x_j, the paths leave in D's cyclic order of the edges around v_j.
    void check_order() {
        const Network& net = out_.network;
        const domain::Domain& D = *D_;
        for (VertexId vj : D.mesh.vertices()) {
            std::vector<DHalfedgeId> in_d, in_t;
            D.mesh.for_each_outgoing(vj, [&](HalfedgeId h) { in_d.push_back(DHalfedgeId(h)); });
            net.mesh.for_each_outgoing(D.t_vertex[vj], [&](HalfedgeId h) {
                if (net.d_halfedge[h].valid()) in_t.push_back(net.d_halfedge[h]);
            });
            const std::vector<std::uint8_t> wrong = out_of_order(in_d, in_t);
            for (std::size_t k = 0; k < in_d.size(); ++k) {
                if (!wrong[k]) continue;
                // The curve's first node after x_j: a vertex of D there puts it in its place.
                const DEdgeId e = TriMesh::edge(in_d[k]);
                const auto& path = net.path[e];
                const VertexId first = in_d[k] == TriMesh::halfedge(e, 1) ? path[path.size() - 2] : path[1];
                conflict(Kind::order, e.idx(), e.idx(), {nearest(first), {}, {}}, DVertexId(vj));
            }
        }
    }
};

}  // namespace

std::vector<std::uint8_t> out_of_order(std::span<const DHalfedgeId> in_d, std::span<const DHalfedgeId> in_t) {
    const std::size_t n = in_d.size();
    std::vector<std::uint8_t> wrong(n, in_t.size() != n);
    for (std::size_t k = 0; k < n && in_t.size() == n; ++k) {
        const auto at = std::find(in_t.begin(), in_t.end(), in_d[k]);
        if (at == in_t.end()) {
            std::fill(wrong.begin(), wrong.end(), 1);
            break;
        }
        if (in_t[(static_cast<std::size_t>(at - in_t.begin()) + 1) % n] != in_d[(k + 1) % n])
            wrong[k] = wrong[(k + 1) % n] = 1;
    }
    return wrong;
}

std::string Conflict::describe() const {
    const std::string a = "domain edge " + std::to_string(d_edge_a.idx()),
                      b = "domain edge " + std::to_string(d_edge_b.idx());
    switch (kind) {
        case Kind::shared_node:
            return d_edge_a == d_edge_b
                       ? "the path of " + a + " passes a point twice"
                       : "the paths of " + a + " and " + b + " meet at a point that is not a common end";
        case Kind::crossing: return "the paths of " + a + " and " + b + " cross";
        case Kind::through_corner:
            return "the path of " + a + " passes through the corner of domain vertex " + std::to_string(d_vertex.idx());
        case Kind::order:
            return "around domain vertex " + std::to_string(d_vertex.idx()) + " the path of " + a +
                   " is out of the domain's cyclic order";
    }
    return {};
}

Embedding embed(const TriMesh& T, const domain::Domain& D, std::span<const geodesic::GeodesicPath> paths,
                std::span<const std::uint8_t> unsnapped, Executor* executor) {
    if (!unsnapped.empty() && unsnapped.size() != paths.size())
        throw ContractViolation("embed: one unsnapped flag per path");
    return Embedder(T, &D, paths, unsnapped, executor_or_default(executor)).run();
}

Embedding embed_curves(const TriMesh& T, std::span<const geodesic::GeodesicPath> curves,
                       std::span<const std::uint8_t> unsnapped, Executor* executor) {
    if (!unsnapped.empty() && unsnapped.size() != curves.size())
        throw ContractViolation("embed: one unsnapped flag per curve");
    return Embedder(T, nullptr, curves, unsnapped, executor_or_default(executor)).run();
}

}  // namespace fhr::partition
