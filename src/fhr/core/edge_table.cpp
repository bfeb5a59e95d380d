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

std::uint32_t first_non_manifold_vertex(std::size_t n_vertices, std::span<const Triangle> t,
                                        const EdgeTable& table) {
    // Corners grouped by their tail vertex: corner c = 3f+k has tail t[f][k], i.e. it is the
    // corner of face f at that vertex.
    const auto n_corners = static_cast<std::uint32_t>(3 * t.size());
    std::vector<std::uint32_t> offsets(n_vertices + 1, 0), at(n_corners);
    for (std::uint32_t c = 0; c < n_corners; ++c) ++offsets[corner_tail(t, c) + 1];
    for (std::size_t v = 0; v < n_vertices; ++v) offsets[v + 1] += offsets[v];
    {
        std::vector<std::uint32_t> fill(offsets.begin(), offsets.end() - 1);
        for (std::uint32_t c = 0; c < n_corners; ++c) at[fill[corner_tail(t, c)]++] = c;
    }
    // The corner on the other side of the edge of corner c, or UINT32_MAX on the boundary.
    auto across = [&](std::uint32_t c) -> std::uint32_t {
        const std::uint32_t e = table.corner_edge[c];
        if (table.edge_degree(e) != 2) return UINT32_MAX;
        const std::uint32_t* pair = &table.edge_corners[table.edge_offsets[e]];
        return pair[0] == c ? pair[1] : pair[0];
    };
    auto prev_in_face = [](std::uint32_t c) { return c - c % 3 + (c % 3 + 2) % 3; };
    for (std::uint32_t v = 0; v < n_vertices; ++v) {
        const std::uint32_t incident = offsets[v + 1] - offsets[v];
        if (incident == 0) continue;
        // Around v, the corner of v in the next face is found across the edge leaving v
        // (corner c itself): with consistent orientation that edge is traversed backwards there,
        // so the next corner at v follows the crossed one. Walk forward, then backward.
        const std::uint32_t start = at[offsets[v]];
        std::uint32_t visited = 1;
        bool closed = false;
        for (std::uint32_t c = start;;) {
            const std::uint32_t o = across(c);
            if (o == UINT32_MAX) break;
            const std::uint32_t n = o - o % 3 + (o % 3 + 1) % 3;  // corner of v in o's face
            if (n == start) { closed = true; break; }
            if (++visited > incident) break;
            c = n;
        }
        if (!closed) {
            for (std::uint32_t c = start;;) {
                const std::uint32_t o = across(prev_in_face(c));  // the edge entering v in c's face
                if (o == UINT32_MAX || ++visited > incident) break;
                c = o;  // o leaves v in its face, so o is the corner of v there
            }
        }
        if (visited != incident) return v;
    }
    return UINT32_MAX;
}

}  // namespace fhr::detail
