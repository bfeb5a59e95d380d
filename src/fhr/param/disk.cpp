// FHR §3/§4 — the patch S_i as a disk: its validity rules (MAP-1) and its sides.
#include <fhr/core/detail/contract.hpp>
#include <fhr/param/disk.hpp>

#include <bit>
#include <numeric>

#include <fhr/core/errors.hpp>
#include <fhr/param/detail/disk_topology.hpp>

namespace fhr::param {
namespace detail {

void DirectedEdges::resize_for(std::size_t edges) {
    std::size_t slots = 16;
    while (slots < 2 * edges) slots *= 2;
    std::vector<std::uint64_t> keys(slots, empty);
    std::vector<std::uint32_t> triangles(slots);
    key_.swap(keys);
    triangle_.swap(triangles);
    shift_ = 64 - static_cast<unsigned>(std::countr_zero(slots));
    used_ = 0;
    for (std::size_t i = 0; i < keys.size(); ++i)
        if (keys[i] != empty && triangles[i] != none) assign(keys[i], triangles[i]);
}

bool DirectedEdges::insert(std::uint64_t key, std::uint32_t t) {
    const std::size_t i = place(key);
    if (key_[i] == key && triangle_[i] != none) return false;
    if (key_[i] == empty) {
        if (2 * (used_ + 1) > key_.size()) {
            resize_for(2 * used_ + 2);
            return insert(key, t);
        }
        key_[i] = key;
        ++used_;
    }
    triangle_[i] = t;
    return true;
}

void DirectedEdges::assign(std::uint64_t key, std::uint32_t t) {
    if (!insert(key, t)) triangle_[place(key)] = t;
}

void DirectedEdges::erase(std::uint64_t key) {
    const std::size_t i = place(key);
    if (key_[i] == key) triangle_[i] = none;
}

DirectedEdges directed_edges(const Disk& disk) {
    DirectedEdges table(3 * disk.triangles.size());
    for (std::uint32_t t = 0; t < disk.triangles.size(); ++t) {
        const auto& f = disk.triangles[t];
        for (int k = 0; k < 3; ++k) table.insert(edge_key(f[k], f[(k + 1) % 3]), t);
    }
    return table;
}

}  // namespace detail

namespace {

std::uint32_t find_root(std::vector<std::uint32_t>& parent, std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
}

Violation broken(Element element, std::int64_t index, std::string what) {
    return Violation{"MAP-1", element, index, std::move(what)};
}

constexpr std::uint32_t none = detail::DirectedEdges::none;

// What disk_violation learns of the triangles on its way.
struct DiskScan {
    explicit DiskScan(std::size_t nv, std::size_t nt)
        : incident(nv, 0), edges(3 * nt), boundary_next(nv, none), boundary_prev(nv, none) {}
    std::vector<std::uint32_t> incident;  // per vertex, its triangles
    detail::DirectedEdges edges;          // each directed edge's triangle
    std::vector<std::uint32_t> boundary_next, boundary_prev;
    std::size_t n_boundary_edges = 0, n_edges = 0;
};

// Every triangle names three distinct vertices, every directed edge is in one triangle, every
// vertex in some triangle.
std::optional<Violation> triangles_violation(const Disk& disk, DiskScan& scan) {
    const std::size_t nv = disk.positions.size(), nt = disk.triangles.size();
    for (std::size_t t = 0; t < nt; ++t) {
        const auto& f = disk.triangles[t];
        for (int k = 0; k < 3; ++k)
            if (f[k] >= nv)
                return broken(Element::face, t,
                              "triangle " + std::to_string(t) + " names vertex " + std::to_string(f[k]) + " of " +
                                  std::to_string(nv));
        if (f[0] == f[1] || f[1] == f[2] || f[2] == f[0])
            return broken(Element::face, t, "triangle " + std::to_string(t) + " repeats a vertex");
        for (int k = 0; k < 3; ++k) {
            ++scan.incident[f[k]];
            if (!scan.edges.insert(detail::edge_key(f[k], f[(k + 1) % 3]), static_cast<std::uint32_t>(t)))
                return broken(Element::face, static_cast<std::int64_t>(t),
                              "directed edge (" + std::to_string(f[k]) + ", " + std::to_string(f[(k + 1) % 3]) +
                                  ") is in two triangles (inconsistent orientation or a non-manifold edge)");
        }
    }
    for (std::size_t v = 0; v < nv; ++v)
        if (scan.incident[v] == 0)
            return broken(Element::vertex, v, "vertex " + std::to_string(v) + " is in no triangle");
    return std::nullopt;
}

// Boundary edges: directed edges without their reverse, in triangle order. Each vertex starts at
// most one.
std::optional<Violation> boundary_violation(const Disk& disk, DiskScan& scan) {
    for (std::size_t e = 0; e < 3 * disk.triangles.size(); ++e) {
        const auto& f = disk.triangles[e / 3];
        const std::uint32_t a = f[e % 3], b = f[(e + 1) % 3];
        if (scan.edges.find(detail::edge_key(b, a)) != none) {
            if (a < b) ++scan.n_edges;
            continue;
        }
        ++scan.n_edges;
        ++scan.n_boundary_edges;
        if (scan.boundary_next[a] != none)
            return broken(Element::vertex, a,
                          "vertex " + std::to_string(a) + " starts two boundary edges (not a disk)");
        scan.boundary_next[a] = b;
        scan.boundary_prev[b] = a;
    }
    return std::nullopt;
}

// Every vertex's triangles form one fan. From an edge (v, w), the triangle traversing (w, v) is
// (v, y, w) after rotation; the walk continues with (v, y). At an interior vertex it comes back to
// its start; at a boundary vertex it starts at the incoming boundary edge (a, v) and stops at the
// outgoing one, which no triangle traverses backwards. Either way it must visit every triangle at v.
std::optional<Violation> fan_violation(const Disk& disk, const DiskScan& scan) {
    const std::size_t nv = disk.positions.size();
    std::vector<std::uint32_t> some_neighbour(nv, none);  // w with (v, w) traversed by a triangle
    for (const auto& f : disk.triangles)
        for (int k = 0; k < 3; ++k)
            if (some_neighbour[f[k]] == none) some_neighbour[f[k]] = f[(k + 1) % 3];
    for (std::uint32_t v = 0; v < nv; ++v) {
        std::uint32_t w = scan.boundary_prev[v] != none ? scan.boundary_prev[v] : some_neighbour[v];
        const std::uint32_t first = w;
        std::uint32_t visited = 0;
        while (visited <= scan.incident[v]) {
            const std::uint32_t t = scan.edges.find(detail::edge_key(w, v));
            if (t == none) break;
            ++visited;
            const auto& f = disk.triangles[t];
            const int k = f[0] == v ? 0 : f[1] == v ? 1 : 2;
            w = f[(k + 1) % 3];
            if (w == first) break;
        }
        if (visited != scan.incident[v])
            return broken(Element::vertex, v,
                          "vertex " + std::to_string(v) + " is not manifold (its triangles form more than one fan)");
    }
    return std::nullopt;
}

// The boundary loop is exactly `boundary`: distinct vertices, each starting one boundary edge, as
// many as there are boundary edges, so the loop holds every boundary edge.
std::optional<Violation> loop_violation(const Disk& disk, const DiskScan& scan) {
    const auto& loop = disk.boundary;
    const std::size_t nv = disk.positions.size();
    if (loop.size() < 3)
        return broken(Element::boundary_position, -1,
                      "boundary loop has " + std::to_string(loop.size()) + " vertices (needs 3 corners)");
    if (loop.size() != scan.n_boundary_edges)
        return broken(Element::boundary_position, -1,
                      "the triangles have " + std::to_string(scan.n_boundary_edges) +
                          " boundary edges but the loop has " + std::to_string(loop.size()) +
                          " (more than one boundary loop?)");
    std::vector<char> on_loop(nv, 0);
    for (std::size_t i = 0; i < loop.size(); ++i) {
        const std::uint32_t a = loop[i], b = loop[(i + 1) % loop.size()];
        if (a >= nv || scan.boundary_next[a] != b)
            return broken(Element::boundary_position, static_cast<std::int64_t>(i),
                          "boundary position " + std::to_string(i) + ": (" + std::to_string(a) + ", " +
                              std::to_string(b) + ") is not a boundary edge in the triangles' orientation");
        if (on_loop[a]++)
            return broken(Element::boundary_position, static_cast<std::int64_t>(i),
                          "boundary position " + std::to_string(i) + " repeats vertex " + std::to_string(a));
    }
    return std::nullopt;
}

// Connected, and χ = V − E + F = 1: with one boundary loop and manifold vertices, a disk; and its
// corners in order on the loop.
std::optional<Violation> topology_violation(const Disk& disk, const DiskScan& scan) {
    const std::size_t nv = disk.positions.size();
    std::vector<std::uint32_t> parent(nv);
    std::iota(parent.begin(), parent.end(), 0u);
    for (const auto& f : disk.triangles)
        for (int k = 1; k < 3; ++k) parent[find_root(parent, f[k])] = find_root(parent, f[0]);
    for (std::uint32_t v = 1; v < nv; ++v)
        if (find_root(parent, v) != find_root(parent, 0))
            return broken(Element::vertex, v, "not connected (vertex " + std::to_string(v) + ")");
    const long chi = static_cast<long>(nv) - static_cast<long>(scan.n_edges) + static_cast<long>(disk.triangles.size());
    if (chi != 1) return broken(Element::whole, -1, "Euler characteristic " + std::to_string(chi) + " (a disk has 1)");
    const auto& c = disk.corners;
    if (!(c[0] == 0 && c[0] < c[1] && c[1] < c[2] && c[2] < disk.boundary.size()))
        return broken(Element::corners, -1,
                      "corners (" + std::to_string(c[0]) + ", " + std::to_string(c[1]) + ", " + std::to_string(c[2]) +
                          ") are not 0 < c1 < c2 < " + std::to_string(disk.boundary.size()));
    return std::nullopt;
}

}  // namespace

std::optional<Violation> disk_violation(const Disk& disk) {
    if (disk.triangles.empty()) return broken(Element::whole, -1, "no triangles");
    if (disk.positions.size() >= std::uint32_t(-1)) return broken(Element::whole, -1, "too many vertices");
    DiskScan scan(disk.positions.size(), disk.triangles.size());
    if (auto v = triangles_violation(disk, scan)) return v;
    if (auto v = boundary_violation(disk, scan)) return v;
    if (auto v = fan_violation(disk, scan)) return v;
    if (auto v = loop_violation(disk, scan)) return v;
    return topology_violation(disk, scan);
}

void validate(const Disk& disk) {
    if (const auto broken = disk_violation(disk)) throw InvalidInput("patch: " + broken->describe());
}

std::vector<unsigned> boundary_sides(const Disk& disk) {
    FHR_DCHECK(disk.corners[0] == 0 && disk.corners[0] < disk.corners[1] && disk.corners[1] < disk.corners[2] &&
               disk.corners[2] < disk.boundary.size());
    const std::size_t n = disk.boundary.size();
    std::vector<unsigned> sides(n, 0);
    for (unsigned c = 0; c < 3; ++c) {
        const std::size_t from = disk.corners[c], to = c == 2 ? n : disk.corners[c + 1];
        for (std::size_t p = from; p <= to; ++p) sides[p % n] |= 1u << c;
    }
    return sides;
}

}  // namespace fhr::param
