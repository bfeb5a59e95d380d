// Beyond the paper (§3): keeping the domain (see keep.hpp for the pseudocode).
#include <fhr/partition/detail/keep.hpp>

#include <algorithm>
#include <iterator>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <unordered_map>
#include <utility>
#include <variant>

#include <fhr/core/detail/cones.hpp>
#include <fhr/core/errors.hpp>
#include <fhr/core/executor.hpp>
#include <fhr/core/detail/outcome.hpp>
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
    for (FaceId f : patches.patch[df].faces) faces.push_back(FaceId(network.t_face[f]));
    return merged(std::move(faces), {});
}

geodesic::GeodesicPath reversed(geodesic::GeodesicPath p) {
    std::reverse(p.points.begin(), p.points.end());
    return p;
}

// A curve of the network, kept from its smaller vertex of T to its larger.
struct Curve {
    geodesic::GeodesicPath path;
    bool exact = false;           // the exact geodesic of T between its ends
    RestrictedPath restricted{};  // when not exact: how it was found
    // A geodesic of the start is snapped as embed() snaps geodesics; a curve found later is placed
    // as found, since snapping could move it across a curve that it passes closer than snapping.
    bool snapped = false;
    bool fixed = false;  // a cone edge or a boundary arc (domain::on_cone): never changed
};

