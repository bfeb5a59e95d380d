// FHR §5 — the filter bank (spec/wavelet.md WAV-4, WAV-5, WAV-6, and WAV-13 with boundary): the
// round trip reconstruct(decompose(f)) = f, the coarse part is the orthogonal projection onto
// S^{j−1}, the decomposition matrix is symmetric positive definite with spectrum in [2s/7, 2s]
// ([2s/7, 4s] with boundary), and a function already in S^k has no wavelet coefficients at
// levels ≥ k; on closed domains and on domains with boundary and several components.
#include <catch2/catch.hpp>
#include <rapidcheck/catch.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

#include <fhr/core/executor.hpp>
#include <fhr/wavelet/detail/filter_bank.hpp>
#include "wavelet_support.hpp"

using namespace fhr;
using wavelet::Decomposition;
using wavelet::FilterBank;
using wavelet::Refinement;

namespace {

using Rows3 = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

Rows3 as_rows(const std::vector<Vec3>& p) {
    Rows3 m(static_cast<Eigen::Index>(p.size()), 3);
    for (std::size_t i = 0; i < p.size(); ++i) m.row(static_cast<Eigen::Index>(i)) = p[i].transpose();
    return m;
}

double max_abs(const std::vector<Vec3>& p) {
    double m = 0;
    for (const Vec3& x : p) m = std::max(m, x.cwiseAbs().maxCoeff());
    return m;
}

// Domain sizes per level so that D^J stays below ~25,000 faces.
std::size_t max_faces_for(int J) { return J <= 1 ? 600 : J == 2 ? 300 : J == 3 ? 150 : 100; }
// The same for each of up to three components of a domain with boundary (genus 2 needs 100).
std::size_t max_component_faces_for(int J) { return J <= 1 ? 200 : J == 2 ? 100 : J == 3 ? 100 : 40; }

// A = s Σ_v E_v B_v E_vᵀ (the theorem of filter_bank.hpp), built from the rings of D^{j−1}
// directly: B_v = 6/(7t) 𝟙𝟙ᵀ + C_t⁻¹ at an inner vertex with t triangles (C_t⁻¹ from θ), and
// 6/(7t) 𝟙𝟙ᵀ + T_t⁻¹ at a boundary vertex, T_t⁻¹ here a dense LU inverse of the tridiagonal
// (1, 5, 1) with corners 5/2 (independent of the library's θ^∂; entries within a few ulps, as
// κ(T_t) ≤ 14/3).
Eigen::MatrixXd closed_form(const TriMesh& coarse, int j) {
    const double s = std::ldexp(1.0, j - 1);
    Eigen::MatrixXd A =
        Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(coarse.n_edges()), static_cast<Eigen::Index>(coarse.n_edges()));
    for (VertexId v : coarse.vertices()) {
        std::vector<Eigen::Index> ring;
        coarse.for_each_outgoing(v, [&](HalfedgeId h) { ring.push_back(TriMesh::edge(h).idx()); });
        const std::size_t n = ring.size();
        const bool open = coarse.is_boundary(v);
        const std::size_t t = open ? n - 1 : n;
        Eigen::MatrixXd T = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
        for (Eigen::Index k = 0; k < T.rows(); ++k) {
            T(k, k) = k == 0 || k + 1 == T.rows() ? 2.5 : 5.0;
            if (k > 0) T(k, k - 1) = T(k - 1, k) = 1;
        }
        const Eigen::MatrixXd T_inverse = T.inverse();
        for (std::size_t k = 0; k < n; ++k)
            for (std::size_t l = 0; l < n; ++l) {
                const double inverse = open ? T_inverse(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(l))
                                            : wavelet::theta<double>(n, k > l ? k - l : l - k);
                A(ring[k], ring[l]) += s * (6.0 / (7.0 * static_cast<double>(t)) + inverse);
            }
    }
    return A;
}

// A domain for level J: closed, or with boundary and several components.
TriMesh domain_for(bool open, int J) {
    return test::draw_domain(open, open ? max_component_faces_for(J) : max_faces_for(J));
}

