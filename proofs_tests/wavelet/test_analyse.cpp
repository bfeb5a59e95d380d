// FHR §5–§6 — the wavelet stage end to end (spec/wavelet.md WAV-10) with a known φ: D the
// icosahedron, φ the central projection of Ω_D onto the unit sphere, T a geodesic sphere.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>

#include <fhr/core/errors.hpp>
#include <fhr/core/geometry.hpp>
#include <fhr/wavelet/analyse.hpp>
#include "support/analytic_meshes.hpp"

using namespace fhr;

TEST_CASE("WAV-10: analyse: counts, round trip, kept counts, errors and Hausdorff distances on the sphere", "[unit][wavelet]") {
    const TriMesh D = test::icosphere(0);  // 12 vertices, 30 edges, 20 faces
    const TriMesh T = test::icosphere(4);
    const wavelet::DomainMap phi = [&](FaceId f, const std::array<double, 3>& b) {
        const auto c = D.face_vertices(f);
        return Vec3(b[0] * D.position(c[0]) + b[1] * D.position(c[1]) + b[2] * D.position(c[2])).normalized();
    };
    const std::array<double, 3> keep{5, 20, 100};
    const wavelet::WaveletResult w = wavelet::analyse(D, phi, 3, keep, T);
    // D³: V = 12 + 30 + 120 + 480 = 642, F = 20·64 = 1280.
    CHECK(w.levels == 3);
    CHECK(w.remesh_positions.size() == 642);
    CHECK(w.remesh_faces.size() == 1280);
    REQUIRE(w.remesh_level_faces.size() == 4);
    CHECK(w.remesh_level_faces[1].size() == 80);
    CHECK(w.coefficients == 630);
    for (const Vec3& x : w.remesh_positions) CHECK(std::abs(x.norm() - 1) <= 1e-15);
    CHECK(w.reconstruction_max_error <= 1e-12 * w.max_abs_coordinate);
    CHECK(w.cg_iterations.size() == 3);
    // Both surfaces are inscribed in the unit sphere: they differ by less than the larger sagitta,
    // 1 − cos(θ/2) ≈ 0.0024 for the edges of D³ (θ ≈ 0.14); and they do differ.
    CHECK(w.remesh_hausdorff.lower() > 0);
    CHECK(w.remesh_hausdorff.upper() <= 0.005 + w.remesh_hausdorff.resolution);
    CHECK(w.bbox_diagonal == bounding_box(T).diagonal());
    CHECK(w.hausdorff_relative == w.remesh_hausdorff.lower() / w.bbox_diagonal);
    REQUIRE(w.kept.size() == 3);
    CHECK(w.kept[0].count == 31);   // ⌊0.05·630⌋
    CHECK(w.kept[1].count == 126);  // ⌊0.20·630⌋
    CHECK(w.kept[2].count == 630);
    CHECK(w.kept[0].l2_error >= w.kept[1].l2_error);
    CHECK(w.kept[1].l2_error >= w.kept[2].l2_error);
    CHECK(w.kept[2].l2_error <= 1e-12);
    CHECK(w.kept[0].hausdorff.lower() >= w.kept[2].hausdorff.lower() - w.remesh_hausdorff.resolution);
    for (const auto& k : w.kept) CHECK(k.positions.size() == 642);
    CHECK_THROWS_AS(wavelet::analyse(D, phi, 1, std::array<double, 1>{120}, T), InvalidInput);
}
