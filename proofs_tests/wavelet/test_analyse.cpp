// FHR §5–§6 — the wavelet stage end to end (spec/wavelet.md WAV-10) with a known φ: D the
// icosahedron, φ the central projection of Ω_D onto the unit sphere, T a geodesic sphere; and
// (WAV-14) D with boundary and two components: two icosahedral bands, each projected onto its own
// unit sphere.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <fhr/core/errors.hpp>
#include <fhr/core/geometry.hpp>
#include <fhr/wavelet/analyse.hpp>
#include "support/analytic_meshes.hpp"

#include <fhr/wavelet/refine.hpp>

using namespace fhr;

TEST_CASE("WAV-10: analyse: counts, round trip, kept counts, errors and Hausdorff distances on the sphere",
          "[unit][wavelet]") {
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
    // Hausdorff resolution: 0 (the default) means 1e−4 of T's bounding-box diagonal; a positive
    // one is used as given.
    CHECK(w.remesh_hausdorff.resolution == 1e-4 * w.bbox_diagonal);
    for (const auto& k : w.kept) CHECK(k.hausdorff.resolution == w.remesh_hausdorff.resolution);
    // T's tree built by the caller (pipeline::run: beside §2): the same brackets, bit for bit.
    const std::vector<Triangle> t_faces = T.triangles();
    const wavelet::TriangleTree t_tree(T.positions(), t_faces);
    const wavelet::WaveletResult with_tree = wavelet::analyse(D, phi, 3, keep, T, {}, nullptr, nullptr, &t_tree);
    const auto same_bracket = [](const wavelet::Hausdorff& a, const wavelet::Hausdorff& b) {
        return a.a_to_b.lower == b.a_to_b.lower && a.a_to_b.upper == b.a_to_b.upper &&
               a.b_to_a.lower == b.b_to_a.lower && a.b_to_a.upper == b.b_to_a.upper &&
               a.a_to_b.samples == b.a_to_b.samples && a.b_to_a.samples == b.b_to_a.samples;
    };
    CHECK(same_bracket(with_tree.remesh_hausdorff, w.remesh_hausdorff));
    REQUIRE(with_tree.kept.size() == w.kept.size());
    for (std::size_t i = 0; i < w.kept.size(); ++i)
        CHECK(same_bracket(with_tree.kept[i].hausdorff, w.kept[i].hausdorff));
    const wavelet::WaveletResult given =
        wavelet::analyse(D, phi, 1, std::array<double, 1>{50}, T, {.resolution = 0.002});
    CHECK(given.remesh_hausdorff.resolution == 0.002);
    CHECK(given.kept[0].hausdorff.resolution == 0.002);
    CHECK_THROWS_AS(wavelet::analyse(D, phi, 1, std::array<double, 1>{120}, T), InvalidInput);
}

TEST_CASE("WAV-14: analyse with boundary and two components: two icosahedral bands on their spheres",
          "[unit][wavelet]") {
    // D: twice the icosahedron without the triangles at two opposite vertices (an annulus: V = 10,
    // E = 20, F = 10, two boundary loops), the second copy at x + 4. φ: the central projection of
    // each band onto the unit sphere about its own centre. T: f⁴(Ω_D), the same bands one level finer.
    const TriMesh ico = test::icosphere(0);
    std::uint32_t antipode = 0;
    for (VertexId v : ico.vertices())
        if ((ico.position(v) + ico.position(VertexId(0))).norm() < 1e-12) antipode = v.idx();
    REQUIRE(antipode != 0);
    std::vector<Vec3> x;
    std::vector<Triangle> t;
    std::vector<std::uint32_t> id(ico.n_vertices());
    for (int c = 0; c < 2; ++c) {
        for (VertexId v : ico.vertices()) {
            if (v.idx() == 0 || v.idx() == antipode) continue;
            id[v.idx()] = static_cast<std::uint32_t>(x.size());
            x.push_back(ico.position(v) + Vec3(4.0 * c, 0, 0));
        }
        for (const Triangle& f : ico.triangles())
            if (std::count(f.begin(), f.end(), 0u) == 0 && std::count(f.begin(), f.end(), antipode) == 0)
                t.push_back({id[f[0]], id[f[1]], id[f[2]]});
    }
    const TriMesh D = TriMesh::from_triangles(x, t);
    REQUIRE(D.n_vertices() == 20);
    REQUIRE(D.n_edges() == 40);
    REQUIRE(D.n_faces() == 20);
    const wavelet::DomainMap phi = [&](FaceId f, const std::array<double, 3>& b) {
        const auto c = D.face_vertices(f);
        const Vec3 centre(f.idx() < 10 ? 0.0 : 4.0, 0, 0);
        const Vec3 p = b[0] * D.position(c[0]) + b[1] * D.position(c[1]) + b[2] * D.position(c[2]);
        return Vec3(centre + (p - centre).normalized());
    };
    const wavelet::Refinement finer = wavelet::refine(D, 4);
    const TriMesh T = TriMesh::from_triangles(wavelet::sample(finer, phi), finer.finest().triangles());
    const std::array<double, 3> keep{5, 20, 100};
    const wavelet::WaveletResult w = wavelet::analyse(D, phi, 3, keep, T);
    // (V, E, F): (20, 40, 20) → (60, 140, 80) → (200, 520, 320) → (720, ·, 1280).
    CHECK(w.remesh_positions.size() == 720);
    CHECK(w.remesh_faces.size() == 1280);
    CHECK(w.coefficients == 700);
    CHECK(w.reconstruction_max_error <= 1e-12 * w.max_abs_coordinate);
    // f³(Ω_D) and f⁴(Ω_D) are inscribed in the same spheres: they differ by less than the sagitta
    // of D³'s edges (θ ≈ 0.14: 1 − cos(θ/2) ≈ 0.0024), and they do differ.
    CHECK(w.remesh_hausdorff.lower() > 0);
    CHECK(w.remesh_hausdorff.upper() <= 0.005 + w.remesh_hausdorff.resolution);
    REQUIRE(w.kept.size() == 3);
    CHECK(w.kept[0].count == 35);   // ⌊0.05·700⌋
    CHECK(w.kept[1].count == 140);  // ⌊0.20·700⌋
    CHECK(w.kept[0].l2_error >= w.kept[1].l2_error);
    CHECK(w.kept[1].l2_error >= w.kept[2].l2_error);
    CHECK(w.kept[2].l2_error <= 1e-12);
}
