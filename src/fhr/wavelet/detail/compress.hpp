// FHR §6 (Fig. 9) — compression: "sorting the 3,591 wavelet coefficients by magnitude and using
// only the largest 5% or 20%, respectively, to reconstruct f^3".
//
// Magnitude (our normalization, paper_notes/wavelets.md): the coefficient d_u ∈ ℝ³ of ψ_u counts
// as |d_u|₂ · ‖ψ_u‖, the size of its term d_u ψ_u in the paper's inner product. The levels are
// mutually orthogonal (W^{j} ⟂ S^{j} ⊇ W^{k} for k < j), so the squared error of dropping
// coefficients is the sum over levels of the squared error within each level, and within a level
// the prewavelets form a stable (Riesz) basis: keeping the largest terms is then near-optimal in
// the paper's norm. With the scale 2^{j−1} of prewavelet.hpp, ‖ψ_u‖ depends on the valences at
// u's edge only, so this is nearly the raw |d_u| order, made independent of the valences.
//
// Pseudocode:
//   N <- all wavelet coefficients (every level); k <- ⌊p·N/100⌋ (p in percent)
//   order the coefficients by |d_u|·‖ψ_u‖ decreasing, ties by level then index (deterministic)
//   keep the first k, set the others to 0 (the coarse c^0 is always kept), reconstruct
#pragma once

#include <cstddef>
#include <vector>

#include <fhr/wavelet/detail/filter_bank.hpp>

namespace fhr::wavelet {

/// The number of coefficients kept: ⌊percent·total/100⌋ (the fandisk's 3,591 gives 179 at 5 %,
/// 718 at 20 %, and `total` at 100 %).
/// \throws InvalidInput(...) unless 0 ≤ percent ≤ 100.
std::size_t kept_count(std::size_t total, double percent);

/// The decomposition with all but the `count` largest wavelet coefficients set to zero.
/// \pre d = bank.decompose(·); count ≤ d.coefficient_count().
Decomposition keep_largest(const FilterBank& bank, const Decomposition& d, std::size_t count);

/// |d_u|·‖ψ_u‖ for every coefficient, level by level (the order of Decomposition::detail).
std::vector<double> coefficient_magnitudes(const FilterBank& bank, const Decomposition& d);

}  // namespace fhr::wavelet
