// FHR §5 — Hausdorff distance between triangle meshes (spec/wavelet.md WAV-9): the closest point
// of a triangle, the tree search against brute force, the bracket lower ≤ h ≤ upper with
// upper − lower ≤ δ, and known distances.
#include <catch2/catch.hpp>
#include <rapidcheck/catch.h>

#include <cmath>
#include <numbers>
#include <random>
#include <tuple>

#include <fhr/wavelet/hausdorff.hpp>
#include "support/analytic_meshes.hpp"
#include "wavelet_support.hpp"

using namespace fhr;
using wavelet::TriangleTree;

namespace {

// Brute force: the smallest distance from p to any triangle.
double brute_distance(const Vec3& p, const std::vector<Vec3>& x, const std::vector<Triangle>& t) {
    double best = INFINITY;
    for (const Triangle& f : t)
        best = std::min(best, (closest_point_on_triangle(p, x[f[0]], x[f[1]], x[f[2]]) - p).norm());
    return best;
}

// A random icosphere A, its triangles, and the positions of a copy with every vertex moved by up
// to 0.05 (rapidcheck draws).
std::tuple<TriMesh, std::vector<Triangle>, std::vector<Vec3>> noisy_sphere() {
    TriMesh A = test::icosphere(*rc::gen::inRange(1, 3));
    std::vector<Triangle> t = A.triangles();
    std::vector<Vec3> bx = A.positions();
    const std::vector<Vec3> n = test::random_points(bx.size(), *rc::gen::inRange<std::uint64_t>(0, 1u << 30), 0.05);
    for (std::size_t v = 0; v < bx.size(); ++v) bx[v] += n[v];
    return {std::move(A), std::move(t), std::move(bx)};
}

}  // namespace

TEST_CASE("WAV-9: the closest point lies on the triangle and no point of a dense sample is closer",
          "[property][wavelet]") {
    rc::prop("random triangles (some nearly degenerate) and points", [] {
        std::mt19937_64 rng(*rc::gen::inRange<std::uint64_t>(0, 1u << 30));
        std::uniform_real_distribution<double> u(-1, 1);
        auto point = [&] { return Vec3(u(rng), u(rng), u(rng)); };
        const Vec3 a = point(), b = point();
        const Vec3 c = *rc::gen::arbitrary<bool>() ? point() : Vec3(a + 0.5 * (b - a) + 1e-9 * point());
        const Vec3 p = 2 * point();
        const Vec3 q = closest_point_on_triangle(p, a, b, c);
        const double d = (q - p).norm();
        // q = a + s(b − a) + t(c − a) with s, t ≥ 0, s + t ≤ 1 (within rounding): it is on the triangle
        // when the distance to the triangle's plane and to its sides is negligible; check by sampling.
        const int k = 60;
        double dense = INFINITY, nearest_sample_to_q = INFINITY;
        for (int i = 0; i <= k; ++i)
            for (int j = 0; i + j <= k; ++j) {
                const Vec3 s = a + (double(i) / k) * (b - a) + (double(j) / k) * (c - a);
                dense = std::min(dense, (s - p).norm());
                nearest_sample_to_q = std::min(nearest_sample_to_q, (s - q).norm());
            }
        const double L = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
        RC_ASSERT(d <= dense + 1e-14);                                       // no sample of the triangle is closer
        RC_ASSERT(nearest_sample_to_q <= L / (k * std::sqrt(3.0)) + 1e-14);  // q is on the triangle
    });
}

TEST_CASE("WAV-9: the tree's closest point equals brute force over all triangles", "[property][wavelet]") {
    rc::prop("random closed meshes, random query points and hints", [] {
        const fhr::testing::GeneratedMesh m = *test::gen_domain(600);
        const std::vector<Vec3>& x = m.positions();
        const std::vector<Triangle> t = m.triangles();
        const TriangleTree tree(x, t);
        std::mt19937_64 rng(*rc::gen::inRange<std::uint64_t>(0, 1u << 30));
        std::uniform_real_distribution<double> u(-4, 4);
        std::uniform_int_distribution<std::uint32_t> hint(0, static_cast<std::uint32_t>(t.size() - 1));
        for (int q = 0; q < 50; ++q) {
            const Vec3 p(u(rng), u(rng), u(rng));
            const TriangleTree::Hit h = tree.closest(p, hint(rng));
            RC_ASSERT(h.distance == brute_distance(p, x, t));
            RC_ASSERT((h.point - p).norm() == h.distance);
        }
    });
}

