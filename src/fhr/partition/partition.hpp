// FHR §3 — the partition of Ω_T into triangular patches S_i: one exact shortest geodesic per edge
// of D, embedded into T′, conditions (1) and (2), the patches — and recovery when the conditions fail.
//
// Paper §3 requires "a parameter domain Ω_D and a vertex correspondence with the property that
// conditions (1) and (2) hold", found always to hold in its examples, and notes that they "could
// be made part of the stopping criterion" of the decimation. We do that after the fact: when they
// fail, D is changed where they fail — an edge flipped, or T decimated again keeping the vertices
// at the conflicts — or, when that would add too much, refined everywhere by undoing the last
// collapses of its decimation; the paths are recomputed (only those of new edges are new work).
//
// Pseudocode:
//   base <- D (when its history describes it, else T decimated afresh to D's size)
//   loop:
//       for each edge [v_j, v_k] of D: Γ(x_j, x_k) by the ellipse search (cached by its ends)
//       embed the paths into T -> T′, with the conflicts against (1) and (2)
//       if no conflict: cut T′ into the patches; return
//       if keeping D (the default) and D's history describes it, on the first round:
//           restricted shortest paths where the geodesics conflict (partition/detail/keep.hpp); return
//           (no room to separate two curves: go on below, changing D)
//       if D was given by the user: PartitionFailure naming the conflicting domain edges
//       if some curve runs over a corner of a face beside its edge: flip those edges; next round
//           (the flips are made again, where they apply, after each new D below)
//       more <- the vertices of T at the conflicts not in D (a shared node; beside a corner a
//               curve runs over; a crossing face's corners; the first node of a curve out of
//               order), or when all are in D already, the middle node of each conflicting curve,
//               or the ends of the edges its nodes lie on, or the neighbours of the places
//       if more is not empty and 8·|more| ≤ #F(D):
//           keep += more; base <- decimate_again(T, base, #F(D) + 2·|more| faces, keeping
//           `keep`, stopping early if it must: base's collapses are reused up to its first
//           that removes a vertex now kept); D <- base
//       else: base <- base with its last max(1, #F(D)/8) collapses undone; D <- base
//           (at the end of the history D = T, whose paths are T's own edges: (1), (2) hold)
// Decisions and their reasons: paper_notes/partition.md.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include <fhr/core/executor.hpp>
#include <fhr/domain/domain.hpp>
#include <fhr/geodesic/ellipse.hpp>
#include <fhr/partition/embed.hpp>
#include <fhr/partition/patches.hpp>

namespace fhr::partition {

/// How the curve of a domain edge was found.
enum class CurveKind : std::uint8_t {
    geodesic,    ///< the exact shortest geodesic Γ(x_j, x_k) of T (paper §3)
    restricted,  ///< the restricted shortest path in the region the other curves leave free
    boundary,    ///< a boundary edge of D: the arc of T's boundary between its ends (core/detail/cones.hpp)
    /// beyond the paper: moved into the middle of its two patches (pipeline/detail/straighten.hpp)
    straightened,
};

/// "geodesic", "restricted", "boundary" or "straightened" (geodesics.obj, report.json).
const char* name(CurveKind kind);

/// What the report says of one domain edge's curve.
struct CurveInfo {
    CurveKind kind = CurveKind::geodesic;
    double geodesic_length = 0;   ///< |Γ(x_j, x_k)| on T, unrestricted
    double shortest = 0;          ///< restricted: the restricted shortest length before separation
    double separation_bound = 0;  ///< restricted: the bound of what the separation added
    std::string reason;           ///< restricted: the conflict of its geodesic that forced it
};

struct PartitionOptions {
    geodesic::EllipseOptions ellipse;
    /// true (the default): D is kept, conflicting edges get restricted shortest paths
    /// (partition/detail/keep.hpp); false: the paper's geodesics only, D changed where they conflict.
    bool keep_domain = true;
    std::function<void(const std::string&)> progress;  ///< optional: one line per round
    /// optional: runs the independent geodesic and curve searches; default_executor(). Their
    /// reusable arrays are in workspaces the call owns (one leased per running search) and frees
    /// when it returns (geodesic/workspace.hpp); `ellipse.workspace` is not used.
    Executor* executor = nullptr;
};

/// The result of §3: the (possibly refined) domain, its paths, T′ and the patches.
struct Partition {
    domain::Domain domain;                  ///< D after recovery (unchanged when none was needed)
    EdgeData<geodesic::EllipsePath> paths;  ///< #E(D): Γ for D's halfedge (e, 0), from x_j to x_k
    Network network;                        ///< T′ with the paths embedded
    Patches patches;                        ///< one disk per face of D
    std::size_t retries = 0;                ///< rounds that found conflicts and decimated again
    std::size_t vertices_added = 0;         ///< #V(D) − #V(D₀)
    std::vector<VertexId> kept;             ///< the vertices of T that the recovery made D keep
    std::vector<Conflict> resolved;         ///< the conflicts met on the way, in order
    EdgeData<CurveInfo> curves;             ///< #E(D): each curve's kind (geodesic or restricted)
    std::size_t keep_start_faces =
        0;  ///< keeping D: the faces of the start on T (D's own count when kept directly; 0: not needed)
};

/// §3 for T and D.
/// \pre T valid (maybe with boundary and several components: PART-12, paper_notes/boundary.md);
///      D's vertices are vertices of T (decimate or attach_domain), D of T's topology.
/// \throws PartitionFailure when (1)/(2) fail for a user-given domain (one without decimation
///         history); the message names the conflicting domain edges.
Partition partition(const TriMesh& T, domain::Domain D, const PartitionOptions& options = {});

}  // namespace fhr::partition
