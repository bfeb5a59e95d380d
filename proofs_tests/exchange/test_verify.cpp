// FHR tests — the oracle `verify` (src/fhr/exchange/verify.hpp, spec/param.md PARAM-2..11). Valid
// files come from synthetic.hpp (k-to-k² subdivisions of random closed meshes: no
// parameterization code involved); verify must accept all of them, also against the input mesh,
// and must reject each deliberate corruption with the invariant it breaks, named first.
#include <catch2/catch.hpp>
#include <rapidcheck/catch.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <fhr/core/topology.hpp>
#include <fhr/core/trimesh.hpp>
#include <fhr/exchange/fhr_param.hpp>
#include <fhr/exchange/verify.hpp>
#include <fhr/generate/random_mesh.hpp>
#include <fhr/testing/rapidcheck.hpp>
#include "synthetic.hpp"

using fhr::TriMesh;
using fhr::exchange::Beta;
using fhr::exchange::CheckResult;
using fhr::exchange::CheckStatus;
using fhr::exchange::ParamFile;
using fhr::exchange::verify;
using fhr::exchange::VerifyReport;

namespace {

TriMesh random_domain(int genus, std::size_t faces, std::uint64_t seed) {
    fhr::generate::RandomMeshOptions o;
    o.genus = genus;
    o.faces = faces;
    o.seed = seed;
    o.noise = 0.1;
    return fhr::generate::random_closed_mesh(o);
}

const CheckResult& check(const VerifyReport& r, const std::string& id) {
    for (const CheckResult& c : r.checks)
        if (c.id == id) return c;
    throw std::logic_error("no check " + id);
}

std::string first_failure(const VerifyReport& r) { return r.first_failure() ? r.first_failure()->id : "none"; }

std::string describe(const VerifyReport& r) {
    std::string s;
    for (const CheckResult& c : r.checks)
        s += c.id + " " + fhr::exchange::to_string(c.status) + " " + std::to_string(c.failures) + " " + c.first_failure + "\n";
    return s;
}

// ---- finding vertices and moving their images ------------------------------------------------

struct Incidence {
    std::uint32_t face;
    int corner;
};

std::vector<std::vector<Incidence>> incidences(const ParamFile& f) {
    std::vector<std::vector<Incidence>> inc(f.surface_vertices.size());
    for (std::uint32_t i = 0; i < f.surface_faces.size(); ++i)
        for (int c = 0; c < 3; ++c) inc[f.surface_faces[i].v[c]].push_back({i, c});
    return inc;
}

std::vector<std::uint32_t> patches_of(const ParamFile& f, const std::vector<Incidence>& inc) {
    std::vector<std::uint32_t> p;
    for (const Incidence& i : inc) p.push_back(f.surface_faces[i.face].patch);
    std::sort(p.begin(), p.end());
    p.erase(std::unique(p.begin(), p.end()), p.end());
    return p;
}

/// The point of Ω_D of an incidence: weights on domain vertices.
using Point = std::map<std::uint32_t, double>;

Point point(const ParamFile& f, Incidence i) {
    const auto& face = f.surface_faces[i.face];
    Point p;
    for (int r = 0; r < 3; ++r)
        if (face.beta[i.corner][r] != 0) p[f.domain_faces[face.patch][r]] = face.beta[i.corner][r];
    return p;
}

/// Writes `p` as the β of vertex v in every incidence (in patch `only` alone when it is given).
void move_image(ParamFile& f, const std::vector<Incidence>& inc, const Point& p, std::int64_t only = -1) {
    for (const Incidence& i : inc) {
        auto& face = f.surface_faces[i.face];
        if (only >= 0 && face.patch != only) continue;
        for (int r = 0; r < 3; ++r) {
            const auto it = p.find(f.domain_faces[face.patch][r]);
            face.beta[i.corner][r] = it == p.end() ? 0.0 : it->second;
        }
    }
}

/// A vertex inside one patch (β all positive), and one inside a side (two patches, two weights).
std::uint32_t interior_vertex(const ParamFile& f, const std::vector<std::vector<Incidence>>& inc) {
    for (std::uint32_t v = 0; v < inc.size(); ++v)
        if (patches_of(f, inc[v]).size() == 1 && point(f, inc[v][0]).size() == 3) return v;
    throw std::logic_error("no interior vertex (k >= 3 needed)");
}

std::uint32_t side_vertex(const ParamFile& f, const std::vector<std::vector<Incidence>>& inc) {
    for (std::uint32_t v = 0; v < inc.size(); ++v)
        if (patches_of(f, inc[v]).size() == 2 && point(f, inc[v][0]).size() == 2) return v;
    throw std::logic_error("no side vertex (k >= 2 needed)");
}

/// Slides a side vertex by 0.05 along its side, in the patch `only` or (−1) in every patch; returns it.
std::uint32_t slide_side_vertex(ParamFile& f, bool one_patch_only) {
    const auto inc = incidences(f);
    const std::uint32_t v = side_vertex(f, inc);
    Point p = point(f, inc[v][0]);
    p.begin()->second -= 0.05;
    p.rbegin()->second += 0.05;
    move_image(f, inc[v], p, one_patch_only ? std::int64_t{f.surface_faces[inc[v][0].face].patch} : -1);
    return v;
}

// ---- the corruptions ---------------------------------------------------------------------------

struct Expect {
    std::string first;             ///< the id of the first check that fails
    std::string also = "";         ///< another check that must fail
    std::int64_t vertex = -1;      ///< the vertex the first failure names (-1: not checked)
    std::int64_t face = -1;        ///< the face `also` (or `first`) names (-1: not checked)
    std::string says = "";         ///< a phrase of the first failure's description
};

struct Corruption {
    const char* name;
    /// Breaks `file` (and/or the input mesh) and says what verify must report. \pre k >= 4.
    std::function<Expect(ParamFile&, TriMesh& input)> apply;
};

const std::vector<Corruption>& corruptions() {
    static const std::vector<Corruption> all{
        {"a flipped triangle: two beta of a face swapped",
         [](ParamFile& f, TriMesh&) {
             const std::uint32_t face = static_cast<std::uint32_t>(f.surface_faces.size() / 2);
             std::swap(f.surface_faces[face].beta[0], f.surface_faces[face].beta[1]);
             // The swap also gives two vertices a second image: continuity breaks first.
             return Expect{"PARAM-7", "PARAM-8", -1, face};
         }},
        {"a fold: an interior vertex moved across its 1-ring, consistently in all its faces",
         [](ParamFile& f, TriMesh&) {
             const auto inc = incidences(f);
             const std::uint32_t v = interior_vertex(f, inc);
             // Its lightest domain vertex gets weight 0.9: at least 0.4 away, farther than the
             // 1-ring's extent 1/k.
             Point far = point(f, inc[v][0]);
             const auto lightest = std::min_element(far.begin(), far.end(),
                                                    [](const auto& x, const auto& y) { return x.second < y.second; });
             for (auto& [corner, weight] : far) weight = corner == lightest->first ? 0.9 : 0.05;
             move_image(f, inc[v], far);
             return Expect{"PARAM-8"};
         }},
        {"an image triangle of zero area (exact orient2d = 0)",
         [](ParamFile& f, TriMesh&) {
             // Lattice point (1,1) of patch 0 to the midpoint of (2,1) and (1,2): dyadic numbers,
             // so the image of triangle ((1,1), (2,1), (1,2)) is exactly degenerate.
             const auto inc = incidences(f);
             for (std::uint32_t v = 0; v < inc.size(); ++v) {
                 const auto& face = f.surface_faces[inc[v][0].face];
                 if (face.patch == 0 && face.beta[inc[v][0].corner] == Beta{0.5, 0.25, 0.25}) {
                     const fhr::Triangle& d = f.domain_faces[0];
                     move_image(f, inc[v], {{d[0], 0.25}, {d[1], 0.375}, {d[2], 0.375}});
                     return Expect{"PARAM-8", "", -1, -1, "its image is degenerate (exact orient2d = 0)"};
                 }
             }
             throw std::logic_error("k must be 4");
         }},
        {"a boundary vertex moved off its side by 1e-13 (within the continuity tolerance, off the edge of D)",
         [](ParamFile& f, TriMesh&) {
             const auto inc = incidences(f);
             const std::uint32_t v = side_vertex(f, inc);
             const std::uint32_t d = f.surface_faces[inc[v][0].face].patch;
             Point p = point(f, inc[v][0]);
             p.begin()->second -= 1e-13;
             for (std::uint32_t corner : f.domain_faces[d])
                 if (!p.count(corner)) p[corner] = 1e-13;
             move_image(f, inc[v], p, d);
             // The weights differ by 1e-13 only, but the carrier is a face of D on one side and
             // an edge on the other (PARAM-7); and the patch boundary leaves the side (PARAM-9).
             return Expect{"PARAM-7", "PARAM-9", v, -1, "not the same vertex, edge or face of D"};
         }},
        {"a boundary vertex moved off its side by 0.01",
         [](ParamFile& f, TriMesh&) {
             const auto inc = incidences(f);
             const std::uint32_t v = side_vertex(f, inc);
             const std::uint32_t d = f.surface_faces[inc[v][0].face].patch;
             Point p = point(f, inc[v][0]);
             p.begin()->second -= 0.01;
             for (std::uint32_t corner : f.domain_faces[d])
                 if (!p.count(corner)) p[corner] = 0.01;
             move_image(f, inc[v], p, d);
             return Expect{"PARAM-7", "PARAM-9", v};
         }},
        {"broken continuity: a boundary vertex slid along its side in one patch only",
         [](ParamFile& f, TriMesh&) { return Expect{"PARAM-7", "", slide_side_vertex(f, true)}; }},
        {"wrong chord length: a boundary vertex slid along its side in both patches",
         [](ParamFile& f, TriMesh&) { return Expect{"PARAM-10", "", slide_side_vertex(f, false), -1, "but chord length"}; }},
        {"a missing face",
         [](ParamFile& f, TriMesh&) {
             f.surface_faces.pop_back();
             return Expect{"PARAM-3", "PARAM-8", -1, -1, "surface T': the mesh has boundary"};
         }},
        {"an out-of-range vertex index",
         [](ParamFile& f, TriMesh&) {
             f.surface_faces[1].v[2] = static_cast<std::uint32_t>(f.surface_vertices.size());
             return Expect{"PARAM-2", "", -1, 1};
         }},
        {"an out-of-range patch",
         [](ParamFile& f, TriMesh&) {
             f.surface_faces[2].patch = static_cast<std::uint32_t>(f.domain_faces.size());
             return Expect{"PARAM-2", "", -1, 2};
         }},
        {"an out-of-range domain vertex",
         [](ParamFile& f, TriMesh&) {
             f.domain_faces[0][1] = static_cast<std::uint32_t>(f.domain_vertices.size()) + 7;
             return Expect{"PARAM-2"};
         }},
        {"a NaN beta",
         [](ParamFile& f, TriMesh&) {
             f.surface_faces[3].beta[2][1] = std::numeric_limits<double>::quiet_NaN();
             return Expect{"PARAM-2", "", -1, 3};
         }},
        {"an infinite coordinate",
         [](ParamFile& f, TriMesh&) {
             f.surface_vertices[5].y() = -std::numeric_limits<double>::infinity();
             return Expect{"PARAM-2", "", 5};
         }},
        {"beta not summing to one",
         [](ParamFile& f, TriMesh&) {
             double& b = f.surface_faces[4].beta[1][0];
             b = b > 0.5 ? b - 1e-9 : b + 1e-9;
             return Expect{"PARAM-5", "", -1, 4};
         }},
        {"a negative beta",
         [](ParamFile& f, TriMesh&) {
             Beta& b = f.surface_faces[4].beta[1];
             b = {-0.25, 0.75, 0.5};
             return Expect{"PARAM-5", "", -1, 4};
         }},
        {"beta component 0 just above 1, the sum within its tolerance",
         [](ParamFile& f, TriMesh&) {
             f.surface_faces[4].beta[1] = {1 + 4e-13, 0, 0};
             return Expect{"PARAM-5", "", -1, 4, "has a component outside [0, 1]"};
         }},
        {"beta component 0 just below 0, the sum exactly 1",
         [](ParamFile& f, TriMesh&) {
             f.surface_faces[4].beta[1] = {-4e-13, 0.5 + 4e-13, 0.5};
             return Expect{"PARAM-5", "", -1, 4, "has a component outside [0, 1]"};
         }},
        {"beta component 1 just above 1, the sum within its tolerance",
         [](ParamFile& f, TriMesh&) {
             f.surface_faces[4].beta[1] = {0, 1 + 4e-13, 0};
             return Expect{"PARAM-5", "", -1, 4, "has a component outside [0, 1]"};
         }},
        {"beta component 1 just below 0, the sum exactly 1",
         [](ParamFile& f, TriMesh&) {
             f.surface_faces[4].beta[1] = {0.5, -4e-13, 0.5 + 4e-13};
             return Expect{"PARAM-5", "", -1, 4, "has a component outside [0, 1]"};
         }},
        {"beta component 2 just above 1, the sum within its tolerance",
         [](ParamFile& f, TriMesh&) {
             f.surface_faces[4].beta[1] = {0, 0, 1 + 4e-13};
             return Expect{"PARAM-5", "", -1, 4, "has a component outside [0, 1]"};
         }},
        {"beta component 2 just below 0, the sum exactly 1",
         [](ParamFile& f, TriMesh&) {
             f.surface_faces[4].beta[1] = {0.5 + 4e-13, 0.5, -4e-13};
             return Expect{"PARAM-5", "", -1, 4, "has a component outside [0, 1]"};
         }},
        {"a patch that is not a disk: an interior face moved to another patch",
         [](ParamFile& f, TriMesh&) {
             const auto inc = incidences(f);
             for (auto& face : f.surface_faces) {
                 bool inside = true;
                 for (std::uint32_t v : face.v) inside = inside && point(f, inc[v][0]).size() == 3;
                 if (inside) {
                     face.patch = (face.patch + 1) % static_cast<std::uint32_t>(f.domain_faces.size());
                     return Expect{"PARAM-6"};
                 }
             }
             throw std::logic_error("k must be >= 4");
         }},
        {"a domain turned inside out",
         [](ParamFile& f, TriMesh&) {
             for (auto& t : f.domain_faces) std::swap(t[1], t[2]);
             return Expect{"PARAM-3", "", -1, -1, "domain D is not oriented counter-clockwise seen from outside"};
         }},
        {"a domain of another genus",
         [](ParamFile& f, TriMesh&) {
             const TriMesh d = TriMesh::from_triangles(f.domain_vertices, f.domain_faces);
             const int genus = static_cast<int>(fhr::genus(d)) + 1;
             const TriMesh other = random_domain(
                 genus, std::max<std::size_t>(fhr::generate::min_faces(genus), f.domain_faces.size() + f.domain_faces.size() % 2),
                 11);
             f.domain_vertices = other.positions();
             f.domain_faces = other.triangles();
             return Expect{"PARAM-4"};
         }},
        {"--mesh: a vertex of T missing from T' (moved by one ulp)",
         [](ParamFile&, TriMesh& input) {
             auto& x = input.position(fhr::VertexId(0)).x();
             x = std::nextafter(x, 1e300);
             return Expect{"PARAM-11", "", 0, -1, "vertex 0 of T"};
         }},
        {"--mesh: a vertex of T' off T",
         [](ParamFile& f, TriMesh&) {
             const auto inc = incidences(f);
             const std::uint32_t v = interior_vertex(f, inc);
             f.surface_vertices[v] += fhr::Vec3(1e-3, 2e-3, -1e-3);
             return Expect{"PARAM-11", "", v, -1, "is not on T"};
         }},
    };
    return all;
}

/// Applies `c` to the k-subdivision of `domain`, verifies against `domain`, and checks the result.
void expect_caught(const Corruption& c, const TriMesh& domain, int k) {
    ParamFile file = fhr::test::subdivided_param(domain, k);
    TriMesh input = domain;
    const Expect e = c.apply(file, input);
    const VerifyReport r = verify(file, &input);
    INFO(c.name << "\n" << describe(r));
    REQUIRE_FALSE(r.valid());
    CHECK(first_failure(r) == e.first);
    const CheckResult& first = check(r, e.first);
    CHECK(first.status == CheckStatus::fail);
    CHECK(first.failures >= 1);
    CHECK_FALSE(first.first_failure.empty());
    if (e.vertex >= 0) CHECK(first.vertex == e.vertex);
    if (!e.also.empty()) CHECK(check(r, e.also).status == CheckStatus::fail);
    if (e.face >= 0) CHECK(check(r, e.also.empty() ? e.first : e.also).face == e.face);
    CHECK_THAT(first.first_failure, Catch::Contains(e.says));
}

}  // namespace

