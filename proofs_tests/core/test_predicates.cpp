// Exact predicates against an independent oracle: CGAL's Epick kernel (exact predicates,
// filtered with exact fallback), on inputs built to defeat naive floating point: points on or a
// few ulps off a line/plane, tiny and huge magnitudes. Proposition 1's certificate (§4) rests on
// these signs.
#include <catch2/catch.hpp>
#include <rapidcheck/catch.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cmath>
#include <random>

#include <fhr/core/detail/predicates.hpp>

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using fhr::collinear;
using fhr::orient2d;
using fhr::orient3d;
using V2 = Eigen::Vector2d;
using V3 = Eigen::Vector3d;

namespace {

int cgal2(const V2& a, const V2& b, const V2& c) {
    return static_cast<int>(
        CGAL::orientation(K::Point_2(a.x(), a.y()), K::Point_2(b.x(), b.y()), K::Point_2(c.x(), c.y())));
}
int cgal3(const V3& a, const V3& b, const V3& c, const V3& d) {
    auto p = [](const V3& v) { return K::Point_3(v.x(), v.y(), v.z()); };
    // CGAL::orientation(p,q,r,s) is positive when s is on the positive side of (p,q,r), i.e.
    // the opposite sign of Shewchuk's orient3d.
    return -static_cast<int>(CGAL::orientation(p(a), p(b), p(c), p(d)));
}

// A point a few ulps away from t·a + (1−t)·b: the hardest inputs for a naive determinant.
double nudge(double x, int ulps) {
    for (int i = 0; i < std::abs(ulps); ++i) x = std::nextafter(x, ulps > 0 ? INFINITY : -INFINITY);
    return x;
}

}  // namespace

TEST_CASE("orient2d: basic signs", "[unit][predicates]") {
    CHECK(orient2d({0, 0}, {1, 0}, {0, 1}) == 1);
    CHECK(orient2d({0, 0}, {0, 1}, {1, 0}) == -1);
    CHECK(orient2d({0, 0}, {1, 1}, {2, 2}) == 0);
    CHECK(orient2d({0, 0}, {0, 0}, {3, 1}) == 0);
}

TEST_CASE("orient2d agrees with CGAL on nearly collinear points (Kettner et al.'s classic input)",
          "[oracle][predicates]") {
    // Points near the diagonal y = x, stepped by ulps: naive evaluation gets many of these wrong.
    const V2 b(12, 12), c(24, 24);
    int zero = 0, disagreements = 0;
    for (int i = 0; i < 64; ++i)
        for (int j = 0; j < 64; ++j) {
            const V2 a(nudge(0.5, i), nudge(0.5, j));
            const int s = orient2d(a, b, c);
            zero += s == 0;
            disagreements += s != cgal2(a, b, c);
        }
    CHECK(disagreements == 0);
    CHECK(zero > 0);  // the exact line y = x is hit
}

TEST_CASE("orient3d: basic signs", "[unit][predicates]") {
    const V3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
    CHECK(orient3d(a, b, c, {0, 0, -1}) == 1);
    CHECK(orient3d(a, b, c, {0, 0, 1}) == -1);
    CHECK(orient3d(a, b, c, {5, 7, 0}) == 0);
}

TEST_CASE("orient3d agrees with CGAL on nearly coplanar points", "[oracle][predicates]") {
    const V3 a(0.1, 0.2, 0.3), b(10.7, 3.3, 1.9), c(-4.1, 8.2, 0.7);
    int disagreements = 0;
    for (int i = -20; i <= 20; ++i)
        for (int j = 0; j < 20; ++j) {
            const double t = 0.25 + j / 64.0;  // point on the segment b–c is coplanar
            V3 d = t * b + (1 - t) * c;
            d.z() = nudge(d.z(), i);
            disagreements += orient3d(a, b, c, d) != cgal3(a, b, c, d);
        }
    CHECK(disagreements == 0);
}

TEST_CASE("predicates agree with CGAL on random near-degenerate inputs of any scale",
          "[property][oracle][predicates]") {
    rc::prop("orient2d and orient3d match CGAL", [] {
        const int exponent = *rc::gen::inRange(-300, 140);
        const double scale = std::ldexp(1.0, exponent);
        auto coord = [&] { return scale * (*rc::gen::inRange(-1000000, 1000000)) / 1000.0; };
        const V3 a(coord(), coord(), coord()), b(coord(), coord(), coord()), c(coord(), coord(), coord());
        const double t = *rc::gen::inRange(0, 1000) / 1000.0;
        V3 d = t * a + (1 - t) * b;  // near the line a–b, so near every plane through a, b
        const int ulps = *rc::gen::inRange(-3, 4);
        d.x() = nudge(d.x(), ulps);
        RC_ASSERT(orient2d(a.head<2>(), b.head<2>(), d.head<2>()) == cgal2(a.head<2>(), b.head<2>(), d.head<2>()));
        RC_ASSERT(orient3d(a, b, c, d) == cgal3(a, b, c, d));
        const bool cgal_collinear = CGAL::collinear(K::Point_3(a.x(), a.y(), a.z()), K::Point_3(b.x(), b.y(), b.z()),
                                                    K::Point_3(d.x(), d.y(), d.z()));
        RC_ASSERT(collinear(a, b, d) == cgal_collinear);
    });
}

TEST_CASE("predicates are exact for subnormal and huge coordinates", "[unit][predicates]") {
    const double tiny = 4.9406564584124654e-324;  // the smallest subnormal
    CHECK(orient2d({0, 0}, {tiny, 0}, {0, tiny}) == 1);
    CHECK(orient2d({0, 0}, {tiny, tiny}, {2 * tiny, 2 * tiny}) == 0);
    const double huge = 1e150;
    CHECK(orient2d({-huge, -huge}, {huge, -huge}, {0, huge}) == 1);
    CHECK(orient3d({0, 0, 0}, {huge, 0, 0}, {0, huge, 0}, {0, 0, -tiny}) == 1);
    CHECK(collinear({0, 0, 0}, {tiny, tiny, tiny}, {huge, huge, huge}));
    CHECK_FALSE(collinear({0, 0, 0}, {1, 1, 1}, {1, 1, std::nextafter(1.0, 2.0)}));
}

TEST_CASE("orient2d: the rational fallback for coordinates outside the expansion's range 2^±450",
          "[unit][predicates]") {
    // Products of 1e-300 underflow, so the filter sees a zero permanent and the determinant ±1e-600
    // is beyond double; a tiny first point (x, then y) sends the exact sign to rationals.
    const double t = 1e-300;
    CHECK(orient2d({t, 0}, {0, t}, {0, 0}) == 1);
    CHECK(orient2d({0, t}, {0, 0}, {t, 0}) == 1);
    CHECK(orient2d({0, t}, {t, 0}, {0, 0}) == -1);
    CHECK(orient2d({t, t}, {2 * t, 2 * t}, {3 * t, 3 * t}) == 0);
    // Products of 1e200 overflow: an infinite permanent decides nothing, the rationals do.
    const double h = 1e200;
    CHECK(orient2d({h, 0}, {0, h}, {0, 0}) == 1);
    CHECK(orient2d({h, 0}, {0, 0}, {0, h}) == -1);
    CHECK(orient2d({h, h}, {-h, -h}, {0, 0}) == 0);
}
