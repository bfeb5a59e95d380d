// The default map's last tries where every domain misses a goal (CLI-RUN-9, pipeline.hpp's
// another_domain). T refined at D's vertices (src/fhr/pipeline/detail/corners.hpp): on random
// meshes of every embedded family (genus 0–3, with boundary and several components), the
// refinement is T's surface cut exactly where the rule says, D's history describes D on it, and
// §3–§4 on it give a certified map that the oracle accepts against T itself (PARAM-11); on the elk,
// whose map on its D misses the 99th-percentile goal, the map on T refined there meets all three
// goals of spec/distortion.md within their bounds. The sliding weighed by image area
// (src/fhr/pipeline/detail/slide.hpp): on the pinion's D the map so made meets the goals where the
// default one misses.
#include <catch2/catch.hpp>
#include <rapidcheck/catch.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <fhr/app/outputs.hpp>
#include <fhr/core/topology.hpp>
#include <fhr/domain/decimate.hpp>
#include <fhr/exchange/verify.hpp>
#include <fhr/pipeline/detail/corners.hpp>
#include <fhr/pipeline/pipeline.hpp>
#include <fhr/pipeline/run.hpp>
#include <fhr/testing/rapidcheck.hpp>
#include "support/gen_domain.hpp"
#include "support/test_support.hpp"

using namespace fhr;

namespace {

double area(const Vec3& a, const Vec3& b, const Vec3& c) { return 0.5 * (b - a).cross(c - a).norm(); }

// For triangle (a, b, c): L its longest edge and max(L, R), R its largest corner's distance from
// the origin (the scales of its areas' rounding, below).
std::pair<double, double> scales(const Vec3& a, const Vec3& b, const Vec3& c) {
    const double l = std::sqrt(std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()}));
    return {l, std::max({l, a.norm(), b.norm(), c.norm()})};
}

// The edges the rule cuts, found from T and D alone: interior, one end a vertex of D, and each of
// its two faces with no other vertex of D. Each as (its vertex of D, its other end).
std::set<std::pair<std::uint32_t, std::uint32_t>> edges_to_cut(const TriMesh& T, const domain::Domain& D) {
    std::set<std::uint32_t> corners;
    for (VertexId v : D.t_vertex) corners.insert(v.idx());
    auto corners_in = [&](FaceId f) {
        int n = 0;
        for (VertexId v : T.face_vertices(f)) n += static_cast<int>(corners.count(v.idx()));
        return n;
    };
    std::set<std::pair<std::uint32_t, std::uint32_t>> out;
    for (EdgeId e : T.edges()) {
        const HalfedgeId h = TriMesh::halfedge(e, 0);
        if (T.is_boundary(e) || corners_in(T.face(h)) != 1 || corners_in(T.face(TriMesh::twin(h))) != 1) continue;
        const std::uint32_t a = T.from(h).idx(), b = T.to(h).idx();
        if (corners.count(a) && !corners.count(b)) out.emplace(a, b);
        if (corners.count(b) && !corners.count(a)) out.emplace(b, a);
    }
    return out;
}

