// FHR tests — the generator's smooth and immersed families (meshes as hard as real ones;
// src/fhr/generate/families/smooth.cpp, immersed.cpp): spec/generator.md GEN-8 for both, GEN-9
// (smooth: curved everywhere), GEN-14 (immersed: meets itself), GEN-15 (a golden hash each), their
// knobs' ranges, GEN-7 through the CLI, and the fallback of the embedded move.
#include <catch2/catch.hpp>
#include <rapidcheck/catch.h>

#include <cstdint>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <fhr/core/build.hpp>
#include <fhr/core/errors.hpp>
#include <fhr/core/detail/predicates.hpp>
#include <fhr/generate/detail/smooth_map.hpp>
#include <fhr/generate/embedding.hpp>
#include <fhr/generate/random_mesh.hpp>
#include <fhr/io/read.hpp>
#include "generate/generated_checks.hpp"
#include "support/test_support.hpp"

using fhr::TriMesh;
using fhr::Vec3;
using fhr::generate::Family;
using fhr::generate::generate_command;
using fhr::generate::min_faces;
using fhr::generate::random_mesh;
using fhr::generate::RandomMeshOptions;
using namespace fhr::generate::checks;

namespace {

/// A recipe of `family`: genus 0–3, holes 0–3, components 1–2 (totals), faces from the family's
/// least count to max_faces, a seed the CLI accepts, and the family's knobs at their defaults or
/// drawn over their ranges (smooth: roundness 0.01–0.45, amplitude 0.01–0.5; immersed: depth
/// 1.1–4). Shrinks toward genus, holes 0, one component, the fewest faces, seed 0, the defaults.
rc::Gen<RandomMeshOptions> gen_recipe(Family family, std::size_t max_faces) {
    return rc::gen::exec([=] {
        RandomMeshOptions o;
        o.family = family;
        o.genus = *rc::gen::inRange(0, 4);
        o.holes = *rc::gen::inRange(0, 4);
        o.components = *rc::gen::inRange(1, 3);
        if (*rc::gen::inRange(0, 2) == 1) {
            o.knobs.roundness = *rc::gen::inRange(1, 46) / 100.0;
            o.knobs.amplitude = *rc::gen::inRange(1, 51) / 100.0;
            o.knobs.depth = *rc::gen::inRange(11, 41) / 10.0;
        }
        const std::size_t least = min_faces(o), step = o.holes == 0 ? 2 : 1;
        o.faces = least + step * *rc::gen::inRange<std::size_t>(0, (max_faces - least) / step + 1);
        o.seed = *rc::gen::inRange<std::uint64_t>(0, std::numeric_limits<std::int64_t>::max());
        return o;
    });
}

/// Interior edges whose two faces are coplanar (exact orient3d of their four vertices).
std::size_t coplanar_neighbours(const TriMesh& m) {
    std::size_t count = 0;
    for (fhr::EdgeId e : m.edges()) {
        if (m.is_boundary(e)) continue;
        const fhr::HalfedgeId h = TriMesh::halfedge(e, 0), o = TriMesh::halfedge(e, 1);
        count += fhr::orient3d(m.position(m.from(h)), m.position(m.to(h)), m.position(m.to(m.next(h))),
                               m.position(m.to(m.next(o)))) == 0;
    }
    return count;
}

/// Some face lies in an axis-aligned plane (all three vertices share one coordinate exactly).
bool has_axis_aligned_face(const TriMesh& m) {
    for (fhr::FaceId f : m.faces()) {
        const auto v = m.face_vertices(f);
        for (int k = 0; k < 3; ++k)
            if (m.position(v[0])[k] == m.position(v[1])[k] && m.position(v[0])[k] == m.position(v[2])[k]) return true;
    }
    return false;
}

/// check_family_mesh outside a property: a failed RapidCheck assertion fails the test case with
/// its message.
void require_family_mesh(const RandomMeshOptions& o, const TriMesh& m) {
    try {
        check_family_mesh(o, m);
    } catch (const rc::detail::CaseResult& failure) {
        FAIL(generate_command(o) << ": " << failure.description);
    }
}

}  // namespace

