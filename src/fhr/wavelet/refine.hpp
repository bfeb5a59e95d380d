// FHR §5 — dyadic refinement D^0 = D, D^1, …, D^J (paper §5, Fig. 5: the one-to-four split
// [v1,w2,w3], [w1,v2,w3], [w1,w2,v3], [w1,w2,w3] with w_i the midpoints of the edges) and the
// samples f^J(v) = φ(v) at the vertices of D^J.
//
// Pseudocode:
//   D^0 <- D; every face f of D has corner coordinates e_0, e_1, e_2 in itself
//   for j = 1..J:
//       vertices of D^j: D^{j−1}'s (same ids), then one per edge e of D^{j−1}: id #V(D^{j−1}) + e
//       face f = (a, b, c) of D^{j−1} (face_vertices order) with midpoints m_ab, m_bc, m_ca gives
//       faces 4f..4f+3 = (a, m_ab, m_ca), (m_ab, b, m_bc), (m_ca, m_bc, c), (m_ab, m_bc, m_ca);
//       their corner coordinates (in the root face of D) are the parent's corners or averages
//       of two of them
//   location(v) <- the corner coordinates of v in the first face of D^J (lowest id) that has v
//
// D may have boundary (any number of loops) and several components (beyond the paper,
// which takes D closed): the split is face by face, so a boundary edge of D^{j−1} gives a boundary
// vertex of valence 4 and two boundary edges of D^j, and each component refines on its own.
//
// So the face g of D^J lies in the face g >> 2J of D, and every barycentric coordinate is a
// multiple of 2^−J: averaging two such numbers is exact in double, so the coordinates are the
// exact dyadic rationals and a vertex on an edge (vertex) of D has exact zeros (WAV-2).
#pragma once

#include <array>
#include <functional>
#include <vector>

#include <fhr/core/executor.hpp>
#include <fhr/core/trimesh.hpp>

namespace fhr::wavelet {

/// A point of Ω_D: a face of D and barycentric coordinates β, β_c the weight of
/// face_vertices(face)[c] (the corner order of the `fhr-param 1` domain faces, spec/param.md).
struct DomainPoint {
    FaceId face;
    std::array<double, 3> beta;
};

/// φ: Ω_D → Ω_T evaluated at a domain point (face of D, β in that face's corner order). Points on
/// an edge of D must give the same 3-D point from both faces (param::PatchLocator does: MAP-11).
using DomainMap = std::function<Vec3(FaceId, const std::array<double, 3>&)>;

/// D^0..D^J with where every vertex of D^J lies in D.
struct Refinement {
    /// levels[j] = D^j. Positions: D^j as a triangulation of Ω_D (each vertex at its point of D,
    /// Σ_c β_c x_c), so levels[j] is also the geometric refinement of D.
    std::vector<TriMesh> levels;
    /// #V(D^J): location[v] is where vertex v lies in D. The vertices of D^j are the first
    /// #V(D^j) vertices of D^J, with the same locations.
    std::vector<DomainPoint> location;
    /// #F(D^J): the β of face g's corners (face_vertices(g) order) in its root face g >> 2J of D.
    std::vector<std::array<std::array<double, 3>, 3>> corner_beta;

    int depth() const { return static_cast<int>(levels.size()) - 1; }  ///< J
    const TriMesh& finest() const { return levels.back(); }
};

/// The largest D^J accepted: 2^26 ≈ 6.7·10^7 faces (several GB of halfedges and coordinates).
inline constexpr std::size_t max_refined_faces = std::size_t{1} << 26;

/// The dyadic refinements of D up to level J (paper §5, Fig. 5), D closed or with boundary, with
/// one component or several.
/// \pre D passes validate().
/// \post depth() == J; for j ≥ 1, #V(D^j) = #V(D^{j−1}) + #E(D^{j−1}), #F(D^j) = 4 #F(D^{j−1}),
///       #E(D^j) = 2 #E(D^{j−1}) + 3 #F(D^{j−1}) (so χ is kept), each boundary edge of D^{j−1}
///       split into two boundary edges of D^j; numbering as in the file header (WAV-1, WAV-11);
///       every location and corner coordinate is exact (WAV-2).
/// \throws InvalidInput(...) when D has no face or has garbage, J < 0, or
///         #F(D)·4^J > max_refined_faces.
Refinement refine(const TriMesh& D, int J);

/// f^J at every vertex of D^J: samples[v] = phi(location[v].face, location[v].beta). The first
/// #V(D^j) samples are f^j at the vertices of D^j (paper §5: f^j(v) = φ(v)). phi is called from
/// the threads of `executor` (default_executor() when null) at once, so it must be safe to call
/// concurrently; each sample is phi's, on any number of threads.
std::vector<Vec3> sample(const Refinement& r, const DomainMap& phi, Executor* executor = nullptr);

}  // namespace fhr::wavelet