TEST_CASE("PARAM-2..11: every k-to-k^2 subdivision of a random closed mesh is a valid parameterization over it",
          "[exchange][property]") {
    rc::prop("genus 0-3, k = 1..5, with the domain as the input mesh T", [] {
        const auto& domain = *fhr::testing::gen_closed_mesh(0, 3, 300);
        const int k = *rc::gen::inRange(1, 6);
        const ParamFile file = fhr::test::subdivided_param(domain, k);
        const VerifyReport r = verify(file, &domain);
        RC_LOG() << describe(r);
        RC_ASSERT(r.checks.size() == 10u);
        RC_ASSERT(r.valid());
        const VerifyReport without = verify(file, nullptr);
        RC_ASSERT(without.checks.size() == 9u);
        RC_ASSERT(without.valid());
    });
}

TEST_CASE("PARAM-2..11: the checks come in order, each with a count", "[exchange]") {
    const TriMesh domain = random_domain(1, 200, 5);
    const VerifyReport r = verify(fhr::test::subdivided_param(domain, 3), &domain);
    const std::vector<std::string> ids{"PARAM-2", "PARAM-3", "PARAM-4", "PARAM-5", "PARAM-6",
                                       "PARAM-7", "PARAM-8", "PARAM-9", "PARAM-10", "PARAM-11"};
    REQUIRE(r.checks.size() == ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i) {
        CHECK(r.checks[i].id == ids[i]);
        CHECK(r.checks[i].status == CheckStatus::pass);
        CHECK(r.checks[i].failures == 0);
        CHECK(r.checks[i].checked > 0);
        CHECK(r.checks[i].first_failure.empty());
    }
    CHECK(check(r, "PARAM-5").checked == 3 * 200 * 9);  // every corner of every face of T′
    CHECK(check(r, "PARAM-6").checked == 200);          // every patch
    // PARAM-10: the 2 inner points of each side, seen from both of its patches.
    CHECK(check(r, "PARAM-10").checked == 200 * 3 * 2);
}

