// FHR §3 — cutting T′ along the geodesic network into the patches S_i, one per triangle T_i of D.
//
// Paper §3: "to each triangle T_i = [v_j, v_k, v_l] there should be a triangular region S_i ⊂ Ω_T
// bounded by the three curves Γ(x_j, x_k), Γ(x_k, x_l), Γ(x_l, x_j)". When (1) and (2) hold this
// follows from graph theory; we do not rely on it but check it on T′ directly.
//
// Pseudocode:
//   regions <- the faces of T′ joined across every edge that carries no path (flood fill)
//   for each region R:
//       its boundary halfedges (R on their left) carry D halfedges, all of one D face T_i
//       (D's face on the left of each); R is the patch S_i
//   check: every D face has exactly one region; each region is a disk (χ = 1) whose boundary is
//       one loop, the three curves of T_i in D's orientation, corners at x_j, x_k, x_l
#pragma once

#include <vector>

#include <fhr/core/executor.hpp>
#include <fhr/domain/domain.hpp>
#include <fhr/core/disk.hpp>
#include <fhr/partition/embed.hpp>

namespace fhr::partition {

/// The patch S_i of D's face T_i: a topological disk of T′ bounded by three paths.
struct Patch {
    std::vector<FaceId> faces;       ///< faces of T′, in increasing order
    std::vector<VertexId> vertices;  ///< disk vertex -> vertex of T′
    Disk disk;                       ///< local triangles, boundary from corner x_j of D's face (j, k, l)
};

/// The patches, indexed by D's faces, and the patch of every face of T′.
struct Patches {
    FaceData<Patch> patch;           ///< #F(D)
    FaceData<FaceId> patch_of_face;  ///< #F(T′): the D face whose patch holds it
};

/// Cuts T′ along the network into one disk per face of D; the disks are made on `executor`
/// (default_executor() when null), the same on any.
/// \pre network is the conflict-free result of embed() for D.
/// \throws PartitionFailure naming the D face when a region is not a disk bounded by its three
///         curves (Theorem: impossible when (1) and (2) hold; checked all the same).
Patches extract_patches(const domain::Domain& D, const Network& network, Executor* executor = nullptr);

}  // namespace fhr::partition
