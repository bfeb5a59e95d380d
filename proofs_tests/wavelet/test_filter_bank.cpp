// FHR §5 — the filter bank (spec/wavelet.md WAV-4, WAV-5, WAV-6): the round trip
// reconstruct(decompose(f)) = f, the coarse part is the orthogonal projection onto S^{j−1}, the
// decomposition matrix is symmetric positive definite with spectrum in [2s/7, 2s], and a function
// already in S^k has no wavelet coefficients at levels ≥ k.
#include <catch2/catch.hpp>
#include <rapidcheck/catch.h>

#include <Eigen/Dense>

#include <cmath>

#include <fhr/wavelet/filter_bank.hpp>
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

// A = s Σ_v E_v (6/(7n_v) 𝟙𝟙ᵀ + C_{n_v}⁻¹) E_vᵀ (the theorem of filter_bank.hpp), built from the
// rings of D^{j−1} directly.
Eigen::MatrixXd closed_form(const TriMesh& coarse, int j) {
    const double s = std::ldexp(1.0, j - 1);
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(coarse.n_edges()), static_cast<Eigen::Index>(coarse.n_edges()));
    for (VertexId v : coarse.vertices()) {
        std::vector<Eigen::Index> ring;
        coarse.for_each_outgoing(v, [&](HalfedgeId h) { ring.push_back(TriMesh::edge(h).idx()); });
        const std::size_t n = ring.size();
        for (std::size_t k = 0; k < n; ++k)
            for (std::size_t l = 0; l < n; ++l)
                A(ring[k], ring[l]) += s * (6.0 / (7.0 * static_cast<double>(n)) + wavelet::theta<double>(n, k > l ? k - l : l - k));
    }
    return A;
}

}  // namespace

TEST_CASE("WAV-4: reconstruct(decompose(f)) = f to 1e-12 relative, random f on random domains, levels 1..4",
          "[property][wavelet]") {
    rc::prop("random D, J, f (coordinates up to 10^3 away from the origin)", [] {
        const int J = *rc::gen::inRange(1, 5);
        const fhr::testing::GeneratedMesh D = *test::gen_domain(max_faces_for(J));
        const Refinement r = wavelet::refine(D, J);
        const FilterBank bank(r);
        const double offset = *rc::gen::element(0.0, 1.0, 1e3);
        const std::vector<Vec3> f =
            test::random_points(r.finest().n_vertices(), *rc::gen::inRange<std::uint64_t>(0, 1u << 30), 1.0, Vec3::Constant(offset));
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
    });
}

TEST_CASE("WAV-4: the coarse part is the orthogonal projection of f^j onto S^{j−1}", "[property][wavelet]") {
    // Normal equations Pᵀ G (c^j − P c^{j−1}) = 0: each entry sums about 30 terms of size
    // ‖G‖·‖c‖, with c^{j−1} from a solve of residual 1e−13‖c‖: 1e−12 of ‖|Pᵀ| |G|‖_∞‖c‖_∞ bounds it.
    rc::prop("random D, one level", [] {
        const fhr::testing::GeneratedMesh D = *test::gen_domain(400);
        const int j = *rc::gen::inRange(1, 3);
        const Refinement r = wavelet::refine(D, j);
        const FilterBank bank(r);
        const std::vector<Vec3> c = test::random_points(r.levels[j].n_vertices(), *rc::gen::inRange<std::uint64_t>(0, 1u << 30));
        std::vector<Vec3> coarse, detail;
        bank.decompose_level(j, c, coarse, detail);
        const wavelet::SparseRows G = wavelet::gram(r.levels[j], j);
        const wavelet::SparseRows& P = bank.level(j).P;
        const Rows3 normal = P.transpose() * (G * (as_rows(c) - P * as_rows(coarse)));
        const wavelet::SparseRows absP = P.cwiseAbs(), absG = G.cwiseAbs();
        const Eigen::VectorXd scale = absP.transpose() * (absG * Eigen::VectorXd::Ones(G.rows()));
        RC_ASSERT(normal.cwiseAbs().maxCoeff() <= 1e-12 * scale.maxCoeff() * max_abs(c));
    });
}

TEST_CASE("WAV-5: the decomposition matrix is symmetric positive definite, spectrum in [2s/7, 2s]", "[property][wavelet]") {
    rc::prop("random D and bipyramids of valence 3..12, levels 1..2", [] {
        const bool random = *rc::gen::arbitrary<bool>();
        const TriMesh D = random ? static_cast<TriMesh>(*test::gen_domain(120)) : test::bipyramid(*rc::gen::inRange(3u, 13u));
        const int j = *rc::gen::inRange(1, 3);
        const Refinement r = wavelet::refine(D, j);
        const FilterBank bank(r);
        const wavelet::SparseRows& A = bank.level(j).A;
        const Eigen::MatrixXd dense(A);
        RC_ASSERT(dense == Eigen::MatrixXd(dense.transpose()));  // exactly: one term per off-diagonal entry
        const Eigen::MatrixXd expected = closed_form(r.levels[j - 1], j);
        const double s = std::ldexp(1.0, j - 1);
        RC_ASSERT((dense - expected).cwiseAbs().maxCoeff() <= 1e-15 * s);
        const Eigen::VectorXd lambda = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(dense).eigenvalues();
        RC_LOG() << "m = " << dense.rows() << ", spectrum [" << lambda.minCoeff() << ", " << lambda.maxCoeff() << "], s = " << s << "\n";
        // Eigenvalues of a symmetric matrix move by at most ‖perturbation‖ ≈ 1e−15·s under rounding.
        RC_ASSERT(lambda.minCoeff() >= 2 * s / 7 - 1e-12 * s);
        RC_ASSERT(lambda.maxCoeff() <= 2 * s + 1e-12 * s);
    });
}

TEST_CASE("WAV-6: a function already in S^k has every wavelet coefficient at levels ≥ k exactly zero", "[property][wavelet]") {
    // f^J = P_J ⋯ P_{k+1} c^k: at each level c_N − P_N c_O is exactly 0 (½a + ½b and ½(a + b) round
    // alike: halving is exact), so CG returns d = 0 and c^{j−1} = c_O − Q_O·0 = c_O bit for bit.
    rc::prop("random D, J, k < J, c^k", [] {
        const int J = *rc::gen::inRange(1, 4);
        const int k = *rc::gen::inRange(0, J);
        const fhr::testing::GeneratedMesh D = *test::gen_domain(max_faces_for(J));
        const Refinement r = wavelet::refine(D, J);
        const FilterBank bank(r);
        const std::vector<Vec3> ck = test::random_points(r.levels[k].n_vertices(), *rc::gen::inRange<std::uint64_t>(0, 1u << 30));
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
    });
}

TEST_CASE("WAV-4: the fandisk-sized domain (114 faces) at J = 3 decomposes with 3,591 coefficients", "[unit][wavelet]") {
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
