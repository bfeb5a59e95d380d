// Beyond the paper (§3 → §4) — the curves moved between neighbouring patches. A geodesic that
// leaves a corner at a tiny angle to another, or a restricted curve squeezed beside the curves it
// had to avoid, bounds patches far from their domain triangles' shapes; no map of the patch with
// that boundary can be much better (paper_notes/distortion_causes.md). The curve of an interior
// domain edge is therefore replaced by the one that the two patches beside it, mapped together,
// put in the middle of their union.
//
// Pseudocode (for D's halfedge A → C of edge e, with faces [A, C, B] on its left and [C, A, E] on
// its right):
//   Q <- the two domain triangles laid flat along AC (A = (0, 0), C = (|AC|, 0), B above, E below);
//        where Q is not convex enough (an angle at A or C above max_quad_angle), B and E are moved
//        over AC's midpoint at their heights (a kite)
//   U <- the union of the two patches, cut out of T on its own with the four other curves around it
//        (partition/detail/region.hpp: a cost of U's size, not T's); its boundary, those curves,
//        onto Q's sides by chord length; every other vertex the convex combination of its
//        neighbours (eq. 2, the patches' own weights): a one-to-one map onto the convex Q;
//        where the map misses a percentile goal (below), also a second map, nearer conformal:
//        this one moved by Newton steps on Σ_f A_f m_f^p (param/detail/mips_newton.hpp), U's
//        boundary sliding along Q's sides, Q's corners kept (where Q is a kite, B and E then moved
//        in steps to the triangles' own places, the images carried along, Newton steps after
//        each) — each gives a new curve as follows,
//        and the pair better by the rule below is the one tried against the old curve
//   the new curve <- the preimage of the diagonal AC: the points of T's edges (and T's vertices)
//        inside U whose images lie on it, in the order of their images along it; between two of
//        them it runs straight in one face of T (a face's part of U is convex)
//   U cut again along the new curve (placed as embed() places a geodesic, snapped): a conflict
//        with the curves around it (snapping onto a vertex one of them uses) leaves the old curve;
//        else its two new patches are mapped (the caller's §4) and scored, and the curve is kept
//        only when its pair got better — its worst face less anisotropic with the pair's L2 energy
//        at most `l2_slack` higher, or that energy lower with the worst face no worse (or below
//        `poor`)
//   only the curves of patches whose map is poor are tried — a face above `poor` σ₁/σ₂, or above
//   `tail` while more than `tail_share` of the map's image area is above `tail` or more than
//   `poor_share` above `poor` (a percentile goal missed: where both are met, moving curves for
//   them costs time for nothing) — in rounds of edges that share no patch (each round's unions
//   are disjoint: tried at once)
//   thorough sweeps (when the caller asks, `thorough_sweeps` of them, each while a percentile goal
//   is missed): every interior curve is tried, by the nearer conformal map's curve, and kept when
//   both new maps are certified, the pair's worst face is no worse than before or than `poor`, and
//   T′ stays within `thorough_growth` of its faces before the moves. The new pair's L2 energy is
//   not asked: it is measured under the chord-length boundary, which the sliding that follows
//   moves (slide.hpp) — the caller keeps the thorough result only when the final map's L2 stretch
//   is no higher than before
//   stars (when the caller asks, before the thorough sweeps, while a percentile goal is missed):
//   for each vertex v of D inside D whose corner spread — the largest over the least ratio, over
//   the patches at x_v, of a patch's angle at x_v on the surface to its domain triangle's there —
//   is above `star_spread` (largest first, in rounds of vertices no two of them neighbours: their
//   stars share no patch and no moved curve, tried at once):
//       S <- v's domain triangles around v, their angles at v scaled to a full turn, the rim's
//            vertices w_i on a circle (a convex polygon; none scaled to above max_quad_angle)
//       U <- the union of v's patches, cut out with the rim's curves and the spokes (the curves
//            from v); each patch onto its triangle of S by eq. 2 (rim and spokes by chord length:
//            one-to-one), then Newton steps on Σ_f A_f m_f^p with the spokes' vertices free, the
//            rim's sliding along S's sides, x_v and the w_i kept
//       the new spoke to w_i <- the preimage of the segment from v's image to w_i's, as for AC
//       U cut out again with the rim's curves alone and cut along the new spokes; its patches
//            mapped and scored; all kept when every one is certified, their worst face is no worse
//            than before or than `poor`, their image area above `tail` smaller and above `poor` no
//            larger, and T′ within `thorough_growth` — a union moves one curve between two fixed
//            ones; where a corner's angle is split far from D's proportions across several patches
//            (the knot's: 4° to 157° on the surface against 24° to 100° in D), the star's map moves
//            all the curves there at once
//   finally the whole network is embedded into T once (partition/embed.hpp: the unmoved curves
//   exactly as they were, (1) and (2) checked again) and the patches cut
// What it gives up: the curves are no longer Γ(x_j, x_k) (spec/cli.md CLI-RUN-9); report.json says how many moved.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <vector>

