// Beyond the paper (§3): keeping the domain (see keep.hpp for the pseudocode).
#include <fhr/partition/keep.hpp>

#include <algorithm>
#include <iterator>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <unordered_map>
#include <utility>

#include <fhr/core/cones.hpp>
#include <fhr/core/errors.hpp>
#include <fhr/core/executor.hpp>
#include <fhr/partition/detail/restricted.hpp>
#include <fhr/partition/patches.hpp>

namespace fhr::partition {
namespace {

using Pair = std::pair<VertexId::Index, VertexId::Index>;
Pair key_of(VertexId a, VertexId b) { return {std::min(a.idx(), b.idx()), std::max(a.idx(), b.idx())}; }

// A face of D by its vertices of T, in increasing order.
using Corners = std::array<VertexId::Index, 3>;
Corners corners_of(const domain::Domain& D, FaceId f) {
    const auto v = D.mesh.face_vertices(f);
    Corners c{D.t_vertex[v[0]].idx(), D.t_vertex[v[1]].idx(), D.t_vertex[v[2]].idx()};
    std::sort(c.begin(), c.end());
    return c;
}

std::vector<FaceId> merged(std::vector<FaceId> a, std::span<const FaceId> b) {
    a.insert(a.end(), b.begin(), b.end());
    std::sort(a.begin(), a.end());
    a.erase(std::unique(a.begin(), a.end()), a.end());
    return a;
}

// The faces of T that patch df of an embedding's network covers, sorted, each once.
std::vector<FaceId> faces_of_t(const Patches& patches, const Network& network, FaceId df) {
    std::vector<FaceId> faces;
    for (FaceId f : patches.patch[df].faces) faces.push_back(network.t_face[f]);
    return merged(std::move(faces), {});
}

geodesic::GeodesicPath reversed(geodesic::GeodesicPath p) {
    std::reverse(p.points.begin(), p.points.end());
    return p;
}

// A curve of the network, kept from its smaller vertex of T to its larger.
struct Curve {
    geodesic::GeodesicPath path;
    bool exact = false;             // the exact geodesic of T between its ends
    RestrictedPath restricted{};    // when not exact: how it was found
    // A geodesic of the start is snapped as embed() snaps geodesics; a curve found later is placed
    // as found, since snapping could move it across a curve that it passes closer than snapping.
    bool snapped = false;
    bool fixed = false;             // a cone edge or a boundary arc (domain::on_cone): never changed
};

// The network while D is being made: a domain, one curve per edge keyed by the edge's ends in T,
// and per face of D the faces of T its patch touches (the network is never embedded as a whole
// again: each change is made in its region, partition/region.hpp).
class Network_ {
public:
    Network_(const TriMesh& T, std::size_t real_vertices, domain::Domain D) : T_(T), real_(real_vertices), D_(std::move(D)) {}

    const TriMesh& T() const { return T_; }
    std::size_t real_vertices() const { return real_; }
    bool apex(VertexId x) const { return x.idx() >= real_; }  // x a vertex of T̂
    const domain::Domain& domain() const { return D_; }
    domain::Domain& domain() { return D_; }
    std::map<Pair, Curve>& curves() { return curves_; }
    const std::map<Pair, Curve>& curves() const { return curves_; }
    std::map<Corners, std::vector<FaceId>>& touched() { return touched_; }

    VertexId x(VertexId v) const { return D_.t_vertex[v]; }
    // The vertex of D at vertex x of T: D's vertices are numbered in T's order (make_domain), and
    // keep their numbers through flips and collapses until compacted, which keeps the order.
    VertexId at(VertexId::Index x) const {
        const auto it = std::lower_bound(D_.t_vertex.begin(), D_.t_vertex.end(), VertexId(x));
        if (it == D_.t_vertex.end() || it->idx() != x) throw std::logic_error("keeping the domain: a vertex of T that is not in D");
        return VertexId(static_cast<VertexId::Index>(it - D_.t_vertex.begin()));
    }

