// FHR §4 — internals shared by src/fhr/param (not included by other modules): the directed-edge
// table of a disk, the canonical direction of a side's chord-length parameter, and the 2^-53
// grid on which every β is stored.
#pragma once

#include <cmath>
#include <cstdint>
#include <unordered_map>

#include <fhr/param/disk.hpp>

namespace fhr::param::detail {

inline std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
    return (static_cast<std::uint64_t>(a) << 32) | b;
}

/// The directed edge (a, b) → the triangle that traverses it.
using DirectedEdges = std::unordered_map<std::uint64_t, std::uint32_t>;

/// \pre no directed edge is traversed by two triangles (disk_violation checks it).
DirectedEdges directed_edges(const Disk& disk);

/// True when a side from `start` to `end` measures its chord-length parameter from `start`:
/// from the corner whose position is lexicographically smaller (start on a tie). Two patches
/// sharing a geodesic curve traverse it in opposite directions but agree on this end, so they
/// accumulate the same chord lengths in the same order and store bit-identical β (MAP-5).
inline bool measured_from_start(const Vec3& start, const Vec3& end) {
    for (int i = 0; i < 3; ++i)
        if (start[i] != end[i]) return start[i] < end[i];
    return true;
}

/// x rounded to the nearest multiple of 2^-53 (ties to even). On that grid every value in
/// [0, 1], and 1 minus it, and the sum of two of them up to 1, is a double exactly; so a triple
/// (1 − b1 − b2, b1, b2) of grid values sums to exactly 1 in any order (MAP-5, MAP-6). The
/// scalings by powers of two are exact; the change is at most 2^-54 ≈ 5.6e-17.
inline double snap(double x) {
    constexpr double scale = 9007199254740992.0;  // 2^53
    return std::nearbyint(x * scale) / scale;
}

}  // namespace fhr::param::detail
