// FHR tests — the atlas oracle (src/fhr/exchange/atlas.hpp, spec/atlas.md ATLAS-1..8): a
// hand-made atlas for every check (each would pass if its check were removed), the readers' texture
// coordinates (OBJ vt and usemtl, PLY per-vertex u v and per-face texcoord), and properties over
// random meshes of several genera: an atlas made from a valid parameterization file (each patch's
// β laid out in its own triangle of UV) is valid, and each planted fault is named.
#include <catch2/catch.hpp>
#include <rapidcheck/catch.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <fhr/core/errors.hpp>
#include <fhr/core/topology.hpp>
#include <fhr/exchange/atlas.hpp>
#include <fhr/generate/random_mesh.hpp>
#include <fhr/testing/rapidcheck.hpp>
#include "synthetic.hpp"

using fhr::Triangle;
using fhr::TriMesh;
using fhr::Vec3;
using fhr::exchange::Atlas;
using fhr::exchange::AtlasOptions;
using fhr::exchange::AtlasReport;
using fhr::exchange::CheckResult;
using fhr::exchange::CheckStatus;
using fhr::exchange::UV;
using fhr::exchange::verify_atlas;

namespace {

/// An atlas with one UV record per corner: face f's corners have uv[3f], uv[3f+1], uv[3f+2].
Atlas make(std::vector<Vec3> points, std::vector<Triangle> faces, const std::vector<UV>& uv,
           std::vector<std::uint32_t> texture = {}) {
    Atlas a;
    a.source = "test";
    a.points = std::move(points);
    a.faces = std::move(faces);
    a.uv = uv;
    for (std::uint32_t f = 0; f < a.faces.size(); ++f) a.face_uv.push_back({3 * f, 3 * f + 1, 3 * f + 2});
    a.face_texture = texture.empty() ? std::vector<std::uint32_t>(a.faces.size(), 0) : std::move(texture);
    return a;
}

const CheckResult& check(const AtlasReport& r, const std::string& id) {
    for (const CheckResult& c : r.checks)
        if (c.id == id) return c;
    throw std::logic_error("no check " + id);
}

std::string first(const AtlasReport& r) { return r.first_failure() ? r.first_failure()->id : "none"; }

/// The unit square (0,0,0) (1,0,0) (1,1,0) (0,1,0) as faces (0,1,2), (0,2,3).
const std::vector<Vec3> square{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
const std::vector<Triangle> square_faces{{0, 1, 2}, {0, 2, 3}};

}  // namespace

TEST_CASE("ATLAS-2..7: the identity atlas of a square is valid: one chart, nothing folded", "[exchange][atlas]") {
    const Atlas a = make(square, square_faces, {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}});
    const AtlasReport r = verify_atlas(a, nullptr);
    CHECK(first(r) == "none");
    CHECK(r.valid());
    CHECK(r.charts == 1);
    CHECK(r.mirrored_charts == 0);
    CHECK(r.folded.empty());
    CHECK(r.overlapping.empty());
    CHECK(r.contacts.empty());
    CHECK(*r.seam_length == 0);
    CHECK(*r.packing_unit_square == Approx(1).epsilon(1e-15));
    CHECK(*r.packing_bounding_square == Approx(1).epsilon(1e-15));
    CHECK(*r.distortion.l2_stretch == Approx(1).epsilon(1e-15));
    CHECK(r.checks.size() == 7);
}

TEST_CASE("ATLAS-4, ATLAS-6: a face folded over its neighbour is a fold and an overlapping pair", "[exchange][atlas]") {
    // Face 1's far corner (0,1) moved to (0.9, 0.2): on face 0's side of the shared diagonal.
    const Atlas a = make(square, square_faces, {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0.9, 0.2}});
    const AtlasReport r = verify_atlas(a, nullptr);
    CHECK(first(r) == "ATLAS-4");
    CHECK(r.folded == std::vector<std::uint32_t>{1});  // the smaller face has the other sign
    CHECK(check(r, "ATLAS-4").face == 1);
    CHECK(check(r, "ATLAS-4").chart == 0);
    REQUIRE(check(r, "ATLAS-4").uv.has_value());
    CHECK(r.overlapping.size() == 1);
    CHECK(check(r, "ATLAS-6").status == CheckStatus::fail);
}

