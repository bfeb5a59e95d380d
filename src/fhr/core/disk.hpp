// FHR §3/§4 — one patch S_i of T′ as §3 hands it to §4: a triangulated topological disk with its
// own vertex numbering, its boundary loop and its three corners x_j, x_k, x_l (paper §4, eq. 2).
// A plain value of the core, so that §3 (src/fhr/partition) makes it and §4 (src/fhr/param) maps
// it without either including the other; its contract and checks are §4's (param/disk.hpp,
// spec/patch_map.md MAP-1..).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <fhr/core/polygon_soup.hpp>

namespace fhr {

/// One patch S_i of T′ (paper §3/§4): a triangulated topological disk.
struct Disk {
    std::vector<Vec3> positions;                          ///< 3-D positions of the disk's vertices (#V)
    std::vector<std::array<std::uint32_t, 3>> triangles;  ///< counter-clockwise seen from outside the surface
    std::vector<std::uint32_t>
        boundary;  ///< the boundary loop, in the orientation induced by the triangles, starting at corner 0
    std::array<std::size_t, 3>
        corners;                ///< positions IN `boundary` of the corners x_j, x_k, x_l; corners[0] == 0, increasing
    std::size_t midpoints = 0;  ///< the last `midpoints` vertices are split_dividing_edges' (MAP-4), not T′'s
};

}  // namespace fhr
