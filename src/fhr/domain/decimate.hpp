// FHR §2 — the parameter domain D by half-edge-collapse decimation.
//
// Paper §2: D is a coarse triangulation of the same topology as T, found by mesh decimation
// with half-edge collapses, which never move a vertex, so that every vertex v_j of D is a vertex
// x_j of T. The paper used Campagna's method and leaves the error metric and the validity rules
// open; ours are in paper_notes/domain.md.
//
// Pseudocode:
//   Q_v  <- Σ over the faces f at v of area(f) · (plane quadric of f)          (Garland–Heckbert)
//   cost(h = v0 -> v1) = (Q_v0 + Q_v1)(p_v1); queue every edge with its cheaper direction
//   while #faces > target:
//       pop the cheapest h (ties: shorter edge, then lower halfedge index)
//       if the collapse v0 -> v1 is valid (link condition; no face turns by more than
//          max_normal_deviation; no new corner below min_angle; no exactly degenerate face):
//           collapse, Q_v1 += Q_v0, record (v0, v1, va, vb), re-queue the edges near v1
//       else queue the edge's other direction, unless it was found invalid too
//   if the queue runs dry first: the target cannot be met under these rules (error)
//
// Beyond the paper, the graded rules (DOM-24, DOM-25): the normal and angle rules may start
// tighter than their limits; when the queue runs dry, the normal rule is relaxed by a step (up to
// max_normal_deviation), and once it is at its limit the angle rule is lowered by a step (down to
// min_angle) and the normal rule starts again from its first angle; every edge is queued again
// each time, so that D still has the faces asked wherever the plain rules reach them.
//
// Beyond the paper: when T has more than 2^17 faces and the target is at most a
// quarter of them, the loop above is preceded by a pass over the cells — each vertex in the cell
// of its first face, cells being blocks of 2^14 consecutive faces of T̂ — which runs the same
// loop, cell after cell, over the edges whose ends both lie in the cell, until a quarter of the
// cell's vertices are left (or no such collapse is valid). A cell's data stays in cache; the
// greedy loop over all edges then makes the last quarter of the collapses. The collapses then
// depend on T's face order (that of most meshes is spatially coherent: a cell is a compact region).
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include <fhr/core/trimesh.hpp>
#include <fhr/domain/domain.hpp>

namespace fhr::domain {

struct DecimateOptions {
    std::size_t target_faces = 0;            ///< the faces of D asked for (see decimate)
    double max_normal_deviation_deg = 90.0;  ///< no face may turn by more than this (flips)
    double min_angle_deg = 1.0;              ///< no new corner angle below this (needles, degeneracy)
    /// Beyond the paper, the graded normal rule: when in (0, max_normal_deviation_deg), the
    /// normal rule starts at this angle and, each time no collapse is left valid under it, is
    /// relaxed by graded_step_deg, up to max_normal_deviation_deg (DOM-24). 0: the plain rule.
    double first_normal_deviation_deg = 0;
    static constexpr double graded_step_deg = 15;
    /// Beyond the paper, the graded angle rule: when above min_angle_deg, no new corner may be
    /// below this angle at first; each time no collapse is left valid under it and the normal
    /// rule is at its maximum, it is lowered by graded_angle_step_deg, down to min_angle_deg, and
    /// the normal rule starts from its first angle again (DOM-25). 0: the plain rule.
    double first_min_angle_deg = 0;
    static constexpr double graded_angle_step_deg = 5;
    /// A boundary vertex where T's boundary turns by more than this angle (between the directions
    /// of its two boundary edges) is a corner of the boundary: D keeps it.
    double corner_angle_deg = 60.0;
    std::vector<VertexId> keep{};  ///< vertices of T that D must keep (§3 recovery)
    bool best_effort = false;      ///< stop above the target instead of throwing when no collapse is valid
    /// Check every collapse in full each time it is tried, as the plain loop above does, instead
    /// of remembering which were found invalid by rules whose inputs have not changed since, or
    /// whose failing face still fails: slower, and the same D (DOM-22); for tests.
    bool recheck_rejected = false;
    /// The pass over the cells (see the top of this file) runs for T of more than cells_from
    /// faces, with cells of cell_faces faces. The defaults are measured (paper_notes/domain.md);
    /// tests take small ones to exercise the pass on small meshes.
    std::size_t cells_from = std::size_t{1} << 17;
    std::size_t cell_faces = std::size_t{1} << 14;
};

/// The fewest faces of a closed orientable triangulated surface of genus g: F = 2(V − χ) with
/// the fewest vertices V = ⌈(7 + √(1 + 48g)) / 2⌉ (Heawood's bound, attained for every g except
/// g = 2, which needs 10 vertices; Jungerman & Ringel 1980).
std::size_t min_closed_faces(long genus);

/// The faces asked of each component of T (numbered as connected_components(T)) when D is asked
/// for `faces` faces in all: shares in proportion to the components' areas, rounded by largest
/// remainder so that they sum to `faces` exactly — in steps of two faces for a closed component
/// (its face count is even), of one for a component with boundary — then each raised to the
/// least its topology allows (min_closed_faces(g) closed; 5b + 4g − 4 with b ≥ 1 boundary loops,
/// the faces of a triangulation whose vertices all lie on loops of three), and to at most the
/// component's own faces. paper_notes/boundary.md.
/// \throws InvalidInput when `faces` is 0 or more than T has, or odd with every component closed.
struct ComponentTargets {
    std::vector<std::size_t> faces;  ///< per component
    std::size_t raised = 0;          ///< how many faces the minima added to the request
};
ComponentTargets component_targets(const TriMesh& T, std::size_t faces);

/// Half-edge-collapse decimation of T to options.target_faces faces.
/// \pre T is valid (build_trimesh): orientable, manifold, maybe with boundary and several components.
/// \post D is valid with T's topology; D's vertices are T's vertices at unchanged positions; no
///       face of D has a corner below min_angle_deg; deterministic. A boundary vertex of T that
///       D keeps is on D's boundary, and a boundary vertex moves only along the boundary, so each
///       boundary edge of D stands for the arc of T's boundary between its ends (boundary_arc);
///       T's boundary corners (corner_angle_deg) are D's vertices. Each component c gets
///       component_targets(T, target).faces[c] faces; a closed connected T gets exactly the
///       target. A component with boundary may stop above its share when no collapse is valid
///       (its loops and corners need more faces): D is then larger than asked.
/// \throws InvalidInput when the target is out of range (component_targets; for a closed
///         connected T also odd or below min_closed_faces(genus)), or when a closed component
///         cannot reach its share under the validity rules (unless best_effort).
Domain decimate(const TriMesh& T, const DecimateOptions& options);

/// The decimation of T under `options` (typically more vertices to keep and more faces than
/// before), reusing `previous` — a decimation of T that kept a subset of options.keep — up to its
/// first collapse that removes a vertex kept now (or that would go below the target): that
/// prefix is undone to, and the decimation goes on from there with the same rules. Same
/// guarantees as decimate; the §3 recovery's re-decimations (paper_notes/partition.md).
Domain decimate_again(const TriMesh& T, const Domain& previous, const DecimateOptions& options);

}  // namespace fhr::domain
