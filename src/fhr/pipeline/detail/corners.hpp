// Beyond the paper (§4) — T refined around the vertices of D. Where a patch's angle at its corner
// x_j on the surface is far from its domain triangle's angle there, a map near a conformal one
// turns the faces around x_j by the ratio of the two angles (a power map, z ↦ z^λ), and the faces
// of T′ at x_j are too few and too large to follow it: their images stay anisotropic and hold a
// share of the tail (paper_notes/distortion_causes.md, cause 5). Cutting those faces near x_j puts
// the anisotropic ring into a fraction of the area, and the faces around it can turn step by step.
//
// Pseudocode (T* = T refined, `cut` in (0, 1)):
//   for each interior edge [x, a] of T with x a vertex of D, a not, and both its faces holding no
//       other vertex of D: its cut s = x + cut (a − x), a vertex of T* on that edge
//   each face [x, a, b] of T with one vertex x of D: its cuts s_a on [x, a], s_b on [x, b] split it
//       into [x, s_a, s_b], [s_a, a, b], [s_a, b, s_b] (one cut: two faces; none: the face itself);
//       every other face of T as it is
//   D on T*: D itself, its history led by the collapses of each cut s into its x (corner by
//       corner, in the order the cuts were made): undoing all of it gives T*, face for face, so
//       §3's keeping of D (partition/detail/keep.hpp) steps back along it as along D's own
// T's vertices keep their ids and coordinates (bit for bit), the cuts come after them; T* is T's
// surface (a cut lies on its edge up to rounding), so the map of T* is a map of T: each face of T*
// knows the face of T it lies in.
#pragma once

#include <optional>
#include <vector>

#include <fhr/core/ids.hpp>
#include <fhr/core/trimesh.hpp>
#include <fhr/domain/domain.hpp>

namespace fhr::pipeline {

/// Where along an edge from its vertex of D the edge is cut, by the elk, the pinion and the anchor
/// (paper_notes/distortion_causes.md, "T refined at D's vertices").
inline constexpr double corner_cut = 0.3;

struct CornerRefinement {
    TriMesh mesh;                 ///< T*: T's vertices first, with their ids, then the cuts
    domain::Domain domain;        ///< D on T*: D's mesh and vertices, the history as above
    std::vector<TFaceId> parent;  ///< per face of T*: the face of T that holds it
};

/// T refined at D's vertices as above; nothing when no edge is cut, when D's history does not
/// describe it (domain::history_describes: §3's keeping would then not find D's decimation), or when
/// it was decimated by cells (decimate.hpp: their collapses come first in its history).
/// \pre D's vertices are vertices of T.
std::optional<CornerRefinement> refine_corners(const TriMesh& T, const domain::Domain& D, double cut = corner_cut);

}  // namespace fhr::pipeline
