// FHR §3 — the shortest geodesic Γ(x_j, x_k) searched inside the "ellipse" sub-mesh T_jk.
//
// Paper §3: "we compute the geodesic Γ(x_j, x_k) by restricting the search to a small
// subtriangulation T_jk of T … the set of all triangles in T containing a vertex v such that
// d_a(v, x_j) + d_a(v, x_k) <= K d_a(x_j, x_k)", d_a by Kimmel–Sethian fast marching, K = 1.06;
// "in the event that the path is not contained in Ω_Tjk, we simply increase K".
//
// Pseudocode:
//   D_a <- d_a(x_j, x_k): fast marching from x_j, bound doubled from 2|x_j − x_k| until x_k is final
//   K <- K_0
//   loop:
//       fields from x_j and from x_k, each bounded by K·D_a (cost ∝ the ellipse, not the mesh)
//       T_jk <- faces with a vertex v: d_a(v, x_j) + d_a(v, x_k) <= K·D_a
//       Γ <- exact shortest path from x_j to x_k inside T_jk (window propagation, early stop)
//       if T_jk is all of T, or Γ exists, touches no vertex or edge of T_jk's artificial
//          boundary (the paper's test) and no path leaving T_jk can be shorter (a certificate
//          from the exact distances d_R inside T_jk and straight-line lower bounds): return Γ
//       K <- 1 + 2(K − 1)
// Why this is safe, and the accuracy it relies on: paper_notes/ellipse.md.
#pragma once

#include <cstddef>

#include "geodesic/exact.hpp"

namespace fhr::geodesic {

struct EllipseOptions {
    double K = 1.06;  ///< the paper's constant; must be > 1
};

struct EllipsePath {
    GeodesicPath path;
    double K = 0;                     ///< the K of the ellipse that gave the path
    std::size_t attempts = 0;         ///< ellipses tried (1 when K_0 sufficed)
    std::size_t ellipse_faces = 0;    ///< faces of the final T_jk
    std::size_t windows_created = 0;  ///< over all attempts
};

/// Γ(a, b) by the ellipse search. \pre mesh valid, closed, connected; a != b.
/// \post path.length is the exact polyhedral distance on the whole mesh: the sub-mesh's result
///       is returned only when certified (see ellipse.cpp), else K grows, up to the whole mesh.
/// \throws InvalidInput for vertex indices out of range, a == b, or K <= 1.
EllipsePath ellipse_shortest_path(const TriMesh& mesh, VertexId a, VertexId b, const EllipseOptions& options = {});

}  // namespace fhr::geodesic