// What is wrong with `r` as the refinement of T at D's vertices, or "".
std::string refinement_faults(const TriMesh& T, const domain::Domain& D, const pipeline::CornerRefinement& r) {
    const TriMesh& S = r.mesh;
    const std::size_t n = T.n_vertices();
    for (VertexId v : T.vertices())
        if (!(S.position(v) == T.position(v))) return "vertex " + std::to_string(v.idx()) + " of T moved";
    // Each cut on its own edge of the rule, at 0.3 of it from its vertex of D, and each edge cut once.
    const std::set<std::pair<std::uint32_t, std::uint32_t>> cut = edges_to_cut(T, D);
    if (S.n_vertices() != n + cut.size())
        return std::to_string(S.n_vertices() - n) + " cuts, the rule makes " + std::to_string(cut.size());
    std::set<std::pair<std::uint32_t, std::uint32_t>> found;
    for (std::uint32_t s = static_cast<std::uint32_t>(n); s < S.n_vertices(); ++s) {
        const Vec3& p = S.position(VertexId(s));
        for (const auto& [x, a] : cut) {
            const Vec3 &px = T.position(VertexId(x)), &pa = T.position(VertexId(a));
            // A cut is rounded to the coordinates' precision: the tolerance scales with them.
            const double len = (pa - px).norm(), t = (p - px).dot(pa - px) / (len * len);
            const double scale = std::max({len, px.norm(), pa.norm()});
            if (std::abs(t - pipeline::corner_cut) * len <= 1e-12 * scale &&
                (p - (px + t * (pa - px))).norm() <= 1e-12 * scale)
                found.emplace(x, a);
        }
    }
    if (found != cut) return "the cuts are not one on each edge of the rule at 0.3 of it";
    // T's surface: each face of T* inside its face of T, oriented alike, the pieces' areas summing to it.
    if (r.parent.size() != S.n_faces()) return "a face of T* without its face of T";
    std::vector<double> pieces(T.n_faces(), 0);
    for (FaceId f : S.faces()) {
        const FaceId g(r.parent[f.idx()].idx());
        const auto c = T.face_vertices(g);
        const Vec3 &a = T.position(c[0]), &b = T.position(c[1]), &d = T.position(c[2]);
        const Vec3 normal = (b - a).cross(d - a);
        const auto k = S.face_vertices(f);
        const Vec3 mine = (S.position(k[1]) - S.position(k[0])).cross(S.position(k[2]) - S.position(k[0]));
        if (!(mine.dot(normal) > 0)) return "face " + std::to_string(f.idx()) + " of T* turned against its face of T";
        // Rounding of a cross product of edges of length ≤ L, at coordinates of size ≤ R, is of
        // order u L max(L, R), of a triple product u L max(L, R)²: the tolerances scale with them
        // (the generator's slivers have areas far below L², and its needles edges far below R).
        const auto [l, r] = scales(a, b, d);
        for (VertexId v : k) {  // barycentric in the face of T, and in its plane
            const Vec3& p = S.position(v);
            const double w = area(p, b, d) + area(a, p, d) + area(a, b, p) - area(a, b, d);
            if (std::abs(w) > 1e-12 * l * r || std::abs(normal.dot(p - a)) > 1e-12 * l * r * r)
                return "a corner of face " + std::to_string(f.idx()) + " of T* is outside its face of T";
        }
        pieces[g.idx()] += area(S.position(k[0]), S.position(k[1]), S.position(k[2]));
    }
    for (FaceId g : T.faces()) {
        const auto c = T.face_vertices(g);
        const Vec3 &a = T.position(c[0]), &b = T.position(c[1]), &d = T.position(c[2]);
        const auto [l, r] = scales(a, b, d);
        if (std::abs(pieces[g.idx()] - area(a, b, d)) > 1e-12 * l * r)
            return "the pieces of face " + std::to_string(g.idx()) + " of T do not fill it";
    }
    // T's topology and boundary, and D itself, its history describing it on T*.
    if (S.is_closed() != T.is_closed() || boundary_loops(S).size() != boundary_loops(T).size() ||
        connected_components(S).count != connected_components(T).count)
        return "T* has another topology than T";
    if (r.domain.mesh.triangles() != D.mesh.triangles() || r.domain.t_vertex.values() != D.t_vertex.values())
        return "D changed";
    if (!domain::history_describes(r.domain, S)) return "D's history does not describe D on T*";
    return "";
}

exchange::Distortion figures(const pipeline::Parameterization& p) {
    const exchange::Distortion d = exchange::summarize(app::face_stretches(p));
    REQUIRE((d.anisotropy_p99 && d.anisotropy_p999 && d.anisotropy_max && d.l2_stretch));
    return d;
}

// q, a map of corpus mesh T on a D of `faces` faces, meets all three goals of spec/distortion.md
// within their bounds against the paper's map on §2's D (its L2 stretch, T′ a quarter larger), and
// the oracle accepts it against T.
void meets_goals(const TriMesh& T, const pipeline::Parameterization& q, std::size_t faces) {
    REQUIRE(q.certified());
    const exchange::Distortion d = figures(q);
    CHECK(*d.anisotropy_p99 <= 3);
    CHECK(*d.anisotropy_p999 <= 10);
    CHECK(*d.anisotropy_max <= 1e3);
    pipeline::Options paper;
    paper.relax = false;
    const pipeline::Parameterization paper_map =
        pipeline::parameterize(T, domain::decimate(T, {.target_faces = faces}), paper);
    CHECK(*d.l2_stretch <= *figures(paper_map).l2_stretch);
    CHECK(q.refined_faces.size() <= 1.25 * paper_map.refined_faces.size());
    const exchange::VerifyReport oracle = exchange::verify(pipeline::to_param_file(q), &T);
    const exchange::CheckResult* bad = oracle.first_failure();
    CHECK((bad ? bad->id + ": " + bad->first_failure : std::string()) == "");
}

}  // namespace

