// FHR tests — the per-vertex map oracle (src/fhr/exchange/vertex_map.hpp, spec/vertex_map.md
// VMAP-1..9): the four readers and their refusals; hand-made maps for every check (each would pass
// if its check were removed); and properties over random meshes of genus 0-3, with boundary and
// several components: the map of a subdivision's vertices onto its domain (β of a face holding
// each vertex, so the rule `adjacent` reproduces the parameterization) is valid and a planted fault
// is named, and the identity of D onto D with edges flipped — each new edge crossing an edge of D
// in the rule's fan of two faces — is valid.
#include <catch2/catch.hpp>
#include <rapidcheck/catch.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#include <fhr/core/errors.hpp>
#include <fhr/exchange/vertex_map.hpp>
#include <fhr/generate/random_mesh.hpp>
#include <fhr/testing/rapidcheck.hpp>
#include "synthetic.hpp"

using fhr::PolygonSoup;
using fhr::Triangle;
using fhr::TriMesh;
using fhr::Vec3;
using fhr::exchange::CheckResult;
using fhr::exchange::CheckStatus;
using fhr::exchange::parse_vertex_map;
using fhr::exchange::verify_vertex_map;
using fhr::exchange::VertexImageRecord;
using fhr::exchange::VertexMapFile;
using fhr::exchange::VertexMapFormat;
using fhr::exchange::VertexMapReport;

