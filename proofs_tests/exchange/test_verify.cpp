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
#include <set>
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

/// Where two reports differ (check by check: id, status, counts, first failure and its place), or "".
std::string difference(const VerifyReport& a, const VerifyReport& b) {
    if (a.checks.size() != b.checks.size())
        return std::to_string(a.checks.size()) + " checks against " + std::to_string(b.checks.size());
    for (std::size_t i = 0; i < a.checks.size(); ++i) {
        const CheckResult &x = a.checks[i], &y = b.checks[i];
        if (x.id != y.id || x.status != y.status || x.checked != y.checked || x.failures != y.failures ||
            x.first_failure != y.first_failure || x.face != y.face || x.vertex != y.vertex || x.patch != y.patch)
            return x.id + " differs from " + y.id + ": " + x.first_failure + " | " + y.first_failure;
    }
    return "";
}

std::string describe(const VerifyReport& r) {
    std::string s;
    for (const CheckResult& c : r.checks)
        s += c.id + " " + fhr::exchange::to_string(c.status) + " " + std::to_string(c.failures) + " " +
             c.first_failure + "\n";
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

/// A vertex inside one patch (β all positive), and one inside a side: of two patches (an interior
/// edge of D) or, with `patches` = 1, of one (a boundary edge of D; the vertex is on ∂T′).
std::uint32_t interior_vertex(const ParamFile& f, const std::vector<std::vector<Incidence>>& inc) {
    for (std::uint32_t v = 0; v < inc.size(); ++v)
        if (patches_of(f, inc[v]).size() == 1 && point(f, inc[v][0]).size() == 3) return v;
    throw std::logic_error("no interior vertex (k >= 3 needed)");
}

std::uint32_t side_vertex(const ParamFile& f, const std::vector<std::vector<Incidence>>& inc, std::size_t patches = 2) {
    for (std::uint32_t v = 0; v < inc.size(); ++v)
        if (patches_of(f, inc[v]).size() == patches && point(f, inc[v][0]).size() == 2) return v;
    throw std::logic_error("no side vertex (k >= 2 needed)");
}

/// The vertex whose image is `p` (its first incidence's), of a side of `patches` patches.
std::uint32_t vertex_at(const ParamFile& f, const std::vector<std::vector<Incidence>>& inc, const Point& p,
                        std::size_t patches = 2) {
    for (std::uint32_t v = 0; v < inc.size(); ++v)
        if (patches_of(f, inc[v]).size() == patches && point(f, inc[v][0]) == p) return v;
    throw std::logic_error("no vertex at that point");
}

/// Slides a side vertex by 0.05 along its side, in one of its patches only or in every patch; a
/// vertex of a side of `patches` patches. Returns it.
std::uint32_t slide_side_vertex(ParamFile& f, bool one_patch_only, std::size_t patches = 2) {
    const auto inc = incidences(f);
    const std::uint32_t v = side_vertex(f, inc, patches);
    Point p = point(f, inc[v][0]);
    p.begin()->second -= 0.05;
    p.rbegin()->second += 0.05;
    move_image(f, inc[v], p, one_patch_only ? std::int64_t{f.surface_faces[inc[v][0].face].patch} : -1);
    return v;
}

// ---- the corruptions ---------------------------------------------------------------------------

struct Expect {
    std::string first;           ///< the id of the first check that fails
    std::string also = "";       ///< another check that must fail
    std::int64_t vertex = -1;    ///< the vertex the first failure names (-1: not checked)
    std::int64_t face = -1;      ///< the face `also` (or `first`) names (-1: not checked)
    std::string says = "";       ///< a phrase of the first failure's description
    std::string also_says = "";  ///< a phrase of `also`'s first failure
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
         [](ParamFile& f, TriMesh&) {
             return Expect{"PARAM-7", "", slide_side_vertex(f, true)};
         }},
        {"wrong chord length: a boundary vertex slid along its side in both patches",
         [](ParamFile& f, TriMesh&) {
             return Expect{"PARAM-10", "", slide_side_vertex(f, false), -1, "but chord length"};
         }},
        {"a missing face: T' has a hole that the closed D lacks",
         [](ParamFile& f, TriMesh&) {
             f.surface_faces.pop_back();
             return Expect{"PARAM-4", "PARAM-8", -1, -1, "chi(T') = "};
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
        {"a NaN domain vertex",
         [](ParamFile& f, TriMesh&) {
             f.domain_vertices[3].x() = std::numeric_limits<double>::quiet_NaN();
             return Expect{"PARAM-2", "", -1, -1, "domain vertex 3 (nan, "};
         }},
        {"a finite domain vertex beyond 1e150 (INV-IN-1: its squares would overflow)",
         [](ParamFile& f, TriMesh&) {
             f.domain_vertices[2].z() = -1e151;
             return Expect{"PARAM-2", "", -1, -1, "-1e+151) is not finite or exceeds 1e150 in magnitude"};
         }},
        {"a domain vertex in no face (INV-IN-12)",
         [](ParamFile& f, TriMesh&) {
             f.domain_vertices.push_back(fhr::Vec3(0, 0, 0));
             return Expect{"PARAM-3", "", -1, -1, "domain D has vertices in no face: "};
         }},
        {"a side vertex given beta off its side in one face of its patch, not the face the boundary walk reads",
         [](ParamFile& f, TriMesh&) {
             const auto inc = incidences(f);
             const std::uint32_t v = side_vertex(f, inc);
             for (const Incidence& i : inc[v]) {
                 auto& face = f.surface_faces[i.face];
                 Beta& b = face.beta[i.corner];
                 const int zero = static_cast<int>(std::find(b.begin(), b.end(), 0.0) - b.begin());
                 // The middle face of v's three in the patch: neither other corner on v's side.
                 if (face.beta[(i.corner + 1) % 3][zero] == 0 || face.beta[(i.corner + 2) % 3][zero] == 0) continue;
                 *std::max_element(b.begin(), b.end()) -= 1e-13;
                 b[zero] = 1e-13;
                 // PARAM-7 sees a face of D in one face and an edge in the others; PARAM-9 checks
                 // every face of the patch against the side the walk put v on.
                 return Expect{"PARAM-7",
                               "PARAM-9",
                               v,
                               i.face,
                               "not the same vertex, edge or face of D",
                               "boundary vertex " + std::to_string(v) + " lies on the side ("};
             }
             throw std::logic_error("k must be >= 3");
         }},
        {"two neighbouring side vertices swap their images, in both patches (ψ continuous, the side out of order)",
         [](ParamFile& f, TriMesh&) {
             const auto inc = incidences(f);
             const std::uint32_t v = side_vertex(f, inc);
             const Point p = point(f, inc[v][0]);
             Point q = p;  // the next lattice point along the side, towards its middle
             const double step = p.begin()->second > 0.5 ? -0.25 : 0.25;
             q.begin()->second += step;
             q.rbegin()->second -= step;
             const std::uint32_t w = vertex_at(f, inc, q);
             move_image(f, inc[v], q);
             move_image(f, inc[w], p);
             return Expect{"PARAM-8", "PARAM-9", -1, -1, "", "is not monotone: its parameter "};
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
             const TriMesh other =
                 random_domain(genus,
                               std::max<std::size_t>(fhr::generate::min_faces(genus),
                                                     f.domain_faces.size() + f.domain_faces.size() % 2),
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
        {"--mesh: a vertex of T' far off T, outside T's bounding box",
         [](ParamFile& f, TriMesh&) {
             const auto inc = incidences(f);
             const std::uint32_t v = interior_vertex(f, inc);
             // Outward, along its faces' area-weighted normal, so that T' keeps a positive volume
             // (a spike of 10³ inward turned a small random mesh inside out: PARAM-3 first).
             fhr::Vec3 n = fhr::Vec3::Zero();
             for (const Incidence& i : inc[v]) {
                 const auto& t = f.surface_faces[i.face].v;
                 n += (f.surface_vertices[t[1]] - f.surface_vertices[t[0]])
                          .cross(f.surface_vertices[t[2]] - f.surface_vertices[t[0]]);
             }
             f.surface_vertices[v] += 1e3 * n.normalized();
             return Expect{"PARAM-11", "", v, -1, "is not on T (distance > "};
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

/// Applies `c` to the k-subdivision of `domain`, verifies against `domain` as the paper's map
/// (PARAM-10 judged), and checks the result.
void expect_caught(const Corruption& c, const TriMesh& domain, int k) {
    ParamFile file = fhr::test::subdivided_param(domain, k);
    TriMesh input = domain;
    const Expect e = c.apply(file, input);
    const VerifyReport r = verify(file, &input, nullptr, true);
    INFO(c.name << "\n" << describe(r));
    CHECK(difference(r, verify(file, fhr::exchange::PreparedInput(input), nullptr, true))
              .empty());  // T's side prepared apart
    REQUIRE_FALSE(r.valid());
    CHECK(first_failure(r) == e.first);
    const CheckResult& first = check(r, e.first);
    CHECK(first.status == CheckStatus::fail);
    CHECK(first.failures >= 1);
    CHECK_FALSE(first.first_failure.empty());
    if (e.vertex >= 0) CHECK(first.vertex == e.vertex);
    if (!e.also.empty()) CHECK(check(r, e.also).status == CheckStatus::fail);
    if (e.face >= 0) CHECK(check(r, e.also.empty() ? e.first : e.also).face == e.face);
    if (e.first == "PARAM-11") {  // it names vertices (of T or T′), never a face or a patch
        CHECK(first.face == -1);
        CHECK(first.patch == -1);
    }
    CHECK_THAT(first.first_failure, Catch::Contains(e.says));
    if (!e.also.empty()) CHECK_THAT(check(r, e.also).first_failure, Catch::Contains(e.also_says));
}

/// The property form of expect_caught: each corruption of `domain`'s 4-to-16 subdivision.
void rc_expect_caught(const std::vector<Corruption>& list, const TriMesh& domain) {
    for (const Corruption& c : list) {
        ParamFile file = fhr::test::subdivided_param(domain, 4);
        TriMesh input = domain;
        const Expect e = c.apply(file, input);
        const VerifyReport r = verify(file, &input, nullptr, true);
        RC_LOG() << c.name << "\n" << describe(r);
        RC_ASSERT(difference(r, verify(file, fhr::exchange::PreparedInput(input), nullptr, true)) == "");
        RC_ASSERT(first_failure(r) == e.first);
        if (e.vertex >= 0) RC_ASSERT(check(r, e.first).vertex == e.vertex);
        if (!e.also.empty()) RC_ASSERT(check(r, e.also).status == CheckStatus::fail);
    }
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
    const std::vector<std::string> ids{"PARAM-2", "PARAM-3", "PARAM-4", "PARAM-5",  "PARAM-6",
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
    rc::prop("every corruption of the 4-to-16 subdivision of a random domain",
             [] { rc_expect_caught(corruptions(), *fhr::testing::gen_closed_mesh(0, 3, 200)); });
}

TEST_CASE("PARAM-2: when it fails every later check is skipped; without T, PARAM-11 is not listed", "[exchange]") {
    ParamFile file = fhr::test::subdivided_param(random_domain(0, 40, 3), 2);
    file.surface_faces[0].beta[0][0] = std::numeric_limits<double>::infinity();
    const VerifyReport r = verify(file, nullptr);
    REQUIRE(r.checks.size() == 9u);
    CHECK(r.checks.front().status == CheckStatus::fail);
    for (std::size_t i = 1; i < r.checks.size(); ++i) {
        INFO(r.checks[i].id);
        CHECK(r.checks[i].status == CheckStatus::skipped);
        CHECK(r.checks[i].first_failure == "not checked: needs PARAM-2 (indices and numbers)");
    }
    CHECK(r.checks.back().id == "PARAM-10");
}

TEST_CASE("PARAM-9, PARAM-10: a failed check makes the checks that rely on it skipped, with the reason", "[exchange]") {
    const TriMesh domain = random_domain(0, 100, 2);
    ParamFile file = fhr::test::subdivided_param(domain, 4);
    auto& face = file.surface_faces.back();  // turned, with its beta: PARAM-3 fails, PARAM-7 holds
    std::swap(face.v[1], face.v[2]);
    std::swap(face.beta[1], face.beta[2]);
    const VerifyReport r = verify(file, &domain);
    for (const char* id : {"PARAM-4", "PARAM-6", "PARAM-9", "PARAM-10", "PARAM-11"}) {
        INFO(id);
        CHECK(check(r, id).status == CheckStatus::skipped);
        CHECK_THAT(check(r, id).first_failure, Catch::StartsWith("not checked: needs PARAM-"));
    }
    CHECK(check(r, "PARAM-7").status == CheckStatus::pass);  // needs only PARAM-2
}

// ---- surfaces with boundary and several components (spec/param.md, "Boundary and
// components") ------------------------------------------------------------------------------------

namespace {

using fhr::test::disjoint_union;
using fhr::test::hexagon_disk;
using fhr::test::square_annulus;
using fhr::test::with_holes;

/// Every feature at once: a genus-1 mesh with two holes, a hexagonal disk and a closed sphere —
/// three components, two of them with boundary.
TriMesh mixed_domain(std::uint64_t seed) {
    return disjoint_union(disjoint_union(with_holes(random_domain(1, 200, seed), 2, seed), hexagon_disk()),
                          random_domain(0, 60, seed + 1));
}

TriMesh domain_of(const ParamFile& f) { return TriMesh::from_triangles(f.domain_vertices, f.domain_faces); }

/// The component of D of each domain face.
std::vector<std::uint32_t> face_components(const ParamFile& f) {
    const fhr::Components comp = fhr::connected_components(domain_of(f));
    std::vector<std::uint32_t> c;
    for (const fhr::Triangle& t : f.domain_faces) c.push_back(comp.vertex_component[fhr::VertexId(t[0])]);
    return c;
}

/// The edges of T′ in one face only (∂T′), as ordered vertex pairs.
std::set<std::pair<std::uint32_t, std::uint32_t>> surface_boundary_edges(const ParamFile& f) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> count;
    for (const auto& face : f.surface_faces)
        for (int c = 0; c < 3; ++c) ++count[std::minmax(face.v[c], face.v[(c + 1) % 3])];
    std::set<std::pair<std::uint32_t, std::uint32_t>> boundary;
    for (const auto& [edge, n] : count)
        if (n == 1) boundary.insert(edge);
    return boundary;
}

/// Cuts T′ open along a side (j, k) of a patch d where j is inside D, k on ∂D and d's other edge
/// at k on ∂D: patch d gets its own copies of k and of the points inside the side. T′ stays a
/// manifold of the same topology (the slit opens into the boundary loop at k), every vertex keeps
/// its image, but an interior edge of D now has a side on ∂T′. Returns j.
std::uint32_t slit(ParamFile& f) {
    const TriMesh D = domain_of(f);
    for (fhr::FaceId d : D.faces()) {
        fhr::HalfedgeId h = D.halfedge(d);
        for (int i = 0; i < 3; ++i, h = D.next(h)) {
            if (D.is_boundary(TriMesh::twin(h))) continue;
            std::uint32_t j = D.from(h).idx(), k = D.to(h).idx();  // k's other edge in d: next(h)
            if (!D.is_boundary(TriMesh::twin(D.next(h)))) {
                if (!D.is_boundary(TriMesh::twin(D.next(D.next(h))))) continue;
                std::swap(j, k);  // the other edge at from(h) is the previous one
            }
            if (D.is_boundary(fhr::VertexId(j))) continue;
            std::map<std::uint32_t, std::uint32_t> copy;
            for (std::uint32_t x = 0; x < f.surface_faces.size(); ++x) {
                if (f.surface_faces[x].patch != d.idx()) continue;
                for (int c = 0; c < 3; ++c) {
                    const Point p = point(f, {x, c});
                    if (!p.count(k) || (p.size() == 2 && !p.count(j)) || p.size() == 3) continue;
                    std::uint32_t& v = f.surface_faces[x].v[c];
                    if (!copy.count(v)) {
                        copy[v] = static_cast<std::uint32_t>(f.surface_vertices.size());
                        f.surface_vertices.push_back(f.surface_vertices[v]);
                    }
                    v = copy[v];
                }
            }
            return j;
        }
    }
    throw std::logic_error("no interior edge of D from an inner vertex to the boundary");
}

/// At the midpoint v of a side of patch d on ∂D (three faces of d, an open fan), moves the middle
/// face to the last patch e > d of d's component of D: d's faces at v form two fans, separated by
/// that face and by the gap of ∂T′, and d stays connected (the midpoint's neighbours on the side
/// are not corners: k >= 4). Returns v.
std::uint32_t pinch(ParamFile& f) {
    const auto inc = incidences(f);
    const auto boundary = surface_boundary_edges(f);
    const std::vector<std::uint32_t> component = face_components(f);
    for (std::uint32_t v = 0; v < inc.size(); ++v) {
        const Point p = point(f, inc[v][0]);
        if (patches_of(f, inc[v]).size() != 1 || p.size() != 2 || p.begin()->second != 0.5) continue;
        const std::uint32_t d = f.surface_faces[inc[v][0].face].patch;
        std::uint32_t e = d;
        for (std::uint32_t x = d; x < component.size(); ++x)
            if (component[x] == component[d]) e = x;
        if (e == d) continue;
        for (const Incidence& i : inc[v]) {
            const auto& face = f.surface_faces[i.face];
            const std::uint32_t a = face.v[(i.corner + 1) % 3], b = face.v[(i.corner + 2) % 3];
            if (!boundary.count(std::minmax(v, a)) && !boundary.count(std::minmax(v, b))) {
                f.surface_faces[i.face].patch = e;
                return v;
            }
        }
    }
    throw std::logic_error("no side of a patch on the boundary of D");
}

/// Reverses every face of the first component of D with boundary (i j k → i k j) and rewrites the
/// β of T′'s faces in its patches for the new corner order, so that ψ is the same map; with
/// `surface_too`, T′'s faces there are reversed as well (a b c → a c b, with their β).
void turn_over_bounded_component(ParamFile& f, bool surface_too) {
    const TriMesh D = domain_of(f);
    const std::vector<std::uint32_t> component = face_components(f);
    const fhr::Components comp = fhr::connected_components(D);
    std::uint32_t chosen = 0;
    for (fhr::VertexId v : D.vertices())
        if (D.is_boundary(v)) {
            chosen = comp.vertex_component[v];
            break;
        }
    for (std::uint32_t d = 0; d < f.domain_faces.size(); ++d)
        if (component[d] == chosen) std::swap(f.domain_faces[d][1], f.domain_faces[d][2]);
    for (auto& face : f.surface_faces) {
        if (component[face.patch] != chosen) continue;
        for (Beta& b : face.beta) std::swap(b[1], b[2]);
        if (surface_too) {
            std::swap(face.v[1], face.v[2]);
            std::swap(face.beta[1], face.beta[2]);
        }
    }
}

/// Corruptions that only a surface with boundary or several components allows; each applies to
/// the 4-to-16 subdivision of a domain with at least two components with boundary.
const std::vector<Corruption>& boundary_corruptions() {
    static const std::vector<Corruption> all{
        {"a slit: T' cut open along an interior edge of D that reaches the boundary",
         [](ParamFile& f, TriMesh&) {
             slit(f);
             return Expect{"PARAM-9",
                           "PARAM-11",
                           -1,
                           -1,
                           "lies on the boundary of T', but the side is an interior edge of D",
                           "is on the boundary of T' but not on T's boundary"};
         }},
        {"a non-manifold boundary vertex of T': two corners on its boundary glued",
         [](ParamFile& f, TriMesh&) {
             const TriMesh D = domain_of(f);
             std::vector<std::uint32_t> corners;  // T′'s first vertices are D's (synthetic.hpp)
             for (fhr::VertexId v : D.vertices())
                 if (D.is_boundary(v)) corners.push_back(v.idx());
             for (auto& face : f.surface_faces)
                 for (auto& v : face.v)
                     if (v == corners[1]) v = corners[0];
             return Expect{"PARAM-3", "", -1, -1, "surface T': non-manifold vertex " + std::to_string(corners[0])};
         }},
        {"a non-manifold boundary vertex of D: boundary vertices of two components glued",
         [](ParamFile& f, TriMesh&) {
             const TriMesh D = domain_of(f);
             const fhr::Components comp = fhr::connected_components(D);
             std::vector<std::uint32_t> first(comp.count, UINT32_MAX);
             for (fhr::VertexId v : D.vertices())
                 if (D.is_boundary(v) && first[comp.vertex_component[v]] == UINT32_MAX)
                     first[comp.vertex_component[v]] = v.idx();
             std::sort(first.begin(), first.end());  // the two lowest: components with boundary
             for (auto& t : f.domain_faces)
                 for (auto& v : t)
                     if (v == first[1]) v = first[0];
             return Expect{"PARAM-3", "", -1, -1, "domain D: non-manifold vertex " + std::to_string(first[0])};
         }},
        {"a patch touching the boundary pinched there (not a disk)",
         [](ParamFile& f, TriMesh&) {
             const std::uint32_t v = pinch(f);
             return Expect{"PARAM-6", "", v, -1, "is pinched at surface vertex " + std::to_string(v)};
         }},
        {"wrong chord length on a boundary side: a vertex slid along a side on the boundary of D",
         [](ParamFile& f, TriMesh&) {
             return Expect{"PARAM-10", "", slide_side_vertex(f, false, 1), -1, "but chord length"};
         }},
        {"a component of D with boundary turned over, T' not (beta rewritten: psi the same map)",
         [](ParamFile& f, TriMesh&) {
             turn_over_bounded_component(f, false);
             return Expect{"PARAM-8", "PARAM-9", -1, -1, "its image is clockwise"};
         }},
        {"a face of T' in a patch of another component of D",
         [](ParamFile& f, TriMesh&) {
             const std::vector<std::uint32_t> component = face_components(f);
             const auto other = std::find_if(component.begin(), component.end(),
                                             [&](std::uint32_t c) { return c != component[f.surface_faces[0].patch]; });
             f.surface_faces[0].patch = static_cast<std::uint32_t>(other - component.begin());
             return Expect{"PARAM-4", "PARAM-6", -1, -1, "has faces in two components of D"};
         }},
        {"a component of T' moved into the patches of another component of D, which then holds none",
         [](ParamFile& f, TriMesh&) {
             const std::vector<std::uint32_t> component = face_components(f);
             const std::uint32_t last = component.back();  // the sphere (mixed_domain)
             std::uint32_t lowest = UINT32_MAX;            // the vertex that names the moved component
             for (auto& face : f.surface_faces)
                 if (component[face.patch] == last) {
                     lowest = std::min({lowest, face.v[0], face.v[1], face.v[2]});
                     face.patch = 0;
                 }
             return Expect{"PARAM-4", "PARAM-6", -1, -1,
                           "the component of T' at surface vertex 0 and the component of T' at surface vertex " +
                               std::to_string(lowest) +
                               " both lie in patches of the component of D at domain vertex 0"};
         }},
        {"an extra component of D that holds no face of T'",
         [](ParamFile& f, TriMesh&) {
             const auto n = static_cast<std::uint32_t>(f.domain_vertices.size());
             for (const fhr::Vec3& p : {fhr::Vec3(0, 0, 1e3), fhr::Vec3(1, 0, 1e3), fhr::Vec3(0, 1, 1e3)})
                 f.domain_vertices.push_back(p);
             f.domain_faces.push_back({n, n + 1, n + 2});
             return Expect{"PARAM-4", "PARAM-6", -1, -1, "components but D has", "holds no face of T'"};
         }},
        {"an extra component of T': a copy of the patches of a component of D, moved away",
         [](ParamFile& f, TriMesh&) {
             const std::vector<std::uint32_t> component = face_components(f);
             std::map<std::uint32_t, std::uint32_t> copy;
             const std::size_t faces = f.surface_faces.size();
             for (std::size_t x = 0; x < faces; ++x) {
                 auto face = f.surface_faces[x];
                 if (component[face.patch] != 0) continue;
                 for (auto& v : face.v) {
                     if (!copy.count(v)) {
                         copy[v] = static_cast<std::uint32_t>(f.surface_vertices.size());
                         f.surface_vertices.push_back(f.surface_vertices[v] + fhr::Vec3(0, 0, 1e3));
                     }
                     v = copy[v];
                 }
                 f.surface_faces.push_back(face);
             }
             return Expect{"PARAM-4", "", -1, -1, "components but D has"};
         }},
        {"a hole in T' inside a patch: a component of T' of another chi than its component of D",
         [](ParamFile& f, TriMesh&) {
             const auto inc = incidences(f);
             for (std::size_t x = 0; x < f.surface_faces.size(); ++x) {
                 bool inside = true;
                 for (int c = 0; c < 3; ++c)
                     inside = inside && point(f, {static_cast<std::uint32_t>(x), c}).size() == 3;
                 if (inside) {
                     f.surface_faces.erase(f.surface_faces.begin() + static_cast<std::ptrdiff_t>(x));
                     return Expect{"PARAM-4", "PARAM-8", -1, -1, "chi(the component of T' at surface vertex "};
                 }
             }
             throw std::logic_error("k must be >= 4");
         }},
        {"--mesh: T with one more component (a torus: chi, boundary loops and area unchanged)",
         [](ParamFile&, TriMesh& input) {
             input = disjoint_union(input, random_domain(1, fhr::generate::min_faces(1), 3));
             return Expect{"PARAM-11", "", -1, -1, "T' has 3 components but T has 4"};
         }},
        {"--mesh: T with one more hole than T'",
         [](ParamFile&, TriMesh& input) {
             std::vector<fhr::Triangle> faces = input.triangles();
             faces.pop_back();  // a face of the closed sphere, the last component
             input = TriMesh::from_triangles(input.positions(), faces);
             return Expect{"PARAM-11", "", -1, -1, "chi(T') = "};
         }},
    };
    return all;
}

/// D and T′ (the k-subdivision of D) of a file, verified with and without T = D; both valid.
void expect_valid(const TriMesh& domain, int k) {
    const ParamFile file = fhr::test::subdivided_param(domain, k);
    const VerifyReport r = verify(file, &domain);
    INFO("k = " << k << "\n" << describe(r));
    CHECK(r.valid());
    CHECK(r.checks.size() == 10u);
    CHECK(verify(file, nullptr).valid());
}

}  // namespace

TEST_CASE("PARAM-2..11: subdivisions of a disk, an annulus, a mesh with holes and several pieces are valid",
          "[exchange][boundary]") {
    const std::vector<std::pair<const char*, TriMesh>> domains{
        {"hexagonal disk", hexagon_disk()},
        {"square annulus", square_annulus()},
        {"a disk and an annulus", disjoint_union(hexagon_disk(), square_annulus())},
        {"a torus with three holes", with_holes(random_domain(1, 200, 4), 3, 17)},
        {"two closed meshes", disjoint_union(random_domain(0, 40, 1), random_domain(2, 200, 2))},
        {"holes, a disk and a sphere", mixed_domain(5)},
    };
    for (const auto& [name, domain] : domains)
        for (int k = 1; k <= 4; ++k) {
            INFO(name);
            expect_valid(domain, k);
        }
}

TEST_CASE("PARAM-4, PARAM-10: boundary sides are checked from their one patch; components are counted",
          "[exchange][boundary]") {
    // Hexagon, k = 3: 6 spokes inside D seen from 2 patches, 6 rim sides from 1, 2 inner points each.
    const TriMesh disk = hexagon_disk();
    const VerifyReport r = verify(fhr::test::subdivided_param(disk, 3), &disk);
    INFO(describe(r));
    REQUIRE(r.valid());
    CHECK(check(r, "PARAM-10").checked == (6 * 2 + 6) * 2);
    CHECK(check(r, "PARAM-4").checked == 1);
    CHECK(check(r, "PARAM-11").checked == 2 + 7 + fhr::test::subdivided_param(disk, 3).surface_vertices.size() + 6 * 3);
    const VerifyReport mixed = verify(fhr::test::subdivided_param(mixed_domain(5), 2), nullptr);
    CHECK(check(mixed, "PARAM-4").checked == 3);
}

TEST_CASE(
    "PARAM-3..11: verify rejects each corruption of a surface with boundary and several components, naming "
    "the broken invariant first",
    "[exchange][boundary]") {
    const TriMesh domain = mixed_domain(5);
    for (const Corruption& c : boundary_corruptions()) {
        DYNAMIC_SECTION(c.name) { expect_caught(c, domain, 4); }
    }
}

TEST_CASE("PARAM-3..11: the boundary corruptions are caught on random domains with holes and several pieces",
          "[exchange][boundary][property]") {
    rc::prop("every boundary corruption of the 4-to-16 subdivision of a random domain", [] {
        const auto& closed = *fhr::testing::gen_closed_mesh(0, 2, 200);
        const std::size_t holes =
            *rc::gen::inRange<std::size_t>(1, std::max<std::size_t>(2, closed.n_faces() / 12 + 1));
        const bool annulus = *rc::gen::arbitrary<bool>();
        const TriMesh domain = disjoint_union(disjoint_union(with_holes(closed, holes, *rc::gen::inRange(0, 1000)),
                                                             annulus ? square_annulus() : hexagon_disk()),
                                              random_domain(0, 20, 7));
        RC_LOG() << holes << " holes, " << (annulus ? "annulus" : "disk");
        rc_expect_caught(boundary_corruptions(), domain);
    });
}

TEST_CASE("PARAM-2..11: subdivisions of random domains with holes and several pieces are valid",
          "[exchange][boundary][property]") {
    rc::prop("genus 0-2 with 0-3 holes, alone or with a second random piece, k = 1..4, T = D", [] {
        const auto& first = *fhr::testing::gen_closed_mesh(0, 2, 200);
        const std::size_t holes = *rc::gen::inRange<std::size_t>(0, std::min<std::size_t>(4, first.n_faces() / 12 + 1));
        TriMesh domain = with_holes(first, holes, *rc::gen::inRange(0, 1000));
        if (*rc::gen::arbitrary<bool>()) {
            const auto& second = *fhr::testing::gen_closed_mesh(0, 1, 100);
            domain = disjoint_union(domain, with_holes(second, *rc::gen::inRange<std::size_t>(0, 2), 3));
        }
        const int k = *rc::gen::inRange(1, 5);
        const ParamFile file = fhr::test::subdivided_param(domain, k);
        const VerifyReport r = verify(file, &domain);
        RC_LOG() << holes << " holes, k = " << k << "\n" << describe(r);
        RC_ASSERT(r.valid());
        RC_ASSERT(verify(file, nullptr).valid());
    });
}

TEST_CASE("PARAM-3, PARAM-8: a component with boundary may have either orientation, if D's and T''s agree",
          "[exchange][boundary]") {
    const TriMesh domain = mixed_domain(5);
    ParamFile file = fhr::test::subdivided_param(domain, 3);
    turn_over_bounded_component(file, true);  // D and T′ turned over together: the same map, mirrored
    const VerifyReport r = verify(file, nullptr);
    INFO(describe(r));
    CHECK(r.valid());
}

TEST_CASE("PARAM-4: each component of T' has the chi and the boundary loops of its own component of D",
          "[exchange][boundary]") {
    // Totals equal, components swapped: D = X ∪ Y with the face counts of T′'s pieces A ∪ B but
    // X ≅ B, Y ≅ A. The patches of A (faces 0..F−1) now lie in X.
    auto swapped = [](const TriMesh& a, const TriMesh& b, const TriMesh& x, const TriMesh& y) {
        REQUIRE(a.n_faces() == x.n_faces());
        REQUIRE(b.n_faces() == y.n_faces());
        ParamFile file = fhr::test::subdivided_param(disjoint_union(a, b), 2);
        const TriMesh other = disjoint_union(x, y);
        file.domain_vertices = other.positions();
        file.domain_faces = other.triangles();
        return verify(file, nullptr);
    };
    const std::size_t f = 200;
    SECTION("chi: a torus and a sphere against a sphere and a torus") {
        const VerifyReport r =
            swapped(random_domain(1, f, 1), random_domain(0, f, 2), random_domain(0, f, 3), random_domain(1, f, 4));
        INFO(describe(r));
        CHECK(first_failure(r) == "PARAM-4");
        CHECK_THAT(check(r, "PARAM-4").first_failure,
                   Catch::StartsWith("chi(the component of T' at surface vertex 0) = 0 but chi(the component of D at "
                                     "domain vertex 0) = 2"));
    }
    SECTION("boundary loops: a sphere with two holes and a torus against a torus and a sphere with two holes") {
        const VerifyReport r = swapped(with_holes(random_domain(0, f + 2, 1), 2, 0), random_domain(1, f, 2),
                                       random_domain(1, f, 3), with_holes(random_domain(0, f + 2, 4), 2, 0));
        INFO(describe(r));
        CHECK(first_failure(r) == "PARAM-4");
        CHECK_THAT(check(r, "PARAM-4").first_failure,
                   Catch::StartsWith("the component of T' at surface vertex 0 has 2 boundary loops but the component "
                                     "of D at domain vertex 0 has 0 boundary loops"));
    }
    SECTION("one component each: a sphere with two holes against a torus (the same chi)") {
        ParamFile file = fhr::test::subdivided_param(with_holes(random_domain(0, f + 2, 1), 2, 0), 2);
        const TriMesh torus = random_domain(1, f, 3);
        file.domain_vertices = torus.positions();
        file.domain_faces = torus.triangles();
        const VerifyReport r = verify(file, nullptr);
        INFO(describe(r));
        CHECK(first_failure(r) == "PARAM-4");
        CHECK(check(r, "PARAM-4").first_failure == "T' has 2 boundary loops but D has 0 boundary loops");
    }
}

TEST_CASE("PARAM-4: one boundary loop is named in the singular", "[exchange][boundary]") {
    // A torus with one hole against a sphere with three: chi = -1 both, 199 faces both.
    ParamFile file = fhr::test::subdivided_param(with_holes(random_domain(1, 200, 1), 1, 0), 2);
    const TriMesh sphere = with_holes(random_domain(0, 202, 3), 3, 0);
    file.domain_vertices = sphere.positions();
    file.domain_faces = sphere.triangles();
    const VerifyReport r = verify(file, nullptr);
    INFO(describe(r));
    CHECK(first_failure(r) == "PARAM-4");
    CHECK(check(r, "PARAM-4").first_failure == "T' has 1 boundary loop but D has 3 boundary loops");
}

TEST_CASE("PARAM-11: T' with T's vertices, triangulated otherwise, covers another area", "[exchange][boundary]") {
    // The hexagon with its centre raised into a tent; T has the spoke (0, 1) flipped into (6, 2).
    // Every vertex of either mesh is a vertex of the other, boundaries and topology agree: only
    // the area tells the surfaces apart.
    std::vector<fhr::Vec3> p = hexagon_disk().positions();
    p[0].z() = 0.5;
    std::vector<fhr::Triangle> t = hexagon_disk().triangles();
    const TriMesh tent = TriMesh::from_triangles(p, t);
    REQUIRE(t.front() == (fhr::Triangle{0, 1, 2}));
    REQUIRE(t.back() == (fhr::Triangle{0, 6, 1}));
    t.front() = {6, 1, 2};
    t.back() = {6, 2, 0};
    const TriMesh flipped = TriMesh::from_triangles(p, t);
    const VerifyReport r = verify(fhr::test::subdivided_param(tent, 1), &flipped);
    INFO(describe(r));
    CHECK(first_failure(r) == "PARAM-11");
    CHECK(check(r, "PARAM-11").failures == 1);
    CHECK_THAT(check(r, "PARAM-11").first_failure,
               Catch::StartsWith("the area of T' is ") && Catch::EndsWith(", more than 1e-9)") &&
                   Catch::Contains(" but T's is ") && Catch::Contains(" (relative difference "));
}

TEST_CASE("PARAM-3: a flat closed component is refused (INV-IN-13 for each closed component)", "[exchange][boundary]") {
    // Four coplanar points as a tetrahedron: not degenerate triangles, but a flat closed surface.
    const std::vector<fhr::Vec3> p{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
    const TriMesh flat =
        TriMesh::from_triangles(p, std::vector<fhr::Triangle>{{0, 1, 2}, {1, 3, 2}, {0, 3, 1}, {0, 2, 3}});
    SECTION("alone: the message of a closed connected surface") {
        const VerifyReport r = verify(fhr::test::subdivided_param(flat, 2), nullptr);
        CHECK(first_failure(r) == "PARAM-3");
        CHECK(check(r, "PARAM-3").first_failure ==
              "domain D: the closed surface is flat: all 4 vertices lie in the plane of face 0, so its faces cover a "
              "flat region twice");
    }
    SECTION("beside a disk") {
        const VerifyReport r = verify(fhr::test::subdivided_param(disjoint_union(hexagon_disk(), flat), 1), nullptr);
        CHECK(first_failure(r) == "PARAM-3");
        CHECK(check(r, "PARAM-3").first_failure ==
              "domain D: the closed component at vertex 7 is flat: all 4 vertices lie in the plane of face 6, so its "
              "faces cover a flat region twice");
    }
}

namespace {

/// The hexagon slit along the spoke (0, 1): rim vertex 1 doubled (as vertex 7, in the last face),
/// so the centre is on its boundary.
TriMesh slit_hexagon_disk() {
    const TriMesh disk = hexagon_disk();
    std::vector<fhr::Vec3> p = disk.positions();
    p.push_back(p[1]);
    std::vector<fhr::Triangle> t = disk.triangles();
    for (auto& v : t.back())
        if (v == 1) v = 7;
    return TriMesh::from_triangles(p, t);
}

}  // namespace

TEST_CASE("PARAM-11: a vertex on T's boundary must be on T''s boundary", "[exchange][boundary]") {
    // T = the slit hexagon. T′ = the unslit hexagon: the same point set, the same chi, boundary
    // loops and components, the same area — but the centre is inside T′.
    const TriMesh disk = hexagon_disk();
    const TriMesh slit_disk = slit_hexagon_disk();
    const VerifyReport r = verify(fhr::test::subdivided_param(disk, 2), &slit_disk);
    INFO(describe(r));
    CHECK(first_failure(r) == "PARAM-11");
    CHECK_THAT(
        check(r, "PARAM-11").first_failure,
        Catch::StartsWith("vertex 0 of T (0, 0, 0) is on T's boundary, but surface vertex 0 at the same point is "
                          "not on the boundary of T'"));
    // Where: T's vertex 0, no face, no patch.
    CHECK(check(r, "PARAM-11").vertex == 0);
    CHECK(check(r, "PARAM-11").face == -1);
    CHECK(check(r, "PARAM-11").patch == -1);
}

TEST_CASE(
    "the oracle on 1 and 3 threads: the same report (PARAM-11's distances in parallel blocks, the checks side by side)",
    "[exchange]") {
    // T′ with about 10,800 vertices: three blocks of PARAM-11's parallel loop. Every 7th vertex
    // from 5,000 on is moved off T, so failures come from every block after the first; the first
    // is vertex 5,000. Below 2^19 faces of T′ PARAM-3 runs beside PARAM-11's preparation of T and
    // PARAM-11 beside PARAM-4..10 (verify.cpp): one corner's β is broken too, so that checks on
    // both sides fail.
    const TriMesh domain = random_domain(1, 600, 11);
    ParamFile file = fhr::test::subdivided_param(domain, 6);
    REQUIRE(file.surface_vertices.size() > 2 * 4096);
    std::uint64_t moved = 0;
    for (std::size_t v = 5000; v < file.surface_vertices.size(); v += 7, ++moved)
        file.surface_vertices[v] += fhr::Vec3(0, 0, 1);
    file.surface_faces[100].beta[0] = {2.0, -1.0};
    fhr::ThreadPool one(1), three(3);
    const VerifyReport r1 = verify(file, &domain, &one), r3 = verify(file, &domain, &three);
    const CheckResult& a = check(r1, "PARAM-11");
    CHECK(a.status == CheckStatus::fail);
    CHECK(a.failures >= moved);  // T's own vertices there are missing from T′ too
    CHECK_THAT(a.first_failure, Catch::Contains("surface vertex 5000 "));
    CHECK(check(r1, "PARAM-5").status == CheckStatus::fail);
    CHECK(difference(r1, r3).empty());
}

TEST_CASE("PARAM-11: T's side prepared once (PreparedInput) serves several files, moved, on any number of threads",
          "[exchange]") {
    // The same reports as verify(file, &T): a valid file, one with vertices moved off T (PARAM-11
    // fails in several blocks), one with a broken β (PARAM-5), and on a surface with boundary one
    // whose T has a slit (PARAM-11's boundary grid).
    const TriMesh domain = random_domain(1, 600, 11);
    const ParamFile valid = fhr::test::subdivided_param(domain, 6);
    ParamFile moved = valid, broken = valid;
    for (std::size_t v = 5000; v < moved.surface_vertices.size(); v += 7)
        moved.surface_vertices[v] += fhr::Vec3(0, 0, 1);
    broken.surface_faces[100].beta[0] = {2.0, -1.0};
    fhr::exchange::PreparedInput made(domain);
    const fhr::exchange::PreparedInput prepared = std::move(made);
    CHECK(&prepared.mesh() == &domain);
    fhr::ThreadPool one(1), three(3);
    for (const ParamFile* file : std::vector<const ParamFile*>{&valid, &moved, &broken}) {
        const VerifyReport direct = verify(*file, &domain);
        INFO(describe(direct));
        CHECK(difference(direct, verify(*file, prepared, &one)).empty());
        CHECK(difference(direct, verify(*file, prepared, &three)).empty());
    }
    CHECK(verify(valid, prepared).valid());
    CHECK(check(verify(moved, prepared), "PARAM-11").status == CheckStatus::fail);
    CHECK(first_failure(verify(broken, prepared)) == "PARAM-5");

    const TriMesh disk = hexagon_disk();
    const TriMesh slit_disk = slit_hexagon_disk();
    const ParamFile on_disk = fhr::test::subdivided_param(disk, 2);
    const VerifyReport slit = verify(on_disk, fhr::exchange::PreparedInput(slit_disk));
    CHECK(first_failure(slit) == "PARAM-11");
    CHECK(difference(slit, verify(on_disk, &slit_disk)).empty());
    CHECK(verify(on_disk, fhr::exchange::PreparedInput(disk)).valid());
}

TEST_CASE("PARAM-10: chord length is judged only as the paper's map; otherwise reported as info", "[exchange]") {
    fhr::generate::RandomMeshOptions o;
    o.genus = 1;
    o.faces = 120;
    o.seed = 3;
    o.noise = 0.2;
    const TriMesh domain = fhr::generate::random_closed_mesh(o);
    ParamFile file = fhr::test::subdivided_param(domain, 4);
    // The first inner vertex of a side slid along it: still a homeomorphism, no longer chord length.
    TriMesh input = domain;
    slide_side_vertex(file, false);
    const VerifyReport homeomorphism = verify(file, &input);
    INFO(describe(homeomorphism));
    CHECK(homeomorphism.valid());
    CHECK(check(homeomorphism, "PARAM-10").status == CheckStatus::info);
    CHECK(check(homeomorphism, "PARAM-10").failures >= 1);
    CHECK_THAT(check(homeomorphism, "PARAM-10").first_failure, Catch::Contains("but chord length"));
    const VerifyReport paper = verify(file, &input, nullptr, true);
    CHECK_FALSE(paper.valid());
    CHECK(first_failure(paper) == "PARAM-10");
    CHECK(check(paper, "PARAM-10").status == CheckStatus::fail);
}
