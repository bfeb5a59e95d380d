// FHR §3 — one patch cut out of T′ as a disk of its own (the check of patches.hpp's pseudocode on
// one region): the whole network's patches (partition/patches.cpp) and a region's two new patches
// when a curve is moved inside it (pipeline/detail/straighten.hpp) are cut the same way.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <fhr/core/detail/outcome.hpp>
#include <fhr/core/trimesh.hpp>
#include <fhr/partition/patches.hpp>

namespace fhr::partition {

/// The patch of `faces` (faces of M, in increasing order) bounded by the loop of `sides`: three
/// curves of M's vertices in the loop's direction, corner 0 the first vertex of sides[0], each
/// side's last vertex the next side's first; `labels`: the halfedges of M on a curve are valid.
/// Or why not: the faces are not on the left of the loop, or a loop vertex is in none of them, or
/// the loop touches itself, or the faces have another boundary, or they are not a disk.
/// `local` is scratch: #V(M) entries, all −1, and so again on return.
Outcome<Patch> cut_disk(const TriMesh& M, const HalfedgeData<DHalfedgeId>& labels, std::vector<FaceId> faces,
                        const std::array<std::span<const VertexId>, 3>& sides, std::vector<std::int32_t>& local);

}  // namespace fhr::partition
