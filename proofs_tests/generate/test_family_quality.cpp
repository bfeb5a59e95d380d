// FHR tests — the generator's quality and degenerate families (beyond the paper; the
// construction is paper_notes/generator.md, "The quality family" and "The degenerate family"):
// every recipe passes GEN-8 (the shared checks, embedded), quality meshes have their needles, caps
// and slivers exactly as GEN-10 says, degenerate meshes their exact coincidences as GEN-13 says;
// golden hashes (GEN-15), the knobs' errors and the `fhr generate` round trip (GEN-7).
#include <catch2/catch.hpp>
#include <rapidcheck/catch.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <fhr/core/build.hpp>
#include <fhr/core/errors.hpp>
#include <fhr/core/detail/predicates.hpp>
#include <fhr/core/topology.hpp>
#include <fhr/generate/embedding.hpp>
#include <fhr/generate/random_mesh.hpp>
#include <fhr/io/read.hpp>
#include <fhr/testing/rapidcheck.hpp>
#include "generate/generated_checks.hpp"
#include "support/test_support.hpp"

using fhr::FaceId;
using fhr::HalfedgeId;
using fhr::TriMesh;
using fhr::Vec3;
using fhr::VertexId;
using fhr::generate::Family;
using fhr::generate::random_mesh;
using fhr::generate::RandomMeshOptions;
using namespace fhr::generate::checks;

