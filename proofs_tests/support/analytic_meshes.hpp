// Test support — analytic meshes shared by the geodesic suites: the geodesic sphere (icosphere)
// whose vertices lie on the unit sphere, for comparisons with great-circle and GeographicLib
// distances.
#pragma once

#include <cmath>
#include <map>
#include <random>
#include <tuple>
#include <utility>
#include <vector>

#include <fhr/core/trimesh.hpp>

namespace fhr::test {

// The geodesic sphere of `level`: the icosahedron, each triangle split into four `level` times,
// every vertex projected to the unit sphere. All its triangles are acute.
inline TriMesh icosphere(int level) {
    const double g = (1 + std::sqrt(5.0)) / 2;
    std::vector<Vec3> p{{-1, g, 0},  {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                        {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
    std::vector<Triangle> t{{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                            {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                            {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (Vec3& x : p) x.normalize();
    for (int l = 0; l < level; ++l) {
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
        auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
            const auto [lo, hi] = std::minmax(a, b);
            const auto [it, fresh] = mid.try_emplace({lo, hi}, static_cast<std::uint32_t>(p.size()));
            if (fresh) p.push_back((p[a] + p[b]).normalized());
            return it->second;
        };
        std::vector<Triangle> finer;
        for (const Triangle& f : t) {
            const std::uint32_t ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
            finer.push_back({f[0], ab, ca});
            finer.push_back({ab, f[1], bc});
            finer.push_back({ca, bc, f[2]});
            finer.push_back({ab, bc, ca});
        }
        t = std::move(finer);
    }
    return TriMesh::from_triangles(std::move(p), t);
}

// A polyhedron with every face finely and irregularly triangulated, flat: each face (a, b, c) of
// `coarse` becomes the n × n lattice of points a + (i/n)(b − a) + (j/n)(c − a), the points inside an
// edge moved along it and those inside a face moved within it by up to jitter/n of the lattice
// step (the same edge point for both faces of an edge). The coarse vertices come first (vertex k of
// the result is coarse vertex k), so a domain of the polyhedron's own corners has t_vertex = identity.
// \pre coarse is closed and oriented, n >= 1, 0 <= jitter < 0.3 (no triangle can fold).
inline TriMesh refined_polyhedron(const std::vector<Vec3>& corners, const std::vector<Triangle>& coarse, int n,
                                  double jitter, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> shake(-jitter, jitter);
    std::vector<Vec3> p = corners;
    std::map<std::tuple<std::uint32_t, std::uint32_t, int>, std::uint32_t> on_edge;  // (lo, hi, step from lo)
    std::vector<Triangle> t;
    for (const Triangle& f : coarse) {
        std::map<std::pair<int, int>, std::uint32_t> id;
        auto vertex = [&](int i, int j) -> std::uint32_t {
            if (const auto it = id.find({i, j}); it != id.end()) return it->second;
            std::uint32_t v;
            if (i + j == 0 || i == n || j == n) {
                v = i == n ? f[1] : j == n ? f[2] : f[0];
            } else if (i == 0 || j == 0 || i + j == n) {
                // An edge point: (end a, end b, steps from a), shared with the neighbouring face.
                const auto [a, b, k] = j == 0   ? std::tuple{f[0], f[1], i}
                                       : i == 0 ? std::tuple{f[0], f[2], j}
                                                : std::tuple{f[1], f[2], j};
                const std::uint32_t lo = std::min(a, b), hi = std::max(a, b);
                const int from_lo = a == lo ? k : n - k;
                auto [it, fresh] = on_edge.try_emplace({lo, hi, from_lo}, static_cast<std::uint32_t>(p.size()));
                if (fresh) p.push_back(p[lo] + ((from_lo + shake(rng)) / n) * (p[hi] - p[lo]));
                v = it->second;
            } else {
                const double s = (i + shake(rng)) / n, r = (j + shake(rng)) / n;
                v = static_cast<std::uint32_t>(p.size());
                p.push_back(p[f[0]] + s * (p[f[1]] - p[f[0]]) + r * (p[f[2]] - p[f[0]]));
            }
            id[{i, j}] = v;
            return v;
        };
        for (int i = 0; i < n; ++i)
            for (int j = 0; i + j < n; ++j) {
                t.push_back({vertex(i, j), vertex(i + 1, j), vertex(i, j + 1)});
                if (i + j < n - 1) t.push_back({vertex(i + 1, j), vertex(i + 1, j + 1), vertex(i, j + 1)});
            }
    }
    return TriMesh::from_triangles(std::move(p), t);
}

inline const std::vector<Vec3> tetrahedron_corners{{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
inline const std::vector<Triangle> tetrahedron_faces{{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
inline const std::vector<Vec3> octahedron_corners{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
inline const std::vector<Triangle> octahedron_faces{{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                                    {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};

}  // namespace fhr::test
