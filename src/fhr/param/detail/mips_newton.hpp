// Beyond the paper (§4) — Newton's method on the MIPS energy Σ_f A_f m_f^p of a whole map at once
// (param/detail/mips.hpp for m_f and the exponent p), the images' variables coupled through every face. One vertex
// at a time (mips.hpp's step) settles slowly where a whole region must bend, as at a corner whose
// angle on the surface is far from its angle in the domain: a Newton step moves every vertex.
//
// Each face's Hessian (in its Jacobian's four entries) has its negative eigenvalues set to 0 before
// it is assembled (projected Newton, Teran et al. 2005), so that the sparse system is positive
// semidefinite; a tiny multiple of its mean diagonal is added to make it definite. A variable moves
// one or two vertices' images along fixed directions (a vertex's image in its plane: two
// variables; a vertex of a curve along its domain edge, seen from each patch beside it: one).
//
// Pseudocode (for p > 2, first the steps at p = 2, then 4, … up to p, each exponent's result the
// next one's start: far from its minimum, m^p's quadratic model is poor — from a warped map of a
// flat patch, p = 8 alone stalls with faces at σ₁/σ₂ ≈ 45 whose steps would raise the worst face):
//   repeat up to `steps` times:
//       d <- −H⁻¹ ∇E                   (H the projected Hessian, assembled sparse, LDLᵀ)
//       t <- min(1, 0.9 · the least t > 0 at which a face of u + t·du degenerates)
//       halve t until E(u + t·du) ≤ E(u) + 10⁻⁴ t ∇E·d and no face's m_f is above the ceiling
//           (none found in 30 halvings: stop, u unchanged)
//       stop when E fell by less than `settled` of it
#pragma once

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include <fhr/core/geometry.hpp>
#include <fhr/param/detail/mips.hpp>

namespace fhr::param::detail {

/// A variable's effect on a vertex's image: u += direction · x[variable].
struct Lift {
    std::int64_t variable = -1;  ///< −1: none
    Vec2 direction = Vec2::Zero();
};

/// A map of triangles, laid flat one by one, onto their images in a plane.
struct MipsProblem {
    std::vector<Vec2> uv;                                 ///< the images, moved in place
    std::vector<std::array<std::uint32_t, 3>> triangles;  ///< into uv
    std::vector<Eigen::Matrix<double, 3, 2>> gradients;   ///< per face: its corners' hat gradients, laid flat
    std::vector<double> areas;                            ///< per face: its area on the surface
    std::vector<std::array<Lift, 2>> lifts;               ///< per vertex: the variables that move it
    std::int64_t variables = 0;
    double power = 2;  ///< p of the energy Σ_f A_f m_f^p
};

/// Triangle (p0, p1, p2) laid flat in its own plane: p0 at the origin, p1 along x, p2 above.
std::array<Vec2, 3> lay_flat(const Vec3& p0, const Vec3& p1, const Vec3& p2);

/// Triangle (p0, p1, p2) laid flat in its own plane and scaled by `scale`: its corners' hat
/// gradients, and its area unscaled.
std::pair<Eigen::Matrix<double, 3, 2>, double> hat_gradients(const Vec3& p0, const Vec3& p1, const Vec3& p2,
                                                             double scale = 1);

/// `triangles` of a surface with vertices at `positions` as `problem`'s faces: each laid flat, its
/// hat gradients and area.
void set_faces(MipsProblem& problem, const std::vector<Vec3>& positions,
               const std::vector<std::array<std::uint32_t, 3>>& triangles);

/// The least t > 0 at which triangle t of uv + t·du has zero signed area (a quadratic in t), or
/// infinity.
double first_degenerate(const std::vector<Vec2>& uv, const std::vector<Vec2>& du,
                        const std::array<std::uint32_t, 3>& t);

/// Σ_f A_f m_f^p and the largest m_f (both infinite when a face is not positively oriented).
std::array<double, 2> mips_total(const MipsProblem& problem);

/// Up to `steps` Newton steps on `problem` as above, never taking a face's m_f above `ceiling`
/// or the largest m_f at the start, whichever is larger. \pre every face positively oriented.
void mips_newton(MipsProblem& problem, int steps, double settled, double ceiling);

}  // namespace fhr::param::detail
