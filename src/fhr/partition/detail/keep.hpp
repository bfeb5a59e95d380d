// Beyond the paper (§3): keeping the domain that was asked for. When the geodesics of D's edges
// break conditions (1) or (2), D is kept and the conflicting edges get restricted shortest paths
// (partition/restricted.hpp) instead of D being changed.
//
// Pseudocode:
//   direct start (tried first): keep the geodesics with no conflict of their own and none with a
//       kept one (then drop, a round at a time, one curve where the kept ones around a corner are
//       out of D's cyclic order); when the faces joined across the dropped edges are disks (maybe
//       pinched), each with one region of T′ bounded by kept curves, put each dropped edge in as
//       a restricted path: slits from inner vertices first, then diagonals that split a polygon;
//       check the whole network; on any failure take the valid start
//   valid start: step back along D's decimation history until the geodesics of that finer domain
//       D_i satisfy (1) and (2) (at worst D_i = T, whose geodesics are its edges); embed them
//       once, and keep per face of D_i the faces of T its patch touches. Start::fast undoes a
//       quarter more faces, then four times as many collapses a round, and takes T itself once
//       D_i would pass 16 |D| faces; Start::gradual undoes a quarter more faces a round
//   redo the undone collapses on the network, in batches whose closed 1-rings are disjoint (they
//       commute): a collapse v → w is a sequence of flips of v's spokes, each flip [v, u] → [w, y]
//       replacing the curve by the restricted path from x_w to x_y in the two patches beside [v, u],
//       until v has valence 3; then v's three patches merge into one face and its curves go
//   a domain given by the user (same vertices as the decimation H, other edges): flip, in
//       regions with no face in common, the edges not in D whose flip makes an edge of D (a
//       restricted path in the two patches); when there is none, one edge near a missing edge
//       whose flip starts at most four flips that end in such a flip; give up (PartitionFailure)
//       when there is none, or after 4k + 16 flips for k missing edges
//   tighten: in passes, edges in the kept order (edges whose geodesic is in no conflict first,
//       then the others, each group shortest geodesic first), in batches of edges with no face in
//       common: the curve becomes the restricted path between its ends in its two patches when
//       that is shorter, and the exact geodesic itself when that is what it found
//   with boundary (T̂, D̂ closed by cones): the cone edges and D's boundary edges keep their fixed
//       curves — kept first, never dropped, flipped or tightened; a collapse along the boundary
//       v -> w flips v's spokes on the side of its face of T only, until v has its two boundary
//       neighbours w, v' and the apex; then the two cone faces merge into the new cone face, v's
//       face of T joins the face across [v', w], and [v', w] gets the boundary arc from v' to w
//   every flip and tightening works in its region alone (partition/region.hpp): the faces of T
//       the two patches touch are cut along the four curves around them, the new curve is found
//       there, and cutting again along it gives the two new patches' faces of T; a conflict there
//       is an internal error (the separation keeps the curves apart), and the caller embeds the
//       final network into T as a whole and checks it again
// Decisions and their reasons: paper_notes/partition.md, "Keeping the domain".
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <fhr/core/executor.hpp>
#include <fhr/domain/domain.hpp>
#include <fhr/geodesic/ellipse.hpp>
#include <fhr/partition/embed.hpp>
#include <fhr/partition/partition.hpp>
#include <fhr/partition/patches.hpp>

namespace fhr::partition {

struct KeptNetwork {
    EdgeData<geodesic::GeodesicPath> paths;  ///< #E(D): the curve of D's halfedge (e, 0)
    EdgeData<CurveInfo> info;                ///< #E(D)
    EdgeData<std::uint8_t> unsnapped;        ///< #E(D): 1 when embed() must place it as given
    std::size_t start_faces = 0;             ///< #F(D_i), the start, on T (D̂_i's cone faces not counted)
    /// embed(T, D, paths, unsnapped) and its patches when they were already computed (the direct
    /// start's check, its curves unchanged since), so that the caller need not embed the same
    /// curves again nor cut the same patches (at 10⁶ faces 0.8 s and 0.2 s).
    struct Embedded {
        Embedding embedding;
        Patches patches;  ///< extract_patches(D, embedding.network)
    };
    std::optional<Embedded> embedded;
};

/// How far the valid start steps back (see the pseudocode above).
enum class Start : std::uint8_t {
    fast,     ///< few steps, often to T: the fewest geodesics computed
    gradual,  ///< the nearest valid level: the fewest flips, so the least crowded curves
};

/// The network for exactly D.
/// \pre T is T̂ (core/detail/cones.hpp; T itself when closed), whose vertices from `real_vertices` on are
///      cone apexes, and D is D̂ (domain::close_domain); `base()` gives H = Ĥ, a decimation of T
///      whose history describes it (domain::history_describes) with D's vertices (H = D when D is
///      itself that decimation), or throws PartitionFailure naming why there is none; it is called
///      only when the direct start does not serve; geodesics[e] is the curve of D's halfedge (e, 0) — for an edge with a cone
///      face beside it (domain::on_cone) the fixed curve, which is kept as it is; `conflicts` are
///      those of their embedding; `geodesics_of` gives the curves of any domain of T (in its edge
///      order); the separations of one round run on `executor`, each restricted search on a
///      workspace leased from a pool this call owns and frees (geodesic/workspace.hpp).
/// \throws InternalError when a separated curve breaks (1) or (2) (a bug);
///         PartitionFailure when a curve has no room to be separated, or when no flips lead from H
///         to D.
KeptNetwork keep_domain(const TriMesh& T, std::size_t real_vertices, const domain::Domain& D,
                        const std::function<const domain::Domain&()>& base,
                        std::span<const geodesic::EllipsePath> geodesics, std::span<const Conflict> conflicts,
                        const std::function<std::vector<geodesic::EllipsePath>(const domain::Domain&)>& geodesics_of,
                        const std::function<void(const std::string&)>& progress, Executor& executor,
                        Start start = Start::fast);

}  // namespace fhr::partition
