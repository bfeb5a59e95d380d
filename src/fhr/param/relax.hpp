// Beyond the paper (§4) — the patch map relaxed: ψ_i's interior images moved towards less
// anisotropy, the boundary (corners and chord-length sides, the paper's) kept, every image
// triangle kept positively oriented. The paper's convex-combination map is one-to-one
// (Proposition 1) but not the least distorted: a patch whose corner angles differ from its domain
// triangle's crowds its images there (paper_notes/distortion_causes.md). Relaxing gives up the
// convex-combination equation (MAP-6) and linear precision (Proposition 2), not chord length
// (PARAM-10) nor the certificate.
//
// Pseudocode (J_f: the map from face f, laid flat and scaled so that the patch's area is its
// triangle's, onto its image in the triangle laid flat; m_f = ‖J_f‖² / det J_f = σ₁/σ₂ + σ₂/σ₁):
//   u <- ψ_i in T_i laid flat (true shape);  fixed: the boundary loop
//   if Σ_f A_f (‖J_f‖² + ‖J_f⁻¹‖²) ≤ 4 (1 + threshold) Σ_f A_f and max_f σ₁/σ₂ ≤ worst: stop
//       (near an isometry already)
//   repeat up to `iterations` times:
//       u* <- argmin Σ_f A_f ((a − d)² + (b + c)²), J_f = [[a, b], [c, d]]    (least squares
//             conformal, Lévy et al. 2002, with the boundary fixed: one sparse SPD solve)
//       t <- min(1, 0.9 · the least t > 0 at which a face of u + t (u* − u) degenerates)
//       keep u + t (u* − u) only if Σ_f A_img(f) σ₁/σ₂ falls and neither max_f σ₁/σ₂ nor the
//             patch's share of the L2 stretch grows; else stop
//   up to `sweeps` sweeps over the interior vertices, one at a time: its image moved by a damped
//       Newton step lowering Σ_{f ∋ v} A_f m_f^p (param/detail/mips.hpp: convex in the
//       vertex's image, infinite where a face turns over), no face taken above the worst of its
//       ring or σ₁/σ₂ = 2; until a sweep lowers Σ_f A_f m_f by less than a millionth; the sweeps
//       kept only when Σ_f A_f m_f (the patch's share of the L2 stretch) fell. A face whose image
//       is a sliver while the surface's is not (the only kind the LSCM steps, which weigh it by
//       its tiny area, leave) has a huge m_f: the sweeps open it up
//   β of u in the triangle, on the 2^-53 grid (β0 = 1 − β1 − β2 exactly, MAP-5)
// The caller certifies the result and keeps the paper's map when it fails (pipeline.cpp).
#pragma once

#include <array>
#include <optional>

#include <fhr/core/geometry.hpp>
#include <fhr/param/disk.hpp>
#include <fhr/param/patch_map.hpp>

namespace fhr::param {

struct RelaxOptions {
    int iterations = 8;  ///< steps towards the conformal images at most
    int sweeps = 30;     ///< sweeps of the vertices' MIPS steps at most
    /// Relax only a patch whose energy per unit area exceeds the isometry's (4) by this fraction, or
    /// that has a face more anisotropic than `worst`: most patches are already near their optimum,
    /// and relaxing them costs time for nothing; a sliver's share of the energy is its tiny area's.
    double threshold = 0.02;
    double worst = 10;
    double power = 2;  ///< p of the sweeps' energy Σ_f A_f m_f^p (param/detail/mips.hpp)
};

/// ψ_i relaxed, starting from the paper's map `start` of `disk` (one-to-one: certified);
/// `domain_triangle` is T_i's corners in 3-D (its true shape). The boundary's β are start's, bit
/// for bit. Nothing when the patch is below the threshold or no step lowers its energy.
/// \pre start.beta.size() == disk.positions.size(); every image triangle of start positively
///      oriented.
std::optional<PatchMap> relax(const Disk& disk, const PatchMap& start, const std::array<Vec3, 3>& domain_triangle,
                              const RelaxOptions& options = {});

}  // namespace fhr::param
