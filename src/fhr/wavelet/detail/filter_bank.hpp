// FHR §5 — the filter bank (Floater, Quak & Reimers 2000, "Filter bank algorithms for piecewise
// linear prewavelets on arbitrary triangulations", J. Comput. Appl. Math. 119; paper §5
// reference [9]) for S^j = S^{j−1} ⊕ W^{j−1} (paper eq. 3), adapted to manifolds, closed (the
// paper) or with boundary and several components (beyond the paper).
//
// Coefficients: f^j = Σ_w c^j_w φ^j_w (c^j a #V(D^j)×3 array: x, y, z together), its coarse part
// Σ_v c^{j−1}_v φ^{j−1}_v and its detail Σ_u d^{j−1}_u ψ_u, one d per new vertex u of D^j. With
// P = [I; P_N] (refinement_matrix) and Q = [Q_O; Q_N] (the prewavelets, rows old | new vertices):
//
//   reconstruction (explicit):  c^j = P c^{j−1} + Q d^{j−1}
//   decomposition:               A d^{j−1} = c^j_N − P_N c^j_O,   A = Q_N − P_N Q_O   (m × m)
//                                c^{j−1} = c^j_O − Q_O d^{j−1}
// (the new rows of c^j = P c^{j−1} + Q d^{j−1} after eliminating c^{j−1} through its old rows).
// Theorem (paper_notes/wavelets.md): A = s Σ_v E_v B_v E_vᵀ, E_v picking the new vertices around
// coarse vertex v, with t_v coarse triangles at v and B_v = 6/(7t_v) 𝟙𝟙ᵀ + C_{t_v}⁻¹ inside,
// 6/(7t_v) 𝟙𝟙ᵀ + T_{t_v}⁻¹ on the boundary (prewavelet.hpp): symmetric, with spectrum in
// [2s/7, 2s] on a closed D and in [2s/7, 4s] with boundary, so κ(A) ≤ 7 (closed) or ≤ 14
// whatever the valences (WAV-5, WAV-13). We solve it by conjugate gradients with a Jacobi
// preconditioner; the round trip's error at the new vertices is exactly the solve's residual
// (the old rows cancel identically), so CG stops on the true residual, in the max norm:
//   ‖A d − b‖_∞ ≤ τ_j = 1e−14 ‖c^j‖_∞,
// and reconstruct(decompose(f)) differs from f by at most Σ_j τ_j plus rounding (P has max-norm
// 1, so earlier errors do not grow): J·1e−14·max_j ‖c^j‖_∞, below 1e−12·‖f‖_∞ for every J the
// size limit allows (J ≤ 12) while the coarse coefficients stay within 8‖f‖_∞ (they are
// orthogonal projections, local weighted averages of f; WAV-4 tests the 1e−12). The true residual cannot be computed more accurately than its
// rounding floor, measured at ≤ 4e−16 ‖b‖_∞ ≤ 8e−16 ‖c^j‖_∞ (|b| ≤ 2‖c^j‖_∞): τ_j lies 12× above
// it. CG's error after k steps is ≤ 2((√κ − 1)/(√κ + 1))^k of the start; with κ ≤ 7 (≈ 6
// measured) and the 2-norm to max-norm factor √m ≤ 10^4, about 65 steps reach τ_j (about 80 for
// κ ≤ 14 with boundary); 31 are measured on the fandisk at every level. More than
// max_cg_iterations means something is broken: NumericalFailure.
#pragma once

#include <span>
#include <vector>

#include <fhr/wavelet/detail/prewavelet.hpp>
#include <fhr/wavelet/refine.hpp>

namespace fhr::wavelet {

/// The operators between D^{j−1} and D^j.
struct LevelFilter {
    int j = 0;                         ///< the fine level
    std::uint32_t n_coarse = 0;        ///< #V(D^{j−1}); new vertex u = n_coarse + k, k an edge of D^{j−1}
    SparseRows P;                      ///< #V(D^j) × #V(D^{j−1})
    SparseRows Q;                      ///< #V(D^j) × m: column k is ψ_{n_coarse + k}, scale 2^{j−1}
    SparseRows A;                      ///< m × m: Q_N − P_N Q_O
    Eigen::VectorXd inverse_diagonal;  ///< m: 1 / A_kk (Jacobi preconditioner)
    std::vector<double> norm;          ///< m: ‖ψ_u‖ = ⟨ψ_u, ψ_u⟩^½ in the paper's inner product
    std::size_t m() const { return norm.size(); }
};

/// How the decomposition's system went at one level.
struct LevelSolve {
    int iterations = 0;    ///< CG steps, the largest of the three coordinates
    double residual = 0;   ///< ‖A d − b‖_∞ (true residual) over the three coordinates
    double tolerance = 0;  ///< τ_j
};

/// f^J = f^0 + g^0 + … + g^{J−1} (paper §5) as coefficients.
struct Decomposition {
    std::vector<Vec3> coarse;               ///< c^0: #V(D^0)
    std::vector<std::vector<Vec3>> detail;  ///< detail[j] = d^j for j = 0..J−1: #V(D^{j+1}) − #V(D^j)
    std::vector<LevelSolve> solves;         ///< solves[j]: the system for d^j
    std::size_t coefficient_count() const;  ///< Σ_j #detail[j] = #V(D^J) − #V(D)
};

inline constexpr int max_cg_iterations = 200;
/// τ_j / ‖c^j‖_∞ (file header).
inline constexpr double cg_relative_tolerance = 1e-14;

class FilterBank {
public:
    /// Builds P, Q, A and the norms for every level of r, the levels as tasks on `executor`
    /// (default_executor() when null; the same bank on any number of threads).
    /// \pre r = refine(D, J) (D closed or with boundary, one component or several).
    explicit FilterBank(const Refinement& r, Executor* executor = nullptr);

    int depth() const { return static_cast<int>(levels_.size()); }  ///< J
    /// \pre 1 ≤ j ≤ depth().
    const LevelFilter& level(int j) const { return levels_[static_cast<std::size_t>(j - 1)]; }

    /// c^J → (c^0, d^0, …, d^{J−1}), level by level down to D; each level's three coordinates
    /// solved as tasks on `executor` (default_executor() when null; the same result on any number
    /// of threads).
    /// \pre f.size() == #V(D^J), every component finite.
    /// \throws NumericalFailure when CG does not reach τ_j within max_cg_iterations.
    Decomposition decompose(std::span<const Vec3> f, Executor* executor = nullptr) const;

    /// One level: c^j → (c^{j−1}, d^{j−1}). \pre 1 ≤ j ≤ depth(), c.size() == #V(D^j).
    LevelSolve decompose_level(int j, std::span<const Vec3> c, std::vector<Vec3>& coarse, std::vector<Vec3>& detail,
                               Executor* executor = nullptr) const;

    /// c^J = P(…P(P c^0 + Q d^0)…) + Q d^{J−1}, explicit. Each level's rows in blocks on
    /// `executor` (default_executor() when null): the same result on any number of threads.
    /// \pre d has the sizes decompose gives for this bank.
    std::vector<Vec3> reconstruct(const Decomposition& d, Executor* executor = nullptr) const;

    /// One level: c^j = P c^{j−1} + Q d^{j−1}, as reconstruct.
    std::vector<Vec3> reconstruct_level(int j, std::span<const Vec3> coarse, std::span<const Vec3> detail,
                                        Executor* executor = nullptr) const;

private:
    std::vector<LevelFilter> levels_;
};

}  // namespace fhr::wavelet