namespace {

/// Recipes of one family: genus 0–3, holes 0–3, components 1–2 (totals), faces from the family's
/// minimum up to max_faces, any seed; half of them with the default knobs, half with random ones.
/// Shrinks towards fewer handles, holes and components, fewer faces, seed 0, the default knobs,
/// and among random knobs towards the mildest: quality towards a smaller bad fraction and a larger
/// smallest angle (fewer and less thin insertions), degenerate towards a finer grid.
rc::Gen<RandomMeshOptions> gen_recipe(Family family, std::size_t max_faces) {
    return rc::gen::exec([=] {
        RandomMeshOptions o;
        o.family = family;
        o.genus = *rc::gen::inRange(0, 4);
        o.holes = *rc::gen::inRange(0, 4);
        o.components = *rc::gen::inRange(1, 3);
        if (*rc::gen::inRange(0, 2) == 1) {
            if (family == Family::quality) {
                o.knobs.bad_fraction = *rc::gen::inRange(1, 501) / 1000.0;
                constexpr double powers[] = {1, 1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9};
                const int exponent = *rc::gen::inRange(0, 10), mantissa = *rc::gen::inRange(1, 10);
                o.knobs.smallest_angle_deg = std::min(1.0, mantissa * powers[exponent]);
            } else {
                const int base = 1024 >> *rc::gen::inRange(0, 10);  // 1024, 512, ..., 2
                o.knobs.grid_cells = std::min(1024, base + *rc::gen::inRange(0, base));
            }
        }
        const std::size_t least = fhr::generate::min_faces(o), step = o.holes == 0 ? 2 : 1;
        o.faces = least + step * *rc::gen::inRange<std::size_t>(0, (max_faces - least) / step + 1);
        o.seed = *rc::gen::inRange<std::uint64_t>(0, std::numeric_limits<std::int64_t>::max());
        return o;
    });
}

/// The mesh of a drawn recipe; a counterexample shows its `fhr generate` command.
rc::Gen<fhr::testing::GeneratedMesh> gen_family_mesh(Family family, std::size_t max_faces) {
    return rc::gen::map(gen_recipe(family, max_faces), [](const RandomMeshOptions& o) {
        return fhr::testing::GeneratedMesh{random_mesh(o), o};
    });
}

/// The smallest corner of face f, in degrees, as atan2(|u × v|, u · v): accurate to a relative
/// few 1e−16/angle even for the thinnest corners (acos would lose half the digits).
double smallest_corner_degrees(const TriMesh& m, FaceId f) {
    const auto v = m.face_vertices(f);
    double best = 180;
    for (int i = 0; i < 3; ++i) {
        const Vec3 u = m.position(v[(i + 1) % 3]) - m.position(v[i]), w = m.position(v[(i + 2) % 3]) - m.position(v[i]);
        best = std::min(best, std::atan2(u.cross(w).norm(), u.dot(w)) * 180 / std::numbers::pi);
    }
    return best;
}

/// The face's normal has exactly two zero coordinates: it lies in an axis-aligned plane.
bool axis_aligned(const TriMesh& m, FaceId f) {
    const auto v = m.face_vertices(f);
    const Vec3 n = (m.position(v[1]) - m.position(v[0])).cross(m.position(v[2]) - m.position(v[0]));
    return (n.array() == 0).count() == 2;
}

/// GEN-10 for one mesh (degrees, as the knob).
void check_quality(const RandomMeshOptions& o, const TriMesh& m) {
    const double theta = o.knobs.smallest_angle_deg;
    double smallest = 180;
    std::size_t below_one_degree = 0;
    for (FaceId f : m.faces()) {
        const double a = smallest_corner_degrees(m, f);
        smallest = std::min(smallest, a);
        below_one_degree += a < 1;
        RC_ASSERT(axis_aligned(m, f));  // every insertion lies exactly in a facet of the block
    }
    RC_LOG() << "smallest corner " << smallest << "°, θ = " << theta << "°\n";
    RC_ASSERT(smallest <= theta);
    RC_ASSERT(smallest >= 0.875 * theta * (1 - 1e-9));
    RC_ASSERT(below_one_degree ==
              static_cast<std::size_t>(std::ceil(o.knobs.bad_fraction * static_cast<double>(o.faces))));
}

/// The block of the same recipe (the family's starting point).
TriMesh block_of(const RandomMeshOptions& o) {
    RandomMeshOptions block = o;
    block.family = Family::block;
    return random_mesh(block);
}

/// The largest power of two not above min(1/2, ℓ/G): ℓ the block's mean edge length (its edges
/// in order), G the grid_cells knob.
double first_grid_spacing(const RandomMeshOptions& o, const TriMesh& block) {
    double sum = 0;
    for (fhr::EdgeId e : block.edges()) {
        const HalfedgeId h = TriMesh::halfedge(e, 0);
        sum += (block.position(block.to(h)) - block.position(block.from(h))).norm();
    }
    const double target = sum / static_cast<double>(block.n_edges()) / o.knobs.grid_cells;
    double h = 0.5;
    while (h > target) h *= 0.5;
    return h;
}

/// A vertex w of m lies exactly on the line of an edge ab of a face it is not a vertex of, w a
/// neighbour of a or b (where a coarse grid makes it happen); with axis_parallel, only for ab
/// parallel to an axis (w then has the same two coordinates as a and b).
bool has_vertex_on_an_edge_line(const TriMesh& m, bool axis_parallel = false) {
    const auto same = [&](VertexId a, VertexId b) { return (m.position(a).array() == m.position(b).array()).count(); };
    for (FaceId f : m.faces()) {
        const auto t = m.face_vertices(f);
        for (int i = 0; i < 3; ++i) {
            const VertexId a = t[i], b = t[(i + 1) % 3];
            if (axis_parallel && same(a, b) != 2) continue;
            bool found = false;
            for (VertexId end : {a, b})
                m.for_each_outgoing(end, [&](HalfedgeId h) {
                    const VertexId w = m.to(h);
                    if (w != t[0] && w != t[1] && w != t[2] &&
                        fhr::collinear(m.position(a), m.position(b), m.position(w)))
                        found = true;
                });
            if (found) return true;
        }
    }
    return false;
}

/// GEN-13 for one mesh.
void check_degenerate(const RandomMeshOptions& o, const TriMesh& m) {
    const TriMesh block = block_of(o);
    // Every coordinate an integer multiple of the grid spacing h = first spacing / 2^j, j <= 3.
    const double h = first_grid_spacing(o, block);
    int halvings = 0;
    const auto on_grid = [&](double spacing) {
        for (VertexId v : m.vertices())
            for (int k = 0; k < 3; ++k)
                if (std::fmod(m.position(v)[k], spacing) != 0) return false;
        return true;
    };
    while (halvings <= 3 && !on_grid(std::ldexp(h, -halvings))) ++halvings;
    RC_LOG() << "grid spacing " << h << " / 2^" << halvings << "\n";
    RC_ASSERT(halvings <= 3);
    // No zero area, exactly.
    for (FaceId f : m.faces()) {
        const auto v = m.face_vertices(f);
        RC_ASSERT(!fhr::collinear(m.position(v[0]), m.position(v[1]), m.position(v[2])));
    }
    // At least one pair of adjacent faces exactly coplanar.
    bool coplanar = false;
    for (fhr::EdgeId e : m.edges()) {
        if (m.is_boundary(e)) continue;
        const HalfedgeId h0 = TriMesh::halfedge(e, 0), h1 = TriMesh::halfedge(e, 1);
        coplanar = coplanar || fhr::orient3d(m.position(m.from(h0)), m.position(m.to(h0)), m.position(m.to(m.next(h0))),
                                             m.position(m.to(m.next(h1)))) == 0;
    }
    RC_ASSERT(coplanar);
    // A vertex exactly on the line of another face's edge, whenever the block has one on a line
    // parallel to an axis.
    if (has_vertex_on_an_edge_line(block, true)) RC_ASSERT(has_vertex_on_an_edge_line(m));
}

/// The words of generate_command(o, out) without the leading `fhr`, run; the file read back.
TriMesh generated_by_cli(const RandomMeshOptions& o, const std::string& out) {
    std::vector<std::string> args;
    std::istringstream words(fhr::generate::generate_command(o, out));
    for (std::string w; words >> w;) args.push_back(w);
    args.erase(args.begin());
    const auto run = fhr::test::run_fhr(args);
    INFO(run.err);
    REQUIRE(run.exit_code == 0);
    fhr::BuildLog log;
    return fhr::build_trimesh(fhr::io::read_soup(out), {.require_closed = false, .require_connected = false}, log);
}

void refused(const RandomMeshOptions& o, const std::string& part) {
    try {
        random_mesh(o);
        FAIL("accepted " << fhr::generate::generate_command(o));
    } catch (const fhr::InvalidInput& e) {
        CHECK(e.file().empty());
        CHECK(e.line() == 0u);
        CHECK_THAT(e.what(), Catch::Matchers::Contains(part));
    }
}

}  // namespace

