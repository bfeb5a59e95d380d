// FHR §5 — the Floater–Quak prewavelets are orthogonal to S^{j−1} (spec/wavelet.md WAV-3): for
// every new vertex u and every coarse vertex w, ⟨ψ_u, φ^{j−1}_w⟩ = 0, in double and in 100-digit
// arithmetic (boost::multiprecision), on bipyramids with a vertex of each valence 3..12 and on
// random domains; and with boundary (WAV-12): open fans with a boundary vertex of t = 1..12
// triangles and random domains with boundary loops and several components. The inner product here
// is integrated triangle by triangle from the mass matrix of ⟨f,g⟩ = Σ_T 1/a(T) ∫_T f g,
// independently of the library's gram().
#include <catch2/catch.hpp>
#include <rapidcheck/catch.h>

#include <boost/multiprecision/cpp_bin_float.hpp>

#include <cmath>
#include <map>
#include <set>

#include <fhr/wavelet/detail/prewavelet.hpp>
#include <fhr/wavelet/refine.hpp>
#include "wavelet_support.hpp"

using namespace fhr;
using wavelet::SparseFunction;

namespace {

using Real100 = boost::multiprecision::number<boost::multiprecision::cpp_bin_float<100>, boost::multiprecision::et_off>;

template <class Real>
using Coefficients = std::map<std::uint32_t, Real>;

// 12·4^j ⟨f, g⟩ as a function of g: on each triangle of D^j the mass matrix [2 1 1; 1 2 1; 1 1 2]
// (∫_τ φ_a φ_b = a(τ)(1 + δ_ab)/12 and a(τ)/a(T) = 4^−j; the factor does not change a cosine).
template <class Real>
Coefficients<Real> apply_mass(const TriMesh& fine, const std::vector<std::vector<std::uint32_t>>& faces_of,
                              const Coefficients<Real>& f) {
    std::set<std::uint32_t> faces;
    for (const auto& [v, x] : f) faces.insert(faces_of[v].begin(), faces_of[v].end());
    Coefficients<Real> out;
    for (std::uint32_t g : faces) {
        const auto c = fine.face_vertices(FaceId(g));
        for (int a = 0; a < 3; ++a) {
            const auto fa = f.find(c[a].idx());
            if (fa == f.end()) continue;
            for (int b = 0; b < 3; ++b) out[c[b].idx()] += fa->second * Real(a == b ? 2 : 1);
        }
    }
    return out;
}

template <class Real>
Real dot(const Coefficients<Real>& x, const Coefficients<Real>& y) {
    Real s(0);
    for (const auto& [v, a] : x)
        if (const auto it = y.find(v); it != y.end()) s += a * it->second;
    return s;
}

// The coarse hat φ^{j−1}_w in the fine basis: 1 at w, ½ at its fine neighbours (all new).
template <class Real>
Coefficients<Real> coarse_hat(const TriMesh& fine, VertexId w) {
    Coefficients<Real> p{{w.idx(), Real(1)}};
    fine.for_each_outgoing(w, [&](HalfedgeId h) { p[fine.to(h).idx()] = Real(1) / Real(2); });
    return p;
}

struct Orthogonality {
    double max_cosine = 0;  ///< max |⟨ψ_u, φ_w⟩| / (‖ψ_u‖ ‖φ_w‖) over all pairs
    std::size_t pairs = 0;  ///< pairs with overlapping supports (all others are 0 structurally)
};

// Every pair (u, w) between D^{j−1} = coarse and D^j = fine.
template <class Real>
Orthogonality orthogonality(const TriMesh& coarse, const TriMesh& fine, int j) {
    using std::abs;
    using std::sqrt;
    std::vector<std::vector<std::uint32_t>> faces_of(fine.n_vertices());
    for (FaceId g : fine.faces())
        for (VertexId v : fine.face_vertices(g)) faces_of[v.idx()].push_back(g.idx());
    const std::uint32_t nc = static_cast<std::uint32_t>(coarse.n_vertices());
    Real scale(1);
    for (int i = 1; i < j; ++i) scale *= Real(2);
    const std::vector<SparseFunction<Real>> psi = wavelet::prewavelets<Real>(coarse, scale);
    REQUIRE(psi.size() == coarse.n_edges());
    Orthogonality o;
    Real worst(0);
    for (const SparseFunction<Real>& column : psi) {
        const Coefficients<Real> q(column.begin(), column.end());
        const Coefficients<Real> Gq = apply_mass(fine, faces_of, q);
        const Real qq = dot(q, Gq);
        std::set<std::uint32_t> candidates;  // coarse w whose hat meets the support of Gq
        for (const auto& [a, x] : Gq) {
            if (a < nc) {
                candidates.insert(a);
            } else {
                const HalfedgeId h = TriMesh::halfedge(EdgeId(a - nc), 0);
                candidates.insert(coarse.from(h).idx());
                candidates.insert(coarse.to(h).idx());
            }
        }
        for (std::uint32_t w : candidates) {
            const Coefficients<Real> p = coarse_hat<Real>(fine, VertexId(w));
            const Real pp = dot(p, apply_mass(fine, faces_of, p));
            const Real cosine = abs(dot(Gq, p)) / sqrt(qq * pp);
            if (cosine > worst) worst = cosine;
            ++o.pairs;
        }
    }
    o.max_cosine = static_cast<double>(worst);
    return o;
}

}  // namespace

