// FHR core — corner grouping by undirected edge (see detail/edge_table.hpp).
#include <fhr/core/detail/edge_table.hpp>

#include <algorithm>
#include <utility>

namespace fhr::detail {

EdgeTable build_edge_table(std::size_t n_vertices, std::span<const Triangle> t) {
    const auto n_corners = static_cast<std::uint32_t>(3 * t.size());
    // Counting sort of the corners by their smaller end vertex.
    std::vector<std::uint32_t> lo_offsets(n_vertices + 1, 0);
    auto lo = [&](std::uint32_t c) { return std::min(corner_tail(t, c), corner_head(t, c)); };
    auto hi = [&](std::uint32_t c) { return std::max(corner_tail(t, c), corner_head(t, c)); };
    for (std::uint32_t c = 0; c < n_corners; ++c) ++lo_offsets[lo(c) + 1];
    for (std::size_t v = 0; v < n_vertices; ++v) lo_offsets[v + 1] += lo_offsets[v];
    std::vector<std::uint32_t> by_lo(n_corners);
    {
        std::vector<std::uint32_t> fill(lo_offsets.begin(), lo_offsets.end() - 1);
        for (std::uint32_t c = 0; c < n_corners; ++c) by_lo[fill[lo(c)]++] = c;
    }
    EdgeTable table;
    table.corner_edge.resize(n_corners);
    table.edge_offsets.reserve(n_corners / 2 + 2);
    table.edge_offsets.push_back(0);
    table.edge_corners.reserve(n_corners);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> group;  // (hi vertex, corner)
    for (std::size_t v = 0; v < n_vertices; ++v) {
        group.clear();
        for (std::uint32_t i = lo_offsets[v]; i < lo_offsets[v + 1]; ++i) group.emplace_back(hi(by_lo[i]), by_lo[i]);
        std::sort(group.begin(), group.end());
        for (std::size_t i = 0; i < group.size(); ++i) {
            if (i > 0 && group[i].first != group[i - 1].first)
                table.edge_offsets.push_back(static_cast<std::uint32_t>(table.edge_corners.size()));
            table.corner_edge[group[i].second] = static_cast<std::uint32_t>(table.edge_offsets.size() - 1);
            table.edge_corners.push_back(group[i].second);
        }
        if (!group.empty()) table.edge_offsets.push_back(static_cast<std::uint32_t>(table.edge_corners.size()));
    }
    return table;
}

}  // namespace fhr::detail

namespace fhr::detail {

std::uint32_t first_non_manifold_vertex(const TriMesh& mesh, std::span<const Triangle> t) {
    std::vector<std::uint32_t> incident(mesh.n_vertices(), 0);
    for (const Triangle& f : t)
        for (const std::uint32_t v : f) ++incident[v];
    // Around v, from out(v): the next halfedge out of v follows the twin of the last one (on the
    // boundary, the boundary halfedge into v links to out(v)). The walk sees one fan of v, the
    // whole star when it is one fan; it stops when back at out(v), or one step after it has seen
    // as many halfedges as v has faces (when another fan's boundary links lead it astray).
    for (std::uint32_t v = 0; v < mesh.n_vertices(); ++v) {
        const HalfedgeId first = mesh.out(VertexId(v));
        HalfedgeId h = first;
        std::uint32_t faces = 0, steps = 0;
        do {
            faces += !mesh.is_boundary(h);
            h = mesh.next(TriMesh::twin(h));
        } while (h != first && ++steps <= incident[v]);
        if (faces != incident[v]) return v;
    }
    return UINT32_MAX;
}

}  // namespace fhr::detail