// WAV-4, WAV-13: the round trip within 1e−12 of ‖f‖_∞ and every solve within its τ_j.
void check_round_trip(const TriMesh& D, int J) {
    const Refinement r = wavelet::refine(D, J);
    const FilterBank bank(r);
    const double offset = *rc::gen::element(0.0, 1.0, 1e3);
    const std::vector<Vec3> f = test::random_points(
        r.finest().n_vertices(), *rc::gen::inRange<std::uint64_t>(0, 1u << 30), 1.0, Vec3::Constant(offset));
    const Decomposition d = bank.decompose(f);
    RC_ASSERT(d.coarse.size() == D.n_vertices());
    RC_ASSERT(d.coefficient_count() == r.finest().n_vertices() - D.n_vertices());
    for (const wavelet::LevelSolve& s : d.solves) {
        RC_LOG() << "CG " << s.iterations << " steps, residual " << s.residual << " <= " << s.tolerance << "\n";
        RC_ASSERT(s.residual <= s.tolerance);
    }
    const std::vector<Vec3> back = bank.reconstruct(d);
    double err = 0;
    for (std::size_t v = 0; v < f.size(); ++v) err = std::max(err, (back[v] - f[v]).cwiseAbs().maxCoeff());
    RC_LOG() << "round trip " << err << " of " << max_abs(f) << "\n";
    RC_ASSERT(err <= 1e-12 * max_abs(f));
}

// WAV-4, WAV-13: Pᵀ G (c^j − P c^{j−1}) = 0. Each entry sums about 30 terms of size ‖G‖·‖c‖,
// with c^{j−1} from a solve of residual 1e−13‖c‖: 1e−12 of ‖|Pᵀ| |G|‖_∞‖c‖_∞ bounds it.
void check_projection(const TriMesh& D, int j) {
    const Refinement r = wavelet::refine(D, j);
    const FilterBank bank(r);
    const std::vector<Vec3> c =
        test::random_points(r.levels[j].n_vertices(), *rc::gen::inRange<std::uint64_t>(0, 1u << 30));
    std::vector<Vec3> coarse, detail;
    bank.decompose_level(j, c, coarse, detail);
    const wavelet::SparseRows G = wavelet::gram(r.levels[j], j);
    const wavelet::SparseRows& P = bank.level(j).P;
    const Rows3 normal = P.transpose() * (G * (as_rows(c) - P * as_rows(coarse)));
    const wavelet::SparseRows absP = P.cwiseAbs(), absG = G.cwiseAbs();
    const Eigen::VectorXd scale = absP.transpose() * (absG * Eigen::VectorXd::Ones(G.rows()));
    RC_ASSERT(normal.cwiseAbs().maxCoeff() <= 1e-12 * scale.maxCoeff() * max_abs(c));
}

// WAV-5, WAV-13: A symmetric, equal to its closed form, spectrum in [2s/7, upper·s].
void check_decomposition_matrix(const TriMesh& D, int j, double upper) {
    const Refinement r = wavelet::refine(D, j);
    const FilterBank bank(r);
    const wavelet::SparseRows& A = bank.level(j).A;
    const Eigen::MatrixXd dense(A);
    RC_ASSERT(dense == Eigen::MatrixXd(dense.transpose()));  // exactly: one term per off-diagonal entry
    const Eigen::MatrixXd expected = closed_form(r.levels[j - 1], j);
    const double s = std::ldexp(1.0, j - 1);
    // Closed: the same θ formula, 1e−15·s (a few ulps); boundary: against an LU inverse, whose
    // entries of size ≤ 1 differ by a few ulps times κ(T_t) ≤ 14/3: 1e−14·s.
    RC_ASSERT((dense - expected).cwiseAbs().maxCoeff() <= (D.is_closed() ? 1e-15 : 1e-14) * s);
    const Eigen::VectorXd lambda = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(dense).eigenvalues();
    RC_LOG() << "m = " << dense.rows() << ", spectrum [" << lambda.minCoeff() << ", " << lambda.maxCoeff()
             << "], s = " << s << "\n";
    // Eigenvalues of a symmetric matrix move by at most ‖perturbation‖ ≈ 1e−15·s under rounding.
    RC_ASSERT(lambda.minCoeff() >= 2 * s / 7 - 1e-12 * s);
    RC_ASSERT(lambda.maxCoeff() <= upper * s + 1e-12 * s);
}

// WAV-6, WAV-13: f^J = P_J ⋯ P_{k+1} c^k: at each level c_N − P_N c_O is exactly 0 (½a + ½b and
// ½(a + b) round alike: halving is exact), so CG returns d = 0 and c^{j−1} = c_O − Q_O·0 = c_O
// bit for bit.
void check_coarse_function(const TriMesh& D, int J, int k) {
    const Refinement r = wavelet::refine(D, J);
    const FilterBank bank(r);
    const std::vector<Vec3> ck =
        test::random_points(r.levels[k].n_vertices(), *rc::gen::inRange<std::uint64_t>(0, 1u << 30));
    std::vector<Vec3> f = ck;
    for (int j = k + 1; j <= J; ++j) {
        const std::vector<Vec3> zero(bank.level(j).m(), Vec3::Zero());
        f = bank.reconstruct_level(j, f, zero);
    }
    const Decomposition d = bank.decompose(f);
    for (int level = k; level < J; ++level)
        for (const Vec3& x : d.detail[static_cast<std::size_t>(level)]) RC_ASSERT(x == Vec3::Zero());
    // Decomposing down to level k gives c^k back exactly.
    std::vector<Vec3> c = f, coarse, detail;
    for (int j = J; j > k; --j) {
        bank.decompose_level(j, c, coarse, detail);
        c = coarse;
    }
    RC_ASSERT(c == ck);
}

}  // namespace

