// FHR §4 — internals shared by src/fhr/param (not included by other modules): the directed-edge
// table of a disk, the canonical direction of a side's chord-length parameter, and the 2^-53
// grid on which every β is stored.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include <fhr/core/errors.hpp>
#include <fhr/param/disk.hpp>

namespace fhr::param::detail {

inline std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) { return (static_cast<std::uint64_t>(a) << 32) | b; }

/// The directed edge (a, b) → the triangle that traverses it: an open-addressing table (a power
/// of two of at least twice as many slots as edges, linear probing) in two flat arrays.
/// As a std::unordered_map (a node allocated per edge, a division per lookup), MAP-1's checks alone,
/// made twice per patch, were 5 % of the fandisk paper run.
class DirectedEdges {
public:
    static constexpr std::uint32_t none = std::uint32_t(-1);
    /// Room for `edges` edges before the table grows.
    explicit DirectedEdges(std::size_t edges) { resize_for(edges); }
    /// Records that triangle t traverses `key`; false (and nothing changed) when one already does.
    bool insert(std::uint64_t key, std::uint32_t t);
    /// Triangle t traverses `key` now, whichever did before.
    void assign(std::uint64_t key, std::uint32_t t);
    /// No triangle traverses `key` any more.
    void erase(std::uint64_t key);
    /// The triangle that traverses `key`. \throws InternalError when none does.
    std::uint32_t at(std::uint64_t key) const {
        const std::uint32_t t = find(key);
        if (t == none) throw InternalError("DirectedEdges::at: no triangle traverses the edge");
        return t;
    }
    /// The triangle that traverses `key`, or none.
    std::uint32_t find(std::uint64_t key) const {
        for (std::size_t i = slot(key); key_[i] != empty; i = (i + 1) & (key_.size() - 1))
            if (key_[i] == key) return triangle_[i];
        return none;
    }

private:
    static constexpr std::uint64_t empty = std::uint64_t(-1);  // no edge_key: its vertices are < 2^32 − 1
    std::vector<std::uint64_t> key_;                           // an erased edge keeps its key, with triangle none
    std::vector<std::uint32_t> triangle_;
    std::size_t used_ = 0;  // slots with a key
    unsigned shift_ = 0;
    std::size_t slot(std::uint64_t key) const {
        return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_);
    }
    // The slot of `key`, or the empty slot where it would go.
    std::size_t place(std::uint64_t key) const {
        std::size_t i = slot(key);
        while (key_[i] != empty && key_[i] != key) i = (i + 1) & (key_.size() - 1);
        return i;
    }
    void resize_for(std::size_t edges);
};

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
