// FHR §4 — the piecewise linear map ψ_i: S_i → T_i of one patch (paper §4, eq. 2), the method of
// Floater 1997 that the paper uses:
//
//   corners:   ψ(x_c) = e_c                                            (c = 0, 1, 2)
//   boundary:  side c = u_1 … u_r from corner c to corner c+1 (chord length, paper §4):
//              L_p = Σ_{q<p} |u_{q+1} − u_q|,  λ_p = L_p / L_r,
//              ψ(u_p) = (1 − λ_p) e_c + λ_p e_{c+1}
//   interior:  ψ(v) = Σ_{w ∈ N_v} λ_vw ψ(w)  (one sparse linear system, two right-hand sides)
//
// ψ is expressed in barycentric coordinates β = (β0, β1, β2) of the domain triangle T_i =
// [v_j, v_k, v_l] (corner c ↦ e_c); the system is solved in the reference plane (β1, β2) with
// β0 = 1 − β1 − β2. Convex-combination maps and chord-length placement commute with affine maps,
// so this is the paper's map onto T_i composed with the affine map T_i → reference triangle.
// Proposition 1 (one-to-one) holds once split_dividing_edges has run; certify() checks it on the
// result. The decisions (canonical direction of chord length, the 2^-53 grid, solver tolerance)
// are in paper_notes/parameterization.md; the contract is spec/patch_map.md.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include <fhr/param/disk.hpp>
#include <fhr/param/weights.hpp>

namespace fhr::param {

enum class Solver { sparse_lu, bicgstab };

/// "sparse-lu" or "bicgstab".
std::string_view name(Solver solver);

/// The inverse of name(). \throws InvalidInput(...) naming the accepted names.
Solver parse_solver(std::string_view text);

struct PatchMapOptions {
    Weights weights = Weights::shape_preserving;  ///< the paper's choice
    Solver solver = Solver::sparse_lu;            ///< direct; BiCGSTAB is the paper's (§6) choice
};

/// BiCGSTAB stops when |A x − b| ≤ bicgstab_tolerance · |b|. The error of x is then at most
/// κ(A) times that; A = I − Λ is a random-walk Laplacian whose condition number grows like the
/// number of interior vertices n (≲ 10^4 in a patch of the paper's meshes), so the solutions
/// agree with the direct solver's to about 1e-10 (MAP-7, tested). Looser tolerances leave
/// folded triangles in practice (236 flips at 1e-6 on an armadillo disk, none at 1e-10;
/// paper_notes/parameterization.md).
inline constexpr double bicgstab_tolerance = 1e-14;

/// BiCGSTAB may take max(2n, this) iterations on a system of n unknowns. Eigen's default, 2n,
/// is too few for a small patch on graded input: 16 iterations on 8 unknowns stalled at 5.4e-14
/// (the pipeline fuzzer's finding, CLI-RUN-1); rounding, not the Krylov space's size, limits
/// such a solve.
inline constexpr long bicgstab_min_iterations = 1000;

/// ψ_i at every vertex of a disk.
struct PatchMap {
    /// #V: β of ψ(v) in the domain triangle, corner c ↦ e_c. Every component is a multiple of
    /// 2^-53, so the three sum to exactly 1 (MAP-5, MAP-6).
    std::vector<std::array<double, 3>> beta;
};

/// Eq. 2 in any plane, for any triangulated disk: every vertex not `fixed` gets the image
/// Σ_w λ_vw ψ(w), the convex combination of its neighbours' images with the weights of
/// options.weights at its 3-D position (uniform for the last `midpoints` vertices, MAP-4); the
/// fixed vertices keep `images`. One sparse system, two right-hand sides. map_patch() is this with
/// the chord-length boundary in the reference plane (β1, β2).
/// \pre positions.size() == fixed.size() == images.size(); every vertex not fixed is interior (its
///      triangles form one cycle around it) and joined to a fixed one through free vertices.
/// \throws NumericalFailure when weights fail (MAP-2) or the solver fails or does not converge.
void convex_combination(std::span<const Vec3> positions, std::span<const std::array<std::uint32_t, 3>> triangles,
                        std::span<const std::uint8_t> fixed, std::size_t midpoints,
                        std::vector<std::array<double, 2>>& images, const PatchMapOptions& options = {});

/// The map ψ_i of `disk` onto its triangle (paper §4).
/// \pre validate(disk) passes (checked). For Proposition 1, split_dividing_edges(disk) has run.
/// \post (MAP-5) corner c has β = e_c; a vertex on side c has β_{c+2} = 0 exactly and β_{c+1}
///       = λ_p (chord length, measured from the side's canonical end and rounded to 2^-53);
///       (MAP-6) every interior vertex satisfies ψ(v) = Σ λ_vw ψ(w) to the solver's accuracy.
/// \throws InvalidInput (MAP-1) for an invalid disk or a side of zero length; NumericalFailure
///         when weights fail (MAP-2) or the solver fails or does not converge.
PatchMap map_patch(const Disk& disk, const PatchMapOptions& options = {});

}  // namespace fhr::param