TEST_CASE(
    "GEN-8, GEN-9: smooth meshes are valid, embedded, outward, the block's triangles, no two adjacent faces "
    "coplanar",
    "[property]") {
    rc::prop("smooth", [] {
        const RandomMeshOptions o = *gen_recipe(Family::smooth, 2500);
        RC_LOG() << "checked: " << generate_command(o) << "\n";
        const TriMesh m = random_mesh(o);
        check_family_mesh(o, m);
        RC_ASSERT(coplanar_neighbours(m) == 0u);
        RandomMeshOptions block = o;
        block.family = Family::block;
        RC_ASSERT(m.triangles() == random_mesh(block).triangles());
    });
}

TEST_CASE("GEN-8, GEN-14: immersed meshes are valid and outward, and two of their faces meet", "[property]") {
    rc::prop("immersed", [] {
        const RandomMeshOptions o = *gen_recipe(Family::immersed, 2500);
        RC_LOG() << "checked: " << generate_command(o) << "\n";
        check_family_mesh(o, random_mesh(o));
    });
}

TEST_CASE("GEN-8, GEN-14: the smallest meshes of both families, every genus, holes and components in range", "[unit]") {
    for (Family family : {Family::smooth, Family::immersed})
        for (int g = 0; g <= 3; ++g)
            for (int b = 0; b <= 3; ++b)
                for (int c = 1; c <= 2; ++c) {
                    RandomMeshOptions o;
                    o.family = family;
                    o.genus = g;
                    o.holes = b;
                    o.components = c;
                    o.faces = min_faces(o);
                    o.seed = static_cast<std::uint64_t>(g * 16 + b * 4 + c);
                    require_family_mesh(o, random_mesh(o));
                }
}

TEST_CASE("GEN-9: with amplitude 0 the smooth family is the block rounded: flat far from its creases", "[unit]") {
    // The rounding alone keeps every point farther than the kernel's radius from a crease where
    // it was (f = 1/2 there exactly), so the middle of the big facets stays flat: the
    // deformation is what GEN-9 needs, and the property tests draw amplitudes >= 0.01.
    RandomMeshOptions o;
    o.family = Family::smooth;
    o.genus = 2;
    o.faces = 4000;
    o.knobs.amplitude = 0;
    const TriMesh m = random_mesh(o);
    CHECK(coplanar_neighbours(m) > 0u);
    CHECK_FALSE(fhr::generate::find_self_intersection(m).has_value());
    o.knobs.amplitude = 0.01;
    CHECK(coplanar_neighbours(random_mesh(o)) == 0u);
}

TEST_CASE("GEN-14: when the curved finger misses, the immersed family keeps the flat one, which meets", "[unit]") {
    // Found by a scan of 2,000 recipes (2 took this path): on a genus-0 tube the rounded facing
    // wall bends away from a finger near the open rim, the curved mesh is embedded, and step 5
    // falls back to the flat finger of steps 1–4 (axis-aligned facets), which is proven to meet.
    RandomMeshOptions o;
    o.family = Family::immersed;
    o.holes = 2;
    o.faces = 103;
    o.seed = 4249561295353340922ull;
    o.knobs.depth = 3.437567151606102;
    const TriMesh m = random_mesh(o);
    CHECK(has_axis_aligned_face(m));
    require_family_mesh(o, m);
    o.seed = 1;  // the common case: curved
    CHECK_FALSE(has_axis_aligned_face(random_mesh(o)));
}

TEST_CASE("GEN-15: the smooth and immersed families do not depend on the compiler", "[unit]") {
    // FNV-1a (mesh_hash) recorded from this implementation when the families were added, and
    // reproduced bit for bit by GCC 12 and Clang 14 at -O0 and -O3 -march=native (all with
    // -ffp-contract=off), as were a 200,000-face smooth mesh and the flat-finger recipe below.
    // Change them only with a deliberate change of the construction, noted in
    // paper_notes/generator.md.
    RandomMeshOptions smooth{2, 1001, 7, 0.0, 1, 2, Family::smooth, {}};
    smooth.knobs.amplitude = 0.4;
    CHECK(mesh_hash(random_mesh(smooth)) == 0x771b04b73c0b126full);
    RandomMeshOptions immersed{1, 1000, 7, 0.0, 0, 2, Family::immersed, {}};
    immersed.knobs.depth = 2;
    CHECK(mesh_hash(random_mesh(immersed)) == 0xcc23add8eb1bfafbull);
}

