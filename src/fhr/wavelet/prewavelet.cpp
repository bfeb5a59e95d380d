// FHR §5 — the hat-function Gram matrix of ⟨f,g⟩ = Σ_T 1/a(T) ∫_T f g and the refinement matrix
// P (see prewavelet.hpp).
#include <fhr/wavelet/detail/prewavelet.hpp>

#include <cmath>

namespace fhr::wavelet {

SparseRows gram(const TriMesh& fine, int j) {
    // ∫_τ φ_a φ_b = a(τ)(1 + δ_ab)/12 on a triangle τ with a(τ) = 4^−j a(T). A vertex has as many
    // triangles as edges, one fewer on the boundary; an edge has two, one on the boundary (unit/2
    // is exact, so a closed mesh's entries are those of unit·valence and unit).
    const double unit = std::ldexp(1.0, -2 * j) / 6.0;
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(fine.n_vertices() + fine.n_halfedges());
    for (VertexId v : fine.vertices())
        t.emplace_back(v.idx(), v.idx(), unit * static_cast<double>(fine.valence(v) - (fine.is_boundary(v) ? 1 : 0)));
    for (HalfedgeId h : fine.halfedges())
        t.emplace_back(fine.from(h).idx(), fine.to(h).idx(), fine.is_boundary(TriMesh::edge(h)) ? 0.5 * unit : unit);
    SparseRows G(static_cast<Eigen::Index>(fine.n_vertices()), static_cast<Eigen::Index>(fine.n_vertices()));
    G.setFromTriplets(t.begin(), t.end());
    return G;
}

SparseRows refinement_matrix(const TriMesh& coarse) {
    const std::uint32_t nc = static_cast<std::uint32_t>(coarse.n_vertices());
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(coarse.n_vertices() + 2 * coarse.n_edges());
    for (VertexId v : coarse.vertices()) t.emplace_back(v.idx(), v.idx(), 1.0);
    for (EdgeId e : coarse.edges()) {
        const HalfedgeId h = TriMesh::halfedge(e, 0);
        t.emplace_back(nc + e.idx(), coarse.from(h).idx(), 0.5);
        t.emplace_back(nc + e.idx(), coarse.to(h).idx(), 0.5);
    }
    SparseRows P(static_cast<Eigen::Index>(coarse.n_vertices() + coarse.n_edges()), static_cast<Eigen::Index>(nc));
    P.setFromTriplets(t.begin(), t.end());
    return P;
}

}  // namespace fhr::wavelet
