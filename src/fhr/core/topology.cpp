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

Components connected_components(const TriMesh& m) {
    Components c;
    c.vertex_component.assign(m.n_vertices(), UINT32_MAX);
    std::vector<VertexId> stack;
    for (VertexId seed : m.vertices()) {
        if (c.vertex_component[seed] != UINT32_MAX) continue;
        const auto id = static_cast<std::uint32_t>(c.count++);
        c.vertex_component[seed] = id;
        stack.push_back(seed);
        while (!stack.empty()) {
            const VertexId v = stack.back();
            stack.pop_back();
            m.for_each_outgoing(v, [&](HalfedgeId h) {
                const VertexId w = m.to(h);
                if (c.vertex_component[w] == UINT32_MAX) {
                    c.vertex_component[w] = id;
                    stack.push_back(w);
                }
            });
        }
    }
    return c;
}

long genus(const TriMesh& m) { return genus(m, connected_components(m)); }

long genus(const TriMesh& m, const Components& comp) {
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
