// FHR §4 — the convex-combination weights λ_vw (paper §4: strictly positive, summing to one;
// Floater 1997 shape-preserving, Floater 2003 mean-value, uniform). Properties on random planar
// 1-rings of valence 3..12 (positivity and partition of unity MAP-2, linear reproduction MAP-3),
// on nearly flat, sharp (cone) and saddle rings (MAP-2), the ray-through-a-vertex tie of even
// regular rings, valence 3, and the refusals (spec/patch_map.md).
#include <catch2/catch.hpp>
#include <rapidcheck/catch.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <Eigen/Geometry>

#include <fhr/core/errors.hpp>
#include <fhr/param/weights.hpp>

using namespace fhr;
using param::one_ring_weights;
using param::Weights;

namespace {

constexpr double eps = std::numeric_limits<double>::epsilon();
constexpr double pi = std::numbers::pi;
const Weights all_kinds[] = {Weights::shape_preserving, Weights::mean_value, Weights::uniform};

// A random rigid motion of 3-space (rotation from a random unit quaternion, then translation).
struct Motion {
    Eigen::Quaterniond rotation;
    Vec3 translation;
    Vec3 operator()(const Vec3& x) const { return rotation * x + translation; }
};

rc::Gen<Motion> gen_motion() {
    return rc::gen::exec([] {
        Eigen::Vector4d q;
        do {
            for (int k = 0; k < 4; ++k) q[k] = *rc::gen::inRange(-1000, 1001) / 1000.0;
        } while (q.norm() < 0.1);
        q.normalize();
        const Vec3 t(*rc::gen::inRange(-100, 101), *rc::gen::inRange(-100, 101), *rc::gen::inRange(-100, 101));
        return Motion{Eigen::Quaterniond(q[0], q[1], q[2], q[3]), t};
    });
}

// A star-shaped planar ring around the origin: d ≥ 3 polar angles increasing by gaps that are
// each below 0.95π (so the origin is strictly inside), radii log-uniform in [1e-2, 1e2]
// (both ratios 10^4 apart: the "sharp" planar case of long and short spokes).
struct PlanarRing {
    std::vector<double> angle, radius;
};

rc::Gen<PlanarRing> gen_planar_ring() {
    return rc::gen::exec([] {
        const int d = *rc::gen::inRange(3, 13);
        PlanarRing r;
        std::vector<double> gap(d);
        double total = 0;
        for (double& g : gap) total += g = *rc::gen::inRange(1, 101);
        for (double g : gap) RC_PRE(2 * pi * g / total < 0.95 * pi);
        double a = *rc::gen::inRange(0, 628) / 100.0;
        for (int k = 0; k < d; ++k) {
            r.angle.push_back(a);
            a += 2 * pi * gap[k] / total;
            r.radius.push_back(std::pow(10.0, *rc::gen::inRange(-200, 201) / 100.0));
        }
        return r;
    });
}

double weight_sum(const std::vector<double>& w) {
    double s = 0;
    for (double x : w) s += x;
    return s;
}

// MAP-2 for one result.
bool positive_partition_of_unity(const std::vector<double>& w, std::size_t d) {
    if (w.size() != d) return false;
    for (double x : w)
        if (!(x > 0) || !std::isfinite(x)) return false;
    return std::abs(weight_sum(w) - 1) <= 2 * static_cast<double>(d) * eps;
}

}  // namespace

TEST_CASE("weight names parse and print", "[unit][param]") {
    for (Weights w : all_kinds) CHECK(param::parse_weights(param::name(w)) == w);
    CHECK(param::name(Weights::shape_preserving) == "shape-preserving");
    CHECK(param::name(Weights::mean_value) == "mean-value");
    CHECK(param::name(Weights::uniform) == "uniform");
    CHECK_THROWS_AS(param::parse_weights("harmonic"), InvalidInput);
    CHECK_THROWS_WITH(param::parse_weights("Shape-Preserving"),
                      Catch::Contains("expected shape-preserving, mean-value or uniform"));
    // A bad option value comes from no file and no line: the message is the problem alone.
    try {
        param::parse_weights("harmonic");
    } catch (const InvalidInput& e) {
        CHECK(e.file().empty());
        CHECK(e.line() == 0);
        CHECK(std::string(e.what()) == e.problem());
    }
}

TEST_CASE("MAP-2, MAP-3: planar 1-rings of valence 3..12: positive, partition of unity, linear reproduction",
          "[property][param]") {
    rc::prop("random planar rings in random planes", [] {
        const PlanarRing r = *gen_planar_ring();
        const Motion motion = *gen_motion();
        const std::size_t d = r.angle.size();
        const Vec3 p = motion(Vec3::Zero());
        std::vector<Vec3> ring;
        double largest = 0;
        for (std::size_t k = 0; k < d; ++k) {
            ring.push_back(motion(Vec3(r.radius[k] * std::cos(r.angle[k]), r.radius[k] * std::sin(r.angle[k]), 0)));
            largest = std::max(largest, r.radius[k]);
        }
        for (Weights kind : all_kinds) {
            const std::vector<double> w = one_ring_weights(kind, p, ring, 7);
            RC_ASSERT(positive_partition_of_unity(w, d));
            if (kind == Weights::uniform) continue;  // uniform weights do not reproduce lines
            // MAP-3: Σ λ_k p_k = p. Each spoke's polar image carries a relative error of a few ε
            // (sin, cos, the angle sums); the barycentric coordinates a further ≈ ε / sin(gap)
            // with gaps ≥ 2π/1200; times d ≤ 12 terms of size ≤ `largest`, plus the rounding of
            // the translation (|p| ≤ 175): well below 1e-11 · (largest + |p|).
            Vec3 combination = Vec3::Zero();
            for (std::size_t k = 0; k < d; ++k) combination += w[k] * ring[k];
            RC_ASSERT((combination - p).norm() <= 1e-11 * (largest + p.norm()));
        }
    });
}

