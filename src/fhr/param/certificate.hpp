// FHR §4 Proposition 1 — a certificate that ψ_i is one-to-one, checked on the computed numbers
// (paper_notes/parameterization.md; the patch part of spec/param.md PARAM-8, PARAM-9).
//
// Theorem (degree argument): if ψ maps the boundary loop of a disk monotonically and
// bijectively onto the boundary of the triangle, corners on corners, and every image triangle is
// positively oriented, then ψ is one-to-one and onto the triangle (its images tile it). Both
// conditions are checked exactly: orientation by the exact orient2d (core/predicates), the
// boundary by exact comparisons. The area sum is an independent floating-point cross-check.
//
//   for each triangle t: orient2d(ψ(a), ψ(b), ψ(c)) > 0 in the (β1, β2) plane, else flipped
//   for each side c (corner c to corner c+1) and its vertices u_1..u_r:
//       ψ(u_1) = e_c, ψ(u_r) = e_{c+1} exactly; every ψ(u_p) on the line e_c e_{c+1} (exact
//       orient2d = 0) with β_{c+2} = 0, and its parameter along the side strictly increasing
//   |Σ area(ψ(t)) − 1/2| ≤ 1e-12 · 1/2      (the reference triangle has area 1/2)
//   min over triangles of the image's smallest angle (in the given domain triangle)
#pragma once

#include <array>
#include <cstddef>
#include <optional>

#include <fhr/core/violation.hpp>
#include <fhr/param/disk.hpp>
#include <fhr/param/patch_map.hpp>

namespace fhr::param {

/// Relative tolerance of the area check: the images' areas are summed with Neumaier's
/// compensated summation, so the sum carries a few rounding errors of the largest term plus
/// each triangle's own determinant error (≈ 2ε of its area); 1e-12 leaves a margin of 10^3 over
/// ~10^5 triangles' errors of ε each and matches PARAM-8 of spec/param.md.
inline constexpr double area_tolerance = 1e-12;

/// The result of certify().
struct Certificate {
    bool passed = false;                  ///< every check below holds
    std::size_t triangles = 0;            ///< image triangles checked
    std::size_t flipped_triangles = 0;    ///< exact orient2d ≤ 0 (folded or degenerate)
    std::size_t boundary_violations = 0;  ///< boundary vertices off their side, out of order, or corners off
    double image_area = 0;                ///< Σ signed areas in the (β1, β2) plane (1/2 when one-to-one)
    double min_image_angle_degrees = 0;   ///< smallest angle of the image triangles in the domain triangle
    /// None iff passed; else the first broken check: MAP-1 (the disk, disk_violation), MAP-6 (a
    /// vertex's β), MAP-8 (the image count as a whole, a face's orientation, a boundary position,
    /// the area as a whole).
    std::optional<Violation> first_failure;
};

/// Certifies ψ of `disk` (MAP-8). Angles are measured in `domain_triangle` (the images' true
/// shapes in T_i = [v_j, v_k, v_l]).
/// \pre validate(disk) passes (checked: else the certificate fails with the MAP-1 reason);
///      psi.beta.size() == disk.positions.size() (else it fails).
Certificate certify(const Disk& disk, const PatchMap& psi, const std::array<Vec3, 3>& domain_triangle);

/// The same with angles measured in the equilateral triangle of unit sides.
Certificate certify(const Disk& disk, const PatchMap& psi);

}  // namespace fhr::param
