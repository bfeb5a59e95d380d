// CLI-RUN-9 (beyond the paper, src/fhr/param/detail/mips_newton.hpp): Newton's method on a whole
// map's MIPS energy, the boundary sliding along the domain triangle's sides. A flat patch of its
// triangle's own shape, started from a warped map, comes back to the identity (the energy's unique
// minimum: a similarity on every face, continuous, with the corners fixed); over disks cut from
// random meshes of genus 0–3, started from the paper's map, the energy and the largest m_f never
// grow, every image triangle stays positively oriented (exact orient2d) and every boundary vertex
// on its side between its corners.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include <fhr/core/detail/predicates.hpp>
#include <fhr/generate/random_mesh.hpp>
#include <fhr/param/detail/dividing_edges.hpp>
#include <fhr/param/detail/mips_newton.hpp>
#include <fhr/param/patch_map.hpp>
#include "param/disks.hpp"

using namespace fhr;
using param::detail::Vec2;

namespace {

// The right triangle (0, 0), (1, 0), (0, 1): a vertex's image is (β1, β2).
const std::array<Vec3, 3> right_triangle{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};

// The problem of `disk` with images `uv`: interior vertices free, side vertices sliding along their
// side, corners fixed; and per vertex its side (−1: interior or corner).
param::detail::MipsProblem problem_of(const param::Disk& disk, const std::vector<Vec2>& uv, std::vector<int>& side) {
    param::detail::MipsProblem p;
    p.uv = uv;
    param::detail::set_faces(p, disk.positions, disk.triangles);
    p.lifts.resize(uv.size());
    side.assign(uv.size(), -1);
    std::vector<char> on_boundary(uv.size(), 0);
    for (std::uint32_t v : disk.boundary) on_boundary[v] = 1;
    for (int c = 0; c < 3; ++c) {
        const std::size_t first = disk.corners[c], last = c == 2 ? disk.boundary.size() : disk.corners[c + 1];
        const Vec2 from = uv[disk.boundary[first]], to = uv[disk.boundary[last % disk.boundary.size()]];
        for (std::size_t k = first + 1; k < last; ++k) {
            const std::uint32_t v = disk.boundary[k];
            side[v] = c;
            p.lifts[v][0] = {p.variables++, to - from};
        }
    }
    for (std::size_t v = 0; v < uv.size(); ++v)
        if (!on_boundary[v]) {
            p.lifts[v] = {param::detail::Lift{p.variables, Vec2(1, 0)},
                          param::detail::Lift{p.variables + 1, Vec2(0, 1)}};
            p.variables += 2;
        }
    return p;
}

}  // namespace

TEST_CASE(
    "CLI-RUN-9: a face's m_f^p (p = 2, 3, 4, 8) has the gradient of its finite differences and a positive "
    "semidefinite Hessian that is theirs without its negative part",
    "[param][mips]") {
    const double power = GENERATE(2.0, 3.0, 4.0, 8.0);
    CAPTURE(power);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> entry(-2, 2);
    std::size_t projected = 0;
    for (int trial = 0; trial < 200; ++trial) {
        param::detail::Mat2 j;
        do j << entry(rng), entry(rng), entry(rng), entry(rng);
        while (!(j.determinant() > 0.2));
        CAPTURE(j);
        const param::detail::MipsFace face = param::detail::mips_face(j, power);
        const double m = j.squaredNorm() / j.determinant();
        CHECK(face.energy == Approx(std::pow(m, power)).epsilon(1e-12));
        constexpr double h = 1e-5;
        Eigen::Matrix4d exact;  // the Hessian by central differences of the gradient
        for (int k = 0; k < 4; ++k) {
            param::detail::Mat2 plus = j, minus = j;
            plus(k / 2, k % 2) += h;
            minus(k / 2, k % 2) -= h;
            const double mp = plus.squaredNorm() / plus.determinant(), mm = minus.squaredNorm() / minus.determinant();
            CHECK(face.gradient(k) ==
                  Approx((std::pow(mp, power) - std::pow(mm, power)) / (2 * h)).epsilon(1e-6).margin(1e-6));
            exact.col(k) =
                (param::detail::mips_face(plus, power).gradient - param::detail::mips_face(minus, power).gradient) /
                (2 * h);
        }
        // Positive semidefinite, up to the differences' error: definite once that is added.
        const double slack = 1e-6 * exact.norm();
        auto semidefinite = [&](const Eigen::Matrix4d& a) {
            return Eigen::LLT<Eigen::Matrix4d>(a + slack * Eigen::Matrix4d::Identity()).info() == Eigen::Success;
        };
        CHECK(semidefinite(face.hessian));
        // exact = P − N with P, N positive semidefinite and N P = 0: the projection is P.
        CHECK(semidefinite(face.hessian - exact));
        CHECK(((face.hessian - exact) * face.hessian).norm() <= 1e-4 * exact.squaredNorm());
        CHECK(face.hessian.trace() > 0);
        if ((face.hessian - exact).norm() > 1e-3 * exact.norm()) ++projected;
    }
    CHECK(projected >= 100);  // m_f^p is not convex in J: most faces' Hessians lose a negative part
}