TEST_CASE("MAP-2: nearly flat, sharp (cone) and saddle 1-rings keep positive weights summing to one",
          "[property][param]") {
    rc::prop("random rings lifted off the plane", [] {
        const PlanarRing r = *gen_planar_ring();
        const std::size_t d = r.angle.size();
        // Heights: 1e-9 noise (nearly flat), a cone of slope up to 10^4 (total angle down to
        // about 2π·10^-4: very sharp), or alternating signs (a saddle, total angle above 2π).
        const int shape = *rc::gen::inRange(0, 3);
        const double slope = std::pow(10.0, *rc::gen::inRange(-100, 401) / 100.0);
        std::vector<Vec3> ring;
        for (std::size_t k = 0; k < d; ++k) {
            const double z = shape == 0   ? 1e-9 * r.radius[k] * *rc::gen::inRange(-1000, 1001) / 1000.0
                             : shape == 1 ? slope * r.radius[k]
                                          : (k % 2 == 0 ? 1 : -1) * slope * r.radius[k];
            ring.emplace_back(r.radius[k] * std::cos(r.angle[k]), r.radius[k] * std::sin(r.angle[k]), z);
        }
        for (Weights kind : all_kinds)
            RC_ASSERT(positive_partition_of_unity(one_ring_weights(kind, Vec3::Zero(), ring, 3), d));
    });
}

TEST_CASE("MAP-2: the tie where the ray from q_k passes through q_l (even regular rings) is resolved consistently",
          "[unit][param]") {
    // In a regular ring of even valence the origin lies on every segment [q_k, q_{k+d/2}], so
    // both triangles at that ray qualify; by symmetry every shape-preserving weight is 1/d.
    for (int d : {4, 6, 8, 12}) {
        std::vector<Vec3> ring;
        for (int k = 0; k < d; ++k) ring.emplace_back(std::cos(2 * pi * k / d), std::sin(2 * pi * k / d), 0);
        const std::vector<double> w = one_ring_weights(Weights::shape_preserving, Vec3::Zero(), ring, 0);
        for (double x : w) CHECK(x == Approx(1.0 / d).epsilon(1e-14));
    }
}

TEST_CASE("MAP-2, MAP-3: at valence 3 shape-preserving and mean-value weights are the barycentric coordinates",
          "[unit][param]") {
    // Three neighbours leave one convex combination: p's barycentric coordinates in the
    // triangle (p_1, p_2, p_3), here (0.2, 0.3, 0.5).
    const Vec3 a(0, 0, 0), b(4, 1, 0), c(1, 3, 0);
    const Vec3 p = 0.2 * a + 0.3 * b + 0.5 * c;
    const std::vector<Vec3> ring{a, b, c};
    for (Weights kind : {Weights::shape_preserving, Weights::mean_value}) {
        const std::vector<double> w = one_ring_weights(kind, p, ring, 0);
        REQUIRE(w.size() == 3);
        CHECK(w[0] == Approx(0.2).epsilon(1e-14));
        CHECK(w[1] == Approx(0.3).epsilon(1e-14));
        CHECK(w[2] == Approx(0.5).epsilon(1e-14));
    }
}

TEST_CASE("MAP-2: degenerate 1-rings are refused, naming the vertex", "[unit][param]") {
    const Vec3 p = Vec3::Zero();
    // Valence 2 cannot occur at an interior vertex of a simplicial disk.
    const std::vector<Vec3> two{Vec3(1, 0, 0), Vec3(-1, 0, 0)};
    for (Weights kind : all_kinds) CHECK_THROWS_AS(one_ring_weights(kind, p, two, 5), InvalidInput);
    // A flat ring with a straight angle at p: p lies on [p_3, p_1]; the origin is on the polar
    // polygon's boundary and no strictly positive shape-preserving or mean-value weights exist.
    const std::vector<Vec3> straight{Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(-1, 0, 0)};
    for (Weights kind : {Weights::shape_preserving, Weights::mean_value})
        CHECK_THROWS_WITH(one_ring_weights(kind, p, straight, 17),
                          Catch::Contains("MAP-2") && Catch::Contains("vertex 17"));
    CHECK(positive_partition_of_unity(one_ring_weights(Weights::uniform, p, straight, 17), 3));
    // A neighbour at p's position.
    const std::vector<Vec3> coincident{Vec3(1, 0, 0), Vec3(0, 0, 0), Vec3(-1, -1, 0)};
    for (Weights kind : {Weights::shape_preserving, Weights::mean_value})
        CHECK_THROWS_AS(one_ring_weights(kind, p, coincident, 2), NumericalFailure);
    // A weight of exactly 0, finite among positive ones: q_1 lies between q_0 and q_2 on one ray
    // from p, so both of its angles at p are 0 and its mean-value weight (tan 0 + tan 0) / r_1 is
    // 0. MAP-2 asks for strictly positive weights: refused, not passed on as a zero.
    const std::vector<Vec3> needle{Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(3, 0, 0), Vec3(-1, 1, 0), Vec3(-1, -1, 0)};
    CHECK_THROWS_WITH(one_ring_weights(Weights::mean_value, p, needle, 23),
                      Catch::Contains("MAP-2") && Catch::Contains("vertex 23") && Catch::Contains(" 0 "));
}
