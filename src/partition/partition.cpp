// FHR §3 — the partition with recovery (see partition.hpp for the pseudocode).
#include "partition/partition.hpp"

#include <algorithm>
#include <map>
#include <utility>

#include "core/errors.hpp"

namespace fhr::partition {
namespace {

// Γ(a, b) for every edge of D, reusing the paths of edges whose ends are unchanged.
class PathCache {
public:
    explicit PathCache(const TriMesh& T, const geodesic::EllipseOptions& options) : T_(T), options_(options) {}

    std::vector<geodesic::EllipsePath> all(const domain::Domain& D) {
        std::vector<geodesic::EllipsePath> paths;
        paths.reserve(D.mesh.n_edges());
        for (const auto& [a, b] : domain::edge_endpoints(D)) {
            const std::pair<VertexId::Index, VertexId::Index> key{std::min(a.idx(), b.idx()), std::max(a.idx(), b.idx())};
            auto it = cache_.find(key);
            if (it == cache_.end()) it = cache_.emplace(key, geodesic::ellipse_shortest_path(T_, VertexId(key.first), VertexId(key.second), options_)).first;
            geodesic::EllipsePath p = it->second;
            if (a.idx() != key.first) std::reverse(p.path.points.begin(), p.path.points.end());
            paths.push_back(std::move(p));
        }
        return paths;
    }

private:
    const TriMesh& T_;
    geodesic::EllipseOptions options_;
    std::map<std::pair<VertexId::Index, VertexId::Index>, geodesic::EllipsePath> cache_;
};

// Refines D near one conflict. First the conflicting D edges are split away (their paths, the
// cause, disappear); failing that, D is refined at the vertices of T at the conflict's place,
// then at the conflicting edges' corners and their neighbours, rings outwards. Returns the number
// of collapses undone.
std::size_t refine_near(domain::Domain& D, const TriMesh& T, const Conflict& c) {
    std::size_t undone = 0;
    for (std::uint32_t e : {c.d_edge_a, c.d_edge_b}) {
        if (e == c.d_edge_b && e == c.d_edge_a && undone) break;
        const HalfedgeId h = TriMesh::halfedge(EdgeId(e), 0);
        if (D.mesh.find_halfedge(D.mesh.from(h), D.mesh.to(h)) == h) undone += domain::split_edge_away(D, T, D.mesh.from(h), D.mesh.to(h));
    }
    if (undone) return undone;
    std::vector<VertexId> at;
    for (VertexId v : c.near)
        if (v.valid()) at.push_back(v);
    if ((undone = domain::refine_at(D, T, at))) return undone;
    std::vector<VertexId> ring;  // vertices of D
    std::vector<std::uint8_t> in(D.mesh.n_vertices(), 0);
    for (std::uint32_t e : {c.d_edge_a, c.d_edge_b})
        for (unsigned side = 0; side < 2; ++side) {
            const VertexId v = D.mesh.to(TriMesh::halfedge(EdgeId(e), side));
            if (!in[v.idx()]) {
                in[v.idx()] = 1;
                ring.push_back(v);
            }
        }
    for (;;) {
        at.clear();
        for (VertexId v : ring) at.push_back(D.t_vertex[v.idx()]);
        if (const std::size_t undone = domain::refine_at(D, T, at)) return undone;
        const std::size_t before = ring.size();
        for (std::size_t i = 0; i < before; ++i)
            D.mesh.for_each_outgoing(ring[i], [&](HalfedgeId h) {
                const VertexId w = D.mesh.to(h);
                if (!in[w.idx()]) {
                    in[w.idx()] = 1;
                    ring.push_back(w);
                }
            });
        if (ring.size() == before) return 0;
    }
}

// Refines D near every conflict (the D edges named by later conflicts may have been split by
// earlier ones; a conflict whose edge no longer exists is left for the next round).
std::size_t refine_around(domain::Domain& D, const TriMesh& T, const std::vector<Conflict>& conflicts) {
    const std::size_t n_edges = D.mesh.n_edges();
    std::size_t undone = 0;
    for (const Conflict& c : conflicts)
        if (c.d_edge_b < n_edges) undone += refine_near(D, T, c);
    return undone;
}

}  // namespace

Partition partition(const TriMesh& T, domain::Domain D, const PartitionOptions& options) {
    const domain::Domain D0 = D;
    std::size_t in_order = 0;  // collapses of D0's history undone in order by the fallback
    PathCache cache(T, options.ellipse);
    Partition out;
    for (;;) {
        out.paths = cache.all(D);
        std::vector<geodesic::GeodesicPath> paths;
        paths.reserve(out.paths.size());
        for (const auto& p : out.paths) paths.push_back(p.path);
        Embedding embedding = embed(T, D, paths);
        if (embedding.conflicts.empty()) {
            out.patches = extract_patches(D, embedding.network);
            out.network = std::move(embedding.network);
            out.collapses_undone = D.mesh.n_vertices() - D0.mesh.n_vertices();
            out.domain = std::move(D);
            return out;
        }
        std::size_t undone = refine_around(D, T, embedding.conflicts);
        if (undone == 0 && in_order < D0.history.size()) {
            // Out-of-order splits can leave the remaining collapses without their neighbours;
            // undoing in order (twice as many each time, up to D = T) always can.
            in_order = std::min(D0.history.size(), std::max(2 * in_order, D.mesh.n_vertices() - D0.mesh.n_vertices() + 1));
            const std::size_t before = D.mesh.n_vertices();
            D = domain::undo_collapses(D0, T, in_order);
            undone = D.mesh.n_vertices() > before ? D.mesh.n_vertices() - before : 1;
        }
        if (undone == 0) {
            std::string what = "conditions (1)/(2) of §3 fail and the domain cannot be refined there:";
            for (std::size_t i = 0; i < std::min<std::size_t>(embedding.conflicts.size(), 4); ++i)
                what += (i ? "; " : " ") + embedding.conflicts[i].describe();
            if (embedding.conflicts.size() > 4) what += "; and " + std::to_string(embedding.conflicts.size() - 4) + " more";
            throw PartitionFailure(what);
        }
        out.resolved.insert(out.resolved.end(), embedding.conflicts.begin(), embedding.conflicts.end());
        ++out.retries;
        if (options.progress)
            options.progress("partition: " + std::to_string(embedding.conflicts.size()) + " conflicts (" +
                             embedding.conflicts.front().describe() + "); the domain now has " +
                             std::to_string(D.mesh.n_faces()) + " faces");
    }
}

}  // namespace fhr::partition