#include <fhr/core/executor.hpp>
#include <fhr/core/trimesh.hpp>
#include <fhr/param/patch_map.hpp>
#include <fhr/partition/partition.hpp>

namespace fhr::pipeline {

struct StraightenOptions {
    int sweeps = 2;    ///< rounds over the curves of the patches still poor
    double poor = 10;  ///< a patch whose worst face's σ₁/σ₂ exceeds this is poor
    /// While more than `tail_share` of the map's image area has faces above σ₁/σ₂ = `tail`, or
    /// more than `poor_share` above `poor` (the goals of the 99th and 99.9th percentiles missed,
    /// spec/distortion.md), a patch with a face above `tail` is poor.
    double tail = 3;
    double tail_share = 0.01;
    double poor_share = 0.001;
    double l2_slack = 0;               ///< see the pseudocode
    double max_quad_angle = 170;       ///< degrees: the largest angle of Q at A or C laid flat
    param::PatchMapOptions weights{};  ///< the union's map (eq. 2)
    int newton_steps = 50;             ///< the union's nearer conformal map: Newton steps at most
    double power = 2;                  ///< p of those steps' energy Σ_f A_f m_f^p (param/detail/mips.hpp)
    /// Thorough sweeps (see the pseudocode) while a percentile goal is missed, this many instead of
    /// `sweeps`.
    bool thorough = false;
    int thorough_sweeps = 4;
    /// A thorough sweep keeps no move that takes T′ to more than this fraction above its faces
    /// before the moves, or above `growth_from` faces when that is not 0 (curves that moved
    /// before, counted from T′ before those moves).
    double thorough_growth = 0.2;
    std::size_t growth_from = 0;
    /// Before the thorough sweeps, the stars of D's vertices whose corner spread (the largest over
    /// the least ratio of a patch's angle there on the surface to its domain triangle's) is above
    /// `star_spread` are moved, each at once (see the pseudocode).
    bool stars = false;
    double star_spread = 1.5;
};

/// How good a patch's map is: its worst face's σ₁/σ₂ (the map from the face's image in the
/// domain triangle, laid flat, onto the face) and Σ_f A_f (σ₁² + σ₂²) / 2 over its faces
/// (A_f the area of the face's image), the L2 stretch's numerator before its normalisation
/// (a factor the same for every map of the mesh onto D).
struct PatchScore {
    bool certified = false;
    double worst = 0;
    double l2_energy = 0;
    double image_area = 0;  ///< Σ_f A_f
    double above_tail = 0;  ///< Σ_f A_f over the faces above StraightenOptions::tail
    double above_poor = 0;  ///< Σ_f A_f over the faces above StraightenOptions::poor
    std::size_t faces = 0;  ///< the patch's triangles
};

/// The score of map ψ of `disk` onto the triangle with corners `triangle` (3-D), `options`'s
/// thresholds counted; with `faces`, each triangle's {σ₁/σ₂, image area} appended to it.
PatchScore score(const Disk& disk, const param::PatchMap& psi, const std::array<Vec3, 3>& triangle,
                 const StraightenOptions& options = {}, std::vector<std::array<double, 2>>* faces = nullptr);

/// Whether the map of these scores misses a percentile goal: more than `tail_share` of its image
/// area above σ₁/σ₂ = `tail`, or more than `poor_share` above `poor` (spec/distortion.md's 99th
/// and 99.9th percentiles). Where it does, the curves of patches above `tail` move, and the
/// sliding sweeps longer (pipeline/detail/slide.hpp).
bool goals_missed(const std::vector<PatchScore>& scores, const StraightenOptions& options = {});

/// The caller's §4 for the patch of D's face d, scored.
using Evaluate = std::function<PatchScore(FaceId d, Disk disk)>;

/// Moves the curves of `P`'s interior domain edges as above; P.network, P.patches, P.paths (the
/// moved ones' points and lengths) and P.curves (their kind: straightened) follow. `scores` holds
/// each patch's score now (#F(D)) and is kept up to date. Returns the number of curves moved.
/// \pre P is partition()'s result for T, its network satisfying (1) and (2).
std::size_t straighten(const TriMesh& T, partition::Partition& P, Executor& executor, std::vector<PatchScore>& scores,
                       const Evaluate& evaluate, const StraightenOptions& options = {});

}  // namespace fhr::pipeline