// The network while D is being made: a domain, one curve per edge keyed by the edge's ends in T,
// and per face of D the faces of T its patch touches (the network is never embedded as a whole
// again: each change is made in its region, partition/region.hpp).
class Network_ {
public:
    Network_(const TriMesh& T, std::size_t real_vertices, domain::Domain D)
        : T_(T), real_(real_vertices), D_(std::move(D)) {}

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
        if (it == D_.t_vertex.end() || it->idx() != x)
            throw InternalError("keeping the domain: a vertex of T that is not in D");
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
    double geodesic_length = -1;                // tightening: |Γ| of the edge; a flip: -1
    double current = INFINITY;                  // tightening: the length of its curve now
    std::optional<Curve> curve{};               // the new curve, from a's vertex of T to b's
    std::vector<FaceId> on_left{}, on_right{};  // the faces of T its two patches touch (sides of
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
        // The network's own curves: a region that is not what they promise is a bug (value() throws).
        Region region = Region::cut_out(n.T(), q.touched, q.curves).value();
        const geodesic::WorkspacePool::Lease workspace = searches.workspaces.lease();
        RestrictedPath r =
            restricted_path(region, region.side(0, q.left).value(), n.x(j.a), n.x(j.b), workspace.get()).value();
        const bool exact = r.touches == 0 && j.geodesic_length >= 0 && r.shortest <= j.geodesic_length * (1 + 1e-12);
        if (!exact && !(r.path.length < j.current * (1 - 1e-9))) return;
        geodesic::GeodesicPath path = n.x(j.a).idx() < n.x(j.b).idx() ? std::move(r.path) : reversed(std::move(r.path));
        j.curve = Curve{std::move(path), exact, std::move(r)};
        region.add(RegionCurve{&j.curve->path, false}).value();
        j.on_left = region.t_faces(region.side(4, true).value());
        j.on_right = region.t_faces(region.side(4, false).value());
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

// The next batch of `left`: collapses whose closed 1-rings meet no earlier one's (taken or left),
// so that they commute with every collapse they overtake; the others stay in `left`. `blocked`:
// per vertex of D, all 0, and so again on return.
std::vector<domain::Collapse> next_batch(const Network_& net, std::vector<domain::Collapse>& left,
                                         std::vector<std::uint8_t>& blocked) {
    const TriMesh& m = net.domain().mesh;
    std::vector<domain::Collapse> batch, later;
    std::vector<VertexId> marked;
    const auto mark = [&](VertexId u) {
        if (!blocked[u.idx()]) marked.push_back(u);
        blocked[u.idx()] = 1;
    };
    for (const domain::Collapse& c : left) {
        const VertexId v = net.at(c.removed.idx());
        bool free = blocked[v.idx()] == 0;
        m.for_each_outgoing(v, [&](HalfedgeId h) { free = free && blocked[m.to(h).idx()] == 0; });
        mark(v);
        m.for_each_outgoing(v, [&](HalfedgeId h) { mark(m.to(h)); });
        (free ? batch : later).push_back(c);
    }
    for (VertexId u : marked) blocked[u.idx()] = 0;
    left = std::move(later);
    return batch;
}

// Flips v's spokes until it has valence 3, all collapses of the batch in step. The spoke flipped
// is next to [v, w] on alternate sides: each new curve may have to pass x_v inside the one before
// on its side, so alternating halves how deep they crowd.
void flip_to_valence_3(Network_& net, std::span<const domain::Collapse> batch, Searches& searches) {
    const TriMesh& m = net.domain().mesh;
    for (;;) {
        std::vector<Job> jobs;
        for (const domain::Collapse& c : batch) {
            const VertexId v = net.at(c.removed.idx()), w = net.at(c.kept.idx());
            const std::size_t valence = m.valence(v);
            if (valence <= 3) continue;
            // Spoke [v, u] in the face (v, w, u), or (w, v, u) on the other side; its other face
            // (v, u, y), or (u, v, y): the flip makes [w, y]. Along the boundary only the side of
            // the face of T (the other is a cone face).
            const HalfedgeId vw = m.find_halfedge(v, w);
            const bool along = net.apex(c.left) || net.apex(c.right);
            const HalfedgeId side = along              ? (net.apex(net.x(m.to(m.next(vw)))) ? TriMesh::twin(vw) : vw)
                                    : valence % 2 == 0 ? vw
                                                       : TriMesh::twin(vw);
            const VertexId u = m.to(m.next(side));
            const HalfedgeId spoke = side == vw ? m.find_halfedge(v, u) : m.find_halfedge(u, v);
            const VertexId y = m.to(m.next(spoke));
            if (!m.is_flip_ok(TriMesh::edge(spoke)))
                throw InternalError("keeping the domain: a spoke cannot be flipped");
            jobs.push_back(Job{.e = TriMesh::edge(spoke), .a = w, .b = y});
        }
        if (jobs.empty()) return;
        compute(net, jobs, searches);
        for (Job& j : jobs) apply(net, j);
    }
}

// Along the boundary, before the collapse v -> w (halfedge vw): v's face of T, (v, w, v') or
// (w, v, v'), joins the face across [v', w]; the new boundary edge [v', w] gets the arc of T's
// boundary.
void join_along_boundary(Network_& net, HalfedgeId vw) {
    const domain::Domain& D = net.domain();
    const TriMesh& m = D.mesh;
    const VertexId w = m.to(vw);
    const HalfedgeId side = net.apex(net.x(m.to(m.next(vw)))) ? TriMesh::twin(vw) : vw;
    const VertexId vp = m.to(m.next(side));
    const HalfedgeId inside = side == vw ? m.find_halfedge(w, vp) : m.find_halfedge(vp, w);
    const FaceId own = m.face(side), across = m.face(TriMesh::twin(inside));
    auto& joined = net.touched().at(corners_of(D, across));
    auto& given = net.touched().at(corners_of(D, own));
    joined = merged(std::move(joined), given);
    given.clear();
    // After the collapse, D's face of T beside [v', w] is `across`: left of v' -> w when own =
    // (v, w, v') holds w -> v', else left of w -> v'. The arc passes x_v.
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

// Collapse c, v now of valence 3: v -> w merges its three faces into (w, a, b) and removes its
// three curves; the new face's patch is the three patches' union.
void collapse(Network_& net, const domain::Collapse& c) {
    domain::Domain& D = net.domain();
    const VertexId v = net.at(c.removed.idx()), w = net.at(c.kept.idx());
    const HalfedgeId vw = D.mesh.find_halfedge(v, w);
    if (!D.mesh.is_collapse_ok(vw)) throw InternalError("keeping the domain: a collapse cannot be redone");
    if (net.apex(c.left) || net.apex(c.right)) join_along_boundary(net, vw);
    std::vector<FaceId> touched;
    D.mesh.for_each_outgoing(v, [&](HalfedgeId h) {
        const auto it = net.touched().find(corners_of(D, D.mesh.face(h)));
        touched = merged(std::move(touched), it->second);
        net.touched().erase(it);
        net.curves().erase(key_of(c.removed, net.x(D.mesh.to(h))));
    });
    Corners k{c.kept.idx(), net.x(D.mesh.to(D.mesh.next(vw))).idx(),
              net.x(D.mesh.to(D.mesh.next(TriMesh::twin(vw)))).idx()};
    std::sort(k.begin(), k.end());
    D.mesh.collapse(vw);
    net.touched()[k] = std::move(touched);
}

// Redoes `collapses` (in T's numbering, in their order) on the network, a batch at a time.
void redo(Network_& net, std::span<const domain::Collapse> collapses,
          const std::function<void(const std::string&)>& say, Searches& searches) {
    domain::Domain& D = net.domain();
    // Vertices keep their numbers until the end (removed ones become garbage).
    std::vector<domain::Collapse> left(collapses.begin(), collapses.end());
    std::vector<std::uint8_t> blocked(D.mesh.n_vertices(), 0);
    while (!left.empty()) {
        const std::vector<domain::Collapse> batch = next_batch(net, left, blocked);
        flip_to_valence_3(net, batch, searches);
        for (const domain::Collapse& c : batch) collapse(net, c);
        if (say)
            say("keeping the domain: redid " + std::to_string(batch.size()) + " collapses on the network, " +
                std::to_string(left.size()) + " to go");
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
// are missing, and makes it. Each flip is a restricted path in its region, as in the redo.
constexpr std::size_t search_budget = 200000;

class FlipsTo {
public:
    FlipsTo(Network_& net, const domain::Domain& target, Searches& searches)
        : net_(net), D_(net.domain()), searches_(searches) {
        for (const auto& [a, b] : domain::edge_endpoints(target)) want_.insert(key_of(a, b));
    }

    /// The flips made. \throws PartitionFailure when the target is not reached.
    std::size_t run() {
        const std::size_t first = missing_in(D_.mesh);
        std::size_t flips = 0;
        for (std::size_t missing = first; missing > 0; missing = missing_in(D_.mesh)) {
            if (flips > 4 * first + 16)
                throw PartitionFailure(
                    "keeping the domain: the given domain is not reached by flips from its decimation");
            if (std::vector<Job> jobs = making_target_edges(); !jobs.empty()) {
                flips += flip(std::move(jobs));
                continue;
            }
            for (EdgeId e : sequence_nearer(missing)) flips += flip({job(e)});
        }
        return flips;
    }

private:
    Network_& net_;
    domain::Domain& D_;
    Searches& searches_;
    std::set<Pair> want_;             // the target's edges, by their ends in T
    std::vector<std::uint8_t> near_;  // per vertex of D: an end of a missing edge (sequence_nearer)
    std::vector<EdgeId> sequence_;    // the search's flips so far
    std::size_t states_ = 0;          // meshes the search looked at

    Pair key(const TriMesh& m, EdgeId e) const {
        const HalfedgeId h = TriMesh::halfedge(e, 0);
        return key_of(net_.x(m.from(h)), net_.x(m.to(h)));
    }
    Pair made(const TriMesh& m, EdgeId e) const {  // the edge that flipping e makes
        const HalfedgeId h = TriMesh::halfedge(e, 0);
        return key_of(net_.x(m.to(m.next(h))), net_.x(m.to(m.next(TriMesh::twin(h)))));
    }
    std::size_t missing_in(const TriMesh& m) const {
        std::size_t present = 0;
        for (EdgeId e : m.edges()) present += want_.count(key(m, e));
        return want_.size() - present;
    }
    std::size_t flip(std::vector<Job> jobs) {
        compute(net_, jobs, searches_);
        for (Job& j : jobs) apply(net_, j);
        return jobs.size();
    }
    Job job(EdgeId e) const {
        const HalfedgeId h = TriMesh::halfedge(e, 0);
        return Job{.e = e, .a = D_.mesh.to(D_.mesh.next(h)), .b = D_.mesh.to(D_.mesh.next(TriMesh::twin(h)))};
    }

    // The round's flips: edges not in the target whose flip makes one of its edges, in regions
    // with no face in common, no two making the same edge.
    std::vector<Job> making_target_edges() const {
        std::vector<Job> jobs;
        std::vector<std::uint8_t> used(D_.mesh.n_faces(), 0);
        std::set<Pair> making;
        for (EdgeId e : D_.mesh.edges()) {
            const HalfedgeId h = TriMesh::halfedge(e, 0);
            const FaceId f = D_.mesh.face(h), g = D_.mesh.face(TriMesh::twin(h));
            if (used[f.idx()] || used[g.idx()] || want_.count(key(D_.mesh, e)) || !D_.mesh.is_flip_ok(e) ||
                !want_.count(made(D_.mesh, e)) || !making.insert(made(D_.mesh, e)).second)
                continue;
            used[f.idx()] = used[g.idx()] = 1;
            jobs.push_back(job(e));
        }
        return jobs;
    }

    // The shortest sequence of flips (at most four) after which fewer than `missing` target edges
    // are missing, among flips with an end of a missing edge in their quadrilateral.
    std::vector<EdgeId> sequence_nearer(std::size_t missing) {
        near_.assign(D_.mesh.n_vertices(), 0);
        std::set<Pair> have;
        for (EdgeId e : D_.mesh.edges()) have.insert(key(D_.mesh, e));
        for (const Pair& k : want_)
            if (!have.count(k)) near_[net_.at(k.first).idx()] = near_[net_.at(k.second).idx()] = 1;
        sequence_.clear();
        states_ = 0;
        bool found = false;
        for (int depth = 1; depth <= 4 && !found; ++depth) found = search(D_.mesh, depth, missing);
        if (!found)
            throw PartitionFailure(
                std::string("keeping the domain: ") +
                (states_ > search_budget ? "no short sequence of flips found that brings" : "no four flips bring") +
                " the decimation nearer to the given domain");
        return sequence_;
    }

    bool candidate(const TriMesh& m, EdgeId e) const {
        const HalfedgeId h = TriMesh::halfedge(e, 0);
        if (domain::on_cone(m, D_.t_vertex, e, net_.real_vertices()))
            return false;  // a cone edge or a boundary edge of D: fixed
        return (near_[m.from(h).idx()] || near_[m.to(h).idx()] || near_[m.to(m.next(h)).idx()] ||
                near_[m.to(m.next(TriMesh::twin(h))).idx()]) &&
               m.is_flip_ok(e);
    }

    bool search(const TriMesh& m, int depth, std::size_t missing) {
        if (missing_in(m) < missing) return true;
        if (depth == 0) return false;
        for (EdgeId e : m.edges()) {
            if (!candidate(m, e) || ++states_ > search_budget) continue;
            TriMesh next = m;
            next.flip(e);
            sequence_.push_back(e);
            if (search(next, depth - 1, missing)) return true;
            sequence_.pop_back();
        }
        return false;
    }
};

void flip_to(Network_& net, const domain::Domain& target, const std::function<void(const std::string&)>& say,
             Searches& searches) {
    const std::size_t flips = FlipsTo(net, target, searches).run();
    if (say) say("keeping the domain: " + std::to_string(flips) + " flips from the decimation to the given domain");
}

// The curves in D's edge order, each along D's halfedge (e, 0), and which of them embed() must
// place as given.
std::pair<std::vector<geodesic::GeodesicPath>, std::vector<std::uint8_t>> in_edge_order(
    const domain::Domain& D, const std::map<Pair, Curve>& curves) {
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
using CornerOf = std::function<VertexId(VertexId)>;
using IsKept = std::function<bool(HalfedgeId)>;
using CurveOf = std::function<const geodesic::GeodesicPath&(HalfedgeId)>;

// No two kept curves share a node, none passes through a corner inside, none has a node inside a face.
bool nodes_apart(const TriMesh& T, const TriMesh& m, const CornerOf& x, const IsKept& is_kept, const CurveOf& curve) {
    std::set<std::pair<std::uint32_t, double>> nodes;  // vertices as (index, -1), edge points as (edge, t along (e, 0))
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
                key = {static_cast<std::uint32_t>(T.n_vertices() + TriMesh::edge(p.halfedge).idx()),
                       forward ? p.t : 1 - p.t};
            } else {
                return false;
            }
            if (!nodes.insert(key).second) return false;
        }
    }
    return true;
}

// Where a curve's first step p from x_j leaves in T's fan of spokes around x_j (2k: along spoke
// k; 2k − 1: across the face before it), and where along it; {SIZE_MAX, 0} when it cannot be read.
std::pair<std::size_t, double> place_in_fan(const TriMesh& T, const std::vector<HalfedgeId>& spokes,
                                            const SurfacePoint& p) {
    std::pair<std::size_t, double> place{SIZE_MAX, 0};
    for (std::size_t k = 0; k < spokes.size() && place.first == SIZE_MAX; ++k) {
        const HalfedgeId s = spokes[k];
        if (p.kind == SurfacePoint::Kind::vertex && p.vertex == T.to(s)) place = {2 * k, 0};
        if (p.kind == SurfacePoint::Kind::edge && TriMesh::edge(p.halfedge) == TriMesh::edge(s))
            place = {2 * k, p.halfedge == s ? p.t : 1 - p.t};
        // face(s) = (x_j, to(s), b) lies between s and the spoke before it clockwise
        // (for_each_outgoing's order), x_j -> b: its far edge is crossed from b to to(s).
        if (p.kind == SurfacePoint::Kind::edge && !T.is_boundary(s) &&
            TriMesh::edge(p.halfedge) == TriMesh::edge(T.next(s)))
            place = {(2 * k + 2 * spokes.size() - 1) % (2 * spokes.size()), p.halfedge == T.next(s) ? 1 - p.t : p.t};
    }
    return place;
}

// Around corner x_v the kept curves' first steps leave through distinct points, in D's cyclic order.
bool in_order_at(const TriMesh& T, const TriMesh& m, VertexId v, const CornerOf& x, const IsKept& is_kept,
                 const CurveOf& curve) {
    const VertexId xv = x(v);
    std::vector<HalfedgeId> spokes;
    T.for_each_outgoing(xv, [&](HalfedgeId h) { spokes.push_back(h); });
    std::vector<std::pair<std::pair<std::size_t, double>, std::size_t>> in_t;  // (place in the fan, rank in D)
    std::size_t rank = 0;
    bool readable = true;
    m.for_each_outgoing(v, [&](HalfedgeId h) {
        if (!is_kept(h) || !readable) return;
        const auto& points = curve(h).points;
        const auto place = place_in_fan(T, spokes, points.front().vertex == xv ? points[1] : points[points.size() - 2]);
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
    return true;
}

bool kept_plausible(const TriMesh& T, const TriMesh& m, const CornerOf& x, const IsKept& is_kept,
                    const CurveOf& curve) {
    if (!nodes_apart(T, m, x, is_kept, curve)) return false;
    for (VertexId v : m.vertices())
        if (!in_order_at(T, m, v, x, is_kept, curve)) return false;
    return true;
}

// Whether two cyclic sequences are the same cycle (the same elements in the same order, from any start).
bool same_cycle(const std::vector<Pair>& a, const std::vector<Pair>& b) {
    if (a.size() != b.size()) return false;
    if (a.empty()) return true;
    const auto at = std::find(b.begin(), b.end(), a[0]);
    if (at == b.end()) return false;
    const std::size_t shift = static_cast<std::size_t>(at - b.begin());
    for (std::size_t i = 0; i < a.size(); ++i)
        if (a[i] != b[(i + shift) % b.size()]) return false;
    return true;
}

using Step = Outcome<std::monostate>;
const Step done = std::monostate{};

// The direct start (keep.hpp, step 1): keep the geodesics of D that conflict with no kept one,
// and put each other edge in as a restricted path in the polygon its two faces (and those of other
// removed edges) leave. run() says why not when the kept geodesics do not leave such polygons
// (disks bounded by kept curves, one region of T each), or when a step on the way fails: the
// caller then steps back instead.
//   choose_kept      the kept set in the kept order: no conflict of its own, none with a kept edge
//   embed_kept       the kept geodesics embedded, rounds dropping those out of D's order (2)
//   group_faces      D's faces joined across removed edges: each group a disk (a polygon)
//   find_regions     each polygon's region of T′
//   split_polygons   each removed edge a restricted path in its polygon, slits first
// `check_kept`: embed every kept geodesic first, drop those in conflicts the geodesics' conflicts
// did not name or out of D's order around a corner, and find every polygon's region of T in that
// embedding. Without it (at 10⁶ faces that embedding cost ~0.6 s for one removed edge
// among 15,000), the kept set is taken as it is and only the curves around polygons of more than
// one face are embedded to find their regions; the faces of D kept whole get no touched faces
// (the caller takes them from its check, which also decides whether the kept set was sound).
class DirectStart {
public:
    DirectStart(const TriMesh& T, std::size_t real_vertices, const domain::Domain& D,
                std::span<const geodesic::EllipsePath> geodesics, std::span<const Conflict> conflicts,
                std::span<const Pair> order, Executor& executor, bool check_kept,
                const std::function<void(const std::string&)>& say)
        : T_(T),
          D_(D),
          geodesics_(geodesics),
          conflicts_(conflicts),
          order_(order),
          executor_(executor),
          check_kept_(check_kept),
          say_(say),
          real_vertices_(real_vertices),
          ends_(domain::edge_endpoints(D)),
          net_(T, real_vertices, make_domain(T, faces_in_t(D))) {
        for (std::size_t e = 0; e < ends_.size(); ++e) edge_of_[key_of(ends_[e].first, ends_[e].second)] = e;
    }

    Outcome<Network_> run() {
        choose_kept();
        Step step = embed_kept();
        if (step) step = group_faces();
        if (step) step = find_regions();
        if (step) step = split_polygons();
        if (!step) return Outcome<Network_>::failure(step.why());
        return std::move(net_);
    }

private:
    const TriMesh& T_;
    const domain::Domain& D_;
    std::span<const geodesic::EllipsePath> geodesics_;
    std::span<const Conflict> conflicts_;
    std::span<const Pair> order_;
    Executor& executor_;
    bool check_kept_;
    std::function<void(const std::string&)> say_;
    std::size_t real_vertices_;
    std::vector<std::pair<VertexId, VertexId>> ends_;  // per edge of D, its ends' vertices of T
    std::map<Pair, std::size_t> edge_of_;              // an edge of D by its ends in T
    std::vector<std::uint8_t> kept_, fixed_;           // per edge of D
    std::map<Pair, std::size_t> rank_;                 // place in the kept order
    Network_ net_;
    std::vector<geodesic::GeodesicPath> paths_;  // the kept geodesics, each from its smaller vertex of T
    std::map<Pair, std::size_t> index_;          // a kept edge's place in paths_
    Embedding cut_;                              // the kept geodesics (or the polygons' curves) embedded
    std::vector<std::int32_t> group_;            // per face of D (net_'s), its group
    std::vector<std::vector<FaceId>> groups_;    // the faces of each group
    std::vector<std::vector<FaceId>> touched_;   // per group, the faces of T its region touches

    const TriMesh& m() const { return net_.domain().mesh; }
    Pair edge_key(HalfedgeId h) const { return key_of(net_.x(m().from(h)), net_.x(m().to(h))); }
    bool is_kept(HalfedgeId h) const { return kept_[edge_of_.at(edge_key(h))] != 0; }
    bool on_boundary(VertexId v) const {  // a kept edge at v: v is on the boundary of its groups
        bool any = false;
        m().for_each_outgoing(v, [&](HalfedgeId h) { any = any || is_kept(h); });
        return any;
    }

    void choose_kept() {
        kept_.assign(ends_.size(), 0);
        fixed_.assign(ends_.size(), 0);
        std::vector<std::uint8_t> alone(ends_.size(), 1);
        for (EdgeId e : D_.mesh.edges()) fixed_[e.idx()] = domain::on_cone(D_.mesh, D_.t_vertex, e, real_vertices_);
        std::vector<std::vector<std::size_t>> against(ends_.size());
        for (const Conflict& c : conflicts_) {
            if (c.kind == Conflict::Kind::order) continue;  // settled among the kept ones (embed_kept)
            const std::uint32_t a = c.d_edge_a.idx(), b = c.d_edge_b.idx();
            if (a == b) alone[a] = 0;
            against[a].push_back(b);
            against[b].push_back(a);
        }
        for (const Pair& k : order_) {
            const std::size_t e = edge_of_.at(k);
            rank_[k] = rank_.size();
            kept_[e] = fixed_[e] || (alone[e] && std::none_of(against[e].begin(), against[e].end(),
                                                              [&](std::size_t o) { return kept_[o] != 0; }));
        }
    }

    // The kept geodesics embedded; where the kept curves around a corner are out of D's cyclic
    // order (embed() checks (2) only once (1) holds), one of them is not kept either, a round at
    // a time, until they are in order. Without check_kept, only whether they are plausible.
    Step embed_kept() {
        for (int round = 0;; ++round) {
            paths_.clear();
            index_.clear();
            for (std::size_t e = 0; e < ends_.size(); ++e) {
                if (!kept_[e]) continue;
                const auto [a, b] = ends_[e];
                index_[key_of(a, b)] = paths_.size();
                paths_.push_back(a.idx() < b.idx() ? geodesics_[e].path : reversed(geodesics_[e].path));
            }
            if (!check_kept_) {
                if (!kept_plausible(
                        T_, m(), [&](VertexId v) { return net_.x(v); }, [&](HalfedgeId h) { return is_kept(h); },
                        [&](HalfedgeId h) -> const geodesic::GeodesicPath& {
                            return paths_[index_.at(edge_key(h))];
                        })) {
                    say_(
                        "keeping the domain: the kept geodesics embedded and checked first (two share a point, or some "
                        "leave a corner out of D's order)");
                    return Step::failure("the kept geodesics are not plausible as they are");
                }
                break;
            }
            cut_ = embed_curves(T_, paths_, {}, &executor_);
            if (round == 64) return Step::failure("the kept geodesics still conflict after 64 rounds");
            if (!cut_.conflicts.empty()) {
                drop_conflicting();
                continue;
            }
            Outcome<std::vector<std::size_t>> out_of_order = out_of_d_order();
            if (!out_of_order) return Step::failure(out_of_order.why());
            if (out_of_order->empty()) break;
            for (std::size_t e : *out_of_order) kept_[e] = 0;
        }
        for (const auto& [k, i] : index_)
            net_.curves()[k] = Curve{paths_[i], true, {}, true, fixed_[edge_of_.at(k)] != 0};
        return done;
    }

    // A conflict the first embedding did not report (it names one pair per shared point): the later
    // edge of the pair in the kept order goes.
    void drop_conflicting() {
        for (const Conflict& c : cut_.conflicts) {
            const auto& pa = paths_[c.d_edge_a.idx()].points;
            const auto& pb = paths_[c.d_edge_b.idx()].points;
            const Pair a = key_of(pa.front().vertex, pa.back().vertex), b = key_of(pb.front().vertex, pb.back().vertex);
            kept_[edge_of_.at(rank_.at(a) >= rank_.at(b) ? a : b)] = 0;
        }
    }

    // The kept edges to drop so that the kept curves leave every corner in D's order: a curve of
    // another edge through x_v, and where the others are out of order, the one curve whose removal
    // puts the rest in order (the first such in D's order), or, when no one does, the first of D's.
    Outcome<std::vector<std::size_t>> out_of_d_order() const {
        std::vector<std::size_t> out_of_order;
        for (VertexId v : m().vertices()) {
            std::vector<Pair> in_d, in_t, own;
            m().for_each_outgoing(v, [&](HalfedgeId h) {
                if (is_kept(h)) in_d.push_back(edge_key(h));
            });
            cut_.network.mesh.for_each_outgoing(net_.x(v), [&](HalfedgeId h) {
                const DHalfedgeId label = cut_.network.d_halfedge[h];
                if (!label.valid()) return;
                const auto& p = paths_[TriMesh::edge(label).idx()].points;
                in_t.push_back(key_of(p.front().vertex, p.back().vertex));
            });
            for (const Pair& k : in_t) {
                if (std::find(in_d.begin(), in_d.end(), k) == in_d.end())
                    out_of_order.push_back(edge_of_.at(k));
                else
                    own.push_back(k);
            }
            if (same_cycle(in_d, own)) continue;
            const auto movable =
                std::find_if(in_d.begin(), in_d.end(), [&](const Pair& k) { return !fixed_[edge_of_.at(k)]; });
            if (movable == in_d.end())
                return Outcome<std::vector<std::size_t>>::failure("fixed curves alone out of order: not a domain of T");
            std::size_t drop = edge_of_.at(*movable);
            for (const Pair& k : in_d) {
                if (fixed_[edge_of_.at(k)]) continue;
                std::vector<Pair> a, b;
                std::copy_if(in_d.begin(), in_d.end(), std::back_inserter(a), [&](const Pair& x) { return x != k; });
                std::copy_if(own.begin(), own.end(), std::back_inserter(b), [&](const Pair& x) { return x != k; });
                if (same_cycle(a, b)) {
                    drop = edge_of_.at(k);
                    break;
                }
            }
            out_of_order.push_back(drop);
        }
        return out_of_order;
    }

    // Groups: D's faces joined across removed edges; each must be a disk (is_disk).
    Step group_faces() {
        group_.assign(m().n_faces(), -1);
        for (FaceId f : m().faces()) {
            if (group_[f.idx()] >= 0) continue;
            std::vector<FaceId>& g = groups_.emplace_back();
            std::vector<FaceId> stack{f};
            group_[f.idx()] = static_cast<std::int32_t>(groups_.size() - 1);
            std::size_t inner = 0;
            while (!stack.empty()) {
                const FaceId a = stack.back();
                stack.pop_back();
                g.push_back(a);
                HalfedgeId h = m().halfedge(a);
                for (int i = 0; i < 3; ++i, h = m().next(h)) {
                    if (is_kept(h)) continue;
                    ++inner;
                    const FaceId b = m().face(TriMesh::twin(h));
                    if (group_[b.idx()] < 0) {
                        group_[b.idx()] = group_[a.idx()];
                        stack.push_back(b);
                    }
                }
            }
            if (!is_disk(g, inner)) return Step::failure("the kept curves leave a polygon that is not a disk");
        }
        return done;
    }

    // A group is a disk when its boundary is one closed walk: with V vertices, E edges, F faces and
    // r repeated boundary vertices, V − E + F = 1 − r (a vertex met twice pinches the disk there).
    // `inner`: its inner edges, each counted from both sides.
    bool is_disk(const std::vector<FaceId>& g, std::size_t inner) const {
        std::set<VertexId::Index> vertices;
        std::size_t boundary = 0;
        HalfedgeId start;
        for (FaceId a : g) {
            HalfedgeId h = m().halfedge(a);
            for (int i = 0; i < 3; ++i, h = m().next(h)) {
                vertices.insert(m().from(h).idx());
                if (is_kept(h)) ++boundary, start = h;
            }
        }
        // One closed walk: from a boundary halfedge, the next one turns around its head inside the group.
        std::size_t walk = 0;
        std::set<VertexId::Index> met;
        std::size_t repeated = 0;
        for (HalfedgeId h = start; start.valid() && (walk == 0 || h != start); ++walk) {
            repeated += !met.insert(m().to(h).idx()).second;
            HalfedgeId n = m().next(h);
            while (!is_kept(n)) n = m().next(TriMesh::twin(n));
            h = n;
            if (walk > boundary) return false;
        }
        const long chi =
            static_cast<long>(vertices.size()) - static_cast<long>(inner / 2 + boundary) + static_cast<long>(g.size());
        return boundary != 0 && walk == boundary && chi == 1 - static_cast<long>(repeated);
    }

    // Each group's region of T′, found from one of its boundary curves (without check_kept, only
    // the polygons' curves embedded, and a face kept whole left to the caller).
    Step find_regions() {
        std::map<Pair, std::size_t> embedded = index_;  // a curve's number in cut_
        if (!check_kept_) {
            std::vector<geodesic::GeodesicPath> around;
            embedded.clear();
            for (const std::vector<FaceId>& g : groups_) {
                if (g.size() == 1) continue;
                for (FaceId a : g) {
                    HalfedgeId h = m().halfedge(a);
                    for (int i = 0; i < 3; ++i, h = m().next(h))
                        if (is_kept(h) && embedded.emplace(edge_key(h), around.size()).second)
                            around.push_back(paths_[index_.at(edge_key(h))]);
                }
            }
            cut_ = embed_curves(T_, around, {}, &executor_);
            if (!cut_.conflicts.empty()) return Step::failure("the polygons' curves conflict");
        }
        std::vector<std::int32_t> region(cut_.network.mesh.n_faces(), -1);
        touched_.assign(groups_.size(), {});
        for (std::size_t gi = 0; gi < groups_.size(); ++gi) {
            if (!check_kept_ && groups_[gi].size() == 1) continue;
            if (Step filled = fill_region(gi, embedded, region); !filled) return filled;
        }
        return done;
    }

    // Group gi's region of T′: the faces reached from the side of one of its boundary curves
    // without crossing a curve; none may belong to another group's region.
    Step fill_region(std::size_t gi, const std::map<Pair, std::size_t>& embedded, std::vector<std::int32_t>& region) {
        const TriMesh& M = cut_.network.mesh;
        HalfedgeId boundary;
        for (FaceId a : groups_[gi]) {
            HalfedgeId h = m().halfedge(a);
            for (int i = 0; i < 3; ++i, h = m().next(h))
                if (is_kept(h)) boundary = h;
        }
        const auto& path = cut_.network.path[DEdgeId(embedded.at(edge_key(boundary)))];
        const HalfedgeId first = M.find_halfedge(path[0], path[1]);
        const FaceId seed =
            M.face(net_.x(m().from(boundary)).idx() < net_.x(m().to(boundary)).idx() ? first : TriMesh::twin(first));
        if (region[seed.idx()] >= 0) return Step::failure("two polygons in one region of T′");
        std::vector<FaceId> stack{seed};
        region[seed.idx()] = static_cast<std::int32_t>(gi);
        while (!stack.empty()) {
            const FaceId a = stack.back();
            stack.pop_back();
            touched_[gi].push_back(FaceId(cut_.network.t_face[a]));
            HalfedgeId h = M.halfedge(a);
            for (int i = 0; i < 3; ++i, h = M.next(h)) {
                if (cut_.network.d_halfedge[h].valid()) continue;
                const FaceId b = M.face(TriMesh::twin(h));
                if (region[b.idx()] == static_cast<std::int32_t>(gi)) continue;
                if (region[b.idx()] >= 0) return Step::failure("two polygons in one region of T′");
                region[b.idx()] = static_cast<std::int32_t>(gi);
                stack.push_back(b);
            }
        }
        touched_[gi] = merged(std::move(touched_[gi]), {});
        return done;
    }

    // The removed edges, in the kept order: first those from an inner vertex to the boundary (a
    // slit: the polygon stays whole, the vertex is on its boundary from then on), then diagonals,
    // whose restricted paths split their polygon and its faces of T in two. One after another,
    // on one workspace.
    Step split_polygons() {
        geodesic::Workspace workspace;
        while (const std::optional<Pair> next = next_removed())
            if (Step split = put_in(*next, workspace); !split) return split;
        for (std::size_t gi = 0; gi < groups_.size(); ++gi) {
            if (groups_[gi].size() != 1) throw InternalError("keeping the domain: a polygon left unsplit");
            if (!touched_[gi].empty())
                net_.touched()[corners_of(net_.domain(), groups_[gi][0])] =
                    std::move(touched_[gi]);  // else the caller's
        }
        return done;
    }

    // The next removed edge to put in: a slit (one end inside its polygon) first, in the kept order.
    std::optional<Pair> next_removed() const {
        for (int slit = 1; slit >= 0; --slit)
            for (const Pair& k : order_) {
                if (kept_[edge_of_.at(k)]) continue;
                const int ends_on_boundary = on_boundary(net_.at(k.first)) + on_boundary(net_.at(k.second));
                if (ends_on_boundary == 2 - slit) return k;
            }
        return std::nullopt;
    }

    // Removed edge k as the restricted path in its polygon, cut out on its own (region.hpp); its
    // polygon split in two along it (or, a slit, kept whole).
    Step put_in(const Pair& k, geodesic::Workspace& workspace) {
        const std::size_t e = edge_of_.at(k);
        const HalfedgeId h = m().find_halfedge(net_.at(k.first), net_.at(k.second));
        const std::int32_t gi = group_[m().face(h).idx()];
        std::vector<RegionCurve> around;
        std::set<Pair> listed;  // a slit has the polygon on both sides
        bool left = true;
        for (FaceId a : groups_[static_cast<std::size_t>(gi)]) {
            HalfedgeId g = m().halfedge(a);
            for (int i = 0; i < 3; ++i, g = m().next(g)) {
                if (!is_kept(g) || !listed.insert(edge_key(g)).second) continue;
                if (around.empty()) left = net_.x(m().from(g)).idx() < net_.x(m().to(g)).idx();
                const Curve& c = net_.curves().at(edge_key(g));
                around.push_back(RegionCurve{&c.path, c.snapped});
            }
        }
        Outcome<Region> cut_out = Region::cut_out(T_, touched_[static_cast<std::size_t>(gi)], around);
        if (!cut_out) return Step::failure("a polygon of the kept curves: " + cut_out.why());
        Outcome<FaceData<std::uint8_t>> inside = cut_out->side(0, left);
        if (!inside) return Step::failure("a polygon of the kept curves: " + inside.why());
        if (!cut_out->find_sub(VertexId(k.first)) || !cut_out->find_sub(VertexId(k.second)))
            return Step::failure("a removed edge's end lies outside the faces of its polygon");
        Outcome<RestrictedPath> r =
            restricted_path(*cut_out, *inside, VertexId(k.first), VertexId(k.second), &workspace);
        if (!r) return Step::failure("a polygon of the kept curves: " + r.why());
        Curve& c = net_.curves()[k] = Curve{std::move(r->path), false, *r, false};
        if (Step added = cut_out->add(RegionCurve{&c.path, false}); !added)
            return Step::failure("a polygon of the kept curves: " + added.why());
        kept_[e] = 1;
        return split_group(static_cast<std::size_t>(gi), m().face(h), *cut_out, around.size());
    }

    // Group gi split along its new curve (number `added` in `cut_out`): the faces on the left of
    // lo -> hi (with face `left_of`) stay, those on its right make a new group; a slit has none there.
    Step split_group(std::size_t gi, FaceId left_of, const Region& cut_out, std::size_t added) {
        std::vector<FaceId> stack{left_of};
        std::vector<std::uint8_t> on_left(m().n_faces(), 0);
        on_left[left_of.idx()] = 1;
        while (!stack.empty()) {
            const FaceId a = stack.back();
            stack.pop_back();
            HalfedgeId g = m().halfedge(a);
            for (int i = 0; i < 3; ++i, g = m().next(g)) {
                const FaceId b = m().face(TriMesh::twin(g));
                if (is_kept(g) || on_left[b.idx()]) continue;
                on_left[b.idx()] = 1;
                stack.push_back(b);
            }
        }
        std::vector<FaceId> left_faces, right_faces;
        for (FaceId a : groups_[gi]) (on_left[a.idx()] ? left_faces : right_faces).push_back(a);
        Outcome<FaceData<std::uint8_t>> left_side = cut_out.side(added, true);
        if (!left_side) return Step::failure("a polygon of the kept curves: " + left_side.why());
        if (right_faces.empty()) {  // a slit
            touched_[gi] = cut_out.t_faces(*left_side);
            return done;
        }
        Outcome<FaceData<std::uint8_t>> right_side = cut_out.side(added, false);
        if (!right_side) return Step::failure("a polygon of the kept curves: " + right_side.why());
        const std::int32_t gj = static_cast<std::int32_t>(groups_.size());
        for (FaceId a : right_faces) group_[a.idx()] = gj;
        touched_.push_back(cut_out.t_faces(*right_side));
        touched_[gi] = cut_out.t_faces(*left_side);
        groups_[gi] = std::move(left_faces);
        groups_.push_back(std::move(right_faces));
        return done;
    }
};

// Keeping D (keep.hpp's pseudocode), one method per step: the kept order, the direct start or
// else the valid start, the undone collapses redone, the flips to a given domain, the tightening,
// and the curves in D's edge order.
class KeepNetwork {
public:
    KeepNetwork(const TriMesh& T, std::size_t real_vertices, const domain::Domain& D,
                const std::function<const domain::Domain&()>& base, std::span<const geodesic::EllipsePath> geodesics,
                std::span<const Conflict> conflicts,
                const std::function<std::vector<geodesic::EllipsePath>(const domain::Domain&)>& geodesics_of,
                const std::function<void(const std::string&)>& progress, Executor& executor, Start start)
        : T_(T),
          real_vertices_(real_vertices),
          D_(D),
          base_(base),
          geodesics_(geodesics),
          conflicts_(conflicts),
          geodesics_of_(geodesics_of),
          progress_(progress),
          executor_(executor),
          start_(start),
          searches_{executor},
          ends_(domain::edge_endpoints(D)) {}

    KeptNetwork run() {
        kept_order();
        if (start_ == Start::fast) direct_start();
        const domain::Domain& H = net_ ? D_ : base_();  // the decimation, needed only now
        if (!net_) valid_start(H);
        const std::size_t start_faces = faces_on_t();
        if (undone_ > 0) redo_collapses(H);
        if (canonical_faces(net_->domain()) != canonical_faces(D_)) flip_to_given();
        tighten();
        return in_d_order(start_faces);
    }

private:
    const TriMesh& T_;
    std::size_t real_vertices_;
    const domain::Domain& D_;
    const std::function<const domain::Domain&()>& base_;
    std::span<const geodesic::EllipsePath> geodesics_;
    std::span<const Conflict> conflicts_;
    const std::function<std::vector<geodesic::EllipsePath>(const domain::Domain&)>& geodesics_of_;
    const std::function<void(const std::string&)>& progress_;
    Executor& executor_;
    Start start_;
    Searches searches_;
    std::vector<std::pair<VertexId, VertexId>> ends_;  // per edge of D, its ends' vertices of T
    std::map<Pair, double> geodesic_length_;           // per edge of D by its ends: |Γ|
    std::map<Pair, std::string> reason_;               // why an edge's geodesic conflicts
    std::vector<Pair> order_;                          // the kept order
    std::optional<Network_> net_;
    std::optional<KeptNetwork::Embedded> checked_;  // the direct start's, while its curves stay as they are
    std::size_t undone_ = 0;                        // collapses of the decimation undone by the valid start

    void say(const std::string& line) const {
        if (progress_) progress_(line);
    }

    // The kept order: the fixed curves (cone edges, D's boundary edges) first, then edges whose
    // geodesic is in no conflict, then the others, each group shortest geodesic first.
    void kept_order() {
        for (std::size_t e = 0; e < ends_.size(); ++e)
            geodesic_length_[key_of(ends_[e].first, ends_[e].second)] = geodesics_[e].path.length;
        for (const Conflict& c : conflicts_)
            for (DEdgeId e : {c.d_edge_a, c.d_edge_b})
                reason_.emplace(key_of(ends_[e.idx()].first, ends_[e.idx()].second), c.describe());
        for (const auto& [k, length] : geodesic_length_) order_.push_back(k);
        std::set<Pair> fixed;
        for (EdgeId e : D_.mesh.edges())
            if (domain::on_cone(D_.mesh, D_.t_vertex, e, real_vertices_))
                fixed.insert(key_of(ends_[e.idx()].first, ends_[e.idx()].second));
        std::stable_sort(order_.begin(), order_.end(), [&](const Pair& p, const Pair& q) {
            const bool fp = fixed.count(p) != 0, fq = fixed.count(q) != 0;
            if (fp != fq) return fp;
            const bool cp = reason_.count(p) != 0, cq = reason_.count(q) != 0;
            if (cp != cq) return !cp;
            return geodesic_length_.at(p) < geodesic_length_.at(q);
        });
    }

    // 1. The direct start: first with the kept set taken as it is; when the check refuses it, with
    //    every kept geodesic embedded and checked first (DirectStart's check_kept).
    void direct_start() {
        for (const bool check_kept : {false, true}) {
            try {
                Outcome<Network_> found = DirectStart(T_, real_vertices_, D_, geodesics_, conflicts_, order_, executor_,
                                                      check_kept, [this](const std::string& line) { say(line); })
                                              .run();
                if (found) take_if_checked(std::move(*found), check_kept);
            } catch (const PartitionFailure&) {  // no room to separate: step back instead
            }
            if (net_) break;
        }
        if (net_)
            say("keeping the domain: the geodesics that conflict with no kept one are kept, the others restricted");
    }

    // The direct start's network, checked as a whole before it is used: (1), (2) and the patches.
    void take_if_checked(Network_ found, bool check_kept) {
        const auto [paths, unsnapped] = in_edge_order(D_, found.curves());
        Embedding check = embed(T_, D_, paths, unsnapped, &executor_);
        if (!check.conflicts.empty()) {
            if (!check_kept)
                say("keeping the domain: the kept geodesics, read as in order, refused by the check; embedded and "
                    "checked first");
            return;
        }
        Patches patches = extract_patches(D_, check.network, &executor_);
        for (FaceId df : D_.mesh.faces()) {  // the faces of D that the direct start left whole
            auto& touched = found.touched()[corners_of(D_, df)];
            if (touched.empty()) touched = faces_of_t(patches, check.network, df);
        }
        net_.emplace(std::move(found));
        checked_ = KeptNetwork::Embedded{std::move(check), std::move(patches)};
        if (!check_kept) say("keeping the domain: the kept geodesics taken as they are, without embedding them first");
    }

    // 2. The valid start: D_i, until its geodesics satisfy (1) and (2).
    void valid_start(const domain::Domain& H) {
        std::size_t faces = H.mesh.n_faces();
        while (!net_) {
            if (start_ == Start::gradual) {
                undone_ = std::min(H.history.size(), undone_ + std::max<std::size_t>(1, faces / 8));
            } else {
                undone_ = std::max(4 * undone_, std::max<std::size_t>(1, faces / 8));
                // Past 16 |D| faces (each collapse takes two) the geodesics cost more than redoing from T.
                if (undone_ >= H.history.size() || H.mesh.n_faces() + 2 * undone_ > 16 * H.mesh.n_faces())
                    undone_ = H.history.size();
            }
            const domain::Domain Di = domain::undo_collapses(H, T_, undone_);
            faces = Di.mesh.n_faces();
            const std::vector<geodesic::GeodesicPath> paths = geodesics_on(Di, undone_ == H.history.size());
            const Embedding embedding = embed(T_, Di, paths, {}, &executor_);
            if (embedding.conflicts.empty()) {
                take_valid(Di, paths, embedding);
                say("keeping the domain: the geodesics of a domain of " + std::to_string(faces) + " faces (" +
                    std::to_string(undone_) + " collapses undone) satisfy (1) and (2)");
                return;
            }
            if (undone_ == H.history.size())
                throw InternalError("keeping the domain: conflicts on D = T, whose paths are T's edges");
        }
    }

    // The geodesics of D_i's edges; on D_i = T (`is_t`) the edges themselves (a segment is the
    // shortest curve in space).
    std::vector<geodesic::GeodesicPath> geodesics_on(const domain::Domain& Di, bool is_t) const {
        std::vector<geodesic::GeodesicPath> paths;
        if (is_t) {
            for (const auto& [a, b] : domain::edge_endpoints(Di))
                paths.push_back(geodesic::GeodesicPath{{SurfacePoint::at_vertex(a), SurfacePoint::at_vertex(b)},
                                                       (T_.position(a) - T_.position(b)).norm()});
        } else {
            for (const auto& p : geodesics_of_(Di)) paths.push_back(p.path);
        }
        return paths;
    }

    // The network of D_i, whose geodesics `paths` are embedded without conflict.
    void take_valid(const domain::Domain& Di, const std::vector<geodesic::GeodesicPath>& paths,
                    const Embedding& embedding) {
        net_.emplace(T_, real_vertices_, make_domain(T_, faces_in_t(Di)));
        const auto di_ends = domain::edge_endpoints(Di);
        for (std::size_t e = 0; e < paths.size(); ++e) {
            const auto [a, b] = di_ends[e];
            net_->curves()[key_of(a, b)] =
                Curve{a.idx() < b.idx() ? paths[e] : reversed(paths[e]),
                      true,
                      {},
                      true,
                      domain::on_cone(Di.mesh, Di.t_vertex, EdgeId(static_cast<EdgeId::Index>(e)), real_vertices_)};
        }
        const Patches patches = extract_patches(Di, embedding.network, &executor_);
        for (FaceId df : Di.mesh.faces())
            net_->touched()[corners_of(Di, df)] = faces_of_t(patches, embedding.network, df);
    }

    // The start's size as the caller counts D: its faces on T, without the cone faces of D̂_i (the
    // direct start has exactly D's faces then; on a closed T nothing is left out).
    std::size_t faces_on_t() const {
        std::size_t start_faces = 0;
        for (FaceId f : net_->domain().mesh.faces()) {
            const auto v = net_->domain().mesh.face_vertices(f);
            start_faces += std::none_of(v.begin(), v.end(), [&](VertexId u) { return net_->apex(net_->x(u)); });
        }
        return start_faces;
    }

    // 3. The undone collapses, redone on the network.
    void redo_collapses(const domain::Domain& H) {
        checked_.reset();
        redo(
            *net_, std::span<const domain::Collapse>(H.history).subspan(H.history.size() - undone_),
            [this](const std::string& line) { say(line); }, searches_);
        if (canonical_faces(net_->domain()) != canonical_faces(H))
            throw InternalError("keeping the domain: the collapses redone do not give the decimation");
    }

    // 4. A domain given by the user: from the decimation to its edges by flips.
    void flip_to_given() {
        checked_.reset();
        flip_to(
            *net_, D_, [this](const std::string& line) { say(line); }, searches_);
        // With every edge in place, only the orientation can differ: D turned over is not a domain of T.
        if (canonical_faces(net_->domain()) != canonical_faces(D_))
            throw PartitionFailure(
                "keeping the domain: the given domain has the edges of T's decimation but its faces turned over");
    }

    // 5. Tightening, in the kept order, at most three passes.
    void tighten() {
        constexpr int max_passes = 3;
        for (int pass = 0; pass < max_passes; ++pass) {
            std::vector<Pair> left;
            for (const Pair& k : order_)
                if (!net_->curves().at(k).exact) left.push_back(k);
            std::size_t changed = 0;
            while (!left.empty()) changed += tighten_batch(left);
            say("keeping the domain: tightening pass " + std::to_string(pass + 1) + ", " + std::to_string(changed) +
                " curves shortened");
            if (changed == 0) break;
        }
    }

    // One batch of the curves `left` to tighten, with no face in common; the others stay in `left`.
    // Returns how many curves it shortened.
    std::size_t tighten_batch(std::vector<Pair>& left) {
        const domain::Domain& Dn = net_->domain();
        std::vector<std::uint8_t> used(Dn.mesh.n_faces(), 0);
        std::vector<Job> jobs;
        std::vector<Pair> later;
        for (const Pair& k : left) {
            const VertexId a = net_->at(k.first), b = net_->at(k.second);
            const HalfedgeId h = Dn.mesh.find_halfedge(a, b);
            const FaceId f = Dn.mesh.face(h), g = Dn.mesh.face(TriMesh::twin(h));
            if (used[f.idx()] || used[g.idx()]) {
                later.push_back(k);
                continue;
            }
            used[f.idx()] = used[g.idx()] = 1;
            jobs.push_back(Job{.e = TriMesh::edge(h),
                               .a = a,
                               .b = b,
                               .geodesic_length = geodesic_length_.at(k),
                               .current = net_->curves().at(k).path.length});
        }
        compute(*net_, jobs, searches_);
        std::size_t changed = 0;
        for (Job& j : jobs)
            if (j.curve) {
                apply(*net_, j);
                ++changed;
                checked_.reset();
            }
        left = std::move(later);
        return changed;
    }

    // 6. The curves in D's edge order, with their kinds.
    KeptNetwork in_d_order(std::size_t start_faces) {
        KeptNetwork out;
        out.start_faces = start_faces;
        auto [paths, unsnapped] = in_edge_order(D_, net_->curves());
        out.paths = EdgeData<geodesic::GeodesicPath>(std::move(paths));
        out.unsnapped = EdgeData<std::uint8_t>(std::move(unsnapped));
        out.embedded = std::move(checked_);
        for (const auto& [a, b] : ends_) out.info.push_back(info_of(key_of(a, b)));
        return out;
    }

    CurveInfo info_of(const Pair& k) const {
        const Curve& c = net_->curves().at(k);
        CurveInfo info;
        info.geodesic_length = geodesic_length_.at(k);
        if (c.fixed) info.kind = CurveKind::boundary;
        if (!c.exact) {
            info.kind = CurveKind::restricted;
            info.shortest = c.restricted.shortest;
            info.separation_bound = c.restricted.separation_bound;
            const auto r = reason_.find(k);
            info.reason = r != reason_.end() ? r->second : "its geodesic crosses the region of another curve";
        }
        return info;
    }
};

}  // namespace

const char* name(CurveKind kind) {
    switch (kind) {
        case CurveKind::geodesic: return "geodesic";
        case CurveKind::restricted: return "restricted";
        case CurveKind::boundary: return "boundary";
        case CurveKind::straightened: return "straightened";
    }
    return "";
}

KeptNetwork keep_domain(const TriMesh& T, std::size_t real_vertices, const domain::Domain& D,
                        const std::function<const domain::Domain&()>& base,
                        std::span<const geodesic::EllipsePath> geodesics, std::span<const Conflict> conflicts,
                        const std::function<std::vector<geodesic::EllipsePath>(const domain::Domain&)>& geodesics_of,
                        const std::function<void(const std::string&)>& progress, Executor& executor, Start start) {
    return KeepNetwork(T, real_vertices, D, base, geodesics, conflicts, geodesics_of, progress, executor, start).run();
}

}  // namespace fhr::partition
