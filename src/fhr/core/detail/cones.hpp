// Beyond the paper — surfaces with boundary, closed by virtual cones.
//
// The paper's §2 and §3 are made for closed surfaces: the link condition of a collapse, the cyclic
// order of the curves around a vertex (condition (2)), patches bounded by curves on every side.
// A surface with boundary is closed for them by one cone per boundary loop: a new apex vertex
// joined to every vertex of the loop (TriMesh::fill_hole). The cones are never part of the
// surface: geodesics are computed on T itself; the decimation moves a boundary vertex only along
// the boundary, so every cone of T̂ stays a cone of D̂; and in the partition the cone edges and the
// boundary arcs between D's boundary vertices are fixed curves, never geodesics, never flipped.
// At the end the cones are taken off again. Decisions and their reasons: paper_notes/boundary.md.
#pragma once

#include <cstddef>

#include <fhr/core/trimesh.hpp>

namespace fhr {

/// T̂: T closed by one cone per boundary loop.
struct Coned {
    TriMesh mesh;                   ///< T̂. T's vertices, halfedges and faces keep their ids
    std::size_t real_vertices = 0;  ///< #V(T): the apex of loop i (boundary_loops(T)[i]) is vertex #V(T) + i
    std::size_t real_faces = 0;     ///< #F(T): the cone faces follow T's faces
    bool is_apex(VertexId v) const { return v.idx() >= real_vertices; }
};

/// T̂ for T (a closed T gives T̂ = T). Each apex lies at the centroid of its loop's vertices.
/// \pre T valid, without garbage.
Coned add_cones(const TriMesh& T);

/// The apex positions add_cones gives, one per loop of boundary_loops(T), in that order.
std::vector<Vec3> cone_apexes(const TriMesh& T);

/// The vertices of T's boundary from a to b, both included, given T̂ (`closed`, whose vertices from
/// `real_vertices` on are apexes): the arc of T's boundary loop from a to b in the direction in
/// which T's faces lie on the left — what a boundary edge [a, b] of D (D's face on its left)
/// stands for. In T̂ a boundary edge of T has a cone face on one side.
/// \pre a and b are vertices of one boundary loop of T, a != b.
std::vector<VertexId> boundary_arc(const TriMesh& closed, std::size_t real_vertices, VertexId a, VertexId b);

}  // namespace fhr
