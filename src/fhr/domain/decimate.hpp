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
//       pop the cheapest h (ties: lowest halfedge index); skip stale entries
//       if the collapse v0 -> v1 is valid (link condition; no face turns by more than
//          max_normal_deviation; no new corner below min_angle; no exactly degenerate face):
//           collapse, Q_v1 += Q_v0, record (v0, v1, va, vb), re-queue the edges near v1
//       else queue the edge's other direction, unless it was found invalid too
//   if the queue runs dry first: the target cannot be met under these rules (error)
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include <fhr/core/trimesh.hpp>

namespace fhr::domain {

/// One half-edge collapse in T's vertex numbering: `removed` merged into `kept`, removing the
/// faces (removed, kept, left) and (kept, removed, right). Undone by
/// TriMesh::split_vertex(kept, left, right, position of removed).
struct Collapse {
    VertexId removed, kept, left, right;
};

struct DecimateOptions {
    std::size_t target_faces = 0;            ///< even, >= min_closed_faces(genus), <= T's faces
    double max_normal_deviation_deg = 90.0;  ///< no face may turn by more than this (flips)
    double min_angle_deg = 1.0;              ///< no new corner angle below this (needles, degeneracy)
    std::vector<VertexId> keep{};            ///< vertices of T that D must keep (§3 recovery)
    bool best_effort = false;                ///< stop above the target instead of throwing when no collapse is valid
};

/// D together with its correspondence to T (paper §2).
struct Domain {
    TriMesh mesh;                     ///< D: compact, closed, with T's Euler characteristic
    VertexData<VertexId> t_vertex;    ///< #V(D): the vertex x_j of T at vertex v_j of D
    std::vector<Collapse> history;    ///< the collapses, in the order they were made
};

/// For each edge [v_j, v_k] of D (in edge order), the vertices x_j, x_k of T it stands for: the
/// endpoints of the geodesics Γ(x_j, x_k) of §3.
std::vector<std::pair<VertexId, VertexId>> edge_endpoints(const Domain& d);

/// The fewest faces of a closed orientable triangulated surface of genus g: F = 2(V − χ) with
/// the fewest vertices V = ⌈(7 + √(1 + 48g)) / 2⌉ (Heawood's bound, attained for every g except
/// g = 2, which needs 10 vertices; Jungerman & Ringel 1980).
std::size_t min_closed_faces(long genus);

/// Half-edge-collapse decimation of T to exactly options.target_faces faces.
/// \pre T is valid, closed and connected (build_trimesh).
/// \post D is valid and closed with χ(D) = χ(T); D's vertices are T's vertices at unchanged
///       positions; no face of D has a corner below min_angle_deg; deterministic.
/// \throws InvalidInput when the target is odd, larger than T's face count, below
///         min_closed_faces(genus), or cannot be reached under the validity rules.
Domain decimate(const TriMesh& T, const DecimateOptions& options);

/// The decimation of T under `options` (typically more vertices to keep and more faces than
/// before), reusing `previous` — a decimation of T that kept a subset of options.keep — up to its
/// first collapse that removes a vertex kept now (or that would go below the target): that
/// prefix is undone to, and the decimation goes on from there with the same rules. Same
/// guarantees as decimate; the §3 recovery's re-decimations (paper_notes/partition.md).
Domain decimate_again(const TriMesh& T, const Domain& previous, const DecimateOptions& options);

/// True when undoing all of d.history gives T back, face for face: the history describes d.mesh
/// (false, for instance, after an edge of d.mesh was flipped). O(#F(T) log #F(T)).
bool history_describes(const Domain& d, const TriMesh& T);

/// Undoes the last `count` collapses of d.history (vertex splits, most recent first), giving a
/// finer domain whose vertices are again vertices of T. With count = d.history.size() the result
/// is T itself, with its vertices renumbered: result.t_vertex maps them to T.
/// \pre count <= d.history.size().
Domain undo_collapses(const Domain& d, const TriMesh& T, std::size_t count);


}  // namespace fhr::domain