TEST_CASE("WAV-3: θ_n is the inverse of the circulant (1, 5, 1), n = 3..12, in double and 100 digits",
          "[unit][wavelet]") {
    for (std::size_t n = 3; n <= 12; ++n) {
        for (std::size_t k = 0; k < n; ++k) {
            // Row k of C_n θ_n: θ(k−1, l) + 5θ(k, l) + θ(k+1, l) against δ_kl, for l = 0.
            auto row = [&](auto zero) {
                using Real = decltype(zero);
                auto th = [&](std::size_t a, std::size_t b) { return wavelet::theta<Real>(n, a > b ? a - b : b - a); };
                return th((k + n - 1) % n, 0) + Real(5) * th(k, 0) + th((k + 1) % n, 0) - Real(k == 0 ? 1 : 0);
            };
            CHECK(std::abs(row(0.0)) <= 1e-15);
            CHECK(abs(row(Real100(0))) <= Real100(1e-95));
        }
    }
}

TEST_CASE(
    "WAV-12: θ^∂_t is the inverse of the tridiagonal (1, 5, 1) with corners 5/2, t = 1..12, in double and 100 digits",
    "[unit][wavelet]") {
    for (std::size_t t = 1; t <= 12; ++t) {
        for (std::size_t k = 0; k <= t; ++k) {
            // Row k of T_t θ^∂_t against δ_kl, for every column l.
            auto worst = [&](auto zero) {
                using Real = decltype(zero);
                using std::abs;
                auto T = [&](std::size_t a, std::size_t b) {
                    if (a == b) return Real(a == 0 || a == t ? 5 : 10) / Real(2);
                    return Real((a > b ? a - b : b - a) == 1 ? 1 : 0);
                };
                Real w(0);
                for (std::size_t l = 0; l <= t; ++l) {
                    Real row = -Real(k == l ? 1 : 0);
                    for (std::size_t i = 0; i <= t; ++i) row += T(k, i) * wavelet::theta_boundary<Real>(t, i, l);
                    if (abs(row) > w) w = abs(row);
                }
                return w;
            };
            CHECK(worst(0.0) <= 1e-15);
            CHECK(worst(Real100(0)) <= Real100(1e-95));
        }
    }
}

TEST_CASE(
    "WAV-3, WAV-12: the Gram matrix and P match the per-triangle mass matrix and the coarse hats, closed and open",
    "[unit][wavelet]") {
    const TriMesh D = GENERATE(test::bipyramid(7), test::open_fan(5));
    const wavelet::Refinement r = wavelet::refine(D, 2);
    const TriMesh &coarse = r.levels[1], &fine = r.levels[2];
    std::vector<std::vector<std::uint32_t>> faces_of(fine.n_vertices());
    for (FaceId g : fine.faces())
        for (VertexId v : fine.face_vertices(g)) faces_of[v.idx()].push_back(g.idx());
    const wavelet::SparseRows G = wavelet::gram(fine, 2);
    for (VertexId a : fine.vertices()) {
        const Coefficients<double> Ga = apply_mass<double>(fine, faces_of, {{a.idx(), 1.0}});
        for (const auto& [b, x] : Ga) CHECK(G.coeff(a.idx(), b) == Approx(x / (12.0 * 16.0)).epsilon(1e-15));
        CHECK(G.row(a.idx()).nonZeros() == static_cast<Eigen::Index>(Ga.size()));
    }
    const wavelet::SparseRows P = wavelet::refinement_matrix(coarse);
    for (VertexId w : coarse.vertices()) {
        const Coefficients<double> p = coarse_hat<double>(fine, w);
        Eigen::Index nonzeros = 0;
        for (Eigen::Index row = 0; row < P.rows(); ++row)
            if (P.coeff(row, w.idx()) != 0) {
                ++nonzeros;
                CHECK(P.coeff(row, w.idx()) == p.at(static_cast<std::uint32_t>(row)));
            }
        CHECK(nonzeros == static_cast<Eigen::Index>(p.size()));
    }
}

