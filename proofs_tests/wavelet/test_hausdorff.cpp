// FHR §5 — Hausdorff distance between triangle meshes (spec/wavelet.md WAV-9): the closest point
// of a triangle, the tree search against brute force, the bracket lower ≤ h ≤ upper with
// upper − lower ≤ δ, and known distances.
#include <catch2/catch.hpp>
#include <rapidcheck/catch.h>

#include <cmath>
#include <random>

#include "support/analytic_meshes.hpp"
#include "wavelet/hausdorff.hpp"
#include "wavelet_support.hpp"

using namespace fhr;
using wavelet::TriangleTree;

namespace {

// Brute force: the smallest distance from p to any triangle.
double brute_distance(const Vec3& p, const std::vector<Vec3>& x, const std::vector<Triangle>& t) {
    double best = INFINITY;
    for (const Triangle& f : t) best = std::min(best, (closest_point_on_triangle(p, x[f[0]], x[f[1]], x[f[2]]) - p).norm());
    return best;
}

}  // namespace

TEST_CASE("WAV-9: the closest point lies on the triangle and no point of a dense sample is closer", "[property][wavelet]") {
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
        RC_ASSERT(d <= dense + 1e-14);                           // no sample of the triangle is closer
        RC_ASSERT(nearest_sample_to_q <= L / (k * std::sqrt(3.0)) + 1e-14);  // q is on the triangle
    });
}

TEST_CASE("WAV-9: the tree's closest point equals brute force over all triangles", "[property][wavelet]") {
    rc::prop("random closed meshes, random query points and hints", [] {
        const test::GeneratedMesh m = *test::gen_domain(600);
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

TEST_CASE("WAV-9: lower ≤ h ≤ upper: lower is at least the vertices' brute-force distance, upper at least a denser sample's",
          "[property][wavelet]") {
    rc::prop("a sphere against a noisy copy", [] {
        const TriMesh A = test::icosphere(*rc::gen::inRange(1, 3));
        const std::vector<Triangle> t = A.triangles();
        std::vector<Vec3> bx = A.positions();
        const std::vector<Vec3> n = test::random_points(bx.size(), *rc::gen::inRange<std::uint64_t>(0, 1u << 30), 0.05);
        for (std::size_t v = 0; v < bx.size(); ++v) bx[v] += n[v];
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

TEST_CASE("WAV-9: rms_distance", "[unit][wavelet]") {
    const std::vector<Vec3> a{{0, 0, 0}, {1, 0, 0}}, b{{3, 4, 0}, {1, 0, 0}};
    CHECK(wavelet::rms_distance(a, b) == std::sqrt(12.5));
}
