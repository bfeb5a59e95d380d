// FHR §3/§4 — one patch S_i of T′: the triangulated topological disk that ψ_i maps onto its
// domain triangle T_i = [v_j, v_k, v_l] (paper §4, eq. 2).
//
// §3 hands §4 one disk per triangle of D. Its boundary is the union of the three geodesic curves
// Γ(x_j, x_k), Γ(x_k, x_l), Γ(x_l, x_j), which meet at the corner vertices x_j, x_k, x_l. Here the
// disk is self-contained (local vertex numbering), so §4 can be built and verified without §3.
//
// Sides: side c (c = 0, 1, 2) is the boundary arc from corner c to corner c+1 (mod 3), the image
// of the domain triangle's edge [e_c, e_{c+1}]; a corner belongs to both sides that meet at it.
// The contract is spec/patch_map.md (MAP-1..).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <fhr/core/disk.hpp>
#include <fhr/core/violation.hpp>

namespace fhr::param {

/// The patch as §3 hands it over (core/disk.hpp).
using Disk = fhr::Disk;

/// The first broken rule of MAP-1 (spec/patch_map.md) for `disk` — which element, which one, what
/// is wrong — or nullopt when it is a valid patch: indices in range, no triangle repeating a vertex, every vertex in a triangle, each
/// directed edge in one triangle and each undirected edge in at most two (traversed in opposite
/// directions), every vertex's triangles one fan, connected, Euler characteristic 1, and the
/// edges with one triangle forming exactly the loop `boundary` in its orientation, with
/// 0 == corners[0] < corners[1] < corners[2] < boundary.size().
std::optional<Violation> disk_violation(const Disk& disk);

/// \throws InvalidInput("patch: MAP-1: ...") when disk_violation(disk) finds one.
void validate(const Disk& disk);

/// Bit c (c = 0, 1, 2) of the result's entry for boundary position p is set when the boundary
/// vertex at position p lies on side c (corners lie on two sides). #boundary entries.
/// \pre disk.corners is valid (0 == corners[0] < corners[1] < corners[2] < boundary.size()).
std::vector<unsigned> boundary_sides(const Disk& disk);

}  // namespace fhr::param