TEST_CASE(
    "corners: T refined at D's vertices is T's surface cut by the rule, D's history describes D on it, and the map of "
    "it is certified and valid against T",
    "[pipeline][property][corners]") {
    std::size_t refined = 0;
    rc::prop("refine_corners(T, D) on T of any embedded family", [&] {
        const fhr::testing::GeneratedMesh g = *fhr::testing::gen_mesh(
            {.min_genus = 0,
             .max_genus = 3,
             .max_faces = 1200,
             .min_holes = 0,
             .max_holes = 2,
             .min_components = 1,
             .max_components = 2,
             .families = {std::begin(generate::embedded_families), std::end(generate::embedded_families)}});
        const TriMesh& T = g;
        RC_TAG(generate::family_name(g.options.family));
        const domain::Domain D = test::random_open_domain(T);
        const std::optional<pipeline::CornerRefinement> r = pipeline::refine_corners(T, D);
        RC_ASSERT(r.has_value() == !edges_to_cut(T, D).empty());
        if (!r) return;
        ++refined;
        RC_ASSERT(refinement_faults(T, D, *r) == "");
        const pipeline::Parameterization p = pipeline::parameterize(r->mesh, r->domain, {});
        RC_ASSERT(p.certified());
        RC_ASSERT(p.partition.domain.mesh.triangles() == D.mesh.triangles());  // §3 kept D on T*
        const exchange::VerifyReport oracle = exchange::verify(pipeline::to_param_file(p), &T);
        const exchange::CheckResult* bad = oracle.first_failure();
        RC_ASSERT((bad ? bad->id + ": " + bad->first_failure : std::string()) == "");
    });
    CHECK(refined > 0);
}

TEST_CASE(
    "CLI-RUN-9, DIST-7: on the elk's D of the graded rules from 45° and 10°, the map misses the 99th-percentile goal; "
    "on T refined at D's vertices it meets all three goals, its L2 stretch and T′ within the goals' bounds",
    "[pipeline][distortion][corners]") {
    // The elk at the corpus's 32 faces: no D of the rules of domain_rules carries a map meeting the
    // goals, the one of 45°/10° comes nearest (99th percentile 3.07, paper_notes/distortion_causes.md).
    const TriMesh T = test::load_mesh(test::cgal_mesh("elk.off"));
    const pipeline::Parameterization on_d = pipeline::parameterize(
        T, domain::decimate(T, {.target_faces = 32, .first_normal_deviation_deg = 45, .first_min_angle_deg = 10}), {});
    CHECK(*figures(on_d).anisotropy_p99 > 3);
    const std::optional<pipeline::CornerRefinement> r = pipeline::refine_corners(T, on_d.partition.domain);
    REQUIRE(r);
    CHECK(refinement_faults(T, on_d.partition.domain, *r) == "");
    meets_goals(T, pipeline::parameterize(r->mesh, r->domain, {}), 32);
}

TEST_CASE(
    "CLI-RUN-9, DIST-7: on the pinion's D of the graded rules from 75° and 20°, the map misses the 99th-percentile "
    "goal; made with the sliding weighed by image area it meets all three goals within their bounds",
    "[pipeline][distortion][weighted]") {
    // The pinion at the corpus's 28 faces: that D is the best of domain_rules' (99th percentile
    // 3.17), and T refined at its vertices is worse (paper_notes/distortion_causes.md).
    const TriMesh T = test::load_mesh(test::cgal_mesh("pinion.off"));
    const domain::DecimateOptions rule{
        .target_faces = 28, .first_normal_deviation_deg = 75, .first_min_angle_deg = 20, .best_effort = true};
    CHECK(*figures(pipeline::parameterize(T, domain::decimate(T, rule), {})).anisotropy_p99 > 3);
    pipeline::Options by_image;
    by_image.image_weighted_sliding = true;
    const pipeline::Parameterization weighted = pipeline::parameterize(T, domain::decimate(T, rule), by_image);
    CHECK(weighted.image_weighted_sliding);
    CHECK(weighted.slid_patches > 0);
    meets_goals(T, weighted, 28);
}
