// FHR §5 — the Floater–Quak piecewise linear prewavelets (Floater & Quak 1999, "Piecewise linear
// prewavelets on arbitrary triangulations", Numer. Math. 82; paper §5 reference [8]), on a
// triangulation of any valence, closed (the paper) or with boundary, for the paper's inner product
//     ⟨f, g⟩ = Σ_{T ∈ D} 1/a(T) ∫_T f g.
// A triangle τ of D^j inside T ∈ D has a(τ)/a(T) = 4^−j, so ⟨φ^j_a, φ^j_b⟩ = 4^−j/12 · Σ_{τ ∋ a,b}
// (1 + δ_ab): every coefficient below is combinatorial (Floater–Quak).
//
// The construction, derived in paper_notes/wavelets.md. A coarse vertex v of D^{j−1} with n
// neighbours v_0..v_{n−1} in cyclic order and u_l the new vertex of D^j on edge [v, v_l]:
//   C_n  = the n×n circulant with 5 on the diagonal and 1 at the cyclic neighbours (n ≥ 3),
//   θ_n(k, l) = (C_n⁻¹)_{kl} = (λ^a + λ^{n−a}) / (√21 (1 − λ^n)),  a = |k − l|, λ = (√21 − 5)/2,
//   σ_{v,u_k} = s [ −3/(2n) φ^j_v + Σ_l (3/(28n) + θ_n(k, l)) φ^j_{u_l} ]          (semi-prewavelet)
// σ_{v,u_k} is orthogonal to φ^{j−1}_{v_l} for every l ≠ k, and ⟨σ_{v,u_k}, φ^{j−1}_v⟩ =
// −⟨σ_{v,u_k}, φ^{j−1}_{v_k}⟩ = −2s·4^−j/12 whatever n is, so for the new vertex u on [v1, v2]
//   ψ_u = σ_{v1,u} + σ_{v2,u}
// is orthogonal to every φ^{j−1}_w (WAV-3). Scale s = 2^{j−1} (paper_notes/wavelets.md): ‖ψ_u‖ then depends
// on the valences of v1 and v2 only, not on the level.
//
// Boundary (beyond the paper, which takes D closed; derived in paper_notes/wavelets.md).
// A boundary vertex v of D^{j−1} with t coarse triangles has the t + 1 neighbours v_0..v_t in
// fan order, v_0 and v_t on the boundary, and u_l on [v, v_l] (u_0, u_t of valence 4). In units of
// 4^−j/12, ⟨σ, φ^{j−1}_v⟩ = 3tα + 10 Σ_l d_l β_l and ⟨σ, φ^{j−1}_{v_l}⟩ = d_l α + 2(T_t β)_l with
// d = (½, 1, …, 1, ½) and T_t the (t+1)×(t+1) tridiagonal (1, 5, 1) whose two corner entries are
// 5/2, so that T_t 𝟙 = 7d (the closed ring: d = 𝟙, T = C_n); the same elimination gives
//   σ_{v,u_k} = s [ −3/(2t) φ^j_v + Σ_l (3/(28t) + θ^∂_t(k, l)) φ^j_{u_l} ],
//   θ^∂_t(k, l) = (T_t⁻¹)_{kl} = θ_{2t}(|k − l|) + θ_{2t}(k + l)                   (t ≥ 1)
// (T_t is C_{2t} restricted to vectors symmetric about 0 and t: reflecting the fan's path onto a
// cycle of length 2t), again with ⟨σ_{v,u_k}, φ^{j−1}_v⟩ = −⟨σ_{v,u_k}, φ^{j−1}_{v_k}⟩ = −2s·4^−j/12.
// So ψ_u = σ_{v1,u} + σ_{v2,u} is orthogonal to S^{j−1} for every edge [v1, v2], interior or on
// the boundary, whichever kind of vertex each end is.
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

/// θ_n(k, l) = (C_n⁻¹)_{kl} with a = |k − l| (Floater & Quak 1999): the n-periodic solution of
/// x_{a−1} + 5x_a + x_{a+1} = δ_{a mod n}, so θ_n(n − a) = θ_n(a).
/// \pre n ≥ 2 (n ≥ 3 for the circulant of a closed ring; n = 2t for the boundary's θ^∂_t), a ≤ n.
template <class Real>
Real theta(std::size_t n, std::size_t a) {
    using std::sqrt;
    const Real root21 = sqrt(Real(21));
    const Real lambda = (root21 - Real(5)) / Real(2);
    return (integer_power(lambda, a) + integer_power(lambda, n - a)) / (root21 * (Real(1) - integer_power(lambda, n)));
}

