// FHR tests — the distortion figures (spec/distortion.md DIST-1..9), on the worked examples whose
// values are computed by hand in the spec, and as properties: invariance under rigid motions and
// uniform scaling of either side, σ₁σ₂ the area ratio, and σ against an independent SVD of the
// Jacobian (Eigen's JacobiSVD of the 3×2 matrix P·Q⁻¹ in the image's own frame).
#include <catch2/catch.hpp>
#include <rapidcheck/catch.h>

#include <cmath>
#include <vector>

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include <fhr/exchange/distortion.hpp>

using fhr::Vec3;
using fhr::exchange::Distortion;
using fhr::exchange::face_stretch;
using fhr::exchange::FaceStretch;
using fhr::exchange::summarize;
using fhr::exchange::weighted_percentile;

namespace {

const Vec3 o(0, 0, 0), ex(1, 0, 0), ey(0, 1, 0);

FaceStretch identity() { return face_stretch(o, ex, ey, o, ex, ey); }

}  // namespace

TEST_CASE("DIST-1, DIST-4..8: the identity has σ = 1 and every figure at its ideal value", "[exchange][distortion]") {
    const FaceStretch s = identity();
    CHECK_FALSE(s.degenerate);
    CHECK(s.sigma1 == Approx(1).epsilon(1e-15));
    CHECK(s.sigma2 == Approx(1).epsilon(1e-15));
    const Distortion d = summarize({s});
    CHECK(d.degenerate == 0);
    CHECK(*d.l2_stretch == Approx(1).epsilon(1e-15));
    CHECK(*d.linf_stretch == Approx(1).epsilon(1e-15));
    CHECK(*d.symmetric_dirichlet == Approx(4).epsilon(1e-15));
    CHECK(*d.anisotropy_p50 == Approx(1).epsilon(1e-15));
    CHECK(*d.anisotropy_max == Approx(1).epsilon(1e-15));
    CHECK(*d.area_distortion_max == Approx(1).epsilon(1e-15));
    CHECK(d.anisotropy_above_10 == 0);
}

TEST_CASE("DIST-1, DIST-3..8: a stretch by 2 along x, normalised (spec's worked example)", "[exchange][distortion]") {
    const FaceStretch s = face_stretch(o, ex, ey, o, Vec3(2, 0, 0), ey);
    CHECK(s.sigma1 == Approx(2).epsilon(1e-15));
    CHECK(s.sigma2 == Approx(1).epsilon(1e-15));
    const Distortion d = summarize({s});
    CHECK(*d.l2_stretch == Approx(std::sqrt(1.25)).epsilon(1e-15));
    CHECK(*d.linf_stretch == Approx(std::sqrt(2.0)).epsilon(1e-15));
    CHECK(*d.symmetric_dirichlet == Approx(5).epsilon(1e-14));
    CHECK(*d.anisotropy_p50 == Approx(2).epsilon(1e-15));
    CHECK(*d.area_distortion_max == Approx(1).epsilon(1e-15));
}

TEST_CASE("DIST-3, DIST-9: two faces, the weighted median is the heavier face's (spec's worked example)",
          "[exchange][distortion]") {
    const FaceStretch thin = face_stretch(o, Vec3(3, 0, 0), ey, o, ex, ey);
    CHECK(thin.sigma1 == Approx(1).epsilon(1e-15));
    CHECK(thin.sigma2 == Approx(1.0 / 3).epsilon(1e-15));
    CHECK(thin.image_area == Approx(1.5).epsilon(1e-15));
    const Distortion d = summarize({identity(), thin});
    CHECK(*d.anisotropy_p50 == Approx(3).epsilon(1e-15));  // weights ¼ and ¾
    CHECK(*d.anisotropy_max == Approx(3).epsilon(1e-15));
    // k² = ½: σ′ = √2·σ; L2² = (¼·(2 + 2)/2 + ¾·(2 + 2/9)/2) = ½ + 5/6.
    CHECK(*d.l2_stretch == Approx(std::sqrt(0.5 + 5.0 / 6)).epsilon(1e-14));
    CHECK(*d.linf_stretch == Approx(std::sqrt(2.0)).epsilon(1e-15));
    // Area distortion: σ₁′σ₂′ = 2·(1, ⅓) → max(2, ½) = 2 and max(⅔, 3/2) = 3/2; p99 is 2 (the identity face,
    // ¼ of the weight, lies above 3/2).
    CHECK(*d.area_distortion_max == Approx(2).epsilon(1e-15));
    CHECK(*d.area_distortion_p99 == Approx(2).epsilon(1e-15));
}

