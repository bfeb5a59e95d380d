// Beyond the paper (§4) — the curves' vertices slid along their domain edges. The paper maps each
// curve onto its domain edge by chord length (eq. 3), the same from both patches beside it, so
// that ψ is continuous; but near a corner whose angle on the surface differs from its angle in D,
// or along a curve that the surface stretches unevenly, no map with that boundary is near a
// similarity: the faces there stay anisotropic whatever the interior does
// (paper_notes/distortion_causes.md, cause 5). A vertex of a curve may move along its domain edge,
// if it moves the same in both patches: ψ stays continuous and one-to-one, only chord length
// (PARAM-10) is given up.
//
// Pseudocode (the patches laid flat in their triangles' true shapes, as the relaxation does):
//   active <- the patches whose map is far from conformal: Σ_f A_f m_f > 2 (1 + threshold) Σ_f A_f,
//             or a face with σ₁/σ₂ > worst (m_f = σ₁/σ₂ + σ₂/σ₁, param/detail/mips.hpp)
//   moving <- the active patches and their neighbours across D's edges
//   sliding <- every vertex of a curve beside an active patch, but its ends: its parameter s along
//              D's halfedge (e, 0), the same in both patches (1 − s from the other end)
//   where the map misses a percentile goal: first Newton steps on Σ_f A_f m_f^p over all the moving
//       images and parameters s at once (param/detail/mips_newton.hpp, the same ceiling), then s
//       read back from the images — the sweeps alone settle slowly where a whole patch must bend
//   sweeps until one lowers Σ_f A_f m_f over the moving patches by less than `settled` of it (more
//   and finer where the map misses a percentile goal, `sweeps_missed`):
//       each interior vertex of a moving patch: a MIPS step in its patch
//       each sliding vertex: a MIPS step of s over its faces in both patches
//   β of the interior on the 2^-53 grid (MAP-5), a sliding vertex's β (1 − s, s) on D's edge with
//   s on it, so that both patches hold the same two numbers (MAP-11's canonical direction,
//   PARAM-7); a face whose image is then turned over (exact orient2d; the grid can turn a sliver
//   of T′ whose image was made as thin) sends its moved vertices back to where they started, with
//   their β, and the faces around them are looked at again (each vertex goes back once at most)
//   kept only when Σ_f A_f m_f (the L2 stretch's numerator) fell
// The caller certifies every changed patch and keeps the maps as they were when one fails.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include <fhr/core/executor.hpp>
#include <fhr/core/ids.hpp>
#include <fhr/core/trimesh.hpp>
#include <fhr/param/patch_map.hpp>
#include <fhr/partition/patches.hpp>

namespace fhr::pipeline {

struct SlideOptions {
    int sweeps = 20;        ///< sweeps at most
    double settled = 1e-4;  ///< a sweep that lowers the energy by less than this fraction is the last
    /// Where the map misses a percentile goal (pipeline/detail/straighten.hpp's goals_missed),
    /// Gauss–Seidel's slow convergence is worth more sweeps: these instead, when `missed`.
    int sweeps_missed = 200;
    double settled_missed = 1e-7;
    bool missed = false;
    int newton_steps = 50;   ///< Newton steps on all the moving images at once first, when `missed`
    double threshold = 0.1;  ///< see `active` in the pseudocode
    double worst = 10;       ///< see `active` in the pseudocode
    double power = 2;        ///< p of the steps' energy Σ_f A_f m_f^p (param/detail/mips.hpp)
    /// Each face's A_f weighed by its share of its patch's image area over its share of the patch's
    /// surface area (within [0.1, 10]), taken when the sliding starts: the percentiles of
    /// spec/distortion.md weigh faces by image area (pipeline::Options::image_weighted_sliding).
    bool image_weighted = false;
};

/// The maps of the patches (disks[d] split, maps[d] certified, patches.patch[d].vertices naming
/// the disk's first vertices in T′) with their curves' vertices slid as above: the new maps of the
/// patches that moved (none: nothing was better), not yet certified.
/// \pre every map certified; D is the partition's domain.
std::vector<std::pair<DFaceId, param::PatchMap>> slide(const TriMesh& D, const partition::Patches& patches,
                                                       const IdVector<DFaceId, param::Disk>& disks,
                                                       const IdVector<DFaceId, param::PatchMap>& maps,
                                                       Executor& executor, const SlideOptions& options = {});

}  // namespace fhr::pipeline