TEST_CASE("ATLAS-4: a chart wholly clockwise is mirrored: valid, unless --no-mirror", "[exchange][atlas]") {
    const Atlas a = make(square, square_faces, {{0, 0}, {-1, 0}, {-1, 1}, {0, 0}, {-1, 1}, {0, 1}});
    const AtlasReport r = verify_atlas(a, nullptr);
    CHECK(r.valid());
    CHECK(r.mirrored_charts == 1);
    CHECK(r.folded.empty());
    const AtlasReport strict = verify_atlas(a, nullptr, AtlasOptions{.no_mirror = true});
    CHECK(first(strict) == "ATLAS-4");
    CHECK(check(strict, "ATLAS-4").failures == 1);
}

TEST_CASE("ATLAS-6: a chart that winds past itself overlaps without a fold", "[exchange][atlas]") {
    // An open fan of six faces around vertex 0, each 80° wide in UV: 480° in all.
    std::vector<Vec3> points{{0, 0, 0}};
    std::vector<Triangle> faces;
    std::vector<UV> uv;
    const double pi = std::acos(-1.0);
    for (int k = 0; k <= 6; ++k)
        points.emplace_back(std::cos(k * pi / 3.5), std::sin(k * pi / 3.5), 0.1 * k);  // a helical rim
    for (std::uint32_t k = 0; k < 6; ++k) {
        faces.push_back({0, k + 1, k + 2});
        const double a0 = k * 80.0 * pi / 180, a1 = (k + 1) * 80.0 * pi / 180;
        uv.push_back({0, 0});
        uv.push_back({std::cos(a0), std::sin(a0)});
        uv.push_back({std::cos(a1), std::sin(a1)});
    }
    const AtlasReport r = verify_atlas(make(points, faces, uv), nullptr);
    CHECK(r.charts == 1);
    CHECK(r.folded.empty());
    CHECK(first(r) == "ATLAS-6");
    // Faces k and k+4 and k+5 overlap for (0, 4), (0, 5), (1, 5): 400°..480° covers 40°..120°.
    CHECK(r.overlapping == std::vector<std::pair<std::uint32_t, std::uint32_t>>{{0, 4}, {0, 5}, {1, 5}});
}

TEST_CASE("ATLAS-6, ATLAS-7: two charts overlapping, touching at a corner or along an edge, in one texture or two",
          "[exchange][atlas]") {
    // Two separate triangles in 3D.
    const std::vector<Vec3> points{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 5}, {1, 0, 5}, {0, 1, 5}};
    const std::vector<Triangle> faces{{0, 1, 2}, {3, 4, 5}};
    SECTION("overlapping in one texture") {
        const AtlasReport r =
            verify_atlas(make(points, faces, {{0, 0}, {1, 0}, {0, 1}, {0.2, 0.2}, {1.2, 0.2}, {0.2, 1.2}}), nullptr);
        CHECK(first(r) == "ATLAS-6");
        CHECK(r.overlapping.size() == 1);
        CHECK(r.charts == 2);
        CHECK(check(r, "ATLAS-6").chart == 0);
        // The union counts the overlap once: ½ + ½ − 0.18 (a triangle of legs 0.6) = 0.82, of which
        // two corners of legs 0.2 (0.02 each) lie outside [0, 1]²; the bounding square is 1.2².
        CHECK(*r.packing_unit_square == Approx(0.78).epsilon(1e-12));
        CHECK(*r.packing_bounding_square == Approx(0.82 / 1.44).epsilon(1e-12));
    }
    SECTION("overlapping in two textures: legitimate") {
        const AtlasReport r = verify_atlas(
            make(points, faces, {{0, 0}, {1, 0}, {0, 1}, {0.2, 0.2}, {1.2, 0.2}, {0.2, 1.2}}, {0, 1}), nullptr);
        CHECK(r.valid());
        CHECK(r.overlapping.empty());
    }
    SECTION("touching at a corner: a contact, valid unless --strict") {
        const Atlas a = make(points, faces, {{0, 0}, {1, 0}, {0, 1}, {1, 0}, {2, 0}, {1, 1}});
        const AtlasReport r = verify_atlas(a, nullptr);
        CHECK(r.valid());
        CHECK(r.contacts == std::vector<std::pair<std::uint32_t, std::uint32_t>>{{0, 1}});
        CHECK(check(r, "ATLAS-7").failures == 1);
        CHECK(first(verify_atlas(a, nullptr, AtlasOptions{.strict = true})) == "ATLAS-7");
    }
    SECTION("along an edge") {
        const AtlasReport r =
            verify_atlas(make(points, faces, {{0, 0}, {1, 0}, {0, 1}, {1, 0}, {1, 1}, {0, 1}}), nullptr);
        CHECK(r.contacts.size() == 1);
        CHECK(r.overlapping.empty());
    }
    SECTION("apart by a hair") {
        const AtlasReport r =
            verify_atlas(make(points, faces, {{0, 0}, {1, 0}, {0, 1}, {1 + 1e-12, 0}, {2, 0}, {1, 1}}), nullptr);
        CHECK(r.contacts.empty());
        CHECK(r.overlapping.empty());
    }
}

