// FHR §4 — φ_i = ψ_i⁻¹ on a patch by point location (MAP-11, spec/patch_map.md): every vertex's
// image gives back its position exactly; random points of the patch come back through ψ then φ;
// points on a side follow the chord-length placement (on the boundary edge, exact at the
// vertices) and are bit-identical from both patches sharing the side; refusals.
#include <catch2/catch.hpp>
#include <rapidcheck/catch.h>

#include <cmath>
#include <limits>
#include <random>

#include <fhr/core/errors.hpp>
#include <fhr/core/detail/predicates.hpp>
#include <fhr/param/certificate.hpp>
#include <fhr/param/detail/dividing_edges.hpp>
#include <fhr/param/locate.hpp>
#include <fhr/param/patch_map.hpp>
#include <fhr/testing/rapidcheck.hpp>
#include "param/disks.hpp"

using namespace fhr;
using param::Disk;
using param::PatchLocator;
using param::PatchMap;

namespace {

constexpr double eps = std::numeric_limits<double>::epsilon();

struct Solved {
    Disk disk;
    PatchMap psi;
};

// A certified patch: a disk cut from a random closed mesh (genus 0–2) or a bumpy lattice.
rc::Gen<Solved> gen_solved() {
    return rc::gen::exec([] {
        Disk d;
        if (*rc::gen::arbitrary<bool>()) {
            const fhr::testing::GeneratedMesh m = *fhr::testing::gen_closed_mesh(0, 2, 1200);
            d = test::disk_from_mesh(m, *rc::gen::inRange<std::uint64_t>(0, 1u << 30),
                                     *rc::gen::inRange<std::size_t>(1, std::min<std::size_t>(500, m.n_faces() / 2)));
        } else {
            std::mt19937_64 rng(*rc::gen::inRange<std::uint64_t>(0, 1u << 30));
            std::vector<std::array<double, 2>> st;
            d = test::lattice_triangle(*rc::gen::inRange(1, 14), 0.2, rng, st);
            test::place(d, st, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.2, 1, 0)}, 1.5, 9, 7, 0.5, 0.3);
        }
        param::split_dividing_edges(d);
        PatchMap psi = param::map_patch(d);
        RC_ASSERT(param::certify(d, psi).passed);
        return Solved{std::move(d), std::move(psi)};
    });
}

}  // namespace

TEST_CASE("MAP-11: φ(ψ(v)) is v's position exactly, for every vertex", "[property][param]") {
    rc::prop("certified random patches", [] {
        const Solved s = *gen_solved();
        const PatchLocator phi(s.disk, s.psi);
        // At a vertex two of the three sub-triangle areas are exactly 0 and its own weight is
        // exactly 1 (locate.cpp); on a side the segment starting at the vertex has s = 0.
        for (std::size_t v = 0; v < s.disk.positions.size(); ++v)
            RC_ASSERT(phi.phi(s.psi.beta[v]) == s.disk.positions[v]);
    });
}

