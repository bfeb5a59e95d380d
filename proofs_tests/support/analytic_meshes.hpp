// Test support — analytic meshes shared by the geodesic suites: the geodesic sphere (icosphere)
// whose vertices lie on the unit sphere, for comparisons with great-circle and GeographicLib
// distances.
#pragma once

#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "core/trimesh.hpp"

namespace fhr::test {

// The geodesic sphere of `level`: the icosahedron, each triangle split into four `level` times,
// every vertex projected to the unit sphere. All its triangles are acute.
inline TriMesh icosphere(int level) {
    const double g = (1 + std::sqrt(5.0)) / 2;
    std::vector<Vec3> p{{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                        {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    std::vector<Triangle> t{{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                            {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                            {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
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

}  // namespace fhr::test