TEST_CASE("ATLAS-7: faces sharing a corner meet there legitimately; a side along the other's is a contact",
          "[exchange][atlas]") {
    // The square's two faces joined at vertex 0 only (vertex 2 has two UV points): two charts.
    const AtlasReport r =
        verify_atlas(make(square, square_faces, {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {-1, -1}, {0, -1}}), nullptr);
    CHECK(r.valid());
    CHECK(r.charts == 2);
    CHECK(r.contacts.empty());
    // Face 1 turned so that its side from the shared corner runs along face 0's side: a contact.
    const AtlasReport along =
        verify_atlas(make(square, square_faces, {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {0.5, -1}, {0.5, 0}}), nullptr);
    CHECK(along.contacts == std::vector<std::pair<std::uint32_t, std::uint32_t>>{{0, 1}});
    CHECK(along.overlapping.empty());
}

TEST_CASE("ATLAS-3: a degenerate UV triangle fails, and the checks that need signs are skipped", "[exchange][atlas]") {
    const AtlasReport r =
        verify_atlas(make(square, square_faces, {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {2, 2}}), nullptr);
    CHECK(first(r) == "ATLAS-3");
    CHECK(check(r, "ATLAS-3").face == 1);
    for (const char* id : {"ATLAS-4", "ATLAS-5", "ATLAS-6", "ATLAS-7"})
        CHECK(check(r, id).status == CheckStatus::skipped);
    CHECK(r.distortion.degenerate == 1);
}

TEST_CASE("ATLAS-5: an edge torn in UV by rounding, and a T-vertex, are cracks", "[exchange][atlas]") {
    SECTION("torn edge: one end shared, the other 1e-9 apart") {
        const AtlasReport r =
            verify_atlas(make(square, square_faces, {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1 + 1e-9}, {0, 1}}), nullptr);
        CHECK(first(r) == "ATLAS-5");
        CHECK(check(r, "ATLAS-5").failures == 1);
        CHECK(r.charts == 2);
    }
    SECTION("a seam whose ends are far apart is no crack") {
        const AtlasReport r =
            verify_atlas(make(square, square_faces, {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1.5}, {0, 1}}), nullptr);
        CHECK(check(r, "ATLAS-5").status == CheckStatus::pass);
    }
    SECTION("T-vertices") {
        // A triangle above y = 0 and two below whose vertices p, m, q lie inside its edge a-b.
        const std::vector<Vec3> points{{0, 0, 0}, {2, 0, 0},   {1, 1, 0}, {0.5, 0, 0},
                                       {1, 0, 0}, {1.5, 0, 0}, {1, -1, 0}};
        const std::vector<Triangle> faces{{0, 1, 2}, {3, 6, 4}, {4, 6, 5}};
        const AtlasReport r = verify_atlas(
            make(points, faces,
                 {{0, 0}, {2, 0}, {1, 1}, {0.5, -0.1}, {1, -1}, {1, -0.1}, {1, -0.1}, {1, -1}, {1.5, -0.1}}),
            nullptr);
        CHECK(first(r) == "ATLAS-5");
        CHECK(check(r, "ATLAS-5").failures == 3);
        CHECK(check(r, "ATLAS-5").vertex == 3);
    }
}