    // The region of D's edge e: its two faces' patches, bounded by their four other curves (the
    // first with the region on its left when `left`), and the faces of T they touch.
    struct Quad {
        std::vector<RegionCurve> curves;
        bool left = true;
        std::vector<FaceId> touched;
    };
    Quad quad(EdgeId e) const {
        const TriMesh& m = D_.mesh;
        const HalfedgeId h = TriMesh::halfedge(e, 0), t = TriMesh::twin(h);
        Quad q;
        for (HalfedgeId s : {m.next(h), m.next(m.next(h)), m.next(t), m.next(m.next(t))}) {
            const Curve& c = curves_.at(key_of(x(m.from(s)), x(m.to(s))));
            q.curves.push_back(RegionCurve{&c.path, c.snapped});
        }
        q.left = x(m.from(m.next(h))).idx() < x(m.to(m.next(h))).idx();
        q.touched = merged(touched_.at(corners_of(D_, m.face(h))), touched_.at(corners_of(D_, m.face(t))));
        return q;
    }

private:
    const TriMesh& T_;
    std::size_t real_;
    domain::Domain D_;
    std::map<Pair, Curve> curves_;
    std::map<Corners, std::vector<FaceId>> touched_;
};

// The domain with these faces (vertices of T), its vertices in increasing order of T's numbering.
domain::Domain make_domain(const TriMesh& T, const std::vector<std::array<VertexId, 3>>& faces) {
    std::vector<VertexId::Index> ids;
    for (const auto& f : faces)
        for (VertexId v : f) ids.push_back(v.idx());
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    std::unordered_map<VertexId::Index, std::uint32_t> index;
    domain::Domain D;
    std::vector<Vec3> positions;
    for (std::size_t i = 0; i < ids.size(); ++i) {
        index.emplace(ids[i], static_cast<std::uint32_t>(i));
        D.t_vertex.emplace_back(ids[i]);
        positions.push_back(T.position(VertexId(ids[i])));
    }
    std::vector<Triangle> triangles;
    for (const auto& f : faces) triangles.push_back({index.at(f[0].idx()), index.at(f[1].idx()), index.at(f[2].idx())});
    D.mesh = TriMesh::from_triangles(std::move(positions), triangles);
    return D;
}

std::vector<std::array<VertexId, 3>> faces_in_t(const domain::Domain& D) {
    std::vector<std::array<VertexId, 3>> faces;
    for (FaceId f : D.mesh.faces()) {
        const auto v = D.mesh.face_vertices(f);
        faces.push_back({D.t_vertex[v[0]], D.t_vertex[v[1]], D.t_vertex[v[2]]});
    }
    return faces;
}

// A flip or a tightening: the new curve of D's edge e between D's vertices a and b, found in
// the region of e; taken when it is a flip, an exact geodesic, or shorter than the curve now.
struct Job {
    EdgeId e;
    VertexId a, b;
    double geodesic_length = -1;                 // tightening: |Γ| of the edge; a flip: -1
    double current = INFINITY;                   // tightening: the length of its curve now
    std::optional<Curve> curve{};                // the new curve, from a's vertex of T to b's
    std::vector<FaceId> on_left{}, on_right{};   // the faces of T its two patches touch (sides of
                                                 // the curve from its smaller vertex of T)
};

// What runs the independent restricted searches of one keep_domain call: its executor, and a pool
// of workspaces from which each job leases one, so that the threads reuse the searches'
// arrays across jobs and rounds; keep_domain frees them when it returns.
struct Searches {
    Executor& executor;
    geodesic::WorkspacePool workspaces{};
};

void compute(const Network_& n, std::vector<Job>& jobs, Searches& searches) {
    searches.executor.for_each(jobs.size(), 1, [&](std::size_t i) {
        Job& j = jobs[i];
        Network_::Quad q = n.quad(j.e);
        Region region(n.T(), q.touched, q.curves);
        const geodesic::WorkspacePool::Lease workspace = searches.workspaces.lease();
        RestrictedPath r = restricted_path(region, 0, q.left, n.x(j.a), n.x(j.b), workspace.get());
        const bool exact = r.touches == 0 && j.geodesic_length >= 0 && r.shortest <= j.geodesic_length * (1 + 1e-12);
        if (!exact && !(r.path.length < j.current * (1 - 1e-9))) return;
        geodesic::GeodesicPath path = n.x(j.a).idx() < n.x(j.b).idx() ? std::move(r.path) : reversed(std::move(r.path));
        j.curve = Curve{std::move(path), exact, std::move(r)};
        region.add(RegionCurve{&j.curve->path, false});
        j.on_left = region.t_faces(region.side(4, true));
        j.on_right = region.t_faces(region.side(4, false));
    });
}

// Puts job j's curve in place (after flipping e when the curve joins other vertices).
void apply(Network_& net, Job& j) {
    domain::Domain& D = net.domain();
    const HalfedgeId h = TriMesh::halfedge(j.e, 0);
    const Pair old = key_of(net.x(D.mesh.from(h)), net.x(D.mesh.to(h))), now = key_of(net.x(j.a), net.x(j.b));
    net.touched().erase(corners_of(D, D.mesh.face(h)));
    net.touched().erase(corners_of(D, D.mesh.face(TriMesh::twin(h))));
    if (old != now) {
        net.curves().erase(old);
        D.mesh.flip(j.e);
    }
    net.curves()[now] = std::move(*j.curve);
    const VertexId lo = net.x(j.a).idx() < net.x(j.b).idx() ? j.a : j.b, hi = lo == j.a ? j.b : j.a;
    const HalfedgeId g = D.mesh.find_halfedge(lo, hi);
    net.touched()[corners_of(D, D.mesh.face(g))] = std::move(j.on_left);
    net.touched()[corners_of(D, D.mesh.face(TriMesh::twin(g)))] = std::move(j.on_right);
}

// Redoes `collapses` (in T's numbering, in their order) on the network.
void redo(Network_& net, std::span<const domain::Collapse> collapses, const std::function<void(const std::string&)>& say,
          Searches& searches) {
    domain::Domain& D = net.domain();
    // Vertices keep their numbers until the end (removed ones become garbage).
    std::vector<domain::Collapse> left(collapses.begin(), collapses.end());
    std::vector<std::uint8_t> blocked(D.mesh.n_vertices(), 0);
    while (!left.empty()) {
        // The batch: collapses whose closed 1-rings meet no earlier one's (taken or left), so
        // that they commute with every collapse they overtake.
        std::vector<domain::Collapse> batch, later;
        std::vector<VertexId> marked;
        for (const domain::Collapse& c : left) {
            const VertexId v = net.at(c.removed.idx());
            bool free = blocked[v.idx()] == 0;
            D.mesh.for_each_outgoing(v, [&](HalfedgeId h) { free = free && blocked[D.mesh.to(h).idx()] == 0; });
            auto mark = [&](VertexId u) {
                if (!blocked[u.idx()]) marked.push_back(u);
                blocked[u.idx()] = 1;
            };
            mark(v);
            D.mesh.for_each_outgoing(v, [&](HalfedgeId h) { mark(D.mesh.to(h)); });
            (free ? batch : later).push_back(c);
        }
        for (VertexId u : marked) blocked[u.idx()] = 0;
        // Flip v's spokes until it has valence 3, all collapses of the batch in step. The spoke
        // flipped is next to [v, w] on alternate sides: each new curve may have to pass x_v inside
        // the one before on its side, so alternating halves how deep they crowd.
        for (;;) {
            std::vector<Job> jobs;
            for (const domain::Collapse& c : batch) {
                const VertexId v = net.at(c.removed.idx()), w = net.at(c.kept.idx());
                const std::size_t valence = D.mesh.valence(v);
                if (valence <= 3) continue;
                // Spoke [v, u] in the face (v, w, u), or (w, v, u) on the other side; its other
                // face (v, u, y), or (u, v, y): the flip makes [w, y]. Along the boundary only the
                // side of the face of T (the other is a cone face).
                const HalfedgeId vw = D.mesh.find_halfedge(v, w);
                const bool along = net.apex(c.left) || net.apex(c.right);
                const HalfedgeId side = along ? (net.apex(net.x(D.mesh.to(D.mesh.next(vw)))) ? TriMesh::twin(vw) : vw)
                                              : valence % 2 == 0 ? vw : TriMesh::twin(vw);
                const VertexId u = D.mesh.to(D.mesh.next(side));
                const HalfedgeId spoke = side == vw ? D.mesh.find_halfedge(v, u) : D.mesh.find_halfedge(u, v);
                const VertexId y = D.mesh.to(D.mesh.next(spoke));
                if (!D.mesh.is_flip_ok(TriMesh::edge(spoke))) throw std::logic_error("keeping the domain: a spoke cannot be flipped");
                jobs.push_back(Job{.e = TriMesh::edge(spoke), .a = w, .b = y});
            }
            if (jobs.empty()) break;
            compute(net, jobs, searches);
            for (Job& j : jobs) apply(net, j);
        }
        // Each v now has valence 3: the collapse v -> w merges its three faces into (w, a, b)
        // and removes its three curves; the new face's patch is the three patches' union.
        for (const domain::Collapse& c : batch) {
            const VertexId v = net.at(c.removed.idx()), w = net.at(c.kept.idx());
            const HalfedgeId vw = D.mesh.find_halfedge(v, w);
            if (!D.mesh.is_collapse_ok(vw)) throw std::logic_error("keeping the domain: a collapse cannot be redone");
            if (net.apex(c.left) || net.apex(c.right)) {
                // Along the boundary: v's face of T, (v, w, v') or (w, v, v'), joins the face across
                // [v', w]; the new boundary edge [v', w] gets the arc of T's boundary.
                const HalfedgeId side = net.apex(net.x(D.mesh.to(D.mesh.next(vw)))) ? TriMesh::twin(vw) : vw;
                const VertexId vp = D.mesh.to(D.mesh.next(side));
                const HalfedgeId inside = side == vw ? D.mesh.find_halfedge(w, vp) : D.mesh.find_halfedge(vp, w);
                const FaceId own = D.mesh.face(side), across = D.mesh.face(TriMesh::twin(inside));
                auto& joined = net.touched().at(corners_of(D, across));
                auto& given = net.touched().at(corners_of(D, own));
                joined = merged(std::move(joined), given);
                given.clear();
                // After the collapse, D's face of T beside [v', w] is `across`: left of v' -> w when
                // own = (v, w, v') holds w -> v', else left of w -> v'. The arc passes x_v.
                const VertexId a = side == vw ? vp : w, b = side == vw ? w : vp;
                const std::vector<VertexId> arc = boundary_arc(net.T(), net.real_vertices(), net.x(a), net.x(b));
                geodesic::GeodesicPath path;
                for (std::size_t i = 0; i < arc.size(); ++i) {
                    path.points.push_back(SurfacePoint::at_vertex(arc[i]));
                    if (i) path.length += (net.T().position(arc[i]) - net.T().position(arc[i - 1])).norm();
                }
                if (arc.front().idx() > arc.back().idx()) path = reversed(std::move(path));
                net.curves()[key_of(net.x(vp), net.x(w))] = Curve{std::move(path), true, {}, true, true};
            }
            std::vector<FaceId> touched;
            D.mesh.for_each_outgoing(v, [&](HalfedgeId h) {
                const auto it = net.touched().find(corners_of(D, D.mesh.face(h)));
                touched = merged(std::move(touched), it->second);
                net.touched().erase(it);
                net.curves().erase(key_of(c.removed, net.x(D.mesh.to(h))));
            });
            Corners k{c.kept.idx(), net.x(D.mesh.to(D.mesh.next(vw))).idx(), net.x(D.mesh.to(D.mesh.next(TriMesh::twin(vw)))).idx()};
            std::sort(k.begin(), k.end());
            D.mesh.collapse(vw);
            net.touched()[k] = std::move(touched);
        }
        if (say)
            say("keeping the domain: redid " + std::to_string(batch.size()) + " collapses on the network, " +
                std::to_string(later.size()) + " to go");
        left = std::move(later);
    }
    // The removed vertices go.
    VertexData<VertexId> kept;
    for (VertexId v : D.mesh.vertices())
        if (!D.mesh.is_deleted(v)) kept.push_back(D.t_vertex[v]);
    D.mesh.compact();
    D.t_vertex = std::move(kept);
}

// The faces of a domain as triples of vertices of T, each from its smallest vertex, sorted.
std::vector<std::array<VertexId::Index, 3>> canonical_faces(const domain::Domain& D) {
    std::vector<std::array<VertexId::Index, 3>> faces;
    for (const auto& f : faces_in_t(D)) {
        std::array<VertexId::Index, 3> t{f[0].idx(), f[1].idx(), f[2].idx()};
        std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
        faces.push_back(t);
    }
    std::sort(faces.begin(), faces.end());
    return faces;
}

// Flips the network's domain to D's edges (D has its vertices). Each round flips, in regions with
// no face in common, the edges not in D whose flip makes an edge of D; when there is none, it
// searches (iterative deepening, at most four flips, each near a missing edge, edges of D
// included, at most search_budget meshes looked at) for a sequence after which fewer edges of D
// are missing, and makes it. Each flip is a
// restricted path in its region, as in the redo.
constexpr std::size_t search_budget = 200000;

void flip_to(Network_& net, const domain::Domain& target, const std::function<void(const std::string&)>& say,
             Searches& searches) {
    std::set<Pair> want;
    for (const auto& [a, b] : domain::edge_endpoints(target)) want.insert(key_of(a, b));
    domain::Domain& D = net.domain();
    auto key = [&](const TriMesh& m, EdgeId e) {
        const HalfedgeId h = TriMesh::halfedge(e, 0);
        return key_of(net.x(m.from(h)), net.x(m.to(h)));
    };
    auto made = [&](const TriMesh& m, EdgeId e) {  // the edge that flipping e makes
        const HalfedgeId h = TriMesh::halfedge(e, 0);
        return key_of(net.x(m.to(m.next(h))), net.x(m.to(m.next(TriMesh::twin(h)))));
    };
    auto missing_in = [&](const TriMesh& m) {
        std::size_t present = 0;
        for (EdgeId e : m.edges()) present += want.count(key(m, e));
        return want.size() - present;
    };
    auto flip = [&](std::vector<Job> jobs) {
        compute(net, jobs, searches);
        for (Job& j : jobs) apply(net, j);
        return jobs.size();
    };
    auto job = [&](EdgeId e) {
        const HalfedgeId h = TriMesh::halfedge(e, 0);
        return Job{.e = e, .a = D.mesh.to(D.mesh.next(h)), .b = D.mesh.to(D.mesh.next(TriMesh::twin(h)))};
    };
    const std::size_t first = missing_in(D.mesh);
    std::size_t flips = 0;
    for (std::size_t missing = first; missing > 0; missing = missing_in(D.mesh)) {
        if (flips > 4 * first + 16) throw PartitionFailure("keeping the domain: the given domain is not reached by flips from its decimation");
        std::vector<Job> jobs;
        std::vector<std::uint8_t> used(D.mesh.n_faces(), 0);
        std::set<Pair> making;  // two flips of a round must not make the same edge
        for (EdgeId e : D.mesh.edges()) {
            const HalfedgeId h = TriMesh::halfedge(e, 0);
            const FaceId f = D.mesh.face(h), g = D.mesh.face(TriMesh::twin(h));
            if (used[f.idx()] || used[g.idx()] || want.count(key(D.mesh, e)) || !D.mesh.is_flip_ok(e) || !want.count(made(D.mesh, e)) ||
                !making.insert(made(D.mesh, e)).second)
                continue;
            used[f.idx()] = used[g.idx()] = 1;
            jobs.push_back(job(e));
        }
        if (!jobs.empty()) {
            flips += flip(std::move(jobs));
            continue;
        }
        // The search, among flips with an end of a missing edge in their quadrilateral.
        std::vector<std::uint8_t> near(D.mesh.n_vertices(), 0);
        std::set<Pair> have;
        for (EdgeId e : D.mesh.edges()) have.insert(key(D.mesh, e));
        for (const Pair& k : want)
            if (!have.count(k)) near[net.at(k.first).idx()] = near[net.at(k.second).idx()] = 1;
        auto candidate = [&](const TriMesh& m, EdgeId e) {
            const HalfedgeId h = TriMesh::halfedge(e, 0);
            if (domain::on_cone(m, D.t_vertex, e, net.real_vertices())) return false;  // a cone edge or a boundary edge of D: fixed
            return (near[m.from(h).idx()] || near[m.to(h).idx()] || near[m.to(m.next(h)).idx()] ||
                    near[m.to(m.next(TriMesh::twin(h))).idx()]) &&
                   m.is_flip_ok(e);
        };
        std::vector<EdgeId> sequence;
        std::size_t states = 0;  // meshes looked at: the search gives up past search_budget
        std::function<bool(const TriMesh&, int)> search = [&](const TriMesh& m, int depth) {
            if (missing_in(m) < missing) return true;
            if (depth == 0) return false;
            for (EdgeId e : m.edges()) {
                if (!candidate(m, e) || ++states > search_budget) continue;
                TriMesh next = m;
                next.flip(e);
                sequence.push_back(e);
                if (search(next, depth - 1)) return true;
                sequence.pop_back();
            }
            return false;
        };
        bool found = false;
        for (int depth = 1; depth <= 4 && !found; ++depth) found = search(D.mesh, depth);
        if (!found)
            throw PartitionFailure(std::string("keeping the domain: ") +
                                   (states > search_budget ? "no short sequence of flips found that brings" : "no four flips bring") +
                                   " the decimation nearer to the given domain");
        for (EdgeId e : sequence) flips += flip({job(e)});
    }
    if (say) say("keeping the domain: " + std::to_string(flips) + " flips from the decimation to the given domain");
}

// The curves in D's edge order, each along D's halfedge (e, 0), and which of them embed() must
// place as given.
std::pair<std::vector<geodesic::GeodesicPath>, std::vector<std::uint8_t>> in_edge_order(const domain::Domain& D,
                                                                                         const std::map<Pair, Curve>& curves) {
    std::pair<std::vector<geodesic::GeodesicPath>, std::vector<std::uint8_t>> out;
    for (const auto& [a, b] : domain::edge_endpoints(D)) {
        const Curve& c = curves.at(key_of(a, b));
        out.first.push_back(a.idx() < b.idx() ? c.path : reversed(c.path));
        out.second.push_back(!c.snapped);
    }
    return out;
}

// Whether the kept curves can be taken as they are without embedding them first (direct()
// without check_kept): no two share a node or pass through a corner inside, and around each
// corner x_j their first steps leave in D's cyclic order of the kept edges at v_j. The first
// steps are ordered by T's fan around x_j: along a spoke (a vertex or a point of the spoke), or
// across the face between two spokes (a point of its far edge, ordered along it). False also
// where this cannot be read off (a first step to a point inside a face): the caller then embeds
// and checks them, as it does when anything here was too hopeful (snapping, say).
bool kept_plausible(const TriMesh& T, const TriMesh& m, const std::function<VertexId(VertexId)>& x,
                    const std::function<bool(HalfedgeId)>& is_kept, const std::function<const geodesic::GeodesicPath&(HalfedgeId)>& curve) {
    std::set<std::pair<std::uint32_t, double>> nodes;  // vertices as (index, -1), edge points as (edge, t along halfedge (e, 0))
    std::set<std::uint32_t> corners;
    for (VertexId v : m.vertices()) corners.insert(x(v).idx());
    for (EdgeId e : m.edges()) {
        const HalfedgeId h = TriMesh::halfedge(e, 0);
        if (!is_kept(h)) continue;
        const auto& points = curve(h).points;
        for (std::size_t i = 1; i + 1 < points.size(); ++i) {
            const SurfacePoint& p = points[i];
            std::pair<std::uint32_t, double> key;
            if (p.kind == SurfacePoint::Kind::vertex) {
                if (corners.count(p.vertex.idx())) return false;
                key = {p.vertex.idx(), -1};
            } else if (p.kind == SurfacePoint::Kind::edge) {
                const bool forward = p.halfedge == TriMesh::halfedge(TriMesh::edge(p.halfedge), 0);
                key = {static_cast<std::uint32_t>(T.n_vertices() + TriMesh::edge(p.halfedge).idx()), forward ? p.t : 1 - p.t};
            } else {
                return false;
            }
            if (!nodes.insert(key).second) return false;
        }
    }
    for (VertexId v : m.vertices()) {
        const VertexId xv = x(v);
        std::vector<HalfedgeId> spokes;
        T.for_each_outgoing(xv, [&](HalfedgeId h) { spokes.push_back(h); });
        std::vector<std::pair<std::pair<std::size_t, double>, std::size_t>> in_t;  // (place in the fan, rank in D)
        std::size_t rank = 0;
        bool readable = true;
        m.for_each_outgoing(v, [&](HalfedgeId h) {
            if (!is_kept(h) || !readable) return;
            const auto& points = curve(h).points;
            const SurfacePoint& p = points.front().vertex == xv ? points[1] : points[points.size() - 2];
            std::pair<std::size_t, double> place{SIZE_MAX, 0};
            for (std::size_t k = 0; k < spokes.size() && place.first == SIZE_MAX; ++k) {
                const HalfedgeId s = spokes[k];
                if (p.kind == SurfacePoint::Kind::vertex && p.vertex == T.to(s)) place = {2 * k, 0};
                if (p.kind == SurfacePoint::Kind::edge && TriMesh::edge(p.halfedge) == TriMesh::edge(s))
                    place = {2 * k, p.halfedge == s ? p.t : 1 - p.t};
                // face(s) = (x_j, to(s), b) lies between s and the spoke before it clockwise
                // (for_each_outgoing's order), x_j -> b: its far edge is crossed from b to to(s).
                if (p.kind == SurfacePoint::Kind::edge && !T.is_boundary(s) && TriMesh::edge(p.halfedge) == TriMesh::edge(T.next(s)))
                    place = {(2 * k + 2 * spokes.size() - 1) % (2 * spokes.size()), p.halfedge == T.next(s) ? 1 - p.t : p.t};
            }
            if (place.first == SIZE_MAX) readable = false;
            in_t.push_back({place, rank++});
        });
        if (!readable) return false;
        std::sort(in_t.begin(), in_t.end());
        for (std::size_t i = 0; i < in_t.size(); ++i) {
            if (i > 0 && in_t[i].first == in_t[i - 1].first) return false;  // two curves leave through one point
            // D's cyclic order: the ranks follow each other around, from wherever the fan starts.
            if (in_t[(i + 1) % in_t.size()].second != (in_t[i].second + 1) % in_t.size()) return false;
        }
    }
    return true;
}

// The direct start: keep the geodesics of D that conflict with no kept one, and put each other edge
// in as a restricted path in the polygon its two faces (and those of other removed edges) leave.
// nullopt when the kept geodesics do not leave such polygons (disks bounded by kept curves, one
// region of T each), or when anything on the way fails: the caller then steps back instead.
// `check_kept`: embed every kept geodesic first, drop those in conflicts the geodesics' conflicts
// did not name or out of D's order around a corner, and find every polygon's region of T in that
// embedding. Without it (at 10⁶ faces that embedding cost ~0.6 s for one removed edge
// among 15,000), the kept set is taken as it is and only the curves around polygons of more than
// one face are embedded to find their regions; the faces of D kept whole get no touched faces
// (the caller takes them from its check, which also decides whether the kept set was sound).
std::optional<Network_> direct(const TriMesh& T, std::size_t real_vertices, const domain::Domain& D,
                               std::span<const geodesic::EllipsePath> geodesics, std::span<const Conflict> conflicts,
                               std::span<const Pair> order, Executor& executor, bool check_kept,
                               const std::function<void(const std::string&)>& say) {
    const auto ends = domain::edge_endpoints(D);
    std::map<Pair, std::size_t> edge_of;
    for (std::size_t e = 0; e < ends.size(); ++e) edge_of[key_of(ends[e].first, ends[e].second)] = e;
    // The kept set, in the kept order: no conflict of its own (through a corner, a point twice),
    // none with a kept edge; the cyclic order (2) is settled among the kept ones below.
    std::vector<std::uint8_t> kept(ends.size(), 0), alone(ends.size(), 1), fixed(ends.size(), 0);
    for (EdgeId e : D.mesh.edges()) fixed[e.idx()] = domain::on_cone(D.mesh, D.t_vertex, e, real_vertices);
    std::vector<std::vector<std::size_t>> against(ends.size());
    for (const Conflict& c : conflicts) {
        if (c.kind == Conflict::Kind::order) continue;  // settled among the kept ones below
        const std::uint32_t a = c.d_edge_a.idx(), b = c.d_edge_b.idx();
        if (a == b) alone[a] = 0;
        against[a].push_back(b);
        against[b].push_back(a);
    }
    std::map<Pair, std::size_t> rank;  // place in the kept order
    for (const Pair& k : order) {
        const std::size_t e = edge_of.at(k);
        rank[k] = rank.size();
        kept[e] = fixed[e] || (alone[e] && std::none_of(against[e].begin(), against[e].end(), [&](std::size_t o) { return kept[o] != 0; }));
    }
    Network_ net(T, real_vertices, make_domain(T, faces_in_t(D)));
    const domain::Domain& Dn = net.domain();
    const TriMesh& m = Dn.mesh;
    auto edge_key = [&](HalfedgeId h) { return key_of(net.x(m.from(h)), net.x(m.to(h))); };
    auto is_kept = [&](HalfedgeId h) { return kept[edge_of.at(edge_key(h))] != 0; };
    auto on_boundary = [&](VertexId v) {  // a kept edge at v: v is on the boundary of its groups
        bool any = false;
        m.for_each_outgoing(v, [&](HalfedgeId h) { any = any || is_kept(h); });
        return any;
    };
    // The kept geodesics embedded; where the kept curves around a corner are out of D's cyclic
    // order (embed() checks (2) only once (1) holds), one of them is not kept either, a round at a
    // time, until they are in order.
    std::vector<geodesic::GeodesicPath> paths;
    std::map<Pair, std::size_t> index;
    Embedding cut;
    for (int round = 0;; ++round) {
        paths.clear();
        index.clear();
        for (std::size_t e = 0; e < ends.size(); ++e) {
            if (!kept[e]) continue;
            const auto [a, b] = ends[e];
            index[key_of(a, b)] = paths.size();
            paths.push_back(a.idx() < b.idx() ? geodesics[e].path : reversed(geodesics[e].path));
        }
        if (!check_kept) {
            if (!kept_plausible(T, m, [&](VertexId v) { return net.x(v); }, is_kept,
                                [&](HalfedgeId h) -> const geodesic::GeodesicPath& { return paths[index.at(edge_key(h))]; })) {
                say("keeping the domain: the kept geodesics embedded and checked first (two share a point, or some leave a corner out of D's order)");
                return std::nullopt;
            }
            break;
        }
        cut = embed_curves(T, paths, {}, &executor);
        if (round == 64) return std::nullopt;
        if (!cut.conflicts.empty()) {
            // A conflict the first embedding did not report (it names one pair per shared point):
            // the later edge of the pair in the kept order goes.
            for (const Conflict& c : cut.conflicts) {
                const auto& pa = paths[c.d_edge_a.idx()].points;
                const auto& pb = paths[c.d_edge_b.idx()].points;
                const Pair a = key_of(pa.front().vertex, pa.back().vertex), b = key_of(pb.front().vertex, pb.back().vertex);
                kept[edge_of.at(rank.at(a) >= rank.at(b) ? a : b)] = 0;
            }
            continue;
        }
        std::vector<std::size_t> out_of_order;
        for (VertexId v : m.vertices()) {
            std::vector<Pair> in_d, in_t;
            m.for_each_outgoing(v, [&](HalfedgeId h) {
                if (is_kept(h)) in_d.push_back(edge_key(h));
            });
            cut.network.mesh.for_each_outgoing(net.x(v), [&](HalfedgeId h) {
                const HalfedgeId label = cut.network.d_halfedge[h];
                if (!label.valid()) return;
                const auto& p = paths[TriMesh::edge(label).idx()].points;
                in_t.push_back(key_of(p.front().vertex, p.back().vertex));
            });
            // A curve of another edge through x_v goes; the others must follow D's order.
            std::vector<Pair> own;
            for (const Pair& k : in_t) {
                if (std::find(in_d.begin(), in_d.end(), k) == in_d.end()) out_of_order.push_back(edge_of.at(k));
                else own.push_back(k);
            }
            // In order: the same cyclic sequence. Else the one curve whose removal puts the rest in
            // order goes (the first such in D's order), or, when no one does, the first of D's.
            auto same_cycle = [](const std::vector<Pair>& a, const std::vector<Pair>& b) {
                if (a.size() != b.size()) return false;
                if (a.empty()) return true;
                const auto at = std::find(b.begin(), b.end(), a[0]);
                if (at == b.end()) return false;
                const std::size_t shift = static_cast<std::size_t>(at - b.begin());
                for (std::size_t i = 0; i < a.size(); ++i)
                    if (a[i] != b[(i + shift) % b.size()]) return false;
                return true;
            };
            if (same_cycle(in_d, own)) continue;
            const auto movable = std::find_if(in_d.begin(), in_d.end(), [&](const Pair& k) { return !fixed[edge_of.at(k)]; });
            if (movable == in_d.end()) return std::nullopt;  // fixed curves alone out of order: not a domain of T
            std::size_t drop = edge_of.at(*movable);
            for (const Pair& k : in_d) {
                if (fixed[edge_of.at(k)]) continue;
                std::vector<Pair> a, b;
                std::copy_if(in_d.begin(), in_d.end(), std::back_inserter(a), [&](const Pair& x) { return x != k; });
                std::copy_if(own.begin(), own.end(), std::back_inserter(b), [&](const Pair& x) { return x != k; });
                if (same_cycle(a, b)) {
                    drop = edge_of.at(k);
                    break;
                }
            }
            out_of_order.push_back(drop);
        }
        if (out_of_order.empty()) break;
        for (std::size_t e : out_of_order) kept[e] = 0;
    }
    for (const auto& [k, i] : index) net.curves()[k] = Curve{paths[i], true, {}, true, fixed[edge_of.at(k)] != 0};
    // Groups: D's faces joined across removed edges; each must be a disk, its boundary one closed
    // walk: with V vertices, E edges, F faces and r repeated boundary vertices, V − E + F = 1 − r
    // (a vertex met twice pinches the disk there).
    std::vector<std::int32_t> group(m.n_faces(), -1);
    std::vector<std::vector<FaceId>> groups;
    for (FaceId f : m.faces()) {
        if (group[f.idx()] >= 0) continue;
        std::vector<FaceId>& g = groups.emplace_back();
        std::vector<FaceId> stack{f};
        group[f.idx()] = static_cast<std::int32_t>(groups.size() - 1);
        std::size_t inner = 0;
        while (!stack.empty()) {
            const FaceId a = stack.back();
            stack.pop_back();
            g.push_back(a);
            HalfedgeId h = m.halfedge(a);
            for (int i = 0; i < 3; ++i, h = m.next(h)) {
                if (is_kept(h)) continue;
                ++inner;
                const FaceId b = m.face(TriMesh::twin(h));
                if (group[b.idx()] < 0) {
                    group[b.idx()] = group[a.idx()];
                    stack.push_back(b);
                }
            }
        }
        std::set<VertexId::Index> vertices;
        std::size_t boundary = 0;
        HalfedgeId start;
        for (FaceId a : g) {
            HalfedgeId h = m.halfedge(a);
            for (int i = 0; i < 3; ++i, h = m.next(h)) {
                vertices.insert(m.from(h).idx());
                if (is_kept(h)) ++boundary, start = h;
            }
        }
        // One closed walk: from a boundary halfedge, the next one turns around its head inside the group.
        std::size_t walk = 0;
        std::set<VertexId::Index> met;
        std::size_t repeated = 0;
        for (HalfedgeId h = start; start.valid() && (walk == 0 || h != start); ++walk) {
            repeated += !met.insert(m.to(h).idx()).second;
            HalfedgeId n = m.next(h);
            while (!is_kept(n)) n = m.next(TriMesh::twin(n));
            h = n;
            if (walk > boundary) return std::nullopt;
        }
        // Each inner edge is seen from both sides; χ = V − E + F.
        const long chi = static_cast<long>(vertices.size()) - static_cast<long>(inner / 2 + boundary) + static_cast<long>(g.size());
        if (boundary == 0 || walk != boundary || chi != 1 - static_cast<long>(repeated)) return std::nullopt;
    }
    // Each group's region of T′, found from one of its boundary curves (without check_kept, only
    // the polygons' curves embedded, and a face kept whole left to the caller).
    std::map<Pair, std::size_t> embedded = index;  // a curve's number in `cut`
    if (!check_kept) {
        std::vector<geodesic::GeodesicPath> around;
        embedded.clear();
        for (const std::vector<FaceId>& g : groups) {
            if (g.size() == 1) continue;
            for (FaceId a : g) {
                HalfedgeId h = m.halfedge(a);
                for (int i = 0; i < 3; ++i, h = m.next(h))
                    if (is_kept(h) && embedded.emplace(edge_key(h), around.size()).second) around.push_back(paths[index.at(edge_key(h))]);
            }
        }
        cut = embed_curves(T, around, {}, &executor);
        if (!cut.conflicts.empty()) return std::nullopt;
    }
    const TriMesh& M = cut.network.mesh;
    std::vector<std::int32_t> region(M.n_faces(), -1);
    std::vector<std::vector<FaceId>> touched(groups.size());
    for (std::size_t gi = 0; gi < groups.size(); ++gi) {
        if (!check_kept && groups[gi].size() == 1) continue;
        HalfedgeId boundary;
        for (FaceId a : groups[gi]) {
            HalfedgeId h = m.halfedge(a);
            for (int i = 0; i < 3; ++i, h = m.next(h))
                if (is_kept(h)) boundary = h;
        }
        const auto& path = cut.network.path[EdgeId(embedded.at(edge_key(boundary)))];
        const HalfedgeId first = M.find_halfedge(path[0], path[1]);
        const FaceId seed = M.face(net.x(m.from(boundary)).idx() < net.x(m.to(boundary)).idx() ? first : TriMesh::twin(first));
        if (region[seed.idx()] >= 0) return std::nullopt;
        std::vector<FaceId> stack{seed};
        region[seed.idx()] = static_cast<std::int32_t>(gi);
        while (!stack.empty()) {
            const FaceId a = stack.back();
            stack.pop_back();
            touched[gi].push_back(cut.network.t_face[a]);
            HalfedgeId h = M.halfedge(a);
            for (int i = 0; i < 3; ++i, h = M.next(h)) {
                if (cut.network.d_halfedge[h].valid()) continue;
                const FaceId b = M.face(TriMesh::twin(h));
                if (region[b.idx()] == static_cast<std::int32_t>(gi)) continue;
                if (region[b.idx()] >= 0) return std::nullopt;  // two groups in one region of T′
                region[b.idx()] = static_cast<std::int32_t>(gi);
                stack.push_back(b);
            }
        }
        touched[gi] = merged(std::move(touched[gi]), {});
    }
    // The removed edges, in the kept order: first those from an inner vertex to the boundary (a
    // slit: the polygon stays whole, the vertex is on its boundary from then on), then diagonals,
    // whose restricted paths split their polygon and its faces of T in two. One after another,
    // on one workspace.
    geodesic::Workspace workspace;
    for (;;) {
        std::optional<Pair> next;
        for (int slit = 1; slit >= 0 && !next; --slit)
            for (const Pair& k : order) {
                if (kept[edge_of.at(k)]) continue;
                const int ends_on_boundary = on_boundary(net.at(k.first)) + on_boundary(net.at(k.second));
                if (ends_on_boundary == 2 - slit) {
                    next = k;
                    break;
                }
            }
        if (!next) break;
        const Pair k = *next;
        const std::size_t e = edge_of.at(k);
        const VertexId lo = net.at(k.first), hi = net.at(k.second);
        const HalfedgeId h = m.find_halfedge(lo, hi);
        const std::int32_t gi = group[m.face(h).idx()];
        std::vector<RegionCurve> around;
        std::set<Pair> listed;  // a slit has the polygon on both sides
        bool left = true;
        for (FaceId a : groups[static_cast<std::size_t>(gi)]) {
            HalfedgeId g = m.halfedge(a);
            for (int i = 0; i < 3; ++i, g = m.next(g)) {
                if (!is_kept(g) || !listed.insert(edge_key(g)).second) continue;
                if (around.empty()) left = net.x(m.from(g)).idx() < net.x(m.to(g)).idx();
                const Curve& c = net.curves().at(edge_key(g));
                around.push_back(RegionCurve{&c.path, c.snapped});
            }
        }
        Region cut_out(T, touched[static_cast<std::size_t>(gi)], around);
        RestrictedPath r = restricted_path(cut_out, 0, left, VertexId(k.first), VertexId(k.second), &workspace);
        Curve& c = net.curves()[k] = Curve{std::move(r.path), false, r, false};
        cut_out.add(RegionCurve{&c.path, false});
        const std::size_t added = around.size();
        // The group's faces on the left of lo -> hi (with face(h)) and on its right.
        kept[e] = 1;
        std::vector<FaceId> side_faces;
        std::vector<FaceId> stack{m.face(h)};
        std::vector<std::uint8_t> on_left(m.n_faces(), 0);
        on_left[m.face(h).idx()] = 1;
        while (!stack.empty()) {
            const FaceId a = stack.back();
            stack.pop_back();
            HalfedgeId g = m.halfedge(a);
            for (int i = 0; i < 3; ++i, g = m.next(g)) {
                const FaceId b = m.face(TriMesh::twin(g));
                if (is_kept(g) || on_left[b.idx()]) continue;
                on_left[b.idx()] = 1;
                stack.push_back(b);
            }
        }
        std::vector<FaceId> left_faces, right_faces;
        for (FaceId a : groups[static_cast<std::size_t>(gi)]) (on_left[a.idx()] ? left_faces : right_faces).push_back(a);
        if (right_faces.empty()) {  // a slit
            touched[static_cast<std::size_t>(gi)] = cut_out.t_faces(cut_out.side(added, true));
            continue;
        }
        const std::int32_t gj = static_cast<std::int32_t>(groups.size());
        for (FaceId a : right_faces) group[a.idx()] = gj;
        touched.push_back(cut_out.t_faces(cut_out.side(added, false)));
        touched[static_cast<std::size_t>(gi)] = cut_out.t_faces(cut_out.side(added, true));
        groups[static_cast<std::size_t>(gi)] = std::move(left_faces);
        groups.push_back(std::move(right_faces));
    }
    for (std::size_t gi = 0; gi < groups.size(); ++gi) {
        if (groups[gi].size() != 1) throw std::logic_error("keeping the domain: a polygon left unsplit");
        if (!touched[gi].empty()) net.touched()[corners_of(Dn, groups[gi][0])] = std::move(touched[gi]);  // else the caller's
    }
    return net;
}

}  // namespace

const char* name(CurveKind kind) {
    switch (kind) {
        case CurveKind::geodesic: return "geodesic";
        case CurveKind::restricted: return "restricted";
        case CurveKind::boundary: return "boundary";
    }
    return "";
}

KeptNetwork keep_domain(const TriMesh& T, std::size_t real_vertices, const domain::Domain& D,
                        const std::function<const domain::Domain&()>& base,
                        std::span<const geodesic::EllipsePath> geodesics,
                        std::span<const Conflict> conflicts,
                        const std::function<std::vector<geodesic::EllipsePath>(const domain::Domain&)>& geodesics_of,
                        const std::function<void(const std::string&)>& progress, Executor& executor, Start start) {
    auto say = [&](const std::string& line) {
        if (progress) progress(line);
    };
    Searches searches{executor};
    const auto ends = domain::edge_endpoints(D);
    // The kept order: edges whose geodesic is in no conflict first, then shortest geodesic first.
    std::map<Pair, double> geodesic_length;
    std::map<Pair, std::string> reason;
    for (std::size_t e = 0; e < ends.size(); ++e) geodesic_length[key_of(ends[e].first, ends[e].second)] = geodesics[e].path.length;
    for (const Conflict& c : conflicts)
        for (EdgeId e : {c.d_edge_a, c.d_edge_b}) reason.emplace(key_of(ends[e.idx()].first, ends[e.idx()].second), c.describe());
    std::vector<Pair> order;
    for (const auto& [k, length] : geodesic_length) order.push_back(k);
    std::set<Pair> fixed;  // the cone edges and D's boundary edges, first in the kept order
    for (EdgeId e : D.mesh.edges())
        if (domain::on_cone(D.mesh, D.t_vertex, e, real_vertices)) fixed.insert(key_of(ends[e.idx()].first, ends[e.idx()].second));
    std::stable_sort(order.begin(), order.end(), [&](const Pair& p, const Pair& q) {
        const bool fp = fixed.count(p) != 0, fq = fixed.count(q) != 0;
        if (fp != fq) return fp;
        const bool cp = reason.count(p) != 0, cq = reason.count(q) != 0;
        if (cp != cq) return !cp;
        return geodesic_length.at(p) < geodesic_length.at(q);
    });
    // 1. The direct start, when the kept geodesics leave polygons for the others.
    std::size_t undone = 0;
    std::optional<Network_> net;
    std::optional<KeptNetwork::Embedded> checked;  // the direct start's, while its curves stay as they are
    if (start == Start::fast) {
        // First with the kept set taken as it is; when the check refuses it, with every kept
        // geodesic embedded and checked first (direct's check_kept).
        for (const bool check_kept : {false, true}) {
            try {
                if (std::optional<Network_> found = direct(T, real_vertices, D, geodesics, conflicts, order, executor, check_kept, say)) {
                    // Checked as a whole before it is used: (1), (2) and the patches.
                    const auto [paths, unsnapped] = in_edge_order(D, found->curves());
                    Embedding check = embed(T, D, paths, unsnapped, &executor);
                    if (check.conflicts.empty()) {
                        Patches patches = extract_patches(D, check.network, &executor);
                        for (FaceId df : D.mesh.faces()) {  // the faces of D that direct() left whole
                            auto& touched = found->touched()[corners_of(D, df)];
                            if (touched.empty()) touched = faces_of_t(patches, check.network, df);
                        }
                        net.emplace(std::move(*found));
                        checked = KeptNetwork::Embedded{std::move(check), std::move(patches)};
                        if (!check_kept) say("keeping the domain: the kept geodesics taken as they are, without embedding them first");
                    } else if (!check_kept) {
                        say("keeping the domain: the kept geodesics, read as in order, refused by the check; embedded and checked first");
                    }
                }
            } catch (const PartitionFailure&) {  // no room to separate: step back instead
            } catch (const std::logic_error&) {   // a region that is not what the kept curves promised: the same
            }
            if (net) break;
        }
        if (net) say("keeping the domain: the geodesics that conflict with no kept one are kept, the others restricted");
    }
    // 2. Else a valid start: D_i, until its geodesics satisfy (1) and (2). Only now is the
    //    decimation H needed (and proved or made, which at 10⁶ faces costs seconds).
    const domain::Domain& H = net ? D : base();
    std::size_t faces = H.mesh.n_faces();
    while (!net) {
        if (start == Start::gradual) {
            undone = std::min(H.history.size(), undone + std::max<std::size_t>(1, faces / 8));
        } else {
            undone = std::max(4 * undone, std::max<std::size_t>(1, faces / 8));
            // Past 16 |D| faces (each collapse takes two) the geodesics cost more than redoing from T.
            if (undone >= H.history.size() || H.mesh.n_faces() + 2 * undone > 16 * H.mesh.n_faces()) undone = H.history.size();
        }
        const domain::Domain Di = domain::undo_collapses(H, T, undone);
        faces = Di.mesh.n_faces();
        std::vector<geodesic::GeodesicPath> paths;
        if (undone == H.history.size()) {
            // D_i = T: the geodesic of an edge is the edge (a segment is the shortest curve in space).
            for (const auto& [a, b] : domain::edge_endpoints(Di))
                paths.push_back(geodesic::GeodesicPath{{SurfacePoint::at_vertex(a), SurfacePoint::at_vertex(b)}, (T.position(a) - T.position(b)).norm()});
        } else {
            for (const auto& p : geodesics_of(Di)) paths.push_back(p.path);
        }
        const Embedding embedding = embed(T, Di, paths, {}, &executor);
        if (embedding.conflicts.empty()) {
            net.emplace(T, real_vertices, make_domain(T, faces_in_t(Di)));
            const auto di_ends = domain::edge_endpoints(Di);
            for (std::size_t e = 0; e < paths.size(); ++e) {
                const auto [a, b] = di_ends[e];
                net->curves()[key_of(a, b)] = Curve{a.idx() < b.idx() ? paths[e] : reversed(paths[e]), true, {}, true,
                                                    domain::on_cone(Di.mesh, Di.t_vertex, EdgeId(static_cast<EdgeId::Index>(e)), real_vertices)};
            }
            const Patches patches = extract_patches(Di, embedding.network, &executor);
            for (FaceId df : Di.mesh.faces()) net->touched()[corners_of(Di, df)] = faces_of_t(patches, embedding.network, df);
            say("keeping the domain: the geodesics of a domain of " + std::to_string(faces) + " faces (" +
                std::to_string(undone) + " collapses undone) satisfy (1) and (2)");
            break;
        }
        if (undone == H.history.size()) throw std::logic_error("keeping the domain: conflicts on D = T, whose paths are T's edges");
    }
    // The start's size as the caller counts D: its faces on T, without the cone faces of D̂_i (the
    // direct start has exactly D's faces then; on a closed T nothing is left out).
    std::size_t start_faces = 0;
    for (FaceId f : net->domain().mesh.faces()) {
        const auto v = net->domain().mesh.face_vertices(f);
        start_faces += std::none_of(v.begin(), v.end(), [&](VertexId u) { return net->apex(net->x(u)); });
    }
    // 3. The undone collapses, redone on the network.
    if (undone > 0) {
        checked.reset();
        redo(*net, std::span<const domain::Collapse>(H.history).subspan(H.history.size() - undone), say, searches);
        if (canonical_faces(net->domain()) != canonical_faces(H)) throw std::logic_error("keeping the domain: the collapses redone do not give the decimation");
    }
    // 4. A domain given by the user: from the decimation to its edges by flips.
    if (canonical_faces(net->domain()) != canonical_faces(D)) {
        checked.reset();
        flip_to(*net, D, say, searches);
        // With every edge in place, only the orientation can differ: D turned over is not a domain of T.
        if (canonical_faces(net->domain()) != canonical_faces(D))
            throw PartitionFailure("keeping the domain: the given domain has the edges of T's decimation but its faces turned over");
    }

    // 5. Tightening, in the kept order.
    constexpr int max_passes = 3;
    for (int pass = 0; pass < max_passes; ++pass) {
        std::size_t changed = 0;
        std::vector<Pair> left;
        for (const Pair& k : order)
            if (!net->curves().at(k).exact) left.push_back(k);
        while (!left.empty()) {
            const domain::Domain& Dn = net->domain();
            std::vector<std::uint8_t> used(Dn.mesh.n_faces(), 0);
            std::vector<Job> jobs;
            std::vector<Pair> later;
            for (const Pair& k : left) {
                const VertexId a = net->at(k.first), b = net->at(k.second);
                const HalfedgeId h = Dn.mesh.find_halfedge(a, b);
                const FaceId f = Dn.mesh.face(h), g = Dn.mesh.face(TriMesh::twin(h));
                if (used[f.idx()] || used[g.idx()]) {
                    later.push_back(k);
                    continue;
                }
                used[f.idx()] = used[g.idx()] = 1;
                jobs.push_back(Job{.e = TriMesh::edge(h), .a = a, .b = b, .geodesic_length = geodesic_length.at(k), .current = net->curves().at(k).path.length});
            }
            compute(*net, jobs, searches);
            for (Job& j : jobs)
                if (j.curve) {
                    apply(*net, j);
                    ++changed;
                    checked.reset();
                }
            left = std::move(later);
        }
        say("keeping the domain: tightening pass " + std::to_string(pass + 1) + ", " + std::to_string(changed) + " curves shortened");
        if (changed == 0) break;
    }

    // 6. The curves in D's edge order.
    KeptNetwork out;
    out.start_faces = start_faces;
    auto [paths, unsnapped] = in_edge_order(D, net->curves());
    out.paths = EdgeData<geodesic::GeodesicPath>(std::move(paths));
    out.unsnapped = EdgeData<std::uint8_t>(std::move(unsnapped));
    out.embedded = std::move(checked);
    for (std::size_t e = 0; e < ends.size(); ++e) {
        const auto [a, b] = ends[e];
        const Pair k = key_of(a, b);
        const Curve& c = net->curves().at(k);
        CurveInfo info;
        info.geodesic_length = geodesic_length.at(k);
        if (c.fixed) info.kind = CurveKind::boundary;
        if (!c.exact) {
            info.kind = CurveKind::restricted;
            info.shortest = c.restricted.shortest;
            info.separation_bound = c.restricted.separation_bound;
            const auto r = reason.find(k);
            info.reason = r != reason.end() ? r->second : "its geodesic crosses the region of another curve";
        }
        out.info.push_back(std::move(info));
    }
    return out;
}

}  // namespace fhr::partition
