// FHR §4 — φ_i = ψ_i⁻¹ on one patch: point location in the image triangulation ψ_i(T_i) and
// linear interpolation of the 3-D positions (paper §4: ψ_i is linear on each triangle, eq. 2,
// so φ_i is linear on each image triangle).
//
//   build:  a uniform G×G grid over the reference square [0,1]², G = ⌈√#T⌉; every image
//           triangle is listed in the cells its bounding box meets (compressed rows)
//   φ(β):   if some β_{c+2} = 0 the point lies on side c: binary search of the side's boundary
//           vertices by the chord-length parameter measured from the side's canonical end, and
//           interpolation along that boundary edge (the paper's chord-length placement, inverted);
//           else the triangle of β's grid cell that contains (β1, β2) by exact orient2d, and
//           φ = Σ w_i x_i with w the barycentric coordinates of (β1, β2) in the image triangle
// Points on a side give bit-identical 3-D points from both patches that share the side (MAP-11),
// and ψ(u) of a boundary vertex gives u's position exactly.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <fhr/param/disk.hpp>
#include <fhr/param/patch_map.hpp>

namespace fhr::param {

/// φ_i of one certified patch, for many queries: O(1) expected triangle tests per query for
/// triangles of bounded aspect (G² ≈ #T cells). Keeps its own copy of what it needs.
class PatchLocator {
public:
    /// \pre certify(disk, psi).passed (the images tile the triangle; not checked here).
    PatchLocator(const Disk& disk, const PatchMap& psi);

    /// An image triangle holding a point and the point's barycentric coordinates in it (the
    /// weights of the triangle's vertices in Disk::triangles order, summing to 1 up to rounding).
    struct Location {
        std::uint32_t triangle;
        std::array<double, 3> weights;
    };

    /// The image triangle holding the domain point with barycentric coordinates β.
    /// \pre β finite, each component ≥ −1e-12 (components below 0 count as 0; a component equal
    ///      to 0 puts the point on the opposite side), β0 + β1 + β2 = 1 up to rounding.
    /// \throws InvalidInput for β outside the triangle by more than 1e-12.
    Location locate(const std::array<double, 3>& beta) const;

    /// φ_i(β): the point of the patch S_i that ψ_i maps to β. Same precondition as locate.
    Vec3 phi(const std::array<double, 3>& beta) const;

private:
    /// A boundary edge [u_p, u_{p+1}] of a side, u_p nearer the canonical end: its triangle and
    /// the places (0..2) of u_p and u_{p+1} in it.
    struct Segment {
        std::uint32_t triangle;
        unsigned near_place, far_place;
    };
    struct Side {
        unsigned far_slot;              ///< the β component that is the parameter τ (the far corner's)
        std::vector<double> tau;        ///< τ of u_1..u_r from the canonical end: 0, increasing, 1
        std::vector<Segment> segments;  ///< r − 1
    };
    Location on_side(unsigned c, double tau) const;
    Location in_interior(double x, double y) const;

    std::vector<Vec3> positions_;
    std::vector<std::array<std::uint32_t, 3>> triangles_;
    std::vector<std::array<double, 2>> image_;  ///< (β1, β2) of each vertex
    std::array<Side, 3> sides_;
    std::size_t grid_ = 1;                   ///< G
    std::vector<std::uint32_t> cell_start_;  ///< G² + 1
    std::vector<std::uint32_t> cell_triangles_;
};

}  // namespace fhr::param