TEST_CASE("ATLAS-2: the welded surface must be a consistently wound manifold", "[exchange][atlas]") {
    // Face 1 wound the same way as face 0 along their shared diagonal.
    const AtlasReport r =
        verify_atlas(make(square, {{0, 1, 2}, {0, 3, 2}}, {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {0, 1}, {1, 1}}), nullptr);
    CHECK(first(r) == "ATLAS-2");
    CHECK(check(r, "ATLAS-4").status == CheckStatus::skipped);
    // Points at one position are one vertex: a seam of duplicated points welds into one surface.
    std::vector<Vec3> duplicated = square;
    duplicated.push_back(square[0]);
    duplicated.push_back(square[2]);
    const AtlasReport welded = verify_atlas(
        make(duplicated, {{0, 1, 2}, {4, 5, 3}}, {{0, 0}, {1, 0}, {1, 1}, {5, 5}, {6, 6}, {5, 6}}), nullptr);
    CHECK(welded.valid());
    CHECK(welded.vertices == 4);
    CHECK(welded.charts == 2);
    CHECK(*welded.seam_length == Approx(std::sqrt(2.0)).epsilon(1e-15));  // the diagonal over √1
}

TEST_CASE("ATLAS-2: vertices that coincide inside the surface of the file's indices stay apart", "[exchange][atlas]") {
    // Two closed tetrahedra touching at one point, each with its own vertex there (records 0 and 4):
    // welded, they would make a non-manifold vertex; they are two vertices, the surface two components.
    const std::vector<Vec3> points{{0, 0, 0}, {1, 0, 0},  {0, 1, 0},  {0, 0, 1},
                                   {0, 0, 0}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
    std::vector<Triangle> faces;
    for (std::uint32_t base : {0u, 4u}) {
        const std::vector<Triangle> tetra{{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
        for (const Triangle& t : tetra) faces.push_back({base + t[0], base + t[1], base + t[2]});
    }
    std::vector<UV> uv;  // each face its own triangle in UV, side by side, counter-clockwise
    for (std::size_t f = 0; f < faces.size(); ++f) {
        uv.push_back({2.0 * f, 0});
        uv.push_back({2.0 * f + 1, 0});
        uv.push_back({2.0 * f, 1});
    }
    const AtlasReport r = verify_atlas(make(points, faces, uv), nullptr);
    INFO((r.first_failure() ? r.first_failure()->first_failure : ""));
    CHECK(r.vertices == 8);
    CHECK(check(r, "ATLAS-2").status == CheckStatus::pass);
    CHECK(r.charts == 8);
}

TEST_CASE("ATLAS-1: the readers give texture coordinates; a missing one or a polygon is refused",
          "[exchange][atlas][io]") {
    SECTION("OBJ with vt, negative references and two usemtl groups") {
        const std::string obj =
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
            "usemtl a\nf 1/1 2/2 3/3\nusemtl b\nf 1/-4 3/-2 4/-1\n";
        const Atlas a = fhr::exchange::parse_atlas(obj, "t.obj");
        CHECK(a.faces.size() == 2);
        CHECK(a.face_texture == std::vector<std::uint32_t>{1, 2});
        CHECK(a.uv[a.face_uv[1][1]] == UV{1, 1});
        // Only 0 and 1: as if one significant digit were printed (0.5), and float32 (2⁻²⁴ · 1).
        CHECK(a.rounding == 0.5 + 0x1p-24);
    }
    SECTION("rounding from the printed digits") {
        const std::string face = "vt 0 0\nf 1/1 2/1 3/1\n";
        // Each writer below prints at most 8 significant digits, so it may have held float32 values:
        // half a float32 ulp of the largest coordinate (2⁻²⁴ · 12, or · 1500) is added.
        // A fixed-point writer with 6 decimals: half a unit in the 6th.
        CHECK(fhr::exchange::parse_atlas("v 0.123457 0.000000 12.000000\nv 1.000000 0.500000 0.000000\n"
                                         "v 0.000000 1.000000 0.000000\n" +
                                             face,
                                         "t.obj")
                  .rounding == Approx(5e-7 + 12 * 0x1p-24).epsilon(1e-12));
        // %g: trailing zeros dropped, at most 6 significant digits: half a unit in the 6th of the largest, 12.
        CHECK(fhr::exchange::parse_atlas("v 0.123457 0 12\nv 1 0.5 0\nv 0 1 0\n" + face, "t.obj").rounding ==
              Approx(5e-5 + 12 * 0x1p-24).epsilon(1e-12));
        // An exponent: 2 significant digits (1.5e3), the largest 1500: half a unit in the hundreds.
        CHECK(fhr::exchange::parse_atlas("v 1.5e3 0 0\nv 0 1.2 0\nv 0 1 0\n" + face, "t.obj").rounding ==
              Approx(50 + 1500 * 0x1p-24).epsilon(1e-12));
        // Shortest round-trip doubles (17 significant digits): no float32 term.
        CHECK(fhr::exchange::parse_atlas("v 0.12345678901234568 0 12\nv 1 0.5 0\nv 0 1 0\n" + face, "t.obj").rounding ==
              Approx(0.5e-16 * 10).epsilon(1e-9));
    }
    SECTION("a corner without vt") {
        CHECK_THROWS_WITH(fhr::exchange::parse_atlas("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3\n", "t.obj"),
                          Catch::Contains("t.obj:5") && Catch::Contains("face 0: corner 2 has no texture coordinates"));
    }
    SECTION("a vt out of range, a NaN") {
        CHECK_THROWS_WITH(fhr::exchange::parse_atlas("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/2\n", "t.obj"),
                          Catch::Contains("texture coordinate index 2 out of range"));
        CHECK_THROWS_WITH(fhr::exchange::parse_atlas("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt nan 0\nf 1/1 2/1 3/1\n", "t.obj"),
                          Catch::Contains("t.obj:4"));
    }
    SECTION("a quadrilateral") {
        CHECK_THROWS_WITH(
            fhr::exchange::parse_atlas("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1 4/1\n", "t.obj"),
            Catch::Contains("has 4 corners"));
    }
    SECTION("PLY with per-vertex u v, duplicated at a seam") {
        const std::string ply =
            "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\nproperty float z\n"
            "property float u\nproperty float v\nelement face 2\nproperty list uchar int vertex_indices\n"
            "end_header\n0 0 0 0 0\n1 0 0 1 0\n1 1 0 1 1\n0 0 0 3 3\n1 1 0 4 4\n0 1 0 3 4\n3 0 1 2\n3 3 4 5\n";
        const Atlas a = fhr::exchange::parse_atlas(ply, "t.ply");
        const AtlasReport r = verify_atlas(a, nullptr);
        CHECK(r.valid());
        CHECK(r.vertices == 4);
        CHECK(r.charts == 2);
    }
    SECTION("PLY with per-face texcoord and texnumber; a wrong length refused") {
        const std::string head =
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
            "element face 1\nproperty list uchar int vertex_indices\nproperty list uchar float texcoord\n"
            "property int texnumber\nend_header\n0 0 0\n1 0 0\n0 1 0\n";
        const Atlas a = fhr::exchange::parse_atlas(head + "3 0 1 2 6 0 0 1 0 0 1 4\n", "t.ply");
        CHECK(a.face_texture == std::vector<std::uint32_t>{4});
        CHECK(a.uv[a.face_uv[0][2]] == UV{0, 1});
        CHECK_THROWS_WITH(fhr::exchange::parse_atlas(head + "3 0 1 2 4 0 0 1 0 4\n", "t.ply"),
                          Catch::Contains("texcoord has 4 values, expected 6"));
    }
    SECTION("PLY without texture coordinates") {
        const std::string ply =
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
            "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
        CHECK_THROWS_WITH(fhr::exchange::parse_atlas(ply, "t.ply"), Catch::Contains("has no texture coordinates"));
    }
}

namespace {

/// An atlas from a valid parameterization file: each patch's faces laid out by their β in an
/// equilateral triangle of its own, the triangles side by side in a row (one chart per patch).
Atlas atlas_of(const fhr::exchange::ParamFile& file) {
    Atlas a;
    a.source = "param";
    a.points = file.surface_vertices;
    const double h = std::sqrt(3.0) / 2;
    for (const auto& face : file.surface_faces) {
        Triangle uv;
        for (int c = 0; c < 3; ++c) {
            const auto& b = face.beta[c];
            const double x0 = 1.5 * face.patch;
            uv[c] = static_cast<std::uint32_t>(a.uv.size());
            a.uv.push_back({x0 + b[1] * 1.0 + b[2] * 0.5, b[2] * h});
        }
        a.faces.push_back(face.v);
        a.face_uv.push_back(uv);
        a.face_texture.push_back(0);
    }
    return a;
}

}  // namespace

TEST_CASE("ATLAS-2..8: atlases of valid parameterizations are valid, and match their mesh; faults are named",
          "[exchange][atlas][property]") {
    rc::prop("random meshes of genus 0-3, subdivided", [] {
        fhr::generate::RandomMeshOptions o;
        o.genus = *rc::gen::inRange(0, 4);
        o.faces = static_cast<std::size_t>(*rc::gen::inRange(40, 120)) * 2 + 24 * static_cast<std::size_t>(o.genus);
        o.seed = *rc::gen::inRange<std::uint64_t>(0, 1000000);
        o.noise = 0.2;
        const TriMesh domain = fhr::generate::random_closed_mesh(o);
        const int k = *rc::gen::inRange(3, 5);  // patches with interior vertices
        const fhr::exchange::ParamFile file = fhr::test::subdivided_param(domain, k);
        Atlas a = atlas_of(file);
        const AtlasReport r = verify_atlas(a, &domain);
        RC_ASSERT(first(r) == "none");
        RC_ASSERT(r.charts == domain.n_faces());
        RC_ASSERT(r.contacts.empty());
        RC_ASSERT(r.mirrored_charts == 0);
        // An interior vertex of one patch (all its faces in that patch) moved outside the patch's
        // UV triangle, in every face around it: some face around it turns over.
        std::vector<std::vector<std::uint32_t>> around(a.points.size());
        for (std::uint32_t f = 0; f < a.faces.size(); ++f)
            for (std::uint32_t v : a.faces[f]) around[v].push_back(f);
        const std::uint32_t patch = *rc::gen::inRange<std::uint32_t>(0, static_cast<std::uint32_t>(domain.n_faces()));
        std::uint32_t moved = 0;
        for (std::uint32_t v = 0; v < around.size() && moved == 0; ++v) {
            const bool interior = std::all_of(around[v].begin(), around[v].end(),
                                              [&](std::uint32_t f) { return file.surface_faces[f].patch == patch; });
            if (!interior) continue;
            for (std::uint32_t f : around[v])
                for (int c = 0; c < 3; ++c)
                    if (a.faces[f][c] == v) a.uv[a.face_uv[f][c]] = {1.5 * patch - 0.5, -0.5};
            moved = 1;
        }
        RC_ASSERT(moved == 1);
        const AtlasReport bad = verify_atlas(a, &domain);
        RC_ASSERT(!bad.valid());
        RC_ASSERT(bad.first_failure()->id == "ATLAS-4" || bad.first_failure()->id == "ATLAS-5" ||
                  bad.first_failure()->id == "ATLAS-6");
        RC_ASSERT(!bad.overlapping.empty() || !bad.folded.empty());
    });
}

TEST_CASE("ATLAS-8: a refinement of the input with rounded points is accepted; another surface is refused",
          "[exchange][atlas]") {
    fhr::generate::RandomMeshOptions o;
    o.genus = 1;
    o.faces = 200;
    o.seed = 7;
    o.noise = 0.2;
    const TriMesh t = fhr::generate::random_closed_mesh(o);
    const fhr::exchange::ParamFile file = fhr::test::subdivided_param(t, 2);
    Atlas a = atlas_of(file);
    // Coordinates written with 6 decimals, as many writers do: the tolerance follows.
    for (Vec3& p : a.points)
        for (int c = 0; c < 3; ++c) p[c] = std::round(p[c] * 1e6) / 1e6;
    a.rounding = 5e-7;
    const AtlasReport r = verify_atlas(a, &t);
    CHECK(check(r, "ATLAS-8").status == CheckStatus::pass);
    a.rounding = 0;  // the same points claimed exact: off T
    CHECK(check(verify_atlas(a, &t), "ATLAS-8").status == CheckStatus::fail);
    a.rounding = 5e-7;
    a.points[a.faces[0][0]] += Vec3(0.01, 0.01, 0.01);  // one vertex moved off the surface
    const AtlasReport moved = verify_atlas(a, &t);
    CHECK(check(moved, "ATLAS-8").status == CheckStatus::fail);
    CHECK(check(moved, "ATLAS-8").first_failure.find("is not on T") != std::string::npos);
    // Another mesh altogether (genus 2): a different topology.
    o.genus = 2;
    o.faces = 248;
    const TriMesh other = fhr::generate::random_closed_mesh(o);
    CHECK(check(verify_atlas(atlas_of(file), &other), "ATLAS-8").first_failure.find("chi") != std::string::npos);
}
