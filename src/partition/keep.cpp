// Beyond the paper (§3): keeping the domain (see keep.hpp for the pseudocode).
#include "partition/keep.hpp"

#include <algorithm>
#include <map>
#include <optional>
#include <stdexcept>
#include <unordered_map>
#include <utility>

#include "core/parallel.hpp"
#include "partition/patches.hpp"
#include "partition/restricted.hpp"

namespace fhr::partition {
namespace {

using Pair = std::pair<VertexId::Index, VertexId::Index>;
Pair key_of(VertexId a, VertexId b) { return {std::min(a.idx(), b.idx()), std::max(a.idx(), b.idx())}; }

geodesic::GeodesicPath reversed(geodesic::GeodesicPath p) {
    std::reverse(p.points.begin(), p.points.end());
    return p;
}

// A curve of the network, kept from its smaller vertex of T to its larger.
struct Curve {
    geodesic::GeodesicPath path;
    bool exact = false;             // the exact geodesic of T between its ends
    RestrictedPath restricted{};    // when not exact: how it was found
};

// The network while D is being made: a domain and one curve per edge, keyed by the edge's ends
// in T, with its embedding.
class Network_ {
public:
    Network_(const TriMesh& T, domain::Domain D) : T_(T), D_(std::move(D)) {}

    const TriMesh& T() const { return T_; }
    const domain::Domain& domain() const { return D_; }
    domain::Domain& domain() { return D_; }
    std::map<Pair, Curve>& curves() { return curves_; }
    const Network& network() const { return embedding_.network; }
    const Patches& patches() const { return patches_; }
    std::size_t rounds() const { return rounds_; }

    VertexId x(VertexId v) const { return D_.t_vertex[v.idx()]; }

    // The curves in D's edge order, each along D's halfedge (e, 0).
    std::vector<geodesic::GeodesicPath> ordered() const {
        std::vector<geodesic::GeodesicPath> paths;
        paths.reserve(D_.mesh.n_edges());
        for (const auto& [a, b] : domain::edge_endpoints(D_)) {
            const geodesic::GeodesicPath& p = curves_.at(key_of(a, b)).path;
            paths.push_back(a.idx() < b.idx() ? p : reversed(p));
        }
        return paths;
    }

    void embed_all() {
        const auto paths = ordered();
        std::vector<std::uint8_t> unsnapped;
        for (const auto& [a, b] : domain::edge_endpoints(D_)) unsnapped.push_back(!curves_.at(key_of(a, b)).exact);
        embedding_ = embed(T_, D_, paths, unsnapped);
        ++rounds_;
        if (!embedding_.conflicts.empty())
            throw std::logic_error("keeping the domain: a separated curve breaks (1)/(2): " + embedding_.conflicts.front().describe());
        patches_ = extract_patches(D_, embedding_.network);
    }

