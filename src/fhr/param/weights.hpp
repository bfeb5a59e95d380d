// FHR §4 — the convex-combination weights λ_vw of an interior vertex (paper §4: "the weights
// λ_vw are strictly positive and sum to one"; the paper takes Floater's shape-preserving
// weights [6] = Floater 1997, "Parametrization and smooth approximation of surface
// triangulations", CAGD 14, §4).
//
// Shape-preserving (Floater 1997), for p with neighbours p_1..p_d in cyclic order:
//   r_k = |p_k − p|, θ_k = ∠(p_k − p, p_{k+1} − p) (3-D angles), Θ = Σ θ_k
//   geodesic polar map: q_k = r_k (cos φ_k, sin φ_k), φ_1 = 0, φ_{k+1} = φ_k + 2π θ_k / Θ
//   for each k: the ray from q_k through the origin leaves the polygon through a segment
//     [q_l, q_{l+1}]; the origin then lies in the triangle (q_k, q_l, q_{l+1}); add its
//     barycentric coordinates there to μ_k, μ_l, μ_{l+1}
//   λ_k = μ_k / d
// Mean-value (Floater 2003, "Mean value coordinates", CAGD 20, eq. 3.1):
//   w_k = (tan(θ_{k−1}/2) + tan(θ_k/2)) / r_k,  λ_k = w_k / Σ w
// Uniform (Tutte 1963): λ_k = 1/d.
// The choices for degenerate and sharp rings are in paper_notes/parameterization.md.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include <fhr/core/polygon_soup.hpp>

namespace fhr::param {

enum class Weights { shape_preserving, mean_value, uniform };

/// "shape-preserving", "mean-value" or "uniform".
std::string_view name(Weights kind);

/// The inverse of name(). \throws InvalidInput(...) naming the accepted names.
Weights parse_weights(std::string_view text);

/// The weights λ_{p p_k} of an interior vertex p over its 1-ring p_1..p_d, in the ring's order
/// (either orientation gives the same weights).
/// \param vertex  the vertex's index, named in error messages
/// \pre ring is the cyclic sequence of p's neighbours in a triangulated disk.
/// \post (MAP-2) d weights, each finite and > 0, summing to 1 within 2·d·ε (ε = 2^-52: after
///       the final division by the sum, each of the d − 1 additions of the check and the
///       division round once, relative to a sum of 1). For shape-preserving and mean-value
///       weights on a planar ring, Σ λ_k p_k = p (linear reproduction, MAP-3).
/// \throws InvalidInput when d < 3 (impossible at an interior vertex of a simplicial disk);
///         NumericalFailure naming `vertex` and listing the weights when one is not finite and
///         positive: only at degenerate rings, where no such weights exist (a neighbour at p's
///         position; for shape-preserving and mean-value weights, a flat ring with p on a
///         segment [p_k, p_{k+1}], i.e. a straight angle at p).
std::vector<double> one_ring_weights(Weights kind, const Vec3& p, std::span<const Vec3> ring, std::uint32_t vertex);

}  // namespace fhr::param
