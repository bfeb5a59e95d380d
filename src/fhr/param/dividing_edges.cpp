// FHR §4 Proposition 1 — splitting the dividing edges that would map into the triangle's
// boundary (Floater 2003, Thm 6.1; see dividing_edges.hpp).
#include <fhr/param/detail/dividing_edges.hpp>

#include <utility>
#include <vector>

#include <fhr/param/detail/disk_topology.hpp>

namespace fhr::param {

std::size_t split_dividing_edges(Disk& disk, std::vector<std::uint32_t>* origin) {
    if (origin) {
        origin->resize(disk.triangles.size());
        for (std::uint32_t t = 0; t < origin->size(); ++t) (*origin)[t] = t;
    }
    const std::vector<unsigned> sides_at = boundary_sides(disk);
    std::vector<unsigned> side(disk.positions.size(), 0);  // 0 for interior vertices
    for (std::size_t p = 0; p < disk.boundary.size(); ++p) side[disk.boundary[p]] = sides_at[p];

    detail::DirectedEdges edges = detail::directed_edges(disk);
    // The dividing edges, found in triangle order (deterministic), each once as (a, b) with a < b.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> dividing;
    for (const auto& f : disk.triangles)
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = f[k], b = f[(k + 1) % 3];
            if (a < b && (side[a] & side[b]) != 0 && edges.find(detail::edge_key(b, a)) != detail::DirectedEdges::none)
                dividing.emplace_back(a, b);
        }

    auto set = [&](std::uint32_t t, std::array<std::uint32_t, 3> f) {
        disk.triangles[t] = f;
        for (int k = 0; k < 3; ++k) edges.assign(detail::edge_key(f[k], f[(k + 1) % 3]), t);
    };
    for (const auto& [a, b] : dividing) {
        // The triangles holding the edge now (earlier splits may have moved it to a new one).
        const std::uint32_t t1 = edges.at(detail::edge_key(a, b)), t2 = edges.at(detail::edge_key(b, a));
        auto third = [&, a = a, b = b](std::uint32_t t) {  // structured bindings are captured by copy (C++20, clang)
            const auto& f = disk.triangles[t];
            return f[0] != a && f[0] != b ? f[0] : f[1] != a && f[1] != b ? f[1] : f[2];
        };
        const std::uint32_t c = third(t1), d = third(t2);
        const auto m = static_cast<std::uint32_t>(disk.positions.size());
        disk.positions.push_back(0.5 * (disk.positions[a] + disk.positions[b]));
        ++disk.midpoints;
        edges.erase(detail::edge_key(a, b));
        edges.erase(detail::edge_key(b, a));
        // (a, b, c) -> (a, m, c), (m, b, c);  (b, a, d) -> (b, m, d), (m, a, d): m lies on [a, b],
        // so each half keeps its triangle's orientation.
        const auto t1_second = static_cast<std::uint32_t>(disk.triangles.size());
        disk.triangles.emplace_back();
        const auto t2_second = static_cast<std::uint32_t>(disk.triangles.size());
        disk.triangles.emplace_back();
        if (origin) {
            origin->push_back((*origin)[t1]);
            origin->push_back((*origin)[t2]);
        }
        set(t1, {a, m, c});
        set(t1_second, {m, b, c});
        set(t2, {b, m, d});
        set(t2_second, {m, a, d});
    }
    return dividing.size();
}

}  // namespace fhr::param