TEST_CASE("MAP-11: random points of the patch come back through ψ and then φ", "[property][param]") {
    rc::prop("certified random patches, 200 points each", [] {
        const Solved s = *gen_solved();
        const PatchLocator phi(s.disk, s.psi);
        std::mt19937_64 rng(*rc::gen::inRange<std::uint64_t>(0, 1u << 30));
        std::uniform_real_distribution<double> u(0, 1);
        std::uniform_int_distribution<std::size_t> pick(0, s.disk.triangles.size() - 1);
        for (int q = 0; q < 200; ++q) {
            const std::size_t t = pick(rng);
            const auto& f = s.disk.triangles[t];
            double w1 = u(rng), w2 = u(rng);
            if (w1 + w2 > 1) w1 = 1 - w1, w2 = 1 - w2;
            const double w0 = 1 - w1 - w2;
            const Vec3 x = w0 * s.disk.positions[f[0]] + w1 * s.disk.positions[f[1]] + w2 * s.disk.positions[f[2]];
            std::array<double, 3> beta{};
            for (int c = 0; c < 3; ++c)
                beta[c] = w0 * s.psi.beta[f[0]][c] + w1 * s.psi.beta[f[1]][c] + w2 * s.psi.beta[f[2]][c];
            // The located triangle holds β (exactly, by orient2d, when β is inside); φ is linear
            // there. Error bound: β carries a few ε; the weights in the image triangle then err
            // by ≈ ε / h (h its smallest height in the reference plane), and the 3-D point by
            // that times the 3-D triangle's longest edge L — plus, when β falls in a neighbouring
            // triangle by rounding, the same bound there; so use the patch's worst L / h.
            double worst = 0;
            for (const auto& g : s.disk.triangles) {
                Eigen::Vector2d a(s.psi.beta[g[0]][1], s.psi.beta[g[0]][2]),
                    b(s.psi.beta[g[1]][1], s.psi.beta[g[1]][2]), c(s.psi.beta[g[2]][1], s.psi.beta[g[2]][2]);
                const double twice_area = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
                const double longest_image = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
                double L = 0;
                for (int k = 0; k < 3; ++k)
                    L = std::max(L, (s.disk.positions[g[k]] - s.disk.positions[g[(k + 1) % 3]]).norm());
                worst = std::max(worst, L * longest_image / twice_area);
            }
            const Vec3 back = phi.phi(beta);
            RC_ASSERT((back - x).norm() <= 64 * eps * (worst + x.norm()));
            const PatchLocator::Location where = phi.locate(beta);
            const auto& g = s.disk.triangles[where.triangle];
            // The weights rebuild β: each comes from a determinant with absolute error ≈ ε·L²
            // (L the image triangle's longest edge), divided by twice its area 2A, and moves the
            // rebuilt point by at most L times that.
            Eigen::Vector2d a(s.psi.beta[g[0]][1], s.psi.beta[g[0]][2]), b(s.psi.beta[g[1]][1], s.psi.beta[g[1]][2]),
                c(s.psi.beta[g[2]][1], s.psi.beta[g[2]][2]);
            const double twice_area = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
            const double L = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
            for (int k = 1; k < 3; ++k) {
                const double rebuilt = where.weights[0] * s.psi.beta[g[0]][k] + where.weights[1] * s.psi.beta[g[1]][k] +
                                       where.weights[2] * s.psi.beta[g[2]][k];
                RC_ASSERT(std::abs(rebuilt - beta[k]) <= 16 * eps * (1 + L * L * L / twice_area));
            }
        }
    });
}

TEST_CASE("MAP-11: points on a side lie on its boundary edges, at the chord-length placement", "[property][param]") {
    rc::prop("certified random patches, 100 points per side", [] {
        const Solved s = *gen_solved();
        const PatchLocator phi(s.disk, s.psi);
        std::mt19937_64 rng(*rc::gen::inRange<std::uint64_t>(0, 1u << 30));
        std::uniform_real_distribution<double> u(0, 1);
        const std::size_t n = s.disk.boundary.size();
        for (unsigned c = 0; c < 3; ++c) {
            for (int q = 0; q < 100; ++q) {
                const double t = u(rng);
                std::array<double, 3> beta{};
                beta[(c + 1) % 3] = t;
                beta[c] = 1 - t;
                const PatchLocator::Location where = phi.locate(beta);
                // Its triangle has two boundary vertices of side c with weights 1 − s and s and the
                // third weight 0: φ is on that boundary edge.
                const auto& f = s.disk.triangles[where.triangle];
                int zero = -1;
                for (int k = 0; k < 3; ++k)
                    if (where.weights[k] == 0) zero = k;
                RC_ASSERT(zero >= 0);
                const std::uint32_t a = f[(zero + 1) % 3], b = f[(zero + 2) % 3];
                // a → b is a boundary edge of the loop, on side c: consecutive positions.
                std::size_t pa = n;
                for (std::size_t p = 0; p < n; ++p)
                    if (s.disk.boundary[p] == a) pa = p;
                RC_ASSERT(pa < n);
                RC_ASSERT(s.disk.boundary[(pa + 1) % n] == b);
                // The β of a and b bracket t along the side.
                const double ta = s.psi.beta[a][(c + 1) % 3], tb = s.psi.beta[b][(c + 1) % 3];
                RC_ASSERT(ta <= t + 2 * eps);
                RC_ASSERT(t <= tb + 2 * eps);
            }
        }
    });
}

