// FHR §2 — the parameter domain D: a coarse triangulation with T's topology whose every vertex v_j
// is a vertex x_j of T (paper §2), with the history of collapses that made it from T, and the
// domain's own queries and operations: the vertices of T an edge of D stands for (the ends of §3's
// geodesics), and beyond the paper, for a surface with boundary, the domain closed by cones and
// opened again, and collapses undone to a finer domain (§3's recovery refines D that way).
// How D is made: decimate.hpp (by collapses) and user_domain.hpp (given by the user).
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
    bool operator==(const Collapse&) const = default;
};

/// D together with its correspondence to T (paper §2).
struct Domain {
    TriMesh mesh;                   ///< D: compact, with T's topology (components, genus, boundary loops)
    VertexData<VertexId> t_vertex;  ///< #V(D): the vertex x_j of T at vertex v_j of D
    /// The collapses, in the order they were made, in the numbering of T̂ (core/detail/cones.hpp): on a
    /// surface with boundary, `left` or `right` of a collapse along the boundary is the apex of
    /// its loop's cone, vertex #V(T) + (the loop's place in boundary_loops(T)).
    std::vector<Collapse> history;
    /// The collapses began with the pass over the cells (decimate.hpp: its pass over the cells); decimate_again keeps to it.
    bool by_cells = false;
    /// The first cell_collapses entries of `history` are the pass's, in the cells' order.
    std::size_t cell_collapses = 0;
};

/// For each edge [v_j, v_k] of D (in edge order), the vertices x_j, x_k of T it stands for: the
/// endpoints of the geodesics Γ(x_j, x_k) of §3.
std::vector<std::pair<VertexId, VertexId>> edge_endpoints(const Domain& d);

/// D̂: D closed by the cones of T̂ (core/detail/cones.hpp) — each boundary loop of D gets the apex of the
/// loop of T it lies on (t_vertex #V(T) + i, at T̂'s apex position), filled in the order of T's
/// loops so that D̂'s vertices stay in T̂'s order. D's vertices, edges and faces keep their ids.
/// D = D̂ when T is closed.
/// \throws InvalidInput when D's boundary does not follow T's: a boundary vertex of D that is not
///         on T's boundary, a boundary edge of D whose ends are not consecutive D vertices along one
///         loop of T (in the orientation of T's faces), or loops of T and D that do not match one to one.
Domain close_domain(const Domain& D, const TriMesh& T);

/// True when edge e of D̂ has a cone face on a side: a cone edge, or a boundary edge of D (both
/// stand for fixed curves in §3: the cone edge itself, the arc of T's boundary).
/// `closed` is D̂'s mesh (or one being changed from it) and t_vertex its vertices in T̂.
bool on_cone(const TriMesh& closed, const VertexData<VertexId>& t_vertex, EdgeId e, std::size_t real_vertices);

/// D from D̂: the apexes (t_vertex >= real_vertices) and their faces taken off; the other
/// vertices keep their order.
Domain open_domain(const Domain& closed, std::size_t real_vertices);

/// True when undoing all of d.history gives T back, face for face: the history describes d.mesh
/// (false, for instance, after an edge of d.mesh was flipped). O(#F(T) log #F(T)). With boundary,
/// on D̂ and T̂ (close_domain, add_cones).
bool history_describes(const Domain& d, const TriMesh& T);

/// Undoes the last `count` collapses of d.history (vertex splits, most recent first), giving a
/// finer domain whose vertices are again vertices of T. With count = d.history.size() the result
/// is T itself, with its vertices renumbered: result.t_vertex maps them to T. result.history is
/// d.history's first size − count entries (cell_collapses: the pass's among them). With boundary,
/// the collapses are undone on D̂ and T̂ and the cones taken off again.
/// \pre count <= d.history.size().
Domain undo_collapses(const Domain& d, const TriMesh& T, std::size_t count);

}  // namespace fhr::domain
