// §3 eq. (1): the structural check that a returned path Γ is a geodesic polyline (GEO-4 of
// paper_notes/exact_geodesics.md), the paper's ellipse T_jk built from its definition, and the
// pairs of vertices around holes, shared by the geodesic suite's tests of the exact
// algorithm (test_exact.cpp, test_boundary.cpp) and of the ellipse search (test_ellipse.cpp).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <fhr/core/surface_point.hpp>
#include <fhr/core/trimesh.hpp>
#include <fhr/generate/random_mesh.hpp>
#include <fhr/geodesic/exact.hpp>

namespace fhr::test {

/// The quality family at its extreme knobs (needles of 10⁻⁹°, half the faces bad): the meshes of
/// GEO-E8 and GEO-E9, where the exact search lost windows.
generate::RandomMeshOptions needle_recipe(int genus, int components, std::size_t faces, std::uint64_t seed);

/// |a − b| relative to the larger; 0 when equal (also both infinite), infinite when one is.
double rel_dev(double a, double b);

/// x in scientific notation (Catch prints doubles in fixed notation, hiding small deviations).
std::string sci(double x);

/// The faces a path point lies in (a vertex: its fan; an edge point: the edge's faces); invalid
/// ids stand for the holes.
std::vector<FaceId> faces_at(const TriMesh& m, const SurfacePoint& p);

/// GEO-4: the first way in which `p` is not a geodesic from s to t on the kept faces (all faces
/// of m without a mask), or "". Checked: it runs from s to t; consecutive points share a kept
/// face; its length is the sum of its segments; it is straight across every edge after
/// unfolding; and at every vertex v it passes, the angle between its arriving and leaving
/// segments, measured through the kept faces around v, is ≥ π on every side that is surface:
///   - v interior (its kept faces close around it): on both sides;
///   - v on the boundary (of T or of the mask: its kept faces form one open fan from one border
///     edge to the other): on the side inside the fan. The other side is the hole, which no path
///     can cut across, so there the angle is free; a path can pass v only if v's fan angle is
///     ≥ π (a reflex boundary vertex), and it then wraps around v or runs along the boundary;
///   - v pinched (its kept faces form several fans, only with a mask): not checked.
/// Tolerances (notes, "Test tolerances"): node rounding 10⁻¹²·diag, snapping and cover
/// tolerance at vertex nodes, and a tie allowance at vertices, all times `conditioning` (an
/// unfolding across a needle of ratio r magnifies rounding up to r times: GEO-9).
std::string path_violation(const TriMesh& m, const geodesic::GeodesicPath& p, VertexId s, VertexId t,
                           const FaceData<std::uint8_t>* mask = nullptr, double conditioning = 1);

/// What path_violation saw at the vertices a path passes (for the tests' coverage counts).
struct VertexPassages {
    std::size_t interior = 0;        ///< interior vertices passed (saddles)
    std::size_t boundary = 0;        ///< boundary vertices of T passed
    std::size_t boundary_bends = 0;  ///< of those, where the path bends (fan-side angle > π + 10⁻⁶)
    std::size_t boundary_edges = 0;  ///< segments that run along a boundary edge of T
};
VertexPassages vertex_passages(const TriMesh& m, const geodesic::GeodesicPath& p);

/// The largest ratio of a triangle's longest edge to its height on that edge (1.15 equilateral).
double needle_ratio(const TriMesh& m);

/// The path passes through a vertex between its ends.
bool passes_a_vertex(const geodesic::GeodesicPath& p);

/// The vertices of every boundary loop of m, in loop order.
std::vector<std::vector<VertexId>> boundary_loop_vertices(const TriMesh& m);

/// Pairs whose shortest path is likely to run along a hole: on each boundary loop,
/// the vertices k = 1, 2, 3 steps either side of its most reflex vertex (the largest angle sum:
/// a path between them wraps around it, and on the generator's square holes runs along the
/// boundary), and that vertex with the one half way round the loop.
std::vector<std::pair<VertexId, VertexId>> hugging_pairs(const TriMesh& m);

/// The paper's T_jk for one K, from its definition (§3, independently of ellipse.cpp): the faces
/// with a vertex v such that d_a(v, a) + d_a(v, b) <= K d_a(a, b), d_a by fast marching.
FaceData<std::uint8_t> paper_ellipse(const TriMesh& m, VertexId a, VertexId b, double K);

}  // namespace fhr::test