TEST_CASE(
    "CLI-RUN-9: a Jacobian's singular values in closed form are the known ones and Eigen's SVD's, σ₁/σ₂ up to 10¹²",
    "[param][mips]") {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> angle(0, 6.283185307179586), exponent(-12, 12);
    for (int trial = 0; trial < 2000; ++trial) {
        // J = R(a) diag(s1, ±s2) R(b): its singular values s1, s2 known, σ₁/σ₂ from 1 to 10¹².
        const double s1 = std::pow(10.0, exponent(rng) / 4), s2 = s1 * std::pow(10.0, -std::abs(exponent(rng)));
        const double a = angle(rng), b = angle(rng), sign = trial % 2 ? 1 : -1;
        param::detail::Mat2 ra, rb, sigma;
        ra << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
        rb << std::cos(b), -std::sin(b), std::sin(b), std::cos(b);
        sigma << s1, 0, 0, sign * s2;
        const param::detail::Mat2 j = ra * sigma * rb;
        CAPTURE(j, s1, s2);
        const Vec2 closed = param::detail::singular_values(j);
        const Eigen::Vector2d svd = Eigen::JacobiSVD<param::detail::Mat2>(j).singularValues();
        // σ₂ is known to a relative 2⁻⁵² σ₁/σ₂ at best: J's entries are rounded at σ₁'s scale.
        const double small = 64 * 2.2e-16 * s1 / s2 + 1e-13;
        CHECK(closed[0] == Approx(s1).epsilon(1e-13));
        CHECK(closed[1] == Approx(s2).epsilon(small));
        CHECK(closed[0] == Approx(svd[0]).epsilon(1e-13));
        CHECK(closed[1] == Approx(svd[1]).epsilon(2 * small));
    }
    CHECK(param::detail::singular_values(param::detail::Mat2::Zero()) == Vec2(0, 0));
}

TEST_CASE("CLI-RUN-9: Newton's MIPS steps (p = 2, 4, 8) bring a warped map of a flat patch back to the identity",
          "[param][mips]") {
    const double power = GENERATE(2.0, 4.0, 8.0);
    for (std::uint64_t seed = 0; seed < 5; ++seed) {
        CAPTURE(power, seed);
        std::mt19937_64 rng(seed);
        std::vector<std::array<double, 2>> st;
        param::Disk disk = test::lattice_triangle(10, 0.2, rng, st);
        test::place(disk, st, right_triangle, 0, 1, 1, 0, 0);
        // β ↦ (w_k β_k) / Σ w_k β_k: a projective map of the triangle onto itself, corners fixed,
        // sides onto sides, straight lines onto straight lines (so no image triangle turns over).
        const double w1 = 1.5 + 0.5 * static_cast<double>(seed), w2 = 1 / w1 + 0.2;
        std::vector<Vec2> uv;
        for (const auto& [s, t] : st) {
            const double b0 = 1 - s - t, sum = b0 + w1 * s + w2 * t;
            uv.emplace_back(w1 * s / sum, w2 * t / sum);
        }
        std::vector<int> side;
        param::detail::MipsProblem p = problem_of(disk, uv, side);
        p.power = power;
        REQUIRE(std::isfinite(param::detail::mips_total(p)[0]));
        REQUIRE(param::detail::mips_total(p)[1] > 2.01);  // the start is not the optimum
        param::detail::mips_newton(p, 100, 1e-15, 0);
        CHECK(param::detail::mips_total(p)[1] <= 2 + 1e-8);  // m_f = 2: a similarity on every face
        double farthest = 0;
        for (std::size_t v = 0; v < st.size(); ++v)
            farthest = std::max(farthest, (p.uv[v] - Vec2(st[v][0], st[v][1])).norm());
        CHECK(farthest <= 1e-6);
    }
}

TEST_CASE(
    "CLI-RUN-9: Newton's MIPS steps (p = 2, 8) from the paper's map never raise the energy nor the worst face, "
    "never turn a face over, and keep the boundary on its sides",
    "[param][mips]") {
    const double power = GENERATE(2.0, 8.0);
    std::size_t lowered = 0;
    for (std::uint64_t seed = 0; seed < 40; ++seed) {
        CAPTURE(power, seed);
        const int genus = static_cast<int>(seed % 4);
        const TriMesh m = generate::random_mesh({genus, generate::min_faces(genus) + 600, seed, 0.1});
        param::Disk disk = test::disk_from_mesh(m, seed, 150);
        param::split_dividing_edges(disk);
        const param::PatchMap start = param::map_patch(disk);
        std::vector<Vec2> uv;
        for (const auto& b : start.beta) uv.emplace_back(b[1], b[2]);
        std::vector<int> side;
        param::detail::MipsProblem p = problem_of(disk, uv, side);
        p.power = power;
        const auto before = param::detail::mips_total(p);
        REQUIRE(std::isfinite(before[0]));
        param::detail::mips_newton(p, 20, 1e-9, 0);
        const auto after = param::detail::mips_total(p);
        CHECK(after[0] <= before[0]);
        CHECK(after[1] <= before[1]);
        if (after[0] < 0.999 * before[0]) ++lowered;
        for (const auto& t : p.triangles) CHECK(orient2d(p.uv[t[0]], p.uv[t[1]], p.uv[t[2]]) > 0);
        for (std::size_t v = 0; v < uv.size(); ++v) {
            if (side[v] < 0) continue;
            // Side 0: β2 = 0 (y = 0); side 1: β0 = 0 (x + y = 1); side 2: β1 = 0 (x = 0); inside [0, 1].
            const Vec2 q = p.uv[v];
            const double off = side[v] == 0 ? q.y() : side[v] == 1 ? q.x() + q.y() - 1 : q.x();
            CHECK(std::abs(off) <= 1e-12);
            CHECK(q.x() >= -1e-12);
            CHECK(q.y() >= -1e-12);
            CHECK(q.x() + q.y() <= 1 + 1e-12);
        }
    }
    CHECK(lowered >= 30);  // not vacuous: the paper's map is far from MIPS's optimum on most of these disks
}
