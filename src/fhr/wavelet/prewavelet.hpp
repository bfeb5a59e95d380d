// FHR §5 — the Floater–Quak piecewise linear prewavelets (Floater & Quak 1999, "Piecewise linear
// prewavelets on arbitrary triangulations", Numer. Math. 82; paper §5 reference [8]), on a closed
// triangulation of any valence, for the paper's inner product
//     ⟨f, g⟩ = Σ_{T ∈ D} 1/a(T) ∫_T f g.
// A triangle τ of D^j inside T ∈ D has a(τ)/a(T) = 4^−j, so ⟨φ^j_a, φ^j_b⟩ = 4^−j/12 · Σ_{τ ∋ a,b}
// (1 + δ_ab): every coefficient below is combinatorial (design.md §3).
//
// The construction, derived in paper_notes/wavelets.md. A coarse vertex v of D^{j−1} with n
// neighbours v_0..v_{n−1} in cyclic order and u_l the new vertex of D^j on edge [v, v_l]:
//   C_n  = the n×n circulant with 5 on the diagonal and 1 at the cyclic neighbours (n ≥ 3),
//   θ_n(k, l) = (C_n⁻¹)_{kl} = (λ^a + λ^{n−a}) / (√21 (1 − λ^n)),  a = |k − l|, λ = (√21 − 5)/2,
//   σ_{v,u_k} = s [ −3/(2n) φ^j_v + Σ_l (3/(28n) + θ_n(k, l)) φ^j_{u_l} ]          (semi-prewavelet)
// σ_{v,u_k} is orthogonal to φ^{j−1}_{v_l} for every l ≠ k, and ⟨σ_{v,u_k}, φ^{j−1}_v⟩ =
// −⟨σ_{v,u_k}, φ^{j−1}_{v_k}⟩ = −2s·4^−j/12 whatever n is, so for the new vertex u on [v1, v2]
//   ψ_u = σ_{v1,u} + σ_{v2,u}
// is orthogonal to every φ^{j−1}_w (WAV-3). Scale s = 2^{j−1} (design.md §3): ‖ψ_u‖ then depends
// on the valences of v1 and v2 only, not on the level.
//
// The functions are templates on the number type so that the tests can evaluate the same
// construction in 100-digit arithmetic (boost::multiprecision) as well as in double.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include <Eigen/SparseCore>

#include <fhr/core/trimesh.hpp>

namespace fhr::wavelet {

/// x^k by repeated multiplication (k small: a valence).
template <class Real>
Real integer_power(const Real& x, std::size_t k) {
    Real p(1);
    for (std::size_t i = 0; i < k; ++i) p *= x;
    return p;
}

/// θ_n(k, l) = (C_n⁻¹)_{kl} with a = |k − l| (Floater & Quak 1999).
/// \pre n ≥ 3, a < n.
template <class Real>
Real theta(std::size_t n, std::size_t a) {
    using std::sqrt;
    const Real root21 = sqrt(Real(21));
    const Real lambda = (root21 - Real(5)) / Real(2);
    return (integer_power(lambda, a) + integer_power(lambda, n - a)) /
           (root21 * (Real(1) - integer_power(lambda, n)));
}

/// A prewavelet (or any function of S^j) as coefficients of the fine hat functions φ^j_w:
/// (w, coefficient) pairs sorted by w, each w once.
template <class Real>
using SparseFunction = std::vector<std::pair<std::uint32_t, Real>>;

/// ψ_u for every new vertex u = #V(coarse) + e of D^j, in edge order e of coarse = D^{j−1},
/// scaled by s (2^{j−1} for level j).
/// \pre coarse is closed, without garbage, every valence ≥ 3, and no two edges join the same
///      two vertices (TriMesh guarantees the last).
template <class Real>
std::vector<SparseFunction<Real>> prewavelets(const TriMesh& coarse, const Real& s) {
    const std::uint32_t nc = static_cast<std::uint32_t>(coarse.n_vertices());
    std::vector<SparseFunction<Real>> psi(coarse.n_edges());
    std::vector<std::uint32_t> ring;  // u_0..u_{n−1} of the current v
    std::vector<Real> th;             // θ_n(a), a = 0..n−1
    for (VertexId v : coarse.vertices()) {
        ring.clear();
        coarse.for_each_outgoing(v, [&](HalfedgeId h) { ring.push_back(TriMesh::edge(h).idx()); });
        const std::size_t n = ring.size();
        th.clear();
        for (std::size_t a = 0; a < n; ++a) th.push_back(theta<Real>(n, a));
        const Real centre = -Real(3) / Real(2 * n) * s;
        const Real base = Real(3) / Real(28 * n);
        for (std::size_t k = 0; k < n; ++k) {  // σ_{v,u_k} added to ψ_{u_k}
            SparseFunction<Real>& col = psi[ring[k]];
            col.emplace_back(v.idx(), centre);
            for (std::size_t l = 0; l < n; ++l)
                col.emplace_back(nc + ring[l], (base + th[k > l ? k - l : l - k]) * s);
        }
    }
    // The two semi-prewavelets of ψ_u overlap at u only (two edges share at most one end).
    for (SparseFunction<Real>& col : psi) {
        std::sort(col.begin(), col.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
        std::size_t out = 0;
        for (std::size_t i = 0; i < col.size(); ++i) {
            if (out > 0 && col[out - 1].first == col[i].first)
                col[out - 1].second += col[i].second;
            else
                col[out++] = col[i];
        }
        col.resize(out);
    }
    return psi;
}

using SparseRows = Eigen::SparseMatrix<double, Eigen::RowMajor>;

/// The Gram matrix of the hat functions of D^j for ⟨·,·⟩ (#V × #V, exact up to the rounding of
/// 4^−j/12): 4^−j · valence(a)/6 on the diagonal, 4^−j/6 for every edge [a, b] (closed mesh:
/// two triangles per edge).
SparseRows gram(const TriMesh& fine, int j);

/// The refinement matrix P of level j (#V(D^j) × #V(D^{j−1})): φ^{j−1}_v = φ^j_v + ½ Σ φ^j_u over
/// the new vertices u on v's edges, i.e. P = [I; P_N] with two entries ½ per new vertex.
SparseRows refinement_matrix(const TriMesh& coarse);

}  // namespace fhr::wavelet
