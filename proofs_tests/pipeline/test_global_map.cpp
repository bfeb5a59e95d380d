// §4 the global maps φ: Ω_D → Ω_T and ψ: Ω_T′ → Ω_D of a whole run (pipeline::GlobalMap): corners to
// corners, a point on an edge of D the same from both faces bit for bit, and φ(ψ(p)) = p; and the
// per-face bounds of |f^J − φ| on D^J and on T that start §5's brackets (wavelet::affine_bounds, WAV-15),
// and the brackets a whole run reports with them, against brackets computed from scratch.
#include <catch2/catch.hpp>
#include <rapidcheck/catch.h>

#include <optional>
#include <random>
#include <span>
#include <vector>

#include <fhr/core/errors.hpp>
#include <fhr/core/geometry.hpp>
#include <fhr/domain/decimate.hpp>
#include <fhr/generate/random_mesh.hpp>
#include <fhr/pipeline/pipeline.hpp>
#include <fhr/pipeline/run.hpp>
#include <fhr/testing/rapidcheck.hpp>
#include <fhr/wavelet/analyse.hpp>
#include "support/test_support.hpp"

using namespace fhr;

namespace {

// §5's properties draw from every embedded family: genus 0–2, up to one hole, ≤ 1,200 faces.
rc::Gen<fhr::testing::GeneratedMesh> small_family_mesh() {
    return fhr::testing::gen_mesh(
        {.min_genus = 0,
         .max_genus = 2,
         .max_faces = 1200,
         .min_holes = 0,
         .max_holes = 1,
         .families = {std::begin(generate::embedded_families), std::end(generate::embedded_families)}});
}

// WAV-15's maxima computed another way, for their tightness: every face of T′ clipped against
// every face of D^J under its patch's face of D (Sutherland–Hodgman in the plane of (β_0, β_1)),
// |f^J − φ| evaluated at each corner of each piece, both maps by their own barycentric
// coordinates there. No crossings, no 10⁻¹² margins, no reuse of a vertex: a bound from
// affine_bounds above these maxima by more than rounding counted a point where it lies in no piece.
wavelet::AffineBounds clipped_maxima(const wavelet::Refinement& r, std::span<const Vec3> fj,
                                     const pipeline::Parameterization& p, std::size_t t_faces) {
    using P2 = std::array<double, 2>;
    const int J = r.depth();
    const auto children = static_cast<std::uint32_t>(1u << (2 * J));
    wavelet::AffineBounds out{std::vector<double>(r.finest().n_faces(), 0), std::vector<double>(t_faces, 0)};
    // Barycentric coordinates of q in the triangle (a, b, c).
    const auto bary = [](const P2& q, const P2& a, const P2& b, const P2& c) {
        const double det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
        const double l1 = ((q[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (q[1] - a[1])) / det;
        const double l2 = ((b[0] - a[0]) * (q[1] - a[1]) - (q[0] - a[0]) * (b[1] - a[1])) / det;
        return std::array<double, 3>{1 - l1 - l2, l1, l2};
    };
    for (RefinedFaceId face : p.face_patch.ids()) {
        const std::size_t i = face.idx();
        const auto& beta = p.face_beta[face];
        const std::array<P2, 3> f{P2{beta[0][0], beta[0][1]}, P2{beta[1][0], beta[1][1]}, P2{beta[2][0], beta[2][1]}};
        for (std::uint32_t g = p.face_patch[face].idx() * children; g < (p.face_patch[face].idx() + 1) * children;
             ++g) {
            const auto& cb = r.corner_beta[g];
            const std::array<P2, 3> h{P2{cb[0][0], cb[0][1]}, P2{cb[1][0], cb[1][1]}, P2{cb[2][0], cb[2][1]}};
            const double orientation =
                (h[1][0] - h[0][0]) * (h[2][1] - h[0][1]) - (h[2][0] - h[0][0]) * (h[1][1] - h[0][1]);
            std::vector<P2> poly(f.begin(), f.end());
            for (int k = 0; k < 3 && !poly.empty(); ++k) {  // keep the side of h's edge k where h lies
                const P2 &a = h[k], &b = h[(k + 1) % 3];
                const auto side = [&](const P2& q) {
                    return ((b[0] - a[0]) * (q[1] - a[1]) - (q[0] - a[0]) * (b[1] - a[1])) * orientation;
                };
                std::vector<P2> kept;
                for (std::size_t m = 0; m < poly.size(); ++m) {
                    const P2 &x = poly[m], &y = poly[(m + 1) % poly.size()];
                    const double sx = side(x), sy = side(y);
                    if (sx >= 0) kept.push_back(x);
                    if ((sx < 0) != (sy < 0)) {
                        const double t = sx / (sx - sy);
                        kept.push_back({x[0] + t * (y[0] - x[0]), x[1] + t * (y[1] - x[1])});
                    }
                }
                poly = std::move(kept);
            }
            const auto c = r.finest().face_vertices(FaceId(g));
            for (const P2& q : poly) {
                const auto w = bary(q, f[0], f[1], f[2]), l = bary(q, h[0], h[1], h[2]);
                Vec3 phi = Vec3::Zero(), at = Vec3::Zero();
                for (std::size_t k = 0; k < 3; ++k) {
                    phi += w[k] * p.refined_positions[p.refined_faces[i][k]];
                    at += l[k] * fj[c[k].idx()];
                }
                const double gap = (at - phi).norm();
                out.remesh[g] = std::max(out.remesh[g], gap);
                out.t[p.face_t[face].idx()] = std::max(out.t[p.face_t[face].idx()], gap);
            }
        }
    }
    return out;
}

}  // namespace

TEST_CASE("GlobalMap: φ maps corners to x_j, is continuous across D's edges, and inverts ψ", "[pipeline][global]") {
    const std::string path = test::cgal_mesh("fandisk.off");
    const TriMesh T = test::load_mesh(path);
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
            CHECK(map.phi(DFaceId(d), e) == T.position(D.t_vertex[c[static_cast<std::size_t>(k)]]));
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
                return map.phi(DFaceId(d), beta);
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
        for (int k = 0; k < 3; ++k)
            x += w[static_cast<std::size_t>(k)] * p.refined_positions[p.refined_faces[f][static_cast<std::size_t>(k)]];
        const auto [d, beta] = map.psi(RefinedFaceId(static_cast<RefinedFaceId::Index>(f)), w);
        worst = std::max(worst, (map.phi(d, beta) - x).norm() / scale);
    }
    // The β of ψ carry ~1e−16 relative error; through a triangle of the map that is ~1e−12 of the
    // model at worst for the thinnest image triangles of a certified run.
    CHECK(worst <= 1e-9);
}

TEST_CASE(
    "WAV-15: on every face of D^J, |f^J − φ| is at most its affine bound, and on every face of T |x − f^J(ψ(x))| "
    "its bound from T (random points)",
    "[pipeline][property][wavelet]") {
    // φ from a whole run of §2–§4 on meshes of every embedded family; f^J its samples. Random
    // points of every face of D^J: their φ by point location (GlobalMap), f^J by interpolation;
    // random points x of every face of T′: ψ(x) by GlobalMap, f^J there by the
    // face of D^J that holds it, against the bound of the face of T under it. A bound that missed
    // a corner of the pieces (a crossing of T′'s sides with D^J's, a vertex of T′ on a side shared
    // by two faces of D^J or of T) falls below the gap near it.
    rc::prop("per face of D^J", [] {
        const fhr::testing::GeneratedMesh T = *small_family_mesh();
        const int J = *rc::gen::inRange(1, 4);
        std::optional<pipeline::Parameterization> p;
        // Only the documented failures of decimate and parameterize discard a case; an InternalError
        // or anything else fails the property.
        try {
            p.emplace(pipeline::parameterize(
                T, domain::decimate(T, {.target_faces = std::max<std::size_t>(8, T.n_faces() / 40)}), {}));
        } catch (const fhr::InvalidInput& e) {
            RC_DISCARD(e.what());
        } catch (const fhr::PartitionFailure& e) {
            RC_DISCARD(e.what());
        } catch (const fhr::NumericalFailure& e) {
            RC_DISCARD(e.what());
        }
        RC_PRE(p->certified());
        const pipeline::GlobalMap map(*p);
        const wavelet::Refinement r = wavelet::refine(p->partition.domain.mesh, J);
        const std::vector<Vec3> fj =
            wavelet::sample(r, [&](FaceId d, const std::array<double, 3>& b) { return map.phi(DFaceId(d), b); });
        const wavelet::AffinePieces pieces{p->refined_positions, p->refined_faces.size(),
                                           [&](std::size_t i, Triangle& c, std::uint32_t& d,
                                               std::array<std::array<double, 3>, 3>& beta, std::uint32_t& t) {
                                               const RefinedFaceId f(static_cast<RefinedFaceId::Index>(i));
                                               c = p->refined_faces[i], d = p->face_patch[f].idx(),
                                               beta = p->face_beta[f], t = p->face_t[f].idx();
                                           }};
        const wavelet::AffineBounds bounds = wavelet::affine_bounds(r, fj, pieces, T.n_faces(), 0);
        const double diagonal = (bounding_box(T).max - bounding_box(T).min).norm();
        // Tight: each bound is the exact maximum over its face (found by clipping), up to rounding.
        const wavelet::AffineBounds exact = clipped_maxima(r, fj, *p, T.n_faces());
        for (std::size_t g = 0; g < exact.remesh.size(); ++g)
            RC_ASSERT(std::abs(bounds.remesh[g] - exact.remesh[g]) <= 1e-9 * diagonal);
        for (std::size_t t = 0; t < exact.t.size(); ++t)
            RC_ASSERT(std::abs(bounds.t[t] - exact.t[t]) <= 1e-9 * diagonal);
        // How far T′ lies from T (on_t) is added to every bound.
        const double on_t = 1e-3 * diagonal;
        const wavelet::AffineBounds raised = wavelet::affine_bounds(r, fj, pieces, T.n_faces(), on_t);
        for (std::size_t g = 0; g < exact.remesh.size(); ++g)
            RC_ASSERT(std::abs(raised.remesh[g] - on_t - bounds.remesh[g]) <= 1e-12 * diagonal);
        for (std::size_t t = 0; t < exact.t.size(); ++t)
            RC_ASSERT(std::abs(raised.t[t] - on_t - bounds.t[t]) <= 1e-12 * diagonal);
        std::mt19937_64 rng(*rc::gen::arbitrary<std::uint64_t>());
        std::uniform_real_distribution<double> u(0, 1);
        const TriMesh& finest = r.finest();
        for (FaceId g : finest.faces()) {
            const auto c = finest.face_vertices(g);
            const auto& cb = r.corner_beta[g.idx()];
            const FaceId root(g.idx() >> (2 * J));
            for (int q = 0; q < 8; ++q) {
                double s = u(rng), t = u(rng);
                if (s + t > 1) s = 1 - s, t = 1 - t;
                const std::array<double, 3> l{1 - s - t, s, t};
                std::array<double, 3> beta{};
                for (std::size_t i = 0; i < 3; ++i) beta[i] = l[0] * cb[0][i] + l[1] * cb[1][i] + l[2] * cb[2][i];
                const Vec3 at = l[0] * fj[c[0].idx()] + l[1] * fj[c[1].idx()] + l[2] * fj[c[2].idx()];
                RC_ASSERT((at - map.phi(DFaceId(root), beta)).norm() <=
                          bounds.remesh[g.idx()] * (1 + 1e-9) + 1e-12 * diagonal);
            }
        }
        // From T: f^J at ψ(x), in the face of D^J under the root face that holds ψ(x).
        const auto fj_at = [&](DFaceId d, const std::array<double, 3>& beta) {
            const auto n = static_cast<std::uint32_t>(1u << (2 * J));
            for (std::uint32_t g = d.idx() * n; g < (d.idx() + 1) * n; ++g) {
                const auto& cb = r.corner_beta[g];
                // β = Σ l_k cb[k]: solve in the first two coordinates (the third follows).
                const double a = cb[0][0] - cb[2][0], b = cb[1][0] - cb[2][0], c = cb[0][1] - cb[2][1],
                             e = cb[1][1] - cb[2][1];
                const double x = beta[0] - cb[2][0], y = beta[1] - cb[2][1], det = a * e - b * c;
                const double l0 = (x * e - b * y) / det, l1 = (a * y - c * x) / det, l2 = 1 - l0 - l1;
                if (std::min({l0, l1, l2}) < -1e-9) continue;
                const auto v = finest.face_vertices(FaceId(g));
                return Vec3(l0 * fj[v[0].idx()] + l1 * fj[v[1].idx()] + l2 * fj[v[2].idx()]);
            }
            RC_FAIL("no face of D^J holds the point");
            return Vec3(Vec3::Zero());
        };
        for (std::size_t i = 0; i < p->refined_faces.size(); ++i)
            for (int q = 0; q < 4; ++q) {
                double s = u(rng), t = u(rng);
                if (s + t > 1) s = 1 - s, t = 1 - t;
                const std::array<double, 3> w{1 - s - t, s, t};
                Vec3 x = Vec3::Zero();
                for (std::size_t k = 0; k < 3; ++k) x += w[k] * p->refined_positions[p->refined_faces[i][k]];
                const RefinedFaceId f(static_cast<RefinedFaceId::Index>(i));
                const auto [d, beta] = map.psi(f, w);
                RC_ASSERT((x - fj_at(d, beta)).norm() <= bounds.t[p->face_t[f].idx()] * (1 + 1e-9) + 1e-12 * diagonal);
            }
    });
}

TEST_CASE(
    "WAV-9, WAV-15: a run's Hausdorff brackets (bounds from φ, priors, refitted trees) overlap brackets from scratch",
    "[pipeline][property][wavelet]") {
    // pipeline::run's §5 brackets f^J and each reconstruction with the bounds from φ as priors, the
    // reconstructions' priors from f^J's, their trees refitted from f^J's, and the vertex passes
    // cut short by the priors; wavelet::hausdorff on the same two meshes uses none of that (fresh
    // trees, no priors). Both bracket the same distance, so they must overlap: a prior below the
    // distance somewhere, or a tree that misses a triangle, gives an upper bound below the other's
    // lower.
    rc::prop("every embedded family, J = 1..3, two kept percentages", [] {
        const fhr::testing::GeneratedMesh T = *small_family_mesh();
        pipeline::RunOptions options;
        options.faces = std::max<std::size_t>(8, T.n_faces() / 40);
        options.levels = *rc::gen::inRange(1, 4);
        options.keep = {*rc::gen::element(2.0, 5.0, 10.0), *rc::gen::element(20.0, 50.0)};
        std::optional<pipeline::RunResult> r;
        try {  // pipeline::run's documented failures only discard a case
            r.emplace(pipeline::run(T, options));
        } catch (const fhr::InvalidInput& e) {
            RC_DISCARD(e.what());
        } catch (const fhr::PartitionFailure& e) {
            RC_DISCARD(e.what());
        } catch (const fhr::NumericalFailure& e) {
            RC_DISCARD(e.what());
        }
        RC_PRE(r->certified());
        const wavelet::WaveletResult& w = *r->wavelets;
        const std::vector<Triangle> t_faces = T.triangles();
        const double slack = 1e-12 * w.bbox_diagonal;
        const auto overlaps = [&](const std::vector<Vec3>& positions, const wavelet::Hausdorff& reported) {
            const wavelet::Hausdorff fresh = wavelet::hausdorff(T.positions(), t_faces, positions, w.remesh_faces,
                                                                {.resolution = reported.resolution});
            RC_ASSERT(reported.lower() <= fresh.upper() * (1 + 1e-9) + slack);
            RC_ASSERT(fresh.lower() <= reported.upper() * (1 + 1e-9) + slack);
            RC_ASSERT(reported.upper() - reported.lower() <= reported.resolution * (1 + 1e-9) + slack);
        };
        overlaps(w.remesh_positions, w.remesh_hausdorff);
        for (const wavelet::KeptResult& k : w.kept) overlaps(k.positions, k.hausdorff);
    });
}
