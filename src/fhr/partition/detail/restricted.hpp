// Beyond the paper (§3): the restricted shortest path — the shortest curve between two corners of
// a region of T′ that the other curves of the network leave free, moved off those curves.
//
// Paper §3 takes one shortest geodesic per edge of D and needs conditions (1) and (2) to hold. Where
// they fail, fhr keeps D and gives the edge the shortest curve that stays in the region the other
// curves leave free: the union of the patches beside it (after a flip, the two patches of the
// edge's old position). That region is a disk of T′ bounded by other curves, cut out on its own
// (partition/region.hpp: T′_S, the piece of T′ around it); the exact window propagation of
// src/fhr/geodesic runs on T′_S masked to it (its boundary vertices are pseudo-sources,
// so the shortest path may bend around them). The true restricted shortest curve may touch the
// boundary, which (1) forbids: each node where it does is replaced by points on the edges of T
// around it, inside the region, at most separation_fraction of those edges away (the separation).
//
// Pseudocode:
//   mask <- the faces of T′_S on the region's side of one of its boundary curves
//   Γ* <- exact shortest path from x_a to x_b on T′_S masked to the region;  L* <- its length
//   each node of Γ* within snap_fraction of an end of its edge of T′_S moves to that end (a path
//       through a vertex arrives a rounding error beside it; no curve lies between)
//   for each node u of Γ* (on T′_S, finally mapped to T):
//       an end: x_a or x_b
//       a point inside an edge of T′: on an edge of T → that point of T; across a chord of a
//           face of T (T′'s own edge inside it) → dropped (Γ* is straight inside the face of T)
//       a vertex inside the region → its place on T (a vertex of T or a point of an edge of T)
//       a vertex on the region's boundary ("touched"): walk the region's faces around u from the
//           segment that comes in to the one that goes out; for every edge of T′ crossed on the
//           way that runs along an edge E of T, a point on E at δ·|E| from u (δ ≤ separation_fraction,
//           and at most a third of the way to the next vertex of T′ on E)
//   length bound: every touched node u with k points at most r from u adds at most 2·k·r, every
//       snapped node twice its move
// Decisions and their reasons: paper_notes/partition.md, "Keeping the domain".
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include <fhr/geodesic/exact.hpp>
#include <fhr/partition/detail/region.hpp>

namespace fhr::partition {

/// The separation: a touched node moves to points at most this fraction of an edge of T from it.
/// Each curve separated towards another takes at most a third of the gap between them, so curves
/// squeezed past one vertex get closer by thirds; embed() places restricted paths without snapping,
/// and a gap below min_separation (relative to the edge) is refused as no room. The strip between a
/// restricted path and the curve it was moved off is this wide, and its faces as anisotropic as
/// its inverse: 5 % of the edge, not a rounding distance (paper_notes/distortion_causes.md).
inline constexpr double separation_fraction = 0.05;
inline constexpr double min_separation = 1e-12;

struct RestrictedPath {
    geodesic::GeodesicPath path;  ///< on T, from `from` to `to`; length: the separated curve's length
    double shortest = 0;          ///< L*: the exact shortest length inside the region (before separation)
    double separation_bound = 0;  ///< proven bound of path.length − shortest (Σ 2·k·r over touched nodes)
    std::size_t touches = 0;      ///< nodes of the shortest curve on the region's boundary
};

/// The restricted shortest path from x `from` to x `to` inside a region: the faces of `region`'s
/// T′_S in `mask` (one side of one of its curves, Region::side), separated from the region's boundary.
/// \pre the mask is a disk of T′_S with `from` and `to` (vertices of T) on its boundary; no other
///      curve of the network enters it.
/// \post path runs from `from` to `to` on T, with consecutive nodes in a common face of T; inside
///       the region; touching its boundary only at the ends; path.length ≤ shortest + separation_bound.
/// The exact search borrows its arrays from `workspace` (geodesic/workspace.hpp; nullptr: its own).
/// When the mask is found not to be such a region (a path node inside a face of T′, the walk around
/// a touched vertex leaving it), why not: the network's own regions always are (a failure there is
/// a bug: the caller's value() throws InternalError), the direct start's may not be.
/// \throws PartitionFailure when `to` cannot be reached inside the region, or when a touched node
///         has no room for the separation (less than min_separation of an edge).
Outcome<RestrictedPath> restricted_path(const Region& region, const FaceData<std::uint8_t>& mask, VertexId from,
                                        VertexId to, geodesic::Workspace* workspace = nullptr);

}  // namespace fhr::partition