TEST_CASE("WAV-9: a tree refitted to moved vertices answers as brute force over the moved triangles",
          "[property][wavelet]") {
    rc::prop("random closed meshes, every vertex moved by up to a chosen amount, random queries", [] {
        const fhr::testing::GeneratedMesh m = *test::gen_domain(600);
        const std::vector<Triangle> t = m.triangles();
        const TriangleTree tree(m.positions(), t);
        // From a small displacement (a reconstruction of f^J) to one that scrambles the hierarchy.
        const double move = *rc::gen::element(1e-3, 0.1, 2.0);
        std::mt19937_64 rng(*rc::gen::inRange<std::uint64_t>(0, 1u << 30));
        std::uniform_real_distribution<double> u(-1, 1), q(-4, 4);
        std::vector<Vec3> moved = m.positions();
        for (Vec3& p : moved) p += move * Vec3(u(rng), u(rng), u(rng));
        const TriangleTree refitted(tree, moved);
        for (int k = 0; k < 50; ++k) {
            const Vec3 p(q(rng), q(rng), q(rng));
            const TriangleTree::Hit h = refitted.closest(p, static_cast<std::uint32_t>(k % t.size()));
            RC_ASSERT(h.distance == brute_distance(p, moved, t));
            RC_ASSERT(h.distance == refitted.distance_to(p, h.triangle));
        }
    });
}

