// Beyond the paper (§4) — one vertex's image moved to lower the MIPS energy of the faces around it
// (Hormann and Greiner 2000), the step shared by the patch map's relaxation (param/relax.hpp) and
// the curves' vertices slid along their domain edges (pipeline/detail/slide.hpp).
//
// A face f with surface triangle laid flat and image triangle u_0, u_1, u_2 has the Jacobian
// J_f = Σ_k u_k g_kᵀ (g_k the gradient of corner k's hat function on the flat triangle) and
// m_f = ‖J_f‖² / det J_f = σ₁/σ₂ + σ₂/σ₁ ≥ 2 (equality: a similarity). As a function of one
// corner's image u, J_f = C + u gᵀ: ‖J_f‖² is a convex quadratic and det J_f = det C + (adj(C)ᵀ g)·u
// is affine, so m_f is a quadratic over a linear function — convex where the face is positively
// oriented and infinite at its edge (a barrier). The energy of a vertex is Σ_f A_f m_f^p over the
// faces of one or more patches (A_f the surface area; p ≥ 2 keeps it convex and weighs the
// anisotropic faces more than Σ_f A_f m_f, the L2 stretch's numerator, spec/distortion.md, whose
// steps left the worst faces of a patch far behind: on the cow, σ₁/σ₂'s 99th percentile 14 → 31
// with m_f, 14 → 8.9 with m_f²). p = 2 unless the caller asks for more: the larger p, the nearer
// the minimum comes to the map whose largest m_f is least (paper_notes/distortion_causes.md).
//
// A variable x ∈ R^K (K = 2: a vertex's image in its patch; K = 1: a curve's vertex along its
// domain edge, seen from each of its patches) moves each ring's u by u0 + M x. Newton's step on
// the sum, damped to stay 10 % short of the first face that would degenerate, halved until the
// energy falls without raising the ring's most anisotropic face above a ceiling.
#pragma once

#include <span>
#include <vector>

#include <Eigen/Dense>

namespace fhr::param::detail {

using Vec2 = Eigen::Vector2d;
using Mat2 = Eigen::Matrix2d;

/// J's singular values σ₁ ≥ σ₂ in closed form: σ₁σ₂ = |det J| and σ₁² + σ₂² = ‖J‖², so
/// σ₁ = (√(‖J‖² + 2|det J|) + √(‖J‖² − 2|det J|)) / 2 and σ₂ = |det J| / σ₁ (no cancellation
/// where J is far from a similarity); both 0 for J = 0.
Vec2 singular_values(const Mat2& j);

/// Face f's term as a function of one corner's image u.
struct MipsTerm {
    Mat2 c;           ///< J_f with that corner's part taken out
    Vec2 g;           ///< the corner's hat gradient on the flat surface triangle
    Vec2 dl;          ///< ∇ det J_f
    double l0 = 0;    ///< det C
    double area = 0;  ///< A_f
};

/// The term of a face whose Jacobian is `j` now, with the corner at `u` and hat gradient `g`.
MipsTerm mips_term(const Mat2& j, const Vec2& u, const Vec2& g, double area);

/// A face's m_f^p (p = `power` ≥ 2) as a function of the entries (J₀₀, J₀₁, J₁₀, J₁₁) of its
/// Jacobian: the value, the gradient, and the Hessian with its negative eigenvalues set to 0 (a
/// Newton step on all of a map's images at once then descends: projected Newton, Teran et al.
/// 2005). \pre det J > 0.
struct MipsFace {
    double energy = 0;
    Eigen::Vector4d gradient;
    Eigen::Matrix4d hessian;
};
MipsFace mips_face(const Mat2& j, double power = 2);

/// The faces around one vertex as seen from one patch, and how the variable moves the vertex there.
template <int K>
struct MipsRing {
    std::vector<MipsTerm> terms;
    Vec2 u0;                        ///< the vertex's image now
    Eigen::Matrix<double, 2, K> m;  ///< its image at x: u0 + m x
};

/// Σ over the rings of Σ_f A_f m_f^p (p = `power`) at the variable's value x (infinite where a
/// face is not positively oriented).
template <int K>
double mips_energy(std::span<const MipsRing<K>> rings, const Eigen::Matrix<double, K, 1>& x, double power = 2);

/// Up to `steps` damped Newton steps on Σ_f A_f m_f^p (p = `power`) from x = 0, each taken only
/// when no face's m_f ends above
/// the largest m_f at x = 0 or `cap`, whichever is larger (so the most anisotropic face of a whole
/// map never grows beyond that); the x reached (0 when no step lowers the energy).
template <int K>
Eigen::Matrix<double, K, 1> mips_descend(std::span<const MipsRing<K>> rings, int steps, double cap, double power = 2);

}  // namespace fhr::param::detail