TEST_CASE("DIST-2: degenerate faces are counted apart; all degenerate gives no figure", "[exchange][distortion]") {
    const FaceStretch flat = face_stretch(o, ex, Vec3(2, 0, 0), o, ex, ey);
    CHECK(flat.degenerate);
    const Distortion d = summarize({identity(), flat});
    CHECK(d.faces == 2);
    CHECK(d.degenerate == 1);
    CHECK(*d.l2_stretch == Approx(1).epsilon(1e-15));
    CHECK(*d.anisotropy_max == Approx(1).epsilon(1e-15));
    const Distortion none = summarize({flat, face_stretch(o, ex, ey, o, ex, ex)});
    CHECK(none.degenerate == 2);
    CHECK_FALSE(none.l2_stretch.has_value());
    CHECK_FALSE(none.anisotropy_p50.has_value());
    CHECK_FALSE(none.area_distortion_max.has_value());
}

TEST_CASE("DIST-9: the weighted percentile is the smallest value whose faces at or below weigh p",
          "[exchange][distortion]") {
    const std::vector<double> x{5, 1, 3, 2}, w{1, 1, 1, 1};
    CHECK(weighted_percentile(x, w, 0.5) == 2);
    CHECK(weighted_percentile(x, w, 0.51) == 3);
    CHECK(weighted_percentile(x, w, 0.99) == 5);
    CHECK(weighted_percentile(x, w, 0.0) == 1);
    CHECK(weighted_percentile({1, 100}, {3, 1}, 0.75) == 1);  // exactly ¾ of the weight at 1
    CHECK(weighted_percentile({1, 100}, {2.5, 1.5}, 0.75) == 100);
}

TEST_CASE("DIST-1: σ equals an independent SVD and is invariant under motions and scaling",
          "[exchange][distortion][property]") {
    rc::prop("random triangle pairs", [] {
        const auto point = [] {
            return Vec3(*rc::gen::inRange(-1000, 1000) / 100.0, *rc::gen::inRange(-1000, 1000) / 100.0,
                        *rc::gen::inRange(-1000, 1000) / 100.0);
        };
        const Vec3 p0 = point(), p1 = point(), p2 = point();
        const Eigen::Vector2d q0(*rc::gen::inRange(-100, 100) / 10.0, *rc::gen::inRange(-100, 100) / 10.0);
        const Eigen::Vector2d q1(*rc::gen::inRange(-100, 100) / 10.0, *rc::gen::inRange(-100, 100) / 10.0);
        const Eigen::Vector2d q2(*rc::gen::inRange(-100, 100) / 10.0, *rc::gen::inRange(-100, 100) / 10.0);
        Eigen::Matrix2d Q;
        Q << q1 - q0, q2 - q0;
        Eigen::Matrix<double, 3, 2> P;
        P << p1 - p0, p2 - p0;
        RC_PRE(std::fabs(Q.determinant()) > 1e-3 && (P.col(0).cross(P.col(1))).norm() > 1e-3);
        const Eigen::Matrix<double, 3, 2> J = P * Q.inverse();
        const Eigen::JacobiSVD<Eigen::Matrix<double, 3, 2>> svd(J);
        const Vec3 a(q0[0], q0[1], 0), b(q1[0], q1[1], 0), c(q2[0], q2[1], 0);
        const FaceStretch s = face_stretch(a, b, c, p0, p1, p2);
        RC_ASSERT(!s.degenerate);
        const double tol = 1e-9 * svd.singularValues()(0);
        RC_ASSERT(std::fabs(s.sigma1 - svd.singularValues()(0)) <= tol);
        RC_ASSERT(std::fabs(s.sigma2 - svd.singularValues()(1)) <= tol);
        // σ₁σ₂ is the area ratio.
        RC_ASSERT(std::fabs(s.sigma1 * s.sigma2 - s.surface_area / s.image_area) <= 1e-9 * s.sigma1 * s.sigma2);
        // A rotation and translation of the surface, and a uniform scaling λ of it, scale σ by λ.
        const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
        const double lambda = 3.5;
        const Vec3 t(5, -2, 1);
        const FaceStretch m = face_stretch(a, b, c, lambda * R * p0 + t, lambda * R * p1 + t, lambda * R * p2 + t);
        RC_ASSERT(std::fabs(m.sigma1 - lambda * s.sigma1) <= 1e-9 * lambda * s.sigma1);
        RC_ASSERT(std::fabs(m.sigma2 - lambda * s.sigma2) <= 1e-9 * lambda * s.sigma1);
        // The image given in 3D, rotated out of the plane z = 0, is the same image.
        const FaceStretch lifted = face_stretch(R * a, R * b, R * c, p0, p1, p2);
        RC_ASSERT(std::fabs(lifted.sigma1 - s.sigma1) <= tol);
        RC_ASSERT(std::fabs(lifted.sigma2 - s.sigma2) <= tol);
    });
}
