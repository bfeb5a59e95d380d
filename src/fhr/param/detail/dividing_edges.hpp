// FHR §4 Proposition 1 — dividing edges (Floater 2003, "One-to-one piecewise linear mappings over
// triangulations", Math. Comp. 72, Theorem 6.1).
//
// Theorem 6.1: a convex combination map of a triangulated disk whose boundary maps
// homeomorphically onto the boundary of a convex polygon is one-to-one iff no dividing edge (an
// interior edge whose two ends are boundary vertices) maps into the polygon's boundary. Under
// chord-length boundary mapping (MAP-5), an interior edge maps into the triangle's boundary
// exactly when its two ends lie on the same side. The paper's proof of Proposition 1 argues that
// geodesic patches have no such edge; floating-point geodesics and coarse meshes can produce one,
// so we split every such edge before solving:
//
//   for each interior edge [a, b] with a, b on a common side (in triangle order):
//       m <- new vertex at (p_a + p_b)/2      (on the edge, so Ω_{T′} is unchanged)
//       (a, b, c) -> (a, m, c), (m, b, c);  (b, a, d) -> (b, m, d), (m, a, d)
//
// m is interior and its new edges have an interior end, so one pass removes every dividing edge
// of this kind; a triangle with all three vertices on one side (which no non-degenerate map can
// have) has at least one interior edge joining two of them, hence is split, and every piece
// contains an interior vertex.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <fhr/param/disk.hpp>

namespace fhr::param {

/// Splits every interior edge of `disk` whose two ends lie on a common side at its midpoint.
/// \pre validate(disk) passes.
/// \post (MAP-4) validate(disk) passes; no interior edge joins two vertices of a common side; the
///       boundary, the corners, the old vertices (indices and positions) are unchanged; the new
///       vertices are appended, one per split edge, at its midpoint; each split triangle is
///       replaced in place by its first half and its second half is appended, with the same
///       orientation; the surface (union of the triangles) is unchanged. Deterministic. With
///       `origin`, it holds for every triangle after the splits the triangle before them that holds it.
/// \return the number of edges split.
std::size_t split_dividing_edges(Disk& disk, std::vector<std::uint32_t>* origin = nullptr);

}  // namespace fhr::param