TEST_CASE("PARAM-2..11: verify rejects each deliberate corruption, naming the broken invariant first", "[exchange]") {
    const TriMesh domain = random_domain(1, 200, 5);
    for (const Corruption& c : corruptions()) {
        DYNAMIC_SECTION(c.name) { expect_caught(c, domain, 4); }
    }
}

TEST_CASE("PARAM-2..11: the corruptions are caught on random domains of genus 0-3", "[exchange][property]") {
    rc::prop("every corruption of the 4-to-16 subdivision of a random domain", [] {
        const auto& domain = *fhr::testing::gen_closed_mesh(0, 3, 200);
        for (const Corruption& c : corruptions()) {
            ParamFile file = fhr::test::subdivided_param(domain, 4);
            TriMesh input = domain;
            const Expect e = c.apply(file, input);
            const VerifyReport r = verify(file, &input);
            RC_LOG() << c.name << "\n" << describe(r);
            RC_ASSERT(first_failure(r) == e.first);
            if (e.vertex >= 0) RC_ASSERT(check(r, e.first).vertex == e.vertex);
            if (!e.also.empty()) RC_ASSERT(check(r, e.also).status == CheckStatus::fail);
        }
    });
}

TEST_CASE("PARAM-9, PARAM-10: a failed check makes the checks that rely on it skipped, with the reason", "[exchange]") {
    const TriMesh domain = random_domain(0, 100, 2);
    ParamFile file = fhr::test::subdivided_param(domain, 4);
    file.surface_faces.pop_back();  // T′ is no longer closed: PARAM-3 fails
    const VerifyReport r = verify(file, &domain);
    for (const char* id : {"PARAM-4", "PARAM-6", "PARAM-9", "PARAM-10", "PARAM-11"}) {
        INFO(id);
        CHECK(check(r, id).status == CheckStatus::skipped);
        CHECK_THAT(check(r, id).first_failure, Catch::StartsWith("not checked: needs PARAM-"));
    }
    CHECK(check(r, "PARAM-7").status == CheckStatus::pass);  // needs only PARAM-2
}