TEST_CASE("WAV-9: parallel squares at distance h: h in both directions, bracket width ≤ δ", "[unit][wavelet]") {
    const std::vector<Triangle> t{{0, 1, 2}, {0, 2, 3}};
    const std::vector<Vec3> a{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    const double h = 0.125;
    const std::vector<Vec3> b{{0, 0, h}, {1, 0, h}, {1, 1, h}, {0, 1, h}};
    const wavelet::Hausdorff H = wavelet::hausdorff(a, t, b, t, {.resolution = 0.01});
    CHECK(H.lower() == h);
    CHECK(H.a_to_b.lower == h);
    CHECK(H.b_to_a.lower == h);
    CHECK(H.upper() >= h);
    CHECK(H.upper() - H.lower() <= 0.01);
    // A mesh against itself.
    const wavelet::Hausdorff Z = wavelet::hausdorff(a, t, a, t, {.resolution = 0.01});
    CHECK(Z.lower() <= 1e-15);  // the face-region closest point is exact up to a few ulps
    CHECK(Z.upper() <= 0.01);
}

TEST_CASE(
    "WAV-9: lower ≤ h ≤ upper: lower is at least the vertices' brute-force distance, upper at least a denser sample's",
    "[property][wavelet]") {
    rc::prop("a sphere against a noisy copy", [] {
        const auto [A, t, bx] = noisy_sphere();
        const double delta = *rc::gen::element(0.05, 0.02);
        const wavelet::Hausdorff H = wavelet::hausdorff(A.positions(), t, bx, t, {.resolution = delta});
        RC_ASSERT(H.lower() <= H.upper());
        RC_ASSERT(H.upper() - H.lower() <= delta * (1 + 1e-12));
        // The samples include the vertices.
        double vertices = 0;
        for (const Vec3& p : A.positions()) vertices = std::max(vertices, brute_distance(p, bx, t));
        for (const Vec3& p : bx) vertices = std::max(vertices, brute_distance(p, A.positions(), t));
        RC_ASSERT(H.lower() >= vertices);
        // Any sample of A or B is a point of the surface, so its distance is ≤ h ≤ upper.
        const wavelet::Hausdorff fine = wavelet::hausdorff(A.positions(), t, bx, t, {.resolution = delta / 4});
        RC_ASSERT(fine.lower() <= H.upper() * (1 + 1e-12));
        RC_ASSERT(H.lower() <= fine.upper() * (1 + 1e-12));
    });
}

TEST_CASE("WAV-9: a directed search told a known lower bound still brackets h, δ-narrow above what is known",
          "[property][wavelet]") {
    rc::prop("a sphere against a noisy copy, known anywhere from 0 to twice the distance", [] {
        const auto [A, t, bx] = noisy_sphere();
        const double delta = *rc::gen::element(0.02, 0.005);
        const TriangleTree B(bx, t);
        const wavelet::DirectedHausdorff full = wavelet::directed_hausdorff(A.positions(), t, B, {.resolution = delta});
        const double known = full.upper * *rc::gen::inRange(0, 200) / 100.0;
        const wavelet::DirectedHausdorff told =
            wavelet::directed_hausdorff(A.positions(), t, B, {.resolution = delta, .known = known});
        // Both brackets hold the same h.
        RC_ASSERT(told.lower <= told.upper);
        RC_ASSERT(told.lower <= full.upper * (1 + 1e-12));
        RC_ASSERT(full.lower <= told.upper * (1 + 1e-12));
        // Narrow where it matters: above known.
        RC_ASSERT(std::max(told.upper, known) - std::max(told.lower, known) <= delta * (1 + 1e-12));
        // Nothing known: the same search.
        const wavelet::DirectedHausdorff zero =
            wavelet::directed_hausdorff(A.positions(), t, B, {.resolution = delta, .known = 0});
        RC_ASSERT(zero.lower == full.lower && zero.upper == full.upper && zero.samples == full.samples);
    });
}

TEST_CASE(
    "WAV-9: triangle_upper bounds the distance on each triangle; priors from it plus a displacement give the same h, "
    "δ-narrow, and every vertex counts",
    "[property][wavelet]") {
    rc::prop("a noisy sphere B, its copy B′ moved again, and A, the sphere", [] {
        const auto [A, t, bx] = noisy_sphere();
        const double delta = *rc::gen::element(0.02, 0.005);
        const TriangleTree a_tree(A.positions(), t);
        const wavelet::DirectedHausdorff f = wavelet::directed_hausdorff(bx, t, a_tree, {.resolution = delta});
        RC_ASSERT(f.triangle_upper.size() == t.size());
        // Every point of a triangle of B is within its triangle_upper of A (brute force at a sample).
        std::mt19937_64 rng(*rc::gen::inRange<std::uint64_t>(0, 1u << 30));
        std::uniform_real_distribution<double> u(0, 1);
        for (std::size_t i = 0; i < t.size(); ++i)
            for (int k = 0; k < 4; ++k) {
                double w0 = u(rng), w1 = u(rng);
                if (w0 + w1 > 1) w0 = 1 - w0, w1 = 1 - w1;
                const Vec3 p = w0 * bx[t[i][0]] + w1 * bx[t[i][1]] + (1 - w0 - w1) * bx[t[i][2]];
                RC_ASSERT(brute_distance(p, A.positions(), t) <= f.triangle_upper[i] * (1 + 1e-12));
            }
        // B′: B moved by up to 0.01 more; its prior per triangle is f's bound plus its corners' move.
        std::vector<Vec3> moved = bx;
        const std::vector<Vec3> n = test::random_points(bx.size(), *rc::gen::inRange<std::uint64_t>(0, 1u << 30), 0.01);
        std::vector<double> shift(bx.size());
        for (std::size_t v = 0; v < bx.size(); ++v) moved[v] += n[v], shift[v] = n[v].norm();
        std::vector<double> prior(t.size());
        for (std::size_t i = 0; i < t.size(); ++i)
            prior[i] = (f.triangle_upper[i] + std::max({shift[t[i][0]], shift[t[i][1]], shift[t[i][2]]})) * (1 + 1e-12);
        const double known = *rc::gen::element(0.0, f.lower);
        const wavelet::DirectedHausdorff plain =
            wavelet::directed_hausdorff(moved, t, a_tree, {.resolution = delta, .known = known});
        const wavelet::DirectedHausdorff told =
            wavelet::directed_hausdorff(moved, t, a_tree, {.resolution = delta, .known = known, .prior = prior});
        RC_ASSERT(told.lower <= told.upper);
        RC_ASSERT(told.lower <= plain.upper * (1 + 1e-12));
        RC_ASSERT(plain.lower <= told.upper * (1 + 1e-12));
        RC_ASSERT(std::max(told.upper, known) - std::max(told.lower, known) <= delta * (1 + 1e-12));
        RC_ASSERT(told.samples <= plain.samples + moved.size());
        // The vertices are queried only while their bound (the least prior of their triangles)
        // could raise max(lower, known): that is still at least every vertex's distance.
        double vertices = 0;
        for (const Vec3& p : moved) vertices = std::max(vertices, brute_distance(p, A.positions(), t));
        RC_ASSERT(std::max(told.lower, known) >= vertices);
        // Also when a known bound settles every triangle at once: known between the vertices'
        // largest distance and told's (then lower must find the vertices' largest itself).
        const double mid = vertices * *rc::gen::element(0.0, 0.5, 0.9);
        const wavelet::DirectedHausdorff settled =
            wavelet::directed_hausdorff(moved, t, a_tree, {.resolution = delta, .known = mid, .prior = prior});
        RC_ASSERT(std::max(settled.lower, mid) >= vertices);
    });
}

TEST_CASE(
    "WAV-9, WAV-14: the two-triangle and vertex-fan bounds are upper bounds of the distance on a piece, inside and at "
    "the boundary",
    "[property][wavelet]") {
    rc::prop(
        "pieces near the vertices and edges of an irregular flat-faced octahedron or its open upper half, slightly off "
        "it",
        [] {
            const int n = *rc::gen::inRange(2, 9);
            const double jitter = *rc::gen::element(0.0, 0.1, 0.25);
            const bool open = *rc::gen::arbitrary<bool>();
            const std::vector<Vec3> corners(test::octahedron_corners.begin(),
                                            test::octahedron_corners.begin() + (open ? 5 : 6));
            const std::vector<Triangle> faces(test::octahedron_faces.begin(),
                                              test::octahedron_faces.begin() + (open ? 4 : 8));
            const TriMesh B = test::refined_polyhedron(corners, faces, n, jitter, *rc::gen::inRange(0u, 1000u));
            const std::vector<Vec3>& x = B.positions();
            const std::vector<Triangle> t = B.triangles();
            const TriangleTree tree(x, t);
            std::mt19937_64 rng(*rc::gen::inRange<std::uint64_t>(0, 1u << 30));
            const auto v = *rc::gen::inRange<std::uint32_t>(0, static_cast<std::uint32_t>(x.size()));
            const double step = 1.0 / n, off = *rc::gen::element(0.0, 1e-6, 1e-3, 0.05);
            std::uniform_real_distribution<double> u(-1.5 * step, 1.5 * step), lift(-off, off);
            Vec3 piece[3];
            for (Vec3& p : piece) p = x[v] + Vec3(u(rng), u(rng), u(rng)) + Vec3::Constant(lift(rng));
            // The triangles at v, and one edge's two triangles.
            std::vector<Triangle> fan, pair;
            std::uint32_t first = 0, second = 0;
            auto has = [&](const Triangle& f, std::uint32_t w) { return f[0] == w || f[1] == w || f[2] == w; };
            for (std::uint32_t i = 0; i < t.size(); ++i)
                if (has(t[i], v)) {
                    if (fan.empty()) first = i;
                    fan.push_back(t[i]);
                }
            for (std::uint32_t i = 0; i < t.size(); ++i)  // a neighbour of `first` across one of its edges
                if (i != first && (has(t[first], t[i][0]) + has(t[first], t[i][1]) + has(t[first], t[i][2])) == 2)
                    second = i;
            for (std::uint32_t i : {first, second}) pair.push_back(t[i]);
            const double fan_bound = tree.fan_bound(piece, v), pair_bound = tree.pair_bound(piece, first, second);
            RC_TAG(B.is_boundary(VertexId(v)) ? "boundary vertex" : "inner vertex",
                   std::isfinite(fan_bound) ? "fan bound finite" : "fan bound infinite",
                   std::isfinite(pair_bound) ? "pair bound finite" : "pair bound infinite");
            const int k = 24;
            double fan_sup = 0, pair_sup = 0;
            for (int i = 0; i <= k; ++i)
                for (int j = 0; i + j <= k; ++j) {
                    const Vec3 p =
                        piece[0] + (double(i) / k) * (piece[1] - piece[0]) + (double(j) / k) * (piece[2] - piece[0]);
                    fan_sup = std::max(fan_sup, brute_distance(p, x, fan));
                    pair_sup = std::max(pair_sup, brute_distance(p, x, pair));
                }
            RC_ASSERT(fan_sup <= fan_bound + 1e-14);
            RC_ASSERT(pair_sup <= pair_bound + 1e-14);
        });
}

// The two-triangle bound's premise: τ₁ = (a, b, c) and τ₂ = (b, a, d) share ab, and Q = a d' b c
// (d' = d flattened into τ₁'s plane) is convex. Each bound may be used only where its premise
// holds: on a convex Q it is finite and exact up to its rounding slack (a piece lying on Q across
// the diagonal gets ≤ 2e−12, a piece lifted by 0.01 gets 0.01), and on a reflex ("dart") Q, a
// folded τ₂ (d' on c's side of ab) or two triangles without a common edge it is +∞.
TEST_CASE("WAV-9: the two-triangle bound applies exactly where Q is convex, and is tight there", "[unit][wavelet]") {
    const Vec3 a(0, 0, 0), b(2, 0, 0), c(1, 1, 0);
    const std::vector<Triangle> t{{0, 1, 2}, {1, 0, 3}};
    auto bound = [&](const Vec3& d, const Vec3(&piece)[3]) {
        const std::vector<Vec3> x{a, b, c, d};
        return TriangleTree(x, t).pair_bound(piece, 0, 1);
    };
    const Vec3 across[3] = {{0.5, 0.4, 0}, {1.5, 0.4, 0}, {1, -0.6, 0}};  // inside the kite below
    const Vec3 lifted[3] = {{0.5, 0.4, 0.01}, {1.5, 0.4, 0.01}, {1, -0.6, 0.01}};
    const Vec3 kite(1, -1, 0), dart(4, -1, 0), folded(1, 0.5, 0);
    CHECK(bound(kite, across) <= 2e-12);
    CHECK(bound(kite, lifted) >= 0.01);
    CHECK(bound(kite, lifted) <= 0.01 + 2e-12);
    CHECK(std::isinf(bound(dart, across)));    // b is a reflex corner of Q: a and b on one side of cd'
    CHECK(std::isinf(bound(folded, across)));  // d' and c on one side of ab
    // Both orders of the pair: the bound is taken in the first triangle's plane.
    const std::vector<Vec3> x{a, b, c, kite};
    CHECK(TriangleTree(x, t).pair_bound(across, 1, 0) <= 2e-12);
    // No common edge: triangles that share only the vertex a.
    const std::vector<Vec3> y{a, b, c, kite, Vec3(-1, 1, 0)};
    const std::vector<Triangle> u{{0, 1, 2}, {1, 0, 3}, {0, 2, 4}, {0, 4, 3}};
    CHECK(std::isinf(TriangleTree(y, u).pair_bound(across, 1, 2)));
    CHECK(std::isinf(TriangleTree(y, u).pair_bound(across, 0, 3)));
}

TEST_CASE("WAV-9: two triangulations of one flat-faced surface: the bracket closes at δ with few samples",
          "[unit][wavelet]") {
    // Where A lies on B, the one-triangle bound settles a piece across an edge of B only once the
    // piece is about δ small; the two-triangle and fan bounds settle it at once (WAV-9; the search
    // in wavelet/hausdorff.hpp).
    const TriMesh A = test::refined_polyhedron(test::octahedron_corners, test::octahedron_faces, 12, 0.2, 7);
    const TriMesh B = test::refined_polyhedron(test::octahedron_corners, test::octahedron_faces, 9, 0.1, 3);
    const std::vector<Triangle> a = A.triangles(), b = B.triangles();
    const double delta = 1e-5;
    const wavelet::Hausdorff H = wavelet::hausdorff(A.positions(), a, B.positions(), b, {.resolution = delta});
    CHECK(H.lower() <= 1e-15);
    CHECK(H.upper() <= delta);
    INFO("samples " << H.a_to_b.samples << " + " << H.b_to_a.samples << " for " << a.size() << " + " << b.size()
                    << " triangles");
    CHECK(H.a_to_b.samples + H.b_to_a.samples <= 40 * (a.size() + b.size()));
}

TEST_CASE(
    "WAV-14: two triangulations of one flat-faced surface with boundary and two components: the bracket closes at δ "
    "with few samples",
    "[unit][wavelet]") {
    // The octahedron's upper half (an open square pyramid, its boundary loop the equator) and,
    // translated, its lower half: A and B triangulate the same two disks. At the boundary vertices
    // of B the vertex fan is an open path (WAV-14), flattened the same way.
    const std::vector<Vec3> upper_corners(test::octahedron_corners.begin(), test::octahedron_corners.begin() + 5);
    const std::vector<Triangle> upper(test::octahedron_faces.begin(), test::octahedron_faces.begin() + 4);
    auto two_halves = [&](int n, double jitter, unsigned seed) {
        const TriMesh half = test::refined_polyhedron(upper_corners, upper, n, jitter, seed);
        std::vector<Vec3> x = half.positions();
        std::vector<Triangle> t = half.triangles();
        const auto offset = static_cast<std::uint32_t>(x.size());
        for (const Vec3& p : half.positions()) x.push_back(Vec3(p.x() + 3, p.y(), -p.z()));
        for (const Triangle& f : half.triangles()) t.push_back({f[0] + offset, f[2] + offset, f[1] + offset});
        return std::pair{x, t};
    };
    const auto [ax, a] = two_halves(12, 0.2, 7);
    const auto [bx, b] = two_halves(9, 0.1, 3);
    const double delta = 1e-5;
    const wavelet::Hausdorff H = wavelet::hausdorff(ax, a, bx, b, {.resolution = delta});
    CHECK(H.lower() <= 1e-15);
    CHECK(H.upper() <= delta);
    INFO("samples " << H.a_to_b.samples << " + " << H.b_to_a.samples << " for " << a.size() << " + " << b.size()
                    << " triangles");
    CHECK(H.a_to_b.samples + H.b_to_a.samples <= 40 * (a.size() + b.size()));
}

TEST_CASE("WAV-14: at a boundary vertex of B the open fan's bound settles a piece across it at once",
          "[unit][wavelet]") {
    // B: the flat half disk as an open fan of 6 triangles around v = 0 (v on the straight side);
    // A: the same half disk triangulated from the rim point r_0, so v lies inside A's edge r_6 r_0
    // and the corners of A's pieces at v are nearest to different triangles of v's fan. The
    // bound of a piece through v must come from the whole fan, or the piece is split down to δ.
    const unsigned t = 6;
    std::vector<Vec3> x{{0, 0, 0}};
    for (unsigned k = 0; k <= t; ++k)
        x.emplace_back(std::cos(std::numbers::pi * k / t), std::sin(std::numbers::pi * k / t), 0);
    std::vector<Triangle> b, a;
    for (unsigned k = 1; k <= t; ++k) b.push_back({0, k, k + 1});
    for (unsigned k = 2; k <= t; ++k) a.push_back({1, k, k + 1});
    const TriangleTree tree(x, b);
    const Vec3 piece[3] = {x[1], x[t], x[t + 1]};  // A's triangle through v
    // The bound is exact up to its rounding slack 1e−12·(the link's radius 1) (hausdorff.cpp).
    CHECK(tree.fan_bound(piece, 0) <= 2e-12);
    const double delta = 1e-9;
    const wavelet::Hausdorff H = wavelet::hausdorff(x, a, x, b, {.resolution = delta});
    CHECK(H.upper() <= delta);
    INFO("samples " << H.a_to_b.samples << " + " << H.b_to_a.samples);
    CHECK(H.a_to_b.samples + H.b_to_a.samples <= 100);
}

TEST_CASE("WAV-9: rms_distance", "[unit][wavelet]") {
    const std::vector<Vec3> a{{0, 0, 0}, {1, 0, 0}}, b{{3, 4, 0}, {1, 0, 0}};
    CHECK(wavelet::rms_distance(a, b) == std::sqrt(12.5));
}