TEST_CASE("WAV-4: reconstruct(decompose(f)) = f to 1e-12 relative, random f on random domains, levels 1..4",
          "[property][wavelet]") {
    rc::prop("random D, J, f (coordinates up to 10^3 away from the origin)", [] {
        const int J = *rc::gen::inRange(1, 5);
        check_round_trip(domain_for(false, J), J);
    });
}

TEST_CASE("WAV-13: the round trip to 1e-12 relative with boundary and several components, levels 1..4",
          "[property][wavelet]") {
    rc::prop("random D (1..5 boundary loops, 1..3 components), J, f (up to 10^3 away from the origin)", [] {
        const int J = *rc::gen::inRange(1, 5);
        check_round_trip(domain_for(true, J), J);
    });
}

TEST_CASE("WAV-13: the round trip on open fans with a boundary vertex of t = 1..12 triangles, J = 3",
          "[property][wavelet]") {
    rc::prop("open fan of t = 1..12 triangles, f",
             [] { check_round_trip(test::open_fan(*rc::gen::inRange(1u, 13u)), 3); });
}

TEST_CASE("WAV-4: the coarse part is the orthogonal projection of f^j onto S^{j−1}", "[property][wavelet]") {
    rc::prop("random D, one level", [] {
        const fhr::testing::GeneratedMesh D = *test::gen_domain(400);
        check_projection(D, *rc::gen::inRange(1, 3));
    });
}

TEST_CASE("WAV-13: the coarse part is the orthogonal projection with boundary and several components",
          "[property][wavelet]") {
    rc::prop("random D (1..5 boundary loops, 1..3 components), one level", [] {
        const test::OpenDomain D = *test::gen_open_domain(150);
        check_projection(D, *rc::gen::inRange(1, 3));
    });
}

TEST_CASE("WAV-5: the decomposition matrix is symmetric positive definite, spectrum in [2s/7, 2s]",
          "[property][wavelet]") {
    rc::prop("random D and bipyramids of valence 3..12, levels 1..2", [] {
        const bool random = *rc::gen::arbitrary<bool>();
        const TriMesh D =
            random ? static_cast<TriMesh>(*test::gen_domain(120)) : test::bipyramid(*rc::gen::inRange(3u, 13u));
        check_decomposition_matrix(D, *rc::gen::inRange(1, 3), 2);
    });
}

TEST_CASE("WAV-13: with boundary the decomposition matrix is s Σ_v E_v B_v E_vᵀ, spectrum in [2s/7, 4s]",
          "[property][wavelet]") {
    rc::prop("random D with boundary and several components, and open fans of t = 1..12, levels 1..2", [] {
        const bool random = *rc::gen::arbitrary<bool>();
        const TriMesh D =
            random ? static_cast<TriMesh>(*test::gen_open_domain(60)) : test::open_fan(*rc::gen::inRange(1u, 13u));
        check_decomposition_matrix(D, *rc::gen::inRange(1, 3), 4);
    });
}

TEST_CASE("WAV-13: one triangle: A = s(2I + ⅔𝟙𝟙ᵀ) at j = 1, spectrum {2s, 2s, 4s}: the bound 4s is attained",
          "[unit][wavelet]") {
    // By hand: each corner has t = 1 and B = 6/7 𝟙𝟙ᵀ + T_1⁻¹, T_1 = [5/2 1; 1 5/2], T_1⁻¹ =
    // [10 −4; −4 10]/21, so B = [4/3 2/3; 2/3 4/3]; every new vertex is in two corners' rings and
    // every pair of new vertices in one: A = 8/3 on the diagonal, 2/3 off it (s = 1).
    const TriMesh D = TriMesh::from_triangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, std::vector<Triangle>{{0, 1, 2}});
    const FilterBank bank(wavelet::refine(D, 1));
    const Eigen::MatrixXd A(bank.level(1).A);
    REQUIRE(A.rows() == 3);
    for (Eigen::Index a = 0; a < 3; ++a)
        for (Eigen::Index b = 0; b < 3; ++b) CHECK(A(a, b) == Approx(a == b ? 8.0 / 3.0 : 2.0 / 3.0).epsilon(1e-15));
    const Eigen::VectorXd lambda = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A).eigenvalues();
    CHECK(lambda.maxCoeff() == Approx(4).epsilon(1e-14));
    CHECK(lambda.minCoeff() == Approx(2).epsilon(1e-14));
}