namespace {

// WAV-3/WAV-12 on D refined to levels 1..3: every pair orthogonal in double (1e−14) and, at levels
// 1 and 2, in 100 digits (1e−60); the bounds are argued where the test cases use them.
void check_levels_1_to_3(const TriMesh& D) {
    const wavelet::Refinement r = wavelet::refine(D, 3);
    for (int j = 1; j <= 3; ++j) {
        const Orthogonality d = orthogonality<double>(r.levels[j - 1], r.levels[j], j);
        INFO("level " << j << ": " << d.pairs << " pairs, max cosine " << d.max_cosine);
        CHECK(d.pairs > 0);
        CHECK(d.max_cosine <= 1e-14);
        if (j <= 2) {
            const Orthogonality h = orthogonality<Real100>(r.levels[j - 1], r.levels[j], j);
            INFO("100 digits: max cosine " << h.max_cosine);
            CHECK(h.pairs == d.pairs);
            CHECK(h.max_cosine <= 1e-60);
        }
    }
}

}  // namespace

TEST_CASE("WAV-3: ⟨ψ_u, φ^{j−1}_w⟩ = 0 for every pair on bipyramids of valence 3..12, levels 1..3",
          "[property][wavelet]") {
    // Double: each inner product sums about 40 products of coefficients known to a few ulps, so
    // its error relative to ‖ψ_u‖‖φ_w‖ is a few times 40·2⁻⁵³ ≈ 4.4e−15: 1e−14 bounds it.
    // 100 digits: the same argument with 2^−332 ≈ 1e−100 leaves 40 orders of magnitude below 1e−60.
    for (unsigned n = 3; n <= 12; ++n) {
        INFO("valence " << n);
        check_levels_1_to_3(test::bipyramid(n));
    }
}

TEST_CASE("WAV-3: ⟨ψ_u, φ^{j−1}_w⟩ = 0 for every pair on random domains, in double and 100 digits",
          "[property][wavelet]") {
    rc::prop("random closed D (genus 0..2), levels 1..2", [] {
        const fhr::testing::GeneratedMesh D = *test::gen_domain(160);
        const int j = *rc::gen::inRange(1, 3);
        const wavelet::Refinement r = wavelet::refine(D, j);
        const Orthogonality d = orthogonality<double>(r.levels[j - 1], r.levels[j], j);
        RC_LOG() << "double: " << d.pairs << " pairs, max cosine " << d.max_cosine << "\n";
        RC_ASSERT(d.max_cosine <= 1e-14);
        const Orthogonality h = orthogonality<Real100>(r.levels[j - 1], r.levels[j], j);
        RC_LOG() << "100 digits: max cosine " << h.max_cosine << "\n";
        RC_ASSERT(h.max_cosine <= 1e-60);
    });
}

TEST_CASE(
    "WAV-12: ⟨ψ_u, φ^{j−1}_w⟩ = 0 for every pair on open fans with a boundary vertex of t = 1..12 triangles, levels "
    "1..3",
    "[property][wavelet]") {
    // The same bounds as on the bipyramids (each inner product sums at most about 40 products).
    for (unsigned t = 1; t <= 12; ++t) {
        INFO("t = " << t);
        check_levels_1_to_3(test::open_fan(t));
    }
}

TEST_CASE(
    "WAV-12: ⟨ψ_u, φ^{j−1}_w⟩ = 0 on random domains with boundary and several components, in double and 100 digits",
    "[property][wavelet]") {
    rc::prop("random D: 1..5 boundary loops, 1..3 components of genus 0..2, levels 1..2", [] {
        const test::OpenDomain D = *test::gen_open_domain(100);
        const int j = *rc::gen::inRange(1, 3);
        const wavelet::Refinement r = wavelet::refine(D, j);
        const Orthogonality d = orthogonality<double>(r.levels[j - 1], r.levels[j], j);
        RC_LOG() << "double: " << d.pairs << " pairs, max cosine " << d.max_cosine << "\n";
        RC_ASSERT(d.max_cosine <= 1e-14);
        const Orthogonality h = orthogonality<Real100>(r.levels[j - 1], r.levels[j], j);
        RC_LOG() << "100 digits: max cosine " << h.max_cosine << "\n";
        RC_ASSERT(h.max_cosine <= 1e-60);
    });
}
