// FHR §5 — the filter bank: decomposition by one SPD solve per level, explicit reconstruction
// (see filter_bank.hpp).
#include <fhr/core/detail/contract.hpp>
#include <fhr/wavelet/detail/filter_bank.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include <fhr/core/errors.hpp>

namespace fhr::wavelet {
namespace {

using Rows3 = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using ConstView = Eigen::Map<const Rows3>;
using View = Eigen::Map<Rows3>;

// A #n×3 view of n points (Vec3 is three packed doubles).
ConstView view(std::span<const Vec3> p) {
    return ConstView(p.empty() ? nullptr : p.data()->data(), static_cast<Eigen::Index>(p.size()), 3);
}
View view(std::vector<Vec3>& p) {
    return View(p.empty() ? nullptr : p.data()->data(), static_cast<Eigen::Index>(p.size()), 3);
}

double max_abs(const Eigen::Ref<const Eigen::VectorXd>& v) { return v.size() == 0 ? 0.0 : v.cwiseAbs().maxCoeff(); }

// Jacobi-preconditioned conjugate gradients for A x = b, stopped on the true residual
// ‖b − A x‖_∞ ≤ tau (filter_bank.hpp): when the recurrence says so, the true residual is
// recomputed, and CG restarts from it if the recurrence had drifted.
int conjugate_gradients(const SparseRows& A, const Eigen::VectorXd& inverse_diagonal, const Eigen::VectorXd& b,
                        double tau, Eigen::VectorXd& x, double& residual) {
    x.setZero(b.size());
    Eigen::VectorXd r = b;
    residual = max_abs(r);
    if (residual <= tau) return 0;
    Eigen::VectorXd z = inverse_diagonal.cwiseProduct(r), p = z, Ap(b.size());
    double rz = r.dot(z);
    for (int it = 1; it <= max_cg_iterations; ++it) {
        Ap.noalias() = A * p;
        const double alpha = rz / p.dot(Ap);
        x += alpha * p;
        r -= alpha * Ap;
        if (max_abs(r) <= tau) {
            r = b - A * x;
            residual = max_abs(r);
            if (residual <= tau) return it;
            z = inverse_diagonal.cwiseProduct(r);
            p = z;
            rz = r.dot(z);
            continue;
        }
        z = inverse_diagonal.cwiseProduct(r);
        const double rz_next = r.dot(z);
        p = z + (rz_next / rz) * p;
        rz = rz_next;
    }
    residual = max_abs(b - A * x);
    return max_cg_iterations + 1;
}

LevelFilter build_level(const TriMesh& coarse, const TriMesh& fine, int j) {
    LevelFilter L;
    L.j = j;
    L.n_coarse = static_cast<std::uint32_t>(coarse.n_vertices());
    const auto nf = static_cast<Eigen::Index>(fine.n_vertices());
    const auto nc = static_cast<Eigen::Index>(L.n_coarse);
    const auto m = nf - nc;
    L.P = refinement_matrix(coarse);
    const std::vector<SparseFunction<double>> psi = prewavelets<double>(coarse, std::ldexp(1.0, j - 1));
    std::vector<Eigen::Triplet<double>> t;
    for (std::size_t k = 0; k < psi.size(); ++k)
        for (const auto& [w, q] : psi[k]) t.emplace_back(static_cast<int>(w), static_cast<int>(k), q);
    L.Q.resize(nf, m);
    L.Q.setFromTriplets(t.begin(), t.end());
    // A = Q_N − P_N Q_O.
    const SparseRows PNQO = L.P.bottomRows(m) * L.Q.topRows(nc);
    L.A = SparseRows(L.Q.bottomRows(m)) - PNQO;
    L.inverse_diagonal = L.A.diagonal().cwiseInverse();
    // ‖ψ_u‖² = Σ_ab q_a q_b G_ab, with q scattered into a dense scratch row.
    const SparseRows G = gram(fine, j);
    std::vector<double> scratch(fine.n_vertices(), 0.0);
    L.norm.resize(psi.size());
    for (std::size_t k = 0; k < psi.size(); ++k) {
        for (const auto& [w, q] : psi[k]) scratch[w] = q;
        double sum = 0;
        for (const auto& [a, qa] : psi[k])
            for (SparseRows::InnerIterator it(G, a); it; ++it)
                sum += qa * it.value() * scratch[static_cast<std::size_t>(it.col())];
        for (const auto& [w, q] : psi[k]) scratch[w] = 0.0;
        L.norm[k] = std::sqrt(sum);
    }
    return L;
}

}  // namespace

std::size_t Decomposition::coefficient_count() const {
    std::size_t n = 0;
    for (const auto& d : detail) n += d.size();
    return n;
}

FilterBank::FilterBank(const Refinement& r, Executor* executor) {
    levels_.resize(static_cast<std::size_t>(r.depth()));
    executor_or_default(executor).for_each(levels_.size(), 1, [&](std::size_t i) {
        levels_[i] = build_level(r.levels[i], r.levels[i + 1], static_cast<int>(i) + 1);
    });
}

LevelSolve FilterBank::decompose_level(int j, std::span<const Vec3> c, std::vector<Vec3>& coarse,
                                       std::vector<Vec3>& detail, Executor* executor) const {
    FHR_DCHECK(1 <= j && j <= depth());
    FHR_DCHECK(c.size() == static_cast<std::size_t>(level(j).P.rows()));
    const LevelFilter& L = level(j);
    const auto nc = static_cast<Eigen::Index>(L.n_coarse), m = static_cast<Eigen::Index>(L.m());
    const ConstView C = view(c);
    // b = c_N − P_N c_O: the new vertices' departure from the midpoints (exactly 0 when f^j ∈ S^{j−1}:
    // ½a + ½b rounds like ½(a + b), since halving is exact).
    const Rows3 b = C.bottomRows(m) - L.P.bottomRows(m) * C.topRows(nc);
    LevelSolve s;
    s.tolerance = cg_relative_tolerance * (C.size() == 0 ? 0.0 : C.cwiseAbs().maxCoeff());
    detail.assign(static_cast<std::size_t>(m), Vec3::Zero());
    View D = view(detail);
    // The three coordinates' systems are independent: one task each, checked in coordinate order.
    std::array<Eigen::VectorXd, 3> x;
    std::array<double, 3> residual{};
    std::array<int, 3> steps{};
    executor_or_default(executor).for_each(3, 1, [&](std::size_t k) {
        steps[k] = conjugate_gradients(L.A, L.inverse_diagonal, b.col(static_cast<Eigen::Index>(k)), s.tolerance, x[k],
                                       residual[k]);
    });
    for (int k = 0; k < 3; ++k) {
        if (steps[k] > max_cg_iterations)
            throw NumericalFailure("wavelet decomposition, level " + std::to_string(j) +
                                   ": conjugate gradients left the residual " + std::to_string(residual[k]) +
                                   " above " + std::to_string(s.tolerance) + " after " +
                                   std::to_string(max_cg_iterations) + " steps");
        D.col(k) = x[k];
        s.iterations = std::max(s.iterations, steps[k]);
        s.residual = std::max(s.residual, residual[k]);
    }
    coarse.assign(static_cast<std::size_t>(nc), Vec3::Zero());
    view(coarse) = C.topRows(nc) - L.Q.topRows(nc) * D;
    return s;
}

Decomposition FilterBank::decompose(std::span<const Vec3> f, Executor* executor) const {
    Decomposition out;
    out.detail.resize(levels_.size());
    out.solves.resize(levels_.size());
    std::vector<Vec3> c(f.begin(), f.end()), next;
    for (int j = depth(); j >= 1; --j) {
        out.solves[static_cast<std::size_t>(j - 1)] =
            decompose_level(j, c, next, out.detail[static_cast<std::size_t>(j - 1)], executor);
        c.swap(next);
    }
    out.coarse = std::move(c);
    return out;
}

std::vector<Vec3> FilterBank::reconstruct_level(int j, std::span<const Vec3> coarse, std::span<const Vec3> detail,
                                                Executor* executor) const {
    const LevelFilter& L = level(j);
    std::vector<Vec3> c(static_cast<std::size_t>(L.P.rows()));
    const ConstView C = view(coarse), Dd = view(detail);
    View out = view(c);
    // Row r of the result is row r of P times c^{j−1} plus row r of Q times d^{j−1}, whichever
    // block it is computed in (P and Q are stored by rows).
    for_each_block(executor_or_default(executor), static_cast<std::size_t>(L.P.rows()), 16384, 1,
                   [&](std::size_t first, std::size_t end) {
                       const auto row = static_cast<Eigen::Index>(first),
                                  count = static_cast<Eigen::Index>(end - first);
                       out.middleRows(row, count) = L.P.middleRows(row, count) * C + L.Q.middleRows(row, count) * Dd;
                   });
    return c;
}

std::vector<Vec3> FilterBank::reconstruct(const Decomposition& d, Executor* executor) const {
    FHR_DCHECK(d.detail.size() == static_cast<std::size_t>(depth()));
    std::vector<Vec3> c = d.coarse;
    for (int j = 1; j <= depth(); ++j) c = reconstruct_level(j, c, d.detail[static_cast<std::size_t>(j - 1)], executor);
    return c;
}

}  // namespace fhr::wavelet