// --- quality -------------------------------------------------------------------------------------

TEST_CASE("quality: every recipe is a valid embedded mesh with its thin faces (GEN-8, GEN-10)", "[property]") {
    rc::prop("GEN-8, GEN-10", [] {
        const fhr::testing::GeneratedMesh m = *gen_family_mesh(Family::quality, 2500);
        check_family_mesh(m.options, m);
        check_quality(m.options, m);
    });
}

TEST_CASE("quality: the default knobs reach 1e-3° and below in every mesh, large meshes too", "[unit]") {
    for (const RandomMeshOptions& o : {RandomMeshOptions{3, 60'000, 5, 0.0, 2, 2, Family::quality},
                                       RandomMeshOptions{0, 18, 1, 0.0, 0, 1, Family::quality}}) {
        INFO(fhr::generate::generate_command(o));
        const TriMesh m = random_mesh(o);
        double smallest = 180;
        for (FaceId f : m.faces()) smallest = std::min(smallest, smallest_corner_degrees(m, f));
        CHECK(smallest <= 1e-3);
        CHECK(smallest <= o.knobs.smallest_angle_deg);
        CHECK(!fhr::generate::find_self_intersection(m));
    }
}

TEST_CASE("quality: the least face count, and the knobs' ranges", "[unit]") {
    using fhr::generate::min_faces;
    RandomMeshOptions o{0, 18, 1, 0.0, 0, 1, Family::quality};
    // ⌈(12 + 3)/(1 − 1.2 · 0.1)⌉ = 18; with bad_fraction 0.5: (12 + 3)/0.4 = 37.5 → 38.
    CHECK(min_faces(o) == 18);
    CHECK(random_mesh(o).n_faces() == 18);
    o.faces = 16;
    refused(o, "genus 0 in the quality family needs at least 18 faces (got 16)");
    o.knobs.bad_fraction = 0.5;
    CHECK(min_faces(o) == 38);
    o.faces = 39;  // odd faces need a hole
    o.holes = 1;
    CHECK(random_mesh(o).n_faces() == 39);
    o = {0, 1000, 1, 0.0, 0, 1, Family::quality};
    for (double bad : {0.0, -0.1, 0.6, std::numeric_limits<double>::quiet_NaN()}) {
        o.knobs.bad_fraction = bad;
        refused(o, "--bad-fraction must be in (0, 0.5] (got ");
    }
    o.knobs.bad_fraction = 0.6;
    refused(o, "--bad-fraction must be in (0, 0.5] (got 0.6)");
    o.knobs = {};
    for (double angle : {1e-10, 0.0, 1.5, std::numeric_limits<double>::infinity()}) {
        o.knobs.smallest_angle_deg = angle;
        refused(o, "--smallest-angle must be in [1e-09, 1] (got ");
    }
    o.knobs.smallest_angle_deg = 2;
    refused(o, "--smallest-angle must be in [1e-09, 1] (got 2)");
    // The ends of the ranges are accepted.
    o.knobs = {.bad_fraction = 0.5, .smallest_angle_deg = 1e-9};
    CHECK(random_mesh(o).n_faces() == 1000);
    o.knobs = {.bad_fraction = 0.001, .smallest_angle_deg = 1};
    CHECK(random_mesh(o).n_faces() == 1000);
}

// --- degenerate ------------------------------------------------------------------------------------

TEST_CASE("degenerate: every recipe is a valid embedded mesh on its grid (GEN-8, GEN-13)", "[property]") {
    rc::prop("GEN-8, GEN-13", [] {
        const fhr::testing::GeneratedMesh m = *gen_family_mesh(Family::degenerate, 2500);
        check_family_mesh(m.options, m);
        check_degenerate(m.options, m);
    });
}

TEST_CASE("degenerate: tilted faces, and exact coincidences off the axis planes", "[unit]") {
    // Measured, not promised by GEN-13 (paper_notes/generator.md has the statistics): on this
    // recipe about a fifth of the faces leave the block's axis-aligned planes, and some of them
    // are exactly coplanar with a neighbour.
    const RandomMeshOptions o{1, 5000, 3, 0.0, 0, 1, Family::degenerate};
    const TriMesh m = random_mesh(o);
    std::size_t tilted = 0, tilted_coplanar = 0;
    for (FaceId f : m.faces()) tilted += !axis_aligned(m, f);
    for (fhr::EdgeId e : m.edges()) {
        const HalfedgeId h0 = TriMesh::halfedge(e, 0), h1 = TriMesh::halfedge(e, 1);
        if (!axis_aligned(m, m.face(h0))) {
            tilted_coplanar += fhr::orient3d(m.position(m.from(h0)), m.position(m.to(h0)), m.position(m.to(m.next(h0))),
                                             m.position(m.to(m.next(h1)))) == 0;
        }
    }
    CHECK(tilted > m.n_faces() / 10);
    CHECK(tilted_coplanar > 10);
}

TEST_CASE("degenerate: the least face count is the block's, and the knob's range", "[unit]") {
    RandomMeshOptions o{2, 1000, 1, 0.0, 0, 1, Family::degenerate};
    CHECK(fhr::generate::min_faces(o) == fhr::generate::min_faces(2));
    for (int cells : {1, 0, -8, 1025}) {
        o.knobs.grid_cells = cells;
        refused(o, "--grid-cells must be in [2, 1024] (got " + std::to_string(cells) + ")");
    }
    for (int cells : {2, 3, 1024}) {
        o.knobs.grid_cells = cells;
        CHECK(random_mesh(o).n_faces() == 1000);
    }
}

// --- both ----------------------------------------------------------------------------------------

TEST_CASE("GEN-15: quality and degenerate meshes do not depend on the compiler", "[unit]") {
    // FNV-1a over the position bits and the triangles, recorded from this implementation and
    // reproduced by GCC 12 (-O0, -O3 -march=native) and Clang 14 (-O0, -O2, -O3 -march=native),
    // all with -ffp-contract=off. Every step uses the standard mt19937_64, our own uniform
    // mappings and correctly rounded +, −, ×, ÷, √ in a fixed order (the quality family's tangent
    // is its own Taylor polynomial), so every compiler must reproduce them. A deliberate change of
    // a construction changes them: update them then, and say so in paper_notes/generator.md.
    RandomMeshOptions quality{2, 2001, 7, 0.0, 3, 2, Family::quality};
    quality.knobs.smallest_angle_deg = 1e-9;
    CHECK(mesh_hash(random_mesh(quality)) == 0xa1da702817461b7dull);
    RandomMeshOptions degenerate{2, 2001, 7, 0.0, 3, 2, Family::degenerate};
    degenerate.knobs.grid_cells = 3;
    CHECK(mesh_hash(random_mesh(degenerate)) == 0x3326dd44e9fcc624ull);
}

TEST_CASE("GEN-7: the file of generate_command's command holds exactly the family's mesh", "[unit]") {
    RandomMeshOptions quality{1, 1201, 4, 0.0, 1, 2, Family::quality};
    quality.knobs = {.bad_fraction = 0.37, .smallest_angle_deg = 3e-7};
    RandomMeshOptions degenerate{3, 900, 5, 0.0, 2, 1, Family::degenerate};
    degenerate.knobs.grid_cells = 5;
    for (const RandomMeshOptions& o : {quality, degenerate, RandomMeshOptions{0, 300, 6, 0.0, 0, 1, Family::quality},
                                       RandomMeshOptions{0, 300, 6, 0.0, 0, 1, Family::degenerate}}) {
        DYNAMIC_SECTION(fhr::generate::generate_command(o)) {
            const TriMesh back = generated_by_cli(o, fhr::test::temp_path("family.off"));
            const TriMesh expected = random_mesh(o);
            CHECK(back.positions() == expected.positions());
            CHECK(back.triangles() == expected.triangles());
        }
    }
}