    // The restricted path in the two patches beside D's edge e, between `a` and `b` (vertices of D).
    RestrictedPath restricted(EdgeId e, VertexId a, VertexId b) const {
        const HalfedgeId h = TriMesh::halfedge(e, 0);
        const FaceId region[] = {D_.mesh.face(h), D_.mesh.face(TriMesh::twin(h))};
        RestrictedPath r = restricted_path(T_, embedding_.network, patches_, region, x(a), x(b), static_cast<std::int32_t>(e.idx()));
        if (x(a).idx() > x(b).idx()) r.path = reversed(std::move(r.path));
        return r;
    }

private:
    const TriMesh& T_;
    domain::Domain D_;
    std::map<Pair, Curve> curves_;
    Embedding embedding_;
    Patches patches_;
    std::size_t rounds_ = 0;
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
    for (const Triangle& t : D.mesh.triangles()) faces.push_back({D.t_vertex[t[0]], D.t_vertex[t[1]], D.t_vertex[t[2]]});
    return faces;
}

// A flip or a tightening: the new curve of D's edge e between D's vertices a and b.
struct Job {
    EdgeId e;
    VertexId a, b;
    RestrictedPath result{};
};

void compute(const Network_& net, std::vector<Job>& jobs) {
    parallel_for(jobs.size(), 1, [&](std::size_t i) { jobs[i].result = net.restricted(jobs[i].e, jobs[i].a, jobs[i].b); });
}

// Redoes `collapses` (in T's numbering, in their order) on the network.
void redo(Network_& net, std::span<const domain::Collapse> collapses, const std::function<void(const std::string&)>& say) {
    std::vector<domain::Collapse> left(collapses.begin(), collapses.end());
    while (!left.empty()) {
        domain::Domain& D = net.domain();
        std::unordered_map<VertexId::Index, VertexId> in_d;  // vertex of T -> vertex of D
        for (std::size_t j = 0; j < D.t_vertex.size(); ++j) in_d.emplace(D.t_vertex[j].idx(), VertexId(static_cast<VertexId::Index>(j)));
        // The batch: collapses whose closed 1-rings meet no earlier one's (taken or left), so
        // that they commute with every collapse they overtake.
        std::vector<std::uint8_t> blocked(D.mesh.n_vertices(), 0);
        std::vector<domain::Collapse> batch, later;
        for (const domain::Collapse& c : left) {
            const VertexId v = in_d.at(c.removed.idx());
            std::vector<VertexId> ring{v};
            D.mesh.for_each_outgoing(v, [&](HalfedgeId h) { ring.push_back(D.mesh.to(h)); });
            const bool free = std::none_of(ring.begin(), ring.end(), [&](VertexId u) { return blocked[u.idx()] != 0; });
            for (VertexId u : ring) blocked[u.idx()] = 1;
            (free ? batch : later).push_back(c);
        }
        // Flip v's spokes until it has valence 3, all collapses of the batch in step.
        for (;;) {
            std::vector<Job> jobs;
            for (const domain::Collapse& c : batch) {
                const VertexId v = in_d.at(c.removed.idx()), w = in_d.at(c.kept.idx());
                if (D.mesh.valence(v) <= 3) continue;
                const HalfedgeId vw = D.mesh.find_halfedge(v, w);
                const VertexId u = D.mesh.to(D.mesh.next(vw));            // face (v, w, u)
                const HalfedgeId vu = D.mesh.find_halfedge(v, u);
                const VertexId y = D.mesh.to(D.mesh.next(vu));            // face (v, u, y)
                if (!D.mesh.is_flip_ok(TriMesh::edge(vu))) throw std::logic_error("keeping the domain: a spoke cannot be flipped");
                jobs.push_back(Job{TriMesh::edge(vu), w, y});
            }
            if (jobs.empty()) break;
            compute(net, jobs);
            for (Job& j : jobs) {
                const HalfedgeId h = TriMesh::halfedge(j.e, 0);
                net.curves().erase(key_of(net.x(D.mesh.from(h)), net.x(D.mesh.to(h))));
                D.mesh.flip(j.e);
                net.curves()[key_of(net.x(j.a), net.x(j.b))] = Curve{std::move(j.result.path), false, j.result};
            }
            net.embed_all();
        }
        // Each v now has valence 3: its three faces become one, its three curves go.
        std::vector<std::uint8_t> gone(D.mesh.n_vertices(), 0);
        std::vector<std::array<VertexId, 3>> merged;
        for (const domain::Collapse& c : batch) {
            const VertexId v = in_d.at(c.removed.idx()), w = in_d.at(c.kept.idx());
            const HalfedgeId vw = D.mesh.find_halfedge(v, w);
            const VertexId a = D.mesh.to(D.mesh.next(vw)), b = D.mesh.to(D.mesh.next(TriMesh::twin(vw)));
            merged.push_back({c.kept, net.x(a), net.x(b)});
            gone[v.idx()] = 1;
            for (VertexId u : {w, a, b}) net.curves().erase(key_of(c.removed, net.x(u)));
        }
        std::vector<std::array<VertexId, 3>> faces;
        for (const Triangle& t : D.mesh.triangles())
            if (!gone[t[0]] && !gone[t[1]] && !gone[t[2]]) faces.push_back({D.t_vertex[t[0]], D.t_vertex[t[1]], D.t_vertex[t[2]]});
        faces.insert(faces.end(), merged.begin(), merged.end());
        net.domain() = make_domain(net.T(), faces);
        net.embed_all();
        if (say)
            say("keeping the domain: redid " + std::to_string(batch.size()) + " collapses on the network, " +
                std::to_string(later.size()) + " to go (" + std::to_string(net.domain().mesh.n_faces()) + " faces)");
        left = std::move(later);
    }
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

}  // namespace

KeptNetwork keep_domain(const TriMesh& T, const domain::Domain& D, std::span<const geodesic::EllipsePath> geodesics,
                        std::span<const Conflict> conflicts,
                        const std::function<std::vector<geodesic::EllipsePath>(const domain::Domain&)>& geodesics_of,
                        const std::function<void(const std::string&)>& progress) {
    auto say = [&](const std::string& line) {
        if (progress) progress(line);
    };
    const auto ends = domain::edge_endpoints(D);
    // 1. The valid start: D_i, a quarter more faces a round, until its geodesics satisfy (1), (2).
    std::size_t undone = 0, faces = D.mesh.n_faces();
    std::optional<Network_> net;
    for (;;) {
        undone = std::min(D.history.size(), undone + std::max<std::size_t>(1, faces / 8));
        const domain::Domain Di = domain::undo_collapses(D, T, undone);
        faces = Di.mesh.n_faces();
        const auto g = geodesics_of(Di);
        std::vector<geodesic::GeodesicPath> paths;
        for (const auto& p : g) paths.push_back(p.path);
        if (embed(T, Di, paths).conflicts.empty()) {
            net.emplace(T, make_domain(T, faces_in_t(Di)));
            const auto di_ends = domain::edge_endpoints(Di);
            for (std::size_t e = 0; e < g.size(); ++e) {
                const auto [a, b] = di_ends[e];
                net->curves()[key_of(a, b)] = Curve{a.idx() < b.idx() ? g[e].path : reversed(g[e].path), true, {}};
            }
            net->embed_all();
            say("keeping the domain: the geodesics of a domain of " + std::to_string(faces) + " faces (" +
                std::to_string(undone) + " collapses undone) satisfy (1) and (2)");
            break;
        }
        if (undone == D.history.size()) throw std::logic_error("keeping the domain: conflicts on D = T, whose paths are T's edges");
    }
    // 2. The undone collapses, redone on the network.
    redo(*net, std::span<const domain::Collapse>(D.history).subspan(D.history.size() - undone), say);
    if (canonical_faces(net->domain()) != canonical_faces(D)) throw std::logic_error("keeping the domain: the collapses redone do not give D");

    // 3. Tightening, in the kept order.
    std::map<Pair, double> geodesic_length;
    std::map<Pair, std::string> reason;
    for (std::size_t e = 0; e < ends.size(); ++e) geodesic_length[key_of(ends[e].first, ends[e].second)] = geodesics[e].path.length;
    for (const Conflict& c : conflicts)
        for (std::uint32_t e : {c.d_edge_a, c.d_edge_b}) reason.emplace(key_of(ends[e].first, ends[e].second), c.describe());
    std::vector<Pair> order;
    for (const auto& [k, length] : geodesic_length) order.push_back(k);
    std::stable_sort(order.begin(), order.end(), [&](const Pair& p, const Pair& q) {
        const bool cp = reason.count(p) != 0, cq = reason.count(q) != 0;
        if (cp != cq) return !cp;
        return geodesic_length.at(p) < geodesic_length.at(q);
    });
    constexpr int max_passes = 3;
    for (int pass = 0; pass < max_passes; ++pass) {
        std::size_t changed = 0;
        std::vector<Pair> left;
        for (const Pair& k : order)
            if (!net->curves().at(k).exact) left.push_back(k);
        while (!left.empty()) {
            const domain::Domain& Dn = net->domain();
            std::unordered_map<VertexId::Index, VertexId> in_d;
            for (std::size_t j = 0; j < Dn.t_vertex.size(); ++j) in_d.emplace(Dn.t_vertex[j].idx(), VertexId(static_cast<VertexId::Index>(j)));
            std::vector<std::uint8_t> used(Dn.mesh.n_faces(), 0);
            std::vector<Job> jobs;
            std::vector<Pair> later;
            for (const Pair& k : left) {
                const VertexId a = in_d.at(k.first), b = in_d.at(k.second);
                const HalfedgeId h = Dn.mesh.find_halfedge(a, b);
                const FaceId f = Dn.mesh.face(h), g = Dn.mesh.face(TriMesh::twin(h));
                if (used[f.idx()] || used[g.idx()]) {
                    later.push_back(k);
                    continue;
                }
                used[f.idx()] = used[g.idx()] = 1;
                jobs.push_back(Job{TriMesh::edge(h), a, b});
            }
            compute(*net, jobs);
            for (Job& j : jobs) {
                const Pair k = key_of(net->x(j.a), net->x(j.b));
                Curve& c = net->curves().at(k);
                const double gl = geodesic_length.at(k);
                if (j.result.touches == 0 && j.result.shortest <= gl * (1 + 1e-12)) {
                    c = Curve{std::move(j.result.path), true, j.result};  // an exact shortest geodesic of T
                    ++changed;
                } else if (j.result.path.length < c.path.length * (1 - 1e-9)) {
                    c = Curve{std::move(j.result.path), false, j.result};
                    ++changed;
                }
            }
            net->embed_all();
            left = std::move(later);
        }
        say("keeping the domain: tightening pass " + std::to_string(pass + 1) + ", " + std::to_string(changed) + " curves shortened");
        if (changed == 0) break;
    }

    // 4. The curves in D's edge order.
    KeptNetwork out;
    out.start_faces = faces;
    out.rounds = net->rounds();
    for (std::size_t e = 0; e < ends.size(); ++e) {
        const auto [a, b] = ends[e];
        const Pair k = key_of(a, b);
        const Curve& c = net->curves().at(k);
        out.paths.push_back(a.idx() < b.idx() ? c.path : reversed(c.path));
        CurveInfo info;
        info.geodesic_length = geodesic_length.at(k);
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