namespace {

PolygonSoup soup_of(const std::vector<Vec3>& points, const std::vector<Triangle>& faces) {
    PolygonSoup s;
    s.points = points;
    for (const Triangle& t : faces) s.add_polygon(t.data(), 3);
    return s;
}

PolygonSoup soup_of(const TriMesh& m) { return soup_of(m.positions(), m.triangles()); }

VertexImageRecord at_face(std::uint32_t face, double w0, double w1, double w2) {
    VertexImageRecord r;
    r.ref = VertexImageRecord::Ref::face;
    r.a = face;
    r.weights = {w0, w1, w2};
    return r;
}

/// The identity of a mesh: vertex v at corner c of a face holding it.
VertexMapFile identity(const std::vector<Triangle>& faces, std::size_t n) {
    VertexMapFile m;
    m.source = "test";
    m.records.resize(n);
    for (std::uint32_t f = 0; f < faces.size(); ++f)
        for (int c = 0; c < 3; ++c) {
            std::array<double, 3> w{};
            w[c] = 1;
            m.records[faces[f][c]] = at_face(f, w[0], w[1], w[2]);
        }
    return m;
}

const CheckResult& check(const VertexMapReport& r, const std::string& id) {
    for (const CheckResult& c : r.checks)
        if (c.id == id) return c;
    throw std::logic_error("no check " + id);
}

std::string first(const VertexMapReport& r) { return r.first_failure() ? r.first_failure()->id : "none"; }

/// A regular octahedron: vertices ±x, ±y, ±z; faces counter-clockwise from outside.
const std::vector<Vec3> octahedron{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
const std::vector<Triangle> octahedron_faces{{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                             {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};

/// A square (0,0) (1,0) (1,1) (0,1) in z = 0 as two faces.
const std::vector<Vec3> square{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
const std::vector<Triangle> square_faces{{0, 1, 2}, {0, 2, 3}};

/// The map of the subdivision's vertices onto its domain: each vertex with the β of a face of T′
/// holding it (spec/vertex_map.md: the rule then reproduces the parameterization).
VertexMapFile map_of(const fhr::exchange::ParamFile& p) {
    VertexMapFile m;
    m.source = "test";
    m.records.resize(p.surface_vertices.size());
    for (const auto& face : p.surface_faces)
        for (int c = 0; c < 3; ++c)
            m.records[face.v[c]] = at_face(face.patch, face.beta[c][0], face.beta[c][1], face.beta[c][2]);
    return m;
}

PolygonSoup surface_of(const fhr::exchange::ParamFile& p) {
    std::vector<Triangle> t;
    for (const auto& face : p.surface_faces) t.push_back(face.v);
    return soup_of(p.surface_vertices, t);
}

TriMesh random_surface(fhr::generate::Family family, int genus, std::size_t holes, bool two_components,
                       std::uint64_t seed) {
    fhr::generate::RandomMeshOptions o;
    o.family = family;
    o.genus = genus;
    o.faces = 80 + 24 * static_cast<std::size_t>(genus);
    o.seed = seed;
    o.noise = family == fhr::generate::Family::block ? 0.2 : 0.0;  // the other families shape their own
    o.faces = std::max(o.faces, fhr::generate::min_faces(o));
    TriMesh m = fhr::generate::random_closed_mesh(o);
    if (holes > 0) m = fhr::test::with_holes(m, holes, seed);
    if (two_components) {
        o.family = fhr::generate::Family::block;
        o.noise = 0.2;
        o.genus = 0;
        o.seed = seed + 1;
        m = fhr::test::disjoint_union(m, fhr::generate::random_closed_mesh(o));
    }
    return m;
}

/// The angle at a between b and c, in 3D.
double angle(const Vec3& a, const Vec3& b, const Vec3& c) {
    return std::acos(std::clamp((b - a).normalized().dot((c - a).normalized()), -1.0, 1.0));
}

/// `m` with interior edges (a, b) flipped to (c, d) where the rule can only take the two faces
/// across (a, b): their quadrilateral unfolds convex by a margin (at a and at b its angle is below
/// π − 0.1, and the rest of the angle around a and b above π + 0.1, so that no fan around the other
/// side holds a straight c-d), c and d have no common neighbour but a and b, and no two flipped
/// edges share a face.
TriMesh with_flips(const TriMesh& m) {
    std::vector<Triangle> faces = m.triangles();
    std::vector<bool> used(faces.size(), false);
    std::set<std::pair<std::uint32_t, std::uint32_t>> added;
    std::vector<double> total(m.n_vertices(), 0);
    std::vector<std::set<std::uint32_t>> neighbours(m.n_vertices());
    for (const Triangle& t : faces)
        for (int k = 0; k < 3; ++k) {
            total[t[k]] += angle(m.position(fhr::VertexId(t[k])), m.position(fhr::VertexId(t[(k + 1) % 3])),
                                 m.position(fhr::VertexId(t[(k + 2) % 3])));
            neighbours[t[k]].insert(t[(k + 1) % 3]);
            neighbours[t[k]].insert(t[(k + 2) % 3]);
        }
    for (fhr::EdgeId e : m.edges()) {
        const fhr::HalfedgeId h = TriMesh::halfedge(e, 0), g = TriMesh::twin(h);
        if (m.is_boundary(e)) continue;
        const std::uint32_t f = m.face(h).idx(), k = m.face(g).idx();
        if (used[f] || used[k]) continue;
        const std::uint32_t ia = m.from(h).idx(), ib = m.to(h).idx(), ic = m.to(m.next(h)).idx(),
                            id = m.to(m.next(g)).idx();
        const Vec3 &a = m.position(m.from(h)), &b = m.position(m.to(h)), &c = m.position(m.to(m.next(h))),
                   &d = m.position(m.to(m.next(g)));
        const double at_a = angle(a, b, c) + angle(a, d, b), at_b = angle(b, c, a) + angle(b, a, d);
        if (at_a > M_PI - 0.1 || at_b > M_PI - 0.1 || total[ia] - at_a < M_PI + 0.1 || total[ib] - at_b < M_PI + 0.1)
            continue;
        std::vector<std::uint32_t> common;
        std::set_intersection(neighbours[ic].begin(), neighbours[ic].end(), neighbours[id].begin(),
                              neighbours[id].end(), std::back_inserter(common));
        if (common.size() != 2 || neighbours[ic].count(id) || !added.insert(std::minmax(ic, id)).second) continue;
        faces[f] = {ia, id, ic};
        faces[k] = {ib, ic, id};
        used[f] = used[k] = true;
    }
    return TriMesh::from_triangles(m.positions(), faces);
}

}  // namespace

TEST_CASE("VMAP-2..9: the identity of an octahedron is valid; its distortion is 1", "[exchange][vertex_map]") {
    const PolygonSoup D = soup_of(octahedron, octahedron_faces);
    const VertexMapReport r = verify_vertex_map(identity(octahedron_faces, 6), D, D);
    CHECK(first(r) == "none");
    CHECK(r.checks.size() == 8);
    CHECK(r.folded.empty());
    REQUIRE(r.distortion.l2_stretch);
    CHECK(*r.distortion.l2_stretch == Approx(1.0));
    CHECK(*r.distortion.anisotropy_max == Approx(1.0));
}

TEST_CASE("VMAP-1: the four formats read the same map; bad files are refused naming line and vertex",
          "[exchange][vertex_map][io]") {
    // The octahedron onto itself; vertex 4 (+z) given on face 0 = (0, 2, 4) at corner 2.
    const std::string plain =
        "fhr-vertex-map 1\n6\n0 1 0 0\n1 0 1 0  # face 1 = (2, 1, 4)\n0 0 1 0\n2 0 1 0\n0 0 0 1\n4 0 0 1\n";
    const std::string corr = "1 1 0 0\n2 0 1 0\n1 0 1 0\n3 0 1 0\n1 0 0 1\n5 0 0 1\n";
    const std::string vtpm = "6 6\n0 2 0 0\n1 4 0 0\n2 4 0 0\n3 4 0 0\n4 0 0 0\n5 2 0 0\n";
    const std::string ijv = "1 1 1\n2 2 1\n3 3 1\n4 4 1\n5 5 1\n6 6 1\n";
    const PolygonSoup D = soup_of(octahedron, octahedron_faces);
    for (auto [text, format] : {std::pair{plain, VertexMapFormat::plain},
                                {corr, VertexMapFormat::corr},
                                {vtpm, VertexMapFormat::vtpm},
                                {ijv, VertexMapFormat::ijv}}) {
        INFO(fhr::exchange::to_string(format));
        const VertexMapFile m = parse_vertex_map(text, "m", format, 6, 6);
        REQUIRE(m.records.size() == 6);
        CHECK(first(verify_vertex_map(m, D, D)) == "none");
    }
    CHECK(fhr::exchange::vertex_map_format_of("a/b.CORR") == VertexMapFormat::corr);
    CHECK(fhr::exchange::vertex_map_format_of("a.vmap") == VertexMapFormat::plain);
    CHECK_FALSE(fhr::exchange::vertex_map_format_of("a.txt"));
    auto refused = [](const std::string& text, VertexMapFormat f, const std::string& says) {
        try {
            parse_vertex_map(text, "m.map", f, 6, 6);
            FAIL("accepted: " << text);
        } catch (const fhr::InvalidInput& e) {
            CHECK_THAT(e.what(), Catch::Contains(says));
        }
    };
    refused("fhr-vertex-map 1\n5\n", VertexMapFormat::plain, "5 vertices but T has 6");
    refused("fhr-vertex-map 1\n6\n0 1 0\n", VertexMapFormat::plain, "m.map:3");
    refused("fhr-vertex-map 1\n6\n0 1 0 x\n", VertexMapFormat::plain, "expected a weight");
    refused(corr.substr(0, corr.rfind("5 0 0 1")), VertexMapFormat::corr, "5 records for the 6 vertices");
    refused("0 1 0 0\n", VertexMapFormat::corr, "count from 1");
    refused("6 5\n", VertexMapFormat::vtpm, "onto 5 vertices");
    refused("7 1 1\n", VertexMapFormat::ijv, "out of range 1..6");
    refused("1 1 0.5\n1 1 0.5\n", VertexMapFormat::ijv, "named twice");
    refused("1 1 0.2\n1 2 0.2\n1 3 0.2\n1 4 0.4\n", VertexMapFormat::ijv, "more than three");
}

TEST_CASE("VMAP-2: missing images, faces out of range, NaN and non-barycentric weights are named",
          "[exchange][vertex_map]") {
    const PolygonSoup D = soup_of(octahedron, octahedron_faces);
    VertexMapFile m = identity(octahedron_faces, 6);
    m.records[1].ref = VertexImageRecord::Ref::none;
    m.records[2] = at_face(8, 1, 0, 0);
    m.records[3] = at_face(2, std::nan(""), 1, 0);
    m.records[5] = at_face(4, 0, -1e-9, 1 + 1e-9);
    const VertexMapReport r = verify_vertex_map(m, D, D);
    CHECK(first(r) == "VMAP-2");
    CHECK(check(r, "VMAP-2").failures == 4);
    CHECK(check(r, "VMAP-2").vertex == 1);
    CHECK(check(r, "VMAP-4").status == CheckStatus::skipped);
    // A weight of −2.3e−16, as writers print a zero, is read as 0.
    VertexMapFile ok = identity(octahedron_faces, 6);
    ok.records[0] = at_face(0, 1 + 2.3e-16, -2.3e-16, 0);
    CHECK(first(verify_vertex_map(ok, D, D)) == "none");
    // A halfedge that no face has, and three vertices of D that are not a face.
    VertexMapFile h = identity(octahedron_faces, 6);
    h.records[0].ref = VertexImageRecord::Ref::halfedge;
    h.records[0].a = 0;
    h.records[0].b = 1;  // ±x are opposite: no edge
    h.records[1].ref = VertexImageRecord::Ref::vertices;
    h.records[1].corners = {0, 1, 2};
    h.records[1].weights = {0.2, 0.3, 0.5};
    CHECK(check(verify_vertex_map(h, D, D), "VMAP-2").failures == 2);
}

TEST_CASE("VMAP-3, VMAP-4: a turned face and a surface of another genus are refused", "[exchange][vertex_map]") {
    const PolygonSoup D = soup_of(octahedron, octahedron_faces);
    std::vector<Triangle> turned = octahedron_faces;
    std::swap(turned[3][0], turned[3][1]);
    CHECK(first(verify_vertex_map(identity(octahedron_faces, 6), soup_of(octahedron, turned), D)) == "VMAP-3");
    // A disk (the square) mapped into the octahedron: χ 1 against 2.
    VertexMapFile m;
    m.source = "test";
    m.records = {at_face(0, 1, 0, 0), at_face(0, 0, 1, 0), at_face(0, 0, 0, 1), at_face(1, 0, 1, 0)};
    const VertexMapReport r = verify_vertex_map(m, soup_of(square, square_faces), D);
    CHECK(check(r, "VMAP-4").status == CheckStatus::fail);
    CHECK_THAT(check(r, "VMAP-4").first_failure, Catch::Contains("chi = 1"));
}

TEST_CASE("VMAP-5: an edge whose ends share no fan has no image; the rest is still judged", "[exchange][vertex_map]") {
    // A disk's edge (0, 1) from the centre of the octahedron's face (0, 2, 4) to the centre of the
    // opposite face (3, 1, 5): no vertex of D is in both, so no fan holds both ends.
    const PolygonSoup D = soup_of(octahedron, octahedron_faces);
    VertexMapFile m;
    m.source = "test";
    const double third = 1.0 / 3;
    m.records = {at_face(0, third, third, third), at_face(6, third, third, third), at_face(0, 0, 0, 1),
                 at_face(0, 0, 1, 0)};
    const VertexMapReport r = verify_vertex_map(m, soup_of(square, square_faces), D);
    CHECK(check(r, "VMAP-5").status == CheckStatus::fail);
    CHECK(r.edges_without_image == std::vector<std::pair<std::uint32_t, std::uint32_t>>{{0, 1}});
    CHECK(check(r, "VMAP-6").status == CheckStatus::pass);  // judged without that edge
    CHECK_FALSE(r.distortion.l2_stretch);
    // Ends in two faces around one vertex: the edge from +x to −x crosses the spoke to +z in the
    // unfolding of the two faces around +y (120° there), so it has an image.
    m.records[1] = at_face(1, 0, 1, 0);
    CHECK(check(verify_vertex_map(m, soup_of(square, square_faces), D), "VMAP-5").status == CheckStatus::pass);
}

namespace {

/// The hexagonal disk subdivided 4 times per side, and its map onto the disk.
struct Hexagon {
    TriMesh domain = fhr::test::hexagon_disk();
    fhr::exchange::ParamFile param = fhr::test::subdivided_param(domain, 4);
    PolygonSoup T = surface_of(param), D = soup_of(domain);
    VertexMapFile map = map_of(param);
};

}  // namespace

TEST_CASE("VMAP-6..8: a swapped pair of distant vertices and a vertex moved across an edge of D are named",
          "[exchange][vertex_map]") {
    const Hexagon h;
    REQUIRE(first(verify_vertex_map(h.map, h.T, h.D)) == "none");
    // Two vertices of T inside different patches, far apart, swapped.
    const auto inside = [&](std::uint32_t patch) {
        for (std::uint32_t v = 0; v < h.map.records.size(); ++v) {
            const auto& r = h.map.records[v];
            if (r.a == patch && std::min({r.weights[0], r.weights[1], r.weights[2]}) > 0) return v;
        }
        throw std::logic_error("no vertex inside the patch");
    };
    VertexMapFile swapped = h.map;
    std::swap(swapped.records[inside(0)], swapped.records[inside(3)]);
    const VertexMapReport rs = verify_vertex_map(swapped, h.T, h.D);
    CHECK(first(rs) == "VMAP-6");
    CHECK(check(rs, "VMAP-7").failures > 0);
    CHECK(check(rs, "VMAP-8").failures > 0);
    // A vertex inside patch 0 mirrored across its edge to patch 1 (the faces (0, 1, 2) and
    // (0, 2, 3) of the hexagon share the edge (0, 2)): a face at it folds, and it winds wrongly.
    const std::uint32_t v = inside(0);
    const auto& w = h.map.records[v].weights;  // on (0, 1, 2)
    VertexMapFile moved = h.map;
    moved.records[v] = at_face(1, w[0], w[2], w[1]);  // the same weights on (0, 2, 3)
    const VertexMapReport rm = verify_vertex_map(moved, h.T, h.D);
    CHECK_FALSE(rm.valid());
    bool at_v = false;
    for (std::uint32_t f : rm.folded)
        for (int c = 0; c < 3; ++c) at_v = at_v || h.T.polygon(f)[c] == v;
    CHECK(at_v);
    CHECK(check(rm, "VMAP-8").failures > 0);
}

TEST_CASE("VMAP-6: two vertices of T with one image are named", "[exchange][vertex_map]") {
    const Hexagon h;
    VertexMapFile m = h.map;
    m.records[8] = m.records[7];
    const VertexMapReport r = verify_vertex_map(m, h.T, h.D);
    CHECK(check(r, "VMAP-6").status == CheckStatus::fail);
    CHECK_THAT(check(r, "VMAP-6").first_failure, Catch::Contains("vertices 7 and 8 of T have one image"));
}

TEST_CASE("VMAP-9: a boundary edge pulled inside D, and an interior vertex on the boundary, are named",
          "[exchange][vertex_map]") {
    const PolygonSoup D = soup_of(square, square_faces);
    // The identity, then vertex 3 (a corner) moved inside face (0, 1, 2)... onto the diagonal's
    // middle: the boundary edges (2, 3) and (3, 0) leave ∂D.
    VertexMapFile m = identity(square_faces, 4);
    m.records[3] = at_face(0, 0.5, 0, 0.5);
    const VertexMapReport r = verify_vertex_map(m, D, D);
    CHECK(check(r, "VMAP-9").failures == 2);
    CHECK_THAT(check(r, "VMAP-9").first_failure, Catch::Contains("boundary edge"));
    // The hexagon's centre (an interior vertex of T) sent to a point on the rim.
    const Hexagon h;
    VertexMapFile c = h.map;
    const std::uint32_t centre = 0;  // the hexagon's vertex 0 keeps its number in T'
    c.records[centre] = at_face(0, 0, 0.5, 0.5);
    const VertexMapReport rc = verify_vertex_map(c, h.T, h.D);
    CHECK_THAT(check(rc, "VMAP-9").first_failure, Catch::Contains("interior vertex 0 of T"));
}

TEST_CASE(
    "VMAP-2..9: maps of subdivisions onto their domains are valid and a swap is named; the identity of D onto D with "
    "edges flipped is valid",
    "[exchange][vertex_map][property]") {
    rc::prop("the generator's families, genus 0-3, with holes and components", [] {
        const int genus = *rc::gen::inRange(0, 4);
        const auto holes = static_cast<std::size_t>(*rc::gen::inRange(0, 3));
        const bool two = *rc::gen::inRange(0, 4) == 0;
        const auto family = *rc::gen::elementOf(std::vector<fhr::generate::Family>(
            std::begin(fhr::generate::embedded_families), std::end(fhr::generate::embedded_families)));
        RC_TAG(fhr::generate::family_name(family));
        const TriMesh domain = random_surface(family, genus, holes, two, *rc::gen::inRange<std::uint64_t>(0, 1000000));
        const fhr::exchange::ParamFile p = fhr::test::subdivided_param(domain, *rc::gen::inRange(2, 4));
        const PolygonSoup T = surface_of(p), D = soup_of(domain);
        const VertexMapFile m = map_of(p);
        const VertexMapReport r = verify_vertex_map(m, T, D);
        RC_ASSERT(first(r) == "none");
        // The corners of D keep their numbers in T': two of them, far apart, swapped.
        VertexMapFile swapped = m;
        const auto n = static_cast<std::uint32_t>(domain.n_vertices());
        std::swap(swapped.records[0], swapped.records[n - 1]);
        RC_ASSERT(!verify_vertex_map(swapped, T, D).valid());
        // D with some edges flipped, mapped by the identity: each new edge joins the far corners of
        // two faces of D across the old edge, the rule's fan of two faces (flipped where that
        // quadrilateral is convex, no two flipped edges in one face).
        const TriMesh flipped = with_flips(domain);
        RC_ASSERT(flipped.n_faces() == domain.n_faces());
        const VertexMapReport rf =
            verify_vertex_map(identity(domain.triangles(), domain.n_vertices()), soup_of(flipped), D);
        RC_ASSERT(first(rf) == "none");
    });
}