/// θ^∂_t(k, l) = (T_t⁻¹)_{kl} = θ_{2t}(|k − l|) + θ_{2t}(k + l) for a boundary vertex with t coarse
/// triangles (file header). \pre t ≥ 1, k, l ≤ t.
template <class Real>
Real theta_boundary(std::size_t t, std::size_t k, std::size_t l) {
    return theta<Real>(2 * t, k > l ? k - l : l - k) + theta<Real>(2 * t, k + l);
}

/// A prewavelet (or any function of S^j) as coefficients of the fine hat functions φ^j_w:
/// (w, coefficient) pairs sorted by w, each w once.
template <class Real>
using SparseFunction = std::vector<std::pair<std::uint32_t, Real>>;

/// ψ_u for every new vertex u = #V(coarse) + e of D^j, in edge order e of coarse = D^{j−1},
/// scaled by s (2^{j−1} for level j).
/// \pre coarse is without garbage (closed or with boundary, any number of components; every
///      valence is then ≥ 3 inside and ≥ 2 on the boundary), and no two edges join the same two
///      vertices (TriMesh guarantees the last).
template <class Real>
std::vector<SparseFunction<Real>> prewavelets(const TriMesh& coarse, const Real& s) {
    const std::uint32_t nc = static_cast<std::uint32_t>(coarse.n_vertices());
    std::vector<SparseFunction<Real>> psi(coarse.n_edges());
    std::vector<std::uint32_t> ring;  // u_0..u_{n−1} of the current v (boundary: u_0, u_t on the boundary)
    std::vector<Real> th;             // closed ring: θ_n(a), a = 0..n−1; boundary: θ^∂_t(k, l) at k·n + l
    for (VertexId v : coarse.vertices()) {
        ring.clear();
        // At a boundary vertex out(v) is the boundary halfedge, so the clockwise turn walks the fan
        // from one boundary neighbour to the other.
        coarse.for_each_outgoing(v, [&](HalfedgeId h) { ring.push_back(TriMesh::edge(h).idx()); });
        const std::size_t n = ring.size();
        const bool open = coarse.is_boundary(v);
        const std::size_t t = open ? n - 1 : n;  // coarse triangles at v
        th.clear();
        if (open) {
            for (std::size_t k = 0; k < n; ++k)
                for (std::size_t l = 0; l < n; ++l) th.push_back(theta_boundary<Real>(t, k, l));
        } else {
            for (std::size_t a = 0; a < n; ++a) th.push_back(theta<Real>(n, a));
        }
        auto inverse = [&](std::size_t k, std::size_t l) -> const Real& {  // θ_n(k, l) or θ^∂_t(k, l)
            return open ? th[k * n + l] : th[k > l ? k - l : l - k];
        };
        const Real centre = -Real(3) / Real(2 * t) * s;
        const Real base = Real(3) / Real(28 * t);
        for (std::size_t k = 0; k < n; ++k) {  // σ_{v,u_k} added to ψ_{u_k}
            SparseFunction<Real>& col = psi[ring[k]];
            col.emplace_back(v.idx(), centre);
            for (std::size_t l = 0; l < n; ++l) col.emplace_back(nc + ring[l], (base + inverse(k, l)) * s);
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
/// 4^−j/12): 4^−j/6 times the number of triangles at a on the diagonal, 4^−j/12 times the number
/// of triangles at the edge [a, b] (two inside, one on the boundary) off it.
SparseRows gram(const TriMesh& fine, int j);

/// The refinement matrix P of level j (#V(D^j) × #V(D^{j−1})): φ^{j−1}_v = φ^j_v + ½ Σ φ^j_u over
/// the new vertices u on v's edges, i.e. P = [I; P_N] with two entries ½ per new vertex.
SparseRows refinement_matrix(const TriMesh& coarse);

}  // namespace fhr::wavelet
