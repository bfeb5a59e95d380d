// FHR core (internal) — groups the corners of a triangle list by undirected edge.
// Shared by the mesh builder (manifold and orientation checks) and TriMesh::from_triangles
// (twin pairing), so that both see the same edges in the same deterministic order.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <fhr/core/trimesh.hpp>

namespace fhr::detail {

/// Corner c = 3f + k of triangle f stands for the directed edge tri[f][k] -> tri[f][(k+1)%3].
struct EdgeTable {
    std::vector<std::uint32_t> corner_edge;   ///< #corners: undirected edge id of each corner
    std::vector<std::uint32_t> edge_offsets;  ///< #E+1: edge e has corners edge_corners[off[e]..off[e+1])
    std::vector<std::uint32_t> edge_corners;  ///< corners of each edge, increasing
    std::size_t n_edges() const { return edge_offsets.size() - 1; }
    std::uint32_t edge_degree(std::uint32_t e) const { return edge_offsets[e + 1] - edge_offsets[e]; }
};

inline std::uint32_t corner_tail(std::span<const Triangle> t, std::uint32_t c) { return t[c / 3][c % 3]; }
inline std::uint32_t corner_head(std::span<const Triangle> t, std::uint32_t c) { return t[c / 3][(c % 3 + 1) % 3]; }

/// Edges are numbered by (min vertex, max vertex) lexicographically. O(#corners · valence).
/// \pre every index < n_vertices and no triangle repeats a vertex.
EdgeTable build_edge_table(std::size_t n_vertices, std::span<const Triangle> triangles);

}  // namespace fhr::detail

namespace fhr::detail {

/// The first vertex (in index order) whose incident triangles do not form a single fan, i.e. a
/// non-manifold ("bow-tie") vertex, or UINT32_MAX when there is none. Found on the mesh built from
/// them, by walking around each vertex (grouping the corners by vertex again for this
/// check was a third of building a mesh, 0.065 of 0.19 s per 10⁶ faces; the walk takes 0.014 s).
/// \pre mesh = TriMesh::from_triangles(positions, triangles, build_edge_table(…)): triangles
///      consistently oriented, every edge with at most two corners.
std::uint32_t first_non_manifold_vertex(const TriMesh& mesh, std::span<const Triangle> triangles);

}  // namespace fhr::detail