TEST_CASE("the smooth and immersed knobs are checked: InvalidInput naming the knob and its range", "[unit]") {
    using Catch::Matchers::Contains;
    const auto refused = [](Family family, auto set, const std::string& part) {
        RandomMeshOptions o;
        o.family = family;
        o.faces = 2000;
        set(o.knobs);
        try {
            random_mesh(o);
            FAIL("accepted " << generate_command(o));
        } catch (const fhr::InvalidInput& e) {
            CHECK(e.file().empty());
            CHECK(e.line() == 0u);
            CHECK_THAT(e.what(), Contains(part));
        }
    };
    using Knobs = fhr::generate::FamilyKnobs;
    refused(
        Family::smooth, [](Knobs& k) { k.roundness = 0; }, "--roundness must be in (0, 0.45] (got 0");
    refused(
        Family::smooth, [](Knobs& k) { k.roundness = 0.46; }, "--roundness must be in (0, 0.45] (got 0.46");
    refused(
        Family::smooth, [](Knobs& k) { k.roundness = NAN; }, "--roundness must be in (0, 0.45]");
    refused(
        Family::smooth, [](Knobs& k) { k.amplitude = -0.01; }, "--amplitude must be in [0, 0.5] (got -0.01");
    refused(
        Family::smooth, [](Knobs& k) { k.amplitude = 0.51; }, "--amplitude must be in [0, 0.5] (got 0.51");
    refused(
        Family::immersed, [](Knobs& k) { k.depth = 1.09; }, "--depth must be in [1.1, 4] (got 1.09");
    refused(
        Family::immersed, [](Knobs& k) { k.depth = INFINITY; }, "--depth must be in [1.1, 4]");
    // The immersed family needs 8 faces more per component than the block (its finger).
    RandomMeshOptions o;
    o.family = Family::immersed;
    o.genus = 1;
    o.components = 2;
    CHECK(min_faces(o) == min_faces(1, 0, 2) + 16);
    o.family = Family::smooth;
    CHECK(min_faces(o) == min_faces(1, 0, 2));
}

TEST_CASE("GEN-7: fhr generate --family smooth|immersed with knobs writes exactly random_mesh's mesh", "[unit]") {
    RandomMeshOptions smooth{3, 1501, 11, 0.0, 3, 2, Family::smooth, {}};
    smooth.knobs.roundness = 0.17;
    smooth.knobs.amplitude = 0.4321;
    RandomMeshOptions immersed{0, 700, 12, 0.0, 1, 1, Family::immersed, {}};
    immersed.knobs.depth = 3.3;
    for (const RandomMeshOptions& o : {smooth, immersed}) {
        const std::string out = fhr::test::temp_path(std::string(fhr::generate::family_name(o.family)) + ".off");
        std::vector<std::string> args;  // the command's words (the path has no spaces), without `fhr`
        std::istringstream words(generate_command(o, out));
        for (std::string w; words >> w;) args.push_back(w);
        args.erase(args.begin());
        INFO(generate_command(o, out));
        const auto gen = fhr::test::run_fhr(args);
        INFO(gen.err);
        REQUIRE(gen.exit_code == 0);
        fhr::BuildLog log;
        const TriMesh back =
            fhr::build_trimesh(fhr::io::read_soup(out), {.require_closed = false, .require_connected = false}, log);
        CHECK(identical(back, random_mesh(o)));
    }
}

TEST_CASE("move_embedded: a target that would meet itself is approached only as far as the guard allows", "[unit]") {
    // All at once: the targets of an embedded smooth mesh are reached (the usual path).
    TriMesh m = random_mesh({1, 400, 3, 0.0});
    std::vector<Vec3> target = m.positions();
    for (Vec3& p : target) p.z() *= 0.5;  // a thinner slab: embedded
    CHECK(fhr::generate::detail::move_embedded(m, target) == m.n_vertices());
    CHECK(m.positions() == target);
    // One vertex of the top facet sent through the bottom: the move of all at once meets itself,
    // so the passes of 1/8 move it while the guard accepts (to 3/8 of the way: the top is at
    // z = 1/4 now, the bottom at −1/4, the way is 1) and every other vertex to its target.
    fhr::VertexId top;
    for (fhr::VertexId v : m.vertices())
        if (m.position(v).z() == 0.25 && !m.is_boundary(v)) top = v;
    REQUIRE(top.valid());
    const std::vector<Vec3> before = m.positions();
    target = before;
    target[top.idx()].z() = -0.75;
    CHECK(fhr::generate::detail::move_embedded(m, target) == m.n_vertices() - 1);
    CHECK_FALSE(fhr::generate::find_self_intersection(m).has_value());
    CHECK(m.position(top).z() == 0.25 - 3 * (1.0 / 8));
}
