// FHR §3 — the shortest geodesic Γ(x_j, x_k) searched inside the "ellipse" sub-mesh T_jk.
//
// Paper §3: "we compute the geodesic Γ(x_j, x_k) by restricting the search to a small
// subtriangulation T_jk of T … the set of all triangles in T containing a vertex v such that
// d_a(v, x_j) + d_a(v, x_k) <= K d_a(x_j, x_k)", d_a by Kimmel–Sethian fast marching, K = 1.06;
// "in the event that the path is not contained in Ω_Tjk, we simply increase K".
//
// Pseudocode:
//   FM_a <- fast marching from x_j, run until x_k is final: D_a = d_a(x_j, x_k)
//   FM_b <- fast marching from x_k
//   K <- K_0
//   loop:
//       continue FM_a and FM_b up to K·D_a (one run each over all attempts: cost ∝ the ellipse)
//       T_jk <- faces with a vertex v: d_a(v, x_j) + d_a(v, x_k) <= K·D_a
//       Γ <- exact shortest path from x_j to x_k inside T_jk (window propagation, early stop at
//            x_k), L its length; B <- the smallest key (lower bound of a path to x_k through it)
//            of anything that search brought to T_jk's artificial boundary or left queued
//       if T_jk is all of T: return Γ (no artificial boundary)
//       if Γ exists and touches no vertex or edge of T_jk's artificial boundary (the paper's test):
//           if B >= L: return Γ                                  (certificate 1: the border)
//           S <- exact search from x_j on all of T, early stop at x_k, pruned above L
//           if S finds no path shorter than L: return Γ          (certificate 2: the search)
//           return S's path (Γ was not the shortest path of T: the ellipse missed it)
//       if Γ does not exist and T_jk has no artificial border (it is a's whole component):
//           return no path (the exact search lost x_k to rounding; growing K would repeat it)
//       K <- 1 + 2(K − 1)                                        (the paper's rule)
// Why this is safe (a theorem and its proof): paper_notes/ellipse.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <fhr/geodesic/exact.hpp>

namespace fhr::geodesic {

/// The fast-marching field of one focus, kept for all the paths that start or end there (beyond
/// the paper): a domain vertex has about six edges, and each of their ellipses needs d_a
/// from it; one run to the farthest of them replaces six runs over nearly the same disk.
struct FocusField {
    VertexId source;
    /// Every vertex with d_a(source, v) <= radius is in `vertices` (the run went that far).
    double radius = 0;
    std::vector<VertexId> vertices;  ///< the final vertices, in acceptance order
    std::vector<double> distance;    ///< d_a(source, ·) of each, bitwise a fresh run's (FastMarching)
};

/// The field of `source` far enough for the first ellipse (K·d_a(x_j, x_k)) of every path
/// between it and one of `partners`, whichever end d_a(x_j, x_k) is measured from: fast marching
/// until every partner is final, then on to `reach` times K times the farthest partner's distance
/// (`reach` > 1 covers d_a's asymmetry: d_a(x_k, x_j) may exceed d_a(x_j, x_k)). Partners in
/// another component are left out of the farthest.
/// \pre source and partners are vertices of mesh; K > 1, reach >= 1.
FocusField focus_field(const TriMesh& mesh, VertexId source, std::span<const VertexId> partners, double K, double reach,
                       Workspace* workspace = nullptr);

struct EllipseOptions {
    double K = 1.06;  ///< the paper's constant; must be > 1
    /// Optional: the reusable arrays of its searches (geodesic/workspace.hpp); without one the
    /// call uses a workspace of its own, freed when it returns. partition() ignores it: it runs
    /// its paths in parallel, each on a workspace of its own pool.
    Workspace* workspace = nullptr;
    /// Optional: the fields of a and of b (focus_field). While both reach K·d_a(a, b), the
    /// ellipse is made from them instead of two fast-marching runs of this call: the same T_jk,
    /// the same result. Past their radius (K grown, or a field too short) the call runs its own.
    const FocusField* field_a = nullptr;
    const FocusField* field_b = nullptr;
};

struct EllipsePath {
    /// How the returned path is known to be a shortest path of all of T.
    enum class Certificate : std::uint8_t {
        /// T_jk grew to all of T: no artificial boundary. (On a mesh of several components T_jk
        /// can at most cover a's component; there is then no artificial border either, nothing
        /// reaches one, and the border certificate holds: paper_notes/ellipse.md.)
        whole_mesh,
        border,    ///< nothing the restricted search brought to T_jk's border can be shorter
        search,    ///< the exact search on all of T, pruned above L, found nothing shorter
        replaced,  ///< that search found a shorter path (outside T_jk): its path is returned
        /// No search: the curve of a boundary edge of D is the arc of T's boundary between its
        /// ends, and a cone edge of T̂ is itself (partition.hpp, core/detail/cones.hpp).
        boundary_arc,
    };
    GeodesicPath path;
    double K = 0;                     ///< the K of the last ellipse (the one that gave the path,
                                      ///< except for Certificate::replaced)
    std::size_t attempts = 0;         ///< ellipses tried (1 when K_0 sufficed)
    std::size_t ellipse_faces = 0;    ///< faces of the final T_jk
    std::size_t windows_created = 0;  ///< by the restricted searches, over all attempts
    Certificate certificate = Certificate::whole_mesh;
    std::size_t certificate_windows = 0;  ///< by the certificate search (0 unless it ran)
};

/// Γ(a, b) by the ellipse search. \pre mesh valid without garbage; holes and several components
///      are allowed: a hole of T is no part of T_jk's artificial border, a path may run
///      along it, and no path can leave T_jk through it (paper_notes/ellipse.md).
/// \post path.length is the exact polyhedral distance on the whole mesh (up to the rounding of
///       the exact algorithm, paper_notes/exact_geodesics.md): the sub-mesh's path is returned
///       only when certified, and a certificate that fails yields the whole-mesh search's path.
///       Exception: when the exact search exhausts a's component (all of T, or T_jk once it has
///       no artificial border) without reaching b, the path has no points and length INFINITY.
///       a and b are connected, so this is the exact algorithm losing b to rounding (possible on
///       needles far beyond its tolerances' reach: paper_notes/exact_geodesics.md, "Needles");
///       callers must check it (the partition reports it as a PartitionFailure).
/// \throws InvalidInput for vertex indices out of range, a == b, K <= 1, or a and b not connected.
EllipsePath ellipse_shortest_path(const TriMesh& mesh, VertexId a, VertexId b, const EllipseOptions& options = {});

}  // namespace fhr::geodesic
