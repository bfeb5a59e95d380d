// §3 + §4 end to end: Proposition 2 (linear precision) on flat polyhedra whose domain is their
// own corners, and the certificate plus the independent oracle (fhr verify) on every run.
#include <catch2/catch.hpp>

#include <cmath>

#include <fhr/exchange/verify.hpp>
#include <fhr/pipeline/run.hpp>
#include <fhr/pipeline/pipeline.hpp>
#include "support/analytic_meshes.hpp"

using namespace fhr;

namespace {

// The barycentric coordinates of x in the triangle (a, b, c) it lies in (least squares in its plane).
std::array<double, 3> barycentric(const Vec3& x, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 n = (b - a).cross(c - a);
    const double area = n.squaredNorm();
    const double l1 = (c - a).cross(x - a).dot(n) / area * -1;  // weight of b
    const double l2 = (b - a).cross(x - a).dot(n) / area;       // weight of c
    return {1 - l1 - l2, l1, l2};
}

// The largest deviation of ψ from the linear map over all vertices of T′, for a certified run.
double linear_deviation(const std::vector<Vec3>& corners, const std::vector<Triangle>& faces, param::Weights weights,
                        unsigned seed) {
    const TriMesh T = test::refined_polyhedron(corners, faces, 12, 0.25, seed);
    domain::Domain D;
    D.mesh = TriMesh::from_triangles(corners, faces);
    for (std::uint32_t k = 0; k < corners.size(); ++k) D.t_vertex.push_back(VertexId(k));
    pipeline::Options options;
    options.relax = false;  // Proposition 2 is the paper's map's (a relaxed map gives it up: CLI-RUN-9)
    options.map.weights = weights;
    const pipeline::Parameterization p = pipeline::parameterize(T, D, options);
    REQUIRE(p.partition.retries == 0);
    REQUIRE(p.certified());
    const exchange::VerifyReport oracle = exchange::verify(pipeline::to_param_file(p), &T);
    INFO((oracle.first_failure() ? oracle.first_failure()->first_failure : std::string()));
    CHECK(oracle.valid());
    // Proposition 2: [x_j, x_k, x_l] ⊂ Ω_T, so φ_i is linear: ψ(v) is v's barycentric coordinates
    // in the flat domain triangle. Rounding: the solve reproduces linear functions up to a small
    // multiple of the condition number times 1e−16; 1e−12 leaves a wide margin.
    double worst = 0;
    for (RefinedFaceId f : p.face_patch.ids()) {
        const Triangle& d = faces[p.face_patch[f].idx()];
        for (int c = 0; c < 3; ++c) {
            const auto want = barycentric(p.refined_positions[p.refined_faces[f.idx()][c]], corners[d[0]],
                                          corners[d[1]], corners[d[2]]);
            for (int r = 0; r < 3; ++r) worst = std::max(worst, std::abs(p.face_beta[f][c][r] - want[r]));
        }
    }
    return worst;
}

}  // namespace

TEST_CASE("Prop. 2 end to end: an irregularly triangulated tetrahedron over its corners maps linearly",
          "[pipeline][prop2]") {
    for (param::Weights w : {param::Weights::shape_preserving, param::Weights::mean_value})
        for (unsigned seed : {1u, 2u, 3u})
            CHECK(linear_deviation(test::tetrahedron_corners, test::tetrahedron_faces, w, seed) <= 1e-12);
    // The control: uniform weights have no linear precision, and the check sees it.
    CHECK(linear_deviation(test::tetrahedron_corners, test::tetrahedron_faces, param::Weights::uniform, 1) > 1e-4);
}

TEST_CASE("Prop. 2 end to end: an irregularly triangulated octahedron over its corners maps linearly",
          "[pipeline][prop2]") {
    for (param::Weights w : {param::Weights::shape_preserving, param::Weights::mean_value})
        for (unsigned seed : {4u, 5u})
            CHECK(linear_deviation(test::octahedron_corners, test::octahedron_faces, w, seed) <= 1e-12);
    CHECK(linear_deviation(test::octahedron_corners, test::octahedron_faces, param::Weights::uniform, 4) > 1e-4);
}