TEST_CASE("WAV-6: a function already in S^k has every wavelet coefficient at levels ≥ k exactly zero",
          "[property][wavelet]") {
    rc::prop("random D, J, k < J, c^k", [] {
        const int J = *rc::gen::inRange(1, 4);
        const int k = *rc::gen::inRange(0, J);
        check_coarse_function(domain_for(false, J), J, k);
    });
}

TEST_CASE("WAV-13: with boundary too, a function already in S^k has no wavelet coefficients at levels ≥ k",
          "[property][wavelet]") {
    rc::prop("random D (1..5 boundary loops, 1..3 components), J, k < J, c^k", [] {
        const int J = *rc::gen::inRange(1, 4);
        const int k = *rc::gen::inRange(0, J);
        check_coarse_function(domain_for(true, J), J, k);
    });
}

TEST_CASE("WAV-4: the fandisk-sized domain (114 faces) at J = 3 decomposes with 3,591 coefficients",
          "[unit][wavelet]") {
    const TriMesh D = generate::random_closed_mesh({.genus = 0, .faces = 114, .seed = 3, .noise = 0.1});
    const Refinement r = wavelet::refine(D, 3);
    const FilterBank bank(r);
    // A smooth function: the domain's own geometric refinement pushed out radially.
    std::vector<Vec3> f = r.finest().positions();
    for (Vec3& x : f) x *= 1 + 0.1 * std::sin(3 * x.x());
    const Decomposition d = bank.decompose(f);
    CHECK(d.coefficient_count() == 3591);
    CHECK(d.detail[0].size() == 171);
    CHECK(d.detail[1].size() == 684);
    CHECK(d.detail[2].size() == 2736);
    const std::vector<Vec3> back = bank.reconstruct(d);
    double err = 0;
    for (std::size_t v = 0; v < f.size(); ++v) err = std::max(err, (back[v] - f[v]).cwiseAbs().maxCoeff());
    INFO("round trip error " << err << ", CG steps " << d.solves[0].iterations << ", " << d.solves[1].iterations << ", "
                             << d.solves[2].iterations);
    CHECK(err <= 1e-12 * max_abs(f));
}

TEST_CASE("WAV-4: the bank, decompose and reconstruct give the same numbers bit for bit on one and on three threads",
          "[unit][wavelet]") {
    // 20,482 vertices at J = 6: the finest level's rows make two blocks of 16,384 and more.
    const Refinement r = wavelet::refine(test::bipyramid(5), 6);
    REQUIRE(r.finest().n_vertices() > 16384);
    ThreadPool one(1), three(3);
    const std::vector<Vec3> f = test::random_points(r.finest().n_vertices(), 7, 1.0, Vec3::Zero());
    const FilterBank bank(r, &three), alone(r, &one);
    for (int j = 1; j <= bank.depth(); ++j) {
        CHECK(bank.level(j).norm == alone.level(j).norm);
        const wavelet::SparseRows &a = bank.level(j).A, &b = alone.level(j).A;
        REQUIRE(a.nonZeros() == b.nonZeros());
        CHECK(std::equal(a.valuePtr(), a.valuePtr() + a.nonZeros(), b.valuePtr()));
        CHECK(std::equal(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros(), b.innerIndexPtr()));
    }
    const Decomposition d = bank.decompose(f, &three), d1 = alone.decompose(f, &one);
    CHECK(d.coarse == d1.coarse);
    CHECK(d.detail == d1.detail);
    const std::vector<Vec3> a = bank.reconstruct(d, &one), b = bank.reconstruct(d, &three);
    REQUIRE(a.size() == r.finest().n_vertices());
    CHECK(a == b);
    // And each level's rows are P c^{j−1} + Q d^{j−1} as one product computes them.
    std::vector<Vec3> c = d.coarse;
    for (int j = 1; j <= bank.depth(); ++j) {
        const wavelet::LevelFilter& L = bank.level(j);
        const std::vector<Vec3>& detail = d.detail[static_cast<std::size_t>(j - 1)];
        Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> C(c.size(), 3), Dt(detail.size(), 3);
        for (std::size_t i = 0; i < c.size(); ++i) C.row(static_cast<Eigen::Index>(i)) = c[i].transpose();
        for (std::size_t i = 0; i < detail.size(); ++i) Dt.row(static_cast<Eigen::Index>(i)) = detail[i].transpose();
        const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> whole = L.P * C + L.Q * Dt;
        const std::vector<Vec3> level = bank.reconstruct_level(j, c, detail, &three);
        for (std::size_t i = 0; i < level.size(); ++i)
            REQUIRE(level[i] == whole.row(static_cast<Eigen::Index>(i)).transpose());
        c = level;
    }
    CHECK(c == a);
}