TEST_CASE("MAP-11: a point on a shared side gives the same 3-D point, bit for bit, from both patches",
          "[property][param]") {
    rc::prop("two bumpy lattice triangles sharing their diagonal", [] {
        // As in MAP-5's test: a bumpy square cut along its diagonal B–C.
        const int n = *rc::gen::inRange(1, 10);
        std::mt19937_64 rng(*rc::gen::inRange<std::uint64_t>(0, 1u << 30));
        const auto [p1, p2] = test::diagonal_pair(n, rng, [](const std::array<double, 2>& q) {
            return Vec3(q[0], q[1], std::sin(6 * q[0]) * std::cos(4 * q[1] + 1));
        });
        const PatchMap psi1 = param::map_patch(p1), psi2 = param::map_patch(p2);
        const PatchLocator phi1(p1, psi1), phi2(p2, psi2);
        std::uniform_real_distribution<double> u(0, 1);
        for (int q = 0; q < 200; ++q) {
            // The same point of the domain edge [B, C]: weights (β_B, β_C) = (1 − t, t), in each
            // patch's own corner order.
            const double t = q == 0 ? 0.0 : q == 1 ? 1.0 : u(rng);
            const Vec3 x1 = phi1.phi({0, 1 - t, t}), x2 = phi2.phi({0, t, 1 - t});
            RC_ASSERT(x1 == x2);
        }
    });
}

TEST_CASE("MAP-11: corners, a large patch, and refused coordinates", "[unit][param]") {
    std::mt19937_64 rng(3);
    std::vector<std::array<double, 2>> st;
    Disk d = test::lattice_triangle(40, 0.2, rng, st);
    test::place(d, st, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, 0.5, 8, 8, 0, 0);
    param::split_dividing_edges(d);
    const PatchMap psi = param::map_patch(d);
    REQUIRE(param::certify(d, psi).passed);
    const PatchLocator phi(d, psi);
    for (unsigned c = 0; c < 3; ++c) {
        std::array<double, 3> e{0, 0, 0};
        e[c] = 1;
        CHECK(phi.phi(e) == d.positions[d.boundary[d.corners[c]]]);
    }
    // A point a few ulps outside the triangle (β0 computed as 1 − β1 − β2 can dip below 0) still
    // lands on the nearest triangle.
    const Vec3 near_side = phi.phi({-1e-17, 0.5, 0.5 + 1e-17});
    CHECK((near_side - phi.phi({0, 0.5, 0.5})).norm() < 1e-12);
    // All three components positive, but (β1, β2) a few ulps beyond the side β0 = 0: no closed
    // image triangle holds it (the side's vertices lie exactly on β1 + β2 = 1, MAP-8), and the
    // point location falls back on the triangle whose coordinates are least negative. φ must
    // give the side's point within rounding, whatever triangle the grid cell lists first.
    std::mt19937_64 pick(11);
    std::uniform_real_distribution<double> along(0.001, 0.999);
    for (int q = 0; q < 200; ++q) {
        const double t = along(pick), rest = std::nextafter(std::nextafter(1 - t, 2.0), 2.0);
        REQUIRE(orient2d(Eigen::Vector2d(1, 0), Eigen::Vector2d(0, 1), Eigen::Vector2d(t, rest)) <
                0);  // exactly beyond
        const Vec3 on_side = phi.phi({0, t, 1 - t}), beyond = phi.phi({1e-17, t, rest});
        CAPTURE(t, (beyond - on_side).norm());
        CHECK((beyond - on_side).norm() < 1e-12);
    }
    // Every grid cell is exercised: 10^5 points on a lattice of the triangle, each located in a
    // triangle whose image holds it exactly.
    std::size_t held = 0, total = 0;
    for (int i = 1; i < 447; ++i)
        for (int j = 1; i + j < 447; ++j) {
            const double b1 = i / 447.0, b2 = j / 447.0;
            const auto where = phi.locate({1 - b1 - b2, b1, b2});
            const auto& f = d.triangles[where.triangle];
            auto at = [&](std::uint32_t v) { return Eigen::Vector2d(psi.beta[v][1], psi.beta[v][2]); };
            const Eigen::Vector2d q(b1, b2);
            ++total;
            held += orient2d(at(f[0]), at(f[1]), q) >= 0 && orient2d(at(f[1]), at(f[2]), q) >= 0 &&
                    orient2d(at(f[2]), at(f[0]), q) >= 0;
        }
    CHECK(held == total);
    CHECK_THROWS_AS(phi.phi({-0.1, 0.6, 0.5}), InvalidInput);
    CHECK_THROWS_AS(phi.phi({std::nan(""), 0.5, 0.5}), InvalidInput);
}
