// FHR §3 — the partition of Ω_T into triangular patches S_i: one exact shortest geodesic per edge
// of D, embedded into T′, conditions (1) and (2), the patches — and recovery when the conditions fail.
//
// Paper §3 requires "a parameter domain Ω_D and a vertex correspondence with the property that
// conditions (1) and (2) hold", found always to hold in its examples, and notes that they could be
// made "part of the stopping criterion" of the decimation. We do the equivalent after the fact:
// when they fail, the collapses that made the conflicting corners are undone (selective
// refinement of D near the conflict) and the paths are recomputed; only the paths of D's new
// edges are new work.
//
// Pseudocode:
//   loop:
//       for each edge [v_j, v_k] of D: Γ(x_j, x_k) by the ellipse search (cached by its ends)
//       embed the paths into T -> T′, with the conflicts against (1) and (2)
//       if no conflict: cut T′ into the patches; return
//       refine D at the corners of the conflicting edges (domain::refine_at), or at their
//           neighbours, rings outwards, when those have no collapse left to undo
//       if that is stuck: undo D's collapses in order instead, twice as many each time (ends at
//           D = T, whose paths are T's edges: (1) and (2) hold)
//       if nothing could be refined (a user-given D has no history): PartitionFailure naming
//           the conflicting domain edges
// Decisions and their reasons: paper_notes/partition.md.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "domain/decimate.hpp"
#include "geodesic/ellipse.hpp"
#include "partition/embed.hpp"
#include "partition/patches.hpp"

namespace fhr::partition {

struct PartitionOptions {
    geodesic::EllipseOptions ellipse;
    std::function<void(const std::string&)> progress;  ///< optional: one line per round
};

/// The result of §3: the (possibly refined) domain, its paths, T′ and the patches.
struct Partition {
    domain::Domain domain;                     ///< D after recovery (unchanged when none was needed)
    std::vector<geodesic::EllipsePath> paths;  ///< #E(D): Γ for D's halfedge (e, 0), from x_j to x_k
    Network network;                           ///< T′ with the paths embedded
    Patches patches;                           ///< one disk per face of D
    std::size_t retries = 0;                   ///< rounds that found conflicts and refined D
    std::size_t collapses_undone = 0;          ///< vertices added to D by the recovery
    std::vector<Conflict> resolved;            ///< the conflicts met on the way, in order
};

/// §3 for T and D.
/// \pre T valid, closed, connected; D's vertices are vertices of T (decimate or attach_domain).
/// \throws PartitionFailure when (1)/(2) fail and D cannot be refined near the conflict (a
///         user-given domain has no collapses to undo); the message names the domain edges.
Partition partition(const TriMesh& T, domain::Domain D, const PartitionOptions& options = {});

}  // namespace fhr::partition
