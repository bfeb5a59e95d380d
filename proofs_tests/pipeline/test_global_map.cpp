// §4 the global maps φ: Ω_D → Ω_T and ψ: Ω_T′ → Ω_D of a whole run (pipeline::GlobalMap): corners to
// corners, a point on an edge of D the same from both faces bit for bit, and φ(ψ(p)) = p.
#include <catch2/catch.hpp>

#include <random>

#include <fhr/core/geometry.hpp>
#include <fhr/domain/decimate.hpp>
#include <fhr/pipeline/pipeline.hpp>
#include "support/test_support.hpp"

using namespace fhr;

TEST_CASE("GlobalMap: φ maps corners to x_j, is continuous across D's edges, and inverts ψ", "[pipeline][global]") {
    const auto path = test::cgal_mesh("fandisk.off");
    if (!path) FAIL("fandisk.off is missing: run ./run demo to extract libcgal-demo's meshes");
    const TriMesh T = test::load_mesh(*path);
    const pipeline::Parameterization p = pipeline::parameterize(T, domain::decimate(T, {.target_faces = 114}), {});
    REQUIRE(p.certified());
    const pipeline::GlobalMap map(p);
    const domain::Domain& D = p.partition.domain;
    // Corners: β = e_c is x_j exactly.
    for (FaceId d : D.mesh.faces()) {
        const auto c = D.mesh.face_vertices(d);
        for (int k = 0; k < 3; ++k) {
            std::array<double, 3> e{0, 0, 0};
            e[static_cast<std::size_t>(k)] = 1;
            CHECK(map.phi(d, e) == T.position(D.t_vertex[c[static_cast<std::size_t>(k)]]));
        }
    }
    // Continuity: a point of edge [v_a, v_b] from either face gives the same point, bit for bit.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0, 1);
    std::size_t mismatches = 0;
    for (EdgeId e : D.mesh.edges()) {
        const HalfedgeId h = TriMesh::halfedge(e, 0);
        const VertexId a = D.mesh.from(h), b = D.mesh.to(h);
        for (int q = 0; q < 5; ++q) {
            const double t = u(rng);
            auto in = [&](FaceId d) {
                const auto c = D.mesh.face_vertices(d);
                std::array<double, 3> beta{0, 0, 0};
                for (std::size_t k = 0; k < 3; ++k) beta[k] = c[k] == a ? 1 - t : c[k] == b ? t : 0.0;
                return map.phi(d, beta);
            };
            mismatches += in(D.mesh.face(h)) != in(D.mesh.face(TriMesh::twin(h)));
        }
    }
    CHECK(mismatches == 0);
    // φ(ψ(p)) = p for random points p of T′ (point location and interpolation agree to rounding).
    const double scale = (bounding_box(T).max - bounding_box(T).min).norm();
    double worst = 0;
    std::uniform_int_distribution<std::size_t> face(0, p.refined_faces.size() - 1);
    for (int q = 0; q < 2000; ++q) {
        const std::size_t f = face(rng);
        double w1 = u(rng), w2 = u(rng);
        if (w1 + w2 > 1) w1 = 1 - w1, w2 = 1 - w2;
        const std::array<double, 3> w{1 - w1 - w2, w1, w2};
        Vec3 x = Vec3::Zero();
        for (int k = 0; k < 3; ++k) x += w[static_cast<std::size_t>(k)] * p.refined_positions[p.refined_faces[f][static_cast<std::size_t>(k)]];
        const auto [d, beta] = map.psi(f, w);
        worst = std::max(worst, (map.phi(d, beta) - x).norm() / scale);
    }
    // The β of ψ carry ~1e−16 relative error; through a triangle of the map that is ~1e−12 of the
    // model at worst for the thinnest image triangles of a certified run.
    CHECK(worst <= 1e-9);
}
