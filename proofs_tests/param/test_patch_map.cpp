// FHR §4 — one patch mapped onto its triangle: the disk contract (MAP-1), dividing edges
// (MAP-4, Floater 2003 Thm 6.1), chord-length boundary (MAP-5), the interior system (MAP-6),
// SparseLU against BiCGSTAB (MAP-7), Proposition 1 as a property over disks cut from random
// meshes of genus 0–3 and bumpy lattices, for every weight kind (MAP-8), the certificate
// rejecting unsplit dividing edges and corrupted maps (MAP-9), and Proposition 2 on planar
// patches (MAP-10). Ids: spec/patch_map.md.
#include <catch2/catch.hpp>
#include <rapidcheck/catch.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <set>

#include <fhr/core/errors.hpp>
#include <fhr/param/certificate.hpp>
#include <fhr/param/disk.hpp>
#include <fhr/param/detail/dividing_edges.hpp>
#include <fhr/param/patch_map.hpp>
#include <fhr/param/weights.hpp>
#include <fhr/testing/rapidcheck.hpp>
#include "param/disks.hpp"

using namespace fhr;
using param::Disk;
using param::PatchMap;
using param::PatchMapOptions;
using param::Solver;
using param::Weights;

namespace {

const Weights all_kinds[] = {Weights::shape_preserving, Weights::mean_value, Weights::uniform};

// The smallest patch that needs a split: boundary A → P → B → C, corners A, B, C, triangles
// (A, P, B) and (A, B, C). P lies on side 0 with A and B, so the triangle (A, P, B) has all three
// vertices on one side and [A, B] is a dividing edge. No interior vertex.
Disk ear_disk() {
    Disk d;
    d.positions = {Vec3(0, 0, 0), Vec3(0.5, -0.2, 0.1), Vec3(1, 0, 0), Vec3(0.5, 1, 0)};  // A P B C
    d.triangles = {{0, 1, 2}, {0, 2, 3}};
    d.boundary = {0, 1, 2, 3};
    d.corners = {0, 2, 3};
    return d;
}

// The 3 × 3 grid on the torus (vertex 3i + j at angles (i, j) · 2π/3, each square cut along its
// diagonal: 9 vertices, 27 edges, 18 triangles) without its last triangle: a connected surface
// with one boundary loop, the hole's three vertices, and χ = 9 − 27 + 17 = −1.
Disk holed_torus() {
    Disk d;
    auto id = [](int i, int j) { return static_cast<std::uint32_t>(3 * (i % 3) + j % 3); };
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            const double a = 2 * std::numbers::pi * i / 3, b = 2 * std::numbers::pi * j / 3;
            d.positions.emplace_back((2 + std::cos(b)) * std::cos(a), (2 + std::cos(b)) * std::sin(a), std::sin(b));
        }
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            d.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
            d.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        }
    const auto hole = d.triangles.back();  // (a, b, c): the loop runs a → c → b
    d.triangles.pop_back();
    d.boundary = {hole[0], hole[2], hole[1]};
    d.corners = {0, 1, 2};
    return d;
}

// Interior edges joining two vertices of a common side (what split_dividing_edges removes).
std::size_t count_dividing(const Disk& d) {
    const auto sides_at = param::boundary_sides(d);
    std::vector<unsigned> side(d.positions.size(), 0);
    for (std::size_t p = 0; p < d.boundary.size(); ++p) side[d.boundary[p]] = sides_at[p];
    std::set<std::pair<std::uint32_t, std::uint32_t>> directed;
    for (const auto& f : d.triangles)
        for (int k = 0; k < 3; ++k) directed.emplace(f[k], f[(k + 1) % 3]);
    std::size_t n = 0;
    for (const auto& [a, b] : directed)
        if (a < b && directed.count({b, a}) && (side[a] & side[b])) ++n;
    return n;
}

double surface_area(const Disk& d) {
    double a = 0;
    for (const auto& f : d.triangles)
        a += 0.5 * (d.positions[f[1]] - d.positions[f[0]]).cross(d.positions[f[2]] - d.positions[f[0]]).norm();
    return a;
}

// A disk of up to 600 faces cut from a random closed mesh of genus 0–3, with random corners.
rc::Gen<Disk> gen_mesh_disk() {
    return rc::gen::exec([] {
        const fhr::testing::GeneratedMesh m = *fhr::testing::gen_closed_mesh(0, 3, 1500);
        const auto seed = *rc::gen::inRange<std::uint64_t>(0, 1u << 30);
        const auto faces = *rc::gen::inRange<std::size_t>(1, std::min<std::size_t>(600, m.n_faces() / 2));
        return test::disk_from_mesh(m, seed, faces);
    });
}

// A jittered, flipped lattice triangle of level 2..12 lifted onto a bumpy height field whose
// amplitude reaches 3 times the triangle's size (sharp ridges and deep valleys).
rc::Gen<Disk> gen_bumpy_disk() {
    return rc::gen::exec([] {
        const int n = *rc::gen::inRange(2, 13);
        std::mt19937_64 rng(*rc::gen::inRange<std::uint64_t>(0, 1u << 30));
        std::vector<std::array<double, 2>> st;
        Disk d = test::lattice_triangle(n, 0.2, rng, st);
        std::uniform_real_distribution<double> u(0, 1);
        test::place(d, st, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.3, 0.9, 0)}, 3 * u(rng), 20 * u(rng), 20 * u(rng),
                    6 * u(rng), 6 * u(rng));
        return d;
    });
}

rc::Gen<Disk> gen_disk() { return rc::gen::oneOf(gen_mesh_disk(), gen_bumpy_disk()); }

}  // namespace

TEST_CASE("solver names parse and print", "[unit][param]") {
    CHECK(param::parse_solver("sparse-lu") == Solver::sparse_lu);
    CHECK(param::parse_solver("bicgstab") == Solver::bicgstab);
    CHECK(param::name(Solver::sparse_lu) == "sparse-lu");
    CHECK_THROWS_WITH(param::parse_solver("cg"), Catch::Contains("expected sparse-lu or bicgstab"));
    // A bad option value comes from no file and no line: the message is the problem alone.
    try {
        param::parse_solver("cg");
    } catch (const InvalidInput& e) {
        CHECK(e.file().empty());
        CHECK(e.line() == 0);
        CHECK(std::string(e.what()) == e.problem());
    }
}

TEST_CASE("MAP-1: invalid disks are refused with the broken rule", "[unit][param]") {
    const Disk good = ear_disk();
    CHECK_FALSE(param::disk_violation(good));
    // The message names the rule; the structure names the element (LIB-2).
    auto refused = [](const Disk& d, const char* why, Element element, std::int64_t index) {
        INFO(why);
        CHECK_THROWS_WITH(param::map_patch(d), Catch::Contains("MAP-1") && Catch::Contains(why));
        const auto broken = param::disk_violation(d);
        REQUIRE(broken);
        CHECK(broken->invariant == "MAP-1");
        CHECK(broken->element == element);
        CHECK(broken->index == index);
    };
    Disk d = good;
    d.triangles[1] = {0, 3, 2};  // inconsistent orientation
    refused(d, "directed edge", Element::face, 1);
    d = good;
    d.boundary = {0, 3, 2, 1};  // the loop against the triangles' orientation
    refused(d, "not a boundary edge", Element::boundary_position, 0);
    d = good;
    d.corners = {0, 3, 2};
    refused(d, "corners", Element::corners, -1);
    d = good;
    d.positions.push_back(Vec3(5, 5, 5));  // an unused vertex
    refused(d, "in no triangle", Element::vertex, static_cast<std::int64_t>(good.positions.size()));
    d = good;
    d.triangles[0] = {0, 1, 4};
    refused(d, "names vertex 4", Element::face, 0);
    for (const std::array<std::uint32_t, 3> repeating : {std::array<std::uint32_t, 3>{0, 0, 2}, {0, 2, 2}, {2, 1, 2}}) {
        d = good;
        d.triangles[1] = repeating;
        refused(d, "triangle 1 repeats a vertex", Element::face, 1);
    }
    d = good;
    d.triangles.clear();
    refused(d, "no triangles", Element::whole, -1);
    d = good;
    d.boundary = {0, 1};
    refused(d, "boundary loop has 2 vertices (needs 3 corners)", Element::boundary_position, -1);
    // Each of 0 == c0 < c1 < c2 < #boundary broken alone (the swap above breaks c1 < c2).
    for (const std::array<std::size_t, 3> corners : {std::array<std::size_t, 3>{1, 2, 3}, {0, 0, 2}, {0, 2, 4}}) {
        d = good;
        d.corners = corners;
        refused(d, "are not 0 < c1 < c2 < 4", Element::corners, -1);
    }
    // Two triangles meeting at a vertex only: not manifold there (vertex 0 starts two boundary edges).
    Disk bowtie;
    bowtie.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(-1, 0, 0), Vec3(0, -1, 0)};
    bowtie.triangles = {{0, 1, 2}, {0, 3, 4}};
    bowtie.boundary = {0, 1, 2};
    bowtie.corners = {0, 1, 2};
    refused(bowtie, "vertex 0 starts two boundary edges", Element::vertex, 0);
    // Two closed fans (cones without their bases) sharing their apex 0: no boundary edge starts
    // at 0, but the walk around it from vertex 1 closes after 3 of its 6 triangles.
    Disk cones;
    cones.positions = {Vec3(0, 0, 0),  Vec3(1, 0, 1),  Vec3(0, 1, 1),   Vec3(-1, -1, 1),
                       Vec3(1, 0, -1), Vec3(0, 1, -1), Vec3(-1, -1, -1)};
    cones.triangles = {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {0, 5, 4}, {0, 6, 5}, {0, 4, 6}};
    cones.boundary = {1, 2, 3};
    cones.corners = {0, 1, 2};
    refused(cones, "vertex 0 is not manifold (its triangles form more than one fan)", Element::vertex, 0);
    // The ear disk beside a closed tetrahedron: every rule but connectivity holds.
    d = good;
    for (const Vec3& p : {Vec3(5, 0, 0), Vec3(6, 0, 0), Vec3(5, 1, 0), Vec3(5, 0, 1)}) d.positions.push_back(p);
    for (const std::array<std::uint32_t, 3> f :
         {std::array<std::uint32_t, 3>{4, 5, 6}, {4, 6, 7}, {4, 7, 5}, {5, 7, 6}})
        d.triangles.push_back(f);
    refused(d, "not connected (vertex 4)", Element::vertex, 4);
    // A torus with a hole: connected, manifold, one boundary loop, but χ = −1.
    refused(holed_torus(), "Euler characteristic -1 (a disk has 1)", Element::whole, -1);
    // map_patch also needs each side's chord length positive and finite (MAP-1); the topology is fine.
    d = good;
    d.positions[3] = d.positions[0];  // C on A: side 2 (C → A) has length 0
    CHECK_FALSE(param::disk_violation(d));
    CHECK_THROWS_WITH(param::map_patch(d), Catch::Contains("patch: MAP-1: side 2 has chord length 0.000000"));
    d = good;
    d.positions[0] = Vec3(-1e154, 0, 0);  // A and C 2e154 apart: |C − A|² overflows, the other sides' do not
    d.positions[3] = Vec3(1e154, 0, 0);
    CHECK_THROWS_WITH(param::map_patch(d), Catch::Contains("patch: MAP-1: side 2 has chord length inf"));
    // An annulus (two boundary loops).
    Disk annulus;
    for (int k = 0; k < 3; ++k) {
        const double a = 2 * std::numbers::pi * k / 3;
        annulus.positions.emplace_back(2 * std::cos(a), 2 * std::sin(a), 0);
    }
    for (int k = 0; k < 3; ++k) {
        const double a = 2 * std::numbers::pi * k / 3;
        annulus.positions.emplace_back(std::cos(a), std::sin(a), 0);
    }
    for (std::uint32_t k = 0; k < 3; ++k) {
        const std::uint32_t k1 = (k + 1) % 3;
        annulus.triangles.push_back({k, k1, 3 + k});
        annulus.triangles.push_back({k1, 3 + k1, 3 + k});
    }
    annulus.boundary = {0, 1, 2};
    annulus.corners = {0, 1, 2};
    CHECK_THROWS_WITH(param::validate(annulus), Catch::Contains("boundary edges"));
    annulus.boundary = {0, 1, 2, 0, 1, 2};  // as many entries as boundary edges, one loop twice
    CHECK_THROWS_WITH(param::validate(annulus), Catch::Contains("repeats vertex"));
}

TEST_CASE(
    "MAP-4, MAP-9: a triangle with all three vertices on one side cannot certify until its dividing edge is split",
    "[unit][param]") {
    Disk d = ear_disk();
    // Without the split: the image of (A, P, B) lies on side 0, a degenerate triangle.
    const param::Certificate before = param::certify(d, param::map_patch(d));
    CHECK_FALSE(before.passed);
    CHECK(before.flipped_triangles == 1);
    REQUIRE(before.first_failure);
    CHECK(before.first_failure->invariant == "MAP-8");
    CHECK(before.first_failure->element == fhr::Element::face);
    CHECK_THAT(before.first_failure->what, Catch::Contains("orientation"));
    // The split puts M = (A + B)/2 inside, joined to A, P, B, C.
    CHECK(param::split_dividing_edges(d) == 1);
    CHECK(d.positions.size() == 5);
    CHECK(d.positions[4] == Vec3(0.5, 0, 0));
    CHECK(d.triangles.size() == 4);
    CHECK(count_dividing(d) == 0);
    for (Weights kind : all_kinds) {
        const PatchMap psi = param::map_patch(d, {kind, Solver::sparse_lu});
        const param::Certificate after = param::certify(d, psi);
        INFO((after.first_failure ? after.first_failure->describe() : ""));
        CHECK(after.passed);
        CHECK(after.flipped_triangles == 0);
        CHECK(psi.beta[4][2] > 0);  // M is strictly inside, off side 0
    }
    // Splitting again finds nothing.
    CHECK(param::split_dividing_edges(d) == 0);
}

TEST_CASE(
    "MAP-4: splitting dividing edges keeps the disk, its boundary, its surface and its old vertices; each triangle "
    "lies in its origin",
    "[property][param]") {
    rc::prop("random disks", [] {
        const Disk original = *gen_disk();
        Disk d = original;
        std::vector<std::uint32_t> origin;
        const std::size_t split = param::split_dividing_edges(d, &origin);
        RC_TAG(split == 0 ? "no split" : "split");
        // Each triangle lies in its origin: its corners are the origin's or midpoints of its sides.
        RC_ASSERT(origin.size() == d.triangles.size());
        for (std::size_t t = 0; t < d.triangles.size(); ++t) {
            RC_ASSERT(origin[t] < original.triangles.size());
            const auto& o = original.triangles[origin[t]];
            for (std::uint32_t v : d.triangles[t]) {
                bool in = std::find(o.begin(), o.end(), v) != o.end();
                for (int k = 0; k < 3 && !in; ++k)
                    in = d.positions[v] == 0.5 * (original.positions[o[k]] + original.positions[o[(k + 1) % 3]]);
                RC_ASSERT(in);
            }
        }
        RC_ASSERT(split == count_dividing(original));
        RC_ASSERT(!param::disk_violation(d));
        RC_ASSERT(count_dividing(d) == 0);
        RC_ASSERT(d.boundary == original.boundary);
        RC_ASSERT(d.corners == original.corners);
        RC_ASSERT(d.positions.size() == original.positions.size() + split);
        RC_ASSERT(d.triangles.size() == original.triangles.size() + 2 * split);
        RC_ASSERT(std::equal(original.positions.begin(), original.positions.end(), d.positions.begin()));
        // The halves of a triangle split at the midpoint of an edge have exactly half its area
        // up to rounding of the cross products: 1e-12 relative.
        RC_ASSERT(std::abs(surface_area(d) - surface_area(original)) <= 1e-12 * surface_area(original));
    });
}

TEST_CASE("MAP-5: chord-length boundary, exactly on the sides, bit-identical from both patches of a curve",
          "[property][param]") {
    rc::prop("random disks: β on the sides equals L_p / L_r from the canonical end", [] {
        Disk d = *gen_disk();
        param::split_dividing_edges(d);
        const PatchMap psi = param::map_patch(d);
        const std::size_t n = d.boundary.size();
        const std::array<double, 3> e[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
        for (unsigned c = 0; c < 3; ++c) {
            std::vector<std::uint32_t> u;
            for (std::size_t p = d.corners[c]; p <= (c == 2 ? n : d.corners[c + 1]); ++p)
                u.push_back(d.boundary[p % n]);
            RC_ASSERT(psi.beta[u.front()] == e[c]);
            RC_ASSERT(psi.beta[u.back()] == e[(c + 1) % 3]);
            // The canonical end: the lexicographically smaller corner position.
            const Vec3 &first = d.positions[u.front()], &last = d.positions[u.back()];
            const bool forward =
                std::lexicographical_compare(last.data(), last.data() + 3, first.data(), first.data() + 3) == false;
            if (!forward) std::reverse(u.begin(), u.end());
            const unsigned far = forward ? (c + 1) % 3 : c;
            double L = 0, total = 0;
            for (std::size_t p = 1; p < u.size(); ++p) total += (d.positions[u[p]] - d.positions[u[p - 1]]).norm();
            for (std::size_t p = 0; p < u.size(); ++p) {
                if (p > 0) L += (d.positions[u[p]] - d.positions[u[p - 1]]).norm();
                const auto& b = psi.beta[u[p]];
                RC_ASSERT(b[(c + 2) % 3] == 0.0);
                // τ is L_p / L_r rounded to 2^-53 (|error| ≤ 2^-54, plus the accumulation's
                // rounding, which the test repeats in the same order).
                RC_ASSERT(std::abs(b[far] - L / total) <= std::ldexp(1.0, -54));
                RC_ASSERT(b[0] + b[1] + b[2] == 1.0);
                RC_ASSERT(b[1] + b[2] + b[0] == 1.0);
            }
        }
    });
}

TEST_CASE("MAP-5: two patches sharing a geodesic curve give its vertices bit-identical β", "[property][param]") {
    rc::prop("two bumpy lattice triangles sharing their diagonal", [] {
        const int n = *rc::gen::inRange(1, 10);
        std::mt19937_64 rng(*rc::gen::inRange<std::uint64_t>(0, 1u << 30));
        const double amplitude = *rc::gen::inRange(0, 300) / 100.0;
        auto [p1, p2] = test::diagonal_pair(n, rng, [&](const std::array<double, 2>& q) {
            return Vec3(q[0], q[1], amplitude * std::sin(7 * q[0] + 1) * std::cos(5 * q[1] + 2));
        });
        // The shared vertices now have identical positions (the same doubles went in).
        for (int i = 0; i <= n; ++i)
            RC_ASSERT(p1.positions[p1.boundary[n + i]] == p2.positions[p2.boundary[2 * n - i]]);
        param::split_dividing_edges(p1);
        param::split_dividing_edges(p2);
        const PatchMap psi1 = param::map_patch(p1), psi2 = param::map_patch(p2);
        // Patch 1's corners (A, B, C) = slots (0, 1, 2); patch 2's (D, C, B) = slots (0, 1, 2).
        for (int i = 0; i <= n; ++i) {
            const auto& b1 = psi1.beta[p1.boundary[n + i]];
            const auto& b2 = psi2.beta[p2.boundary[2 * n - i]];
            RC_ASSERT(b1[1] == b2[2]);  // the β of B
            RC_ASSERT(b1[2] == b2[1]);  // the β of C
        }
    });
}

TEST_CASE("MAP-6: every interior vertex is the convex combination of its neighbours' images", "[property][param]") {
    rc::prop("random disks, every weight kind", [] {
        Disk d = *gen_disk();
        param::split_dividing_edges(d);
        const Weights kind = *rc::gen::element(Weights::shape_preserving, Weights::mean_value, Weights::uniform);
        const PatchMap psi = param::map_patch(d, {kind, Solver::sparse_lu});
        std::vector<char> on_boundary(d.positions.size(), 0);
        for (auto v : d.boundary) on_boundary[v] = 1;
        // Rebuild each 1-ring from the triangles and apply the weights again.
        std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> pairs(d.positions.size());
        for (const auto& f : d.triangles)
            for (int k = 0; k < 3; ++k) pairs[f[k]].emplace_back(f[(k + 1) % 3], f[(k + 2) % 3]);
        for (std::uint32_t v = 0; v < d.positions.size(); ++v) {
            const auto& b = psi.beta[v];
            RC_ASSERT(b[0] + b[1] + b[2] == 1.0);  // exactly, on the 2^-53 grid
            if (on_boundary[v]) continue;
            std::vector<std::uint32_t> ring{pairs[v][0].first};
            while (ring.size() < pairs[v].size())
                for (const auto& [x, y] : pairs[v])
                    if (x == ring.back()) {
                        ring.push_back(y);
                        break;
                    }
            std::vector<Vec3> positions;
            for (auto w : ring) positions.push_back(d.positions[w]);
            // A dividing edge's midpoint has uniform weights (MAP-4, MAP-6).
            const std::vector<double> lambda =
                v + d.midpoints >= d.positions.size()
                    ? std::vector<double>(ring.size(), 1.0 / static_cast<double>(ring.size()))
                    : param::one_ring_weights(kind, d.positions[v], positions, v);
            double r1 = b[1], r2 = b[2];
            for (std::size_t k = 0; k < ring.size(); ++k) {
                r1 -= lambda[k] * psi.beta[ring[k]][1];
                r2 -= lambda[k] * psi.beta[ring[k]][2];
            }
            // Residual: the 2^-53 rounding of the stored values (≤ 2 · 2^-54) plus the direct
            // solver's backward error (≈ ε · κ, κ ≲ #V ≤ 10^3 here): below 1e-12.
            RC_ASSERT(std::abs(r1) <= 1e-12);
            RC_ASSERT(std::abs(r2) <= 1e-12);
        }
    });
}

TEST_CASE("MAP-7: SparseLU and BiCGSTAB agree to 1e-10 and both certify", "[property][param]") {
    rc::prop("random disks, every weight kind", [] {
        Disk d = *gen_disk();
        param::split_dividing_edges(d);
        const Weights kind = *rc::gen::element(Weights::shape_preserving, Weights::mean_value, Weights::uniform);
        const PatchMap lu = param::map_patch(d, {kind, Solver::sparse_lu});
        const PatchMap it = param::map_patch(d, {kind, Solver::bicgstab});
        for (std::size_t v = 0; v < d.positions.size(); ++v)
            for (int c = 0; c < 3; ++c) RC_ASSERT(std::abs(lu.beta[v][c] - it.beta[v][c]) <= 1e-10);
        RC_ASSERT(param::certify(d, it).flipped_triangles == 0);
        RC_ASSERT(param::certify(d, it).passed);
    });
}

TEST_CASE("MAP-7: BiCGSTAB on a patch whose incomplete LU is exact (a fuzz_pipeline finding)", "[unit][param]") {
    // A patch of §4 on the density family's graded mesh (fhr generate --family density --genus 2
    // --holes 2 --components 3 --faces 970 --seed 6679101986355545382, 439 domain faces, as §2
    // decimates with ties of cost by index alone), uniform weights: started from 0, BiCGSTAB's half step reached a
    // residual of exactly 0 and its next step divided 0 by 0 (NaN after 2 iterations, exit 4). It
    // starts from the preconditioner's solution now, which already meets the tolerance.
    Disk d;
    d.positions = {{7, 0, -0.5},
                   {7, -0.5, -0.5},
                   {6.5, 0.5, -0.5},
                   {6.5, -0.5, -0.5},
                   {6.5625, -0.375, -0.5},
                   {6.8125, -0.375, -0.5},
                   {7.5, -0.5, -0.5},
                   {7.4921875, -0.5, -0.5},
                   {7.4846153846153847, -0.48461538461538467, -0.5},
                   {7.166666666666667, -0.16666666666666674, -0.5},
                   {7.25, -0.5, -0.5},
                   {7.2999999999999998, -0.30000000000000004, -0.5},
                   {7.375, -0.5, -0.5},
                   {7.3888888888888893, -0.38888888888888884, -0.5},
                   {7.4375, -0.5, -0.5},
                   {7.4411764705882355, -0.44117647058823528, -0.5},
                   {7.46875, -0.5, -0.5},
                   {7.4696969696969697, -0.46969696969696972, -0.5},
                   {7.484375, -0.5, -0.5},
                   {6.5625, 0.125, -0.5},
                   {6.71875, -0.3125, -0.5},
                   {6.59375, -0.0625, -0.5},
                   {6.59375, -0.3125, -0.5},
                   {6.625, -0.25, -0.5}};
    d.triangles = {{0, 1, 2},    {3, 4, 5},    {6, 7, 8},    {9, 1, 0},    {9, 10, 1},   {11, 10, 9},
                   {11, 12, 10}, {13, 12, 11}, {13, 14, 12}, {15, 14, 13}, {15, 16, 14}, {17, 16, 15},
                   {17, 18, 16}, {8, 18, 17},  {8, 7, 18},   {2, 19, 3},   {1, 5, 2},    {5, 1, 3},
                   {5, 20, 19},  {19, 2, 5},   {19, 21, 4},  {4, 3, 19},   {4, 22, 20},  {20, 5, 4},
                   {23, 21, 20}, {21, 19, 20}, {23, 22, 21}, {22, 4, 21},  {22, 23, 20}};
    d.boundary = {3, 2, 0, 9, 11, 13, 15, 17, 8, 6, 7, 18, 16, 14, 12, 10, 1};
    d.corners = {0, 1, 9};
    param::validate(d);
    const PatchMap lu = param::map_patch(d, {Weights::uniform, Solver::sparse_lu});
    const PatchMap it = param::map_patch(d, {Weights::uniform, Solver::bicgstab});
    for (std::size_t v = 0; v < d.positions.size(); ++v)
        for (int c = 0; c < 3; ++c) CHECK(std::abs(lu.beta[v][c] - it.beta[v][c]) <= 1e-10);
    CHECK(param::certify(d, it).passed);
}

TEST_CASE("MAP-8: Proposition 1 — every split disk maps one-to-one with every weight kind", "[property][param]") {
    rc::prop("disks cut from random meshes of genus 0-3 and bumpy lattices", [] {
        Disk d = *gen_disk();
        const std::size_t split = param::split_dividing_edges(d);
        RC_TAG(split == 0 ? "no split" : "split");
        for (Weights kind : all_kinds) {
            const param::Certificate cert = param::certify(d, param::map_patch(d, {kind, Solver::sparse_lu}));
            RC_LOG() << param::name(kind) << ": " << (cert.first_failure ? cert.first_failure->describe() : "") << "\n";
            RC_ASSERT(cert.passed);
            RC_ASSERT(cert.flipped_triangles == 0);
            RC_ASSERT(cert.boundary_violations == 0);
            RC_ASSERT(cert.triangles == d.triangles.size());
            RC_ASSERT(cert.min_image_angle_degrees > 0);
        }
    });
}

TEST_CASE("MAP-9: without the split, a disk certifies exactly when it has no dividing edge on one side",
          "[property][param]") {
    // Theorem (Floater 2003, 6.1) gives "no such edge ⇒ one-to-one"; conversely such an edge
    // cuts off a sub-disk whose whole boundary maps into one side, so its images have total
    // signed area 0 and cannot all be positive.
    rc::prop("random disks, shape-preserving", [] {
        const Disk d = *gen_disk();
        const std::size_t dividing = count_dividing(d);
        RC_TAG(dividing == 0 ? "none" : "dividing edges");
        const param::Certificate cert = param::certify(d, param::map_patch(d));
        RC_ASSERT(cert.passed == (dividing == 0));
    });
}

TEST_CASE("MAP-9: the certificate rejects corrupted maps", "[unit][param]") {
    std::mt19937_64 rng(11);
    std::vector<std::array<double, 2>> st;
    Disk d = test::lattice_triangle(6, 0.2, rng, st);
    test::place(d, st, {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 1)}, 0.3, 5, 4, 0, 1);
    const PatchMap psi = param::map_patch(d);
    REQUIRE(param::certify(d, psi).passed);
    std::set<std::uint32_t> boundary(d.boundary.begin(), d.boundary.end());

    SECTION("two adjacent interior vertices swap images") {
        PatchMap bad = psi;
        for (const auto& f : d.triangles)
            if (!boundary.count(f[0]) && !boundary.count(f[1])) {
                std::swap(bad.beta[f[0]], bad.beta[f[1]]);
                break;
            }
        const param::Certificate cert = param::certify(d, bad);
        CHECK_FALSE(cert.passed);
        CHECK(cert.flipped_triangles >= 2);
        REQUIRE(cert.first_failure);
        CHECK(cert.first_failure->invariant == "MAP-8");
        CHECK(cert.first_failure->element == fhr::Element::face);
        // the face named is one whose image is folded: (β1, β2) of its corners not counter-clockwise
        const auto& named = d.triangles.at(static_cast<std::size_t>(cert.first_failure->index));
        const auto& ba = bad.beta[named[0]];
        const auto& bb = bad.beta[named[1]];
        const auto& bc = bad.beta[named[2]];
        CHECK((bb[1] - ba[1]) * (bc[2] - ba[2]) - (bb[2] - ba[2]) * (bc[1] - ba[1]) <= 0);
        CHECK_THAT(cert.first_failure->what, Catch::Contains("orientation"));
    }
    SECTION("a boundary vertex moved off its side") {
        PatchMap bad = psi;
        auto& b = bad.beta[d.boundary[2]];  // on side 0: β2 = 0
        b = {b[0] - 1.0 / 1024, b[1], 1.0 / 1024};
        const param::Certificate cert = param::certify(d, bad);
        CHECK_FALSE(cert.passed);
        CHECK(cert.boundary_violations == 1);
        REQUIRE(cert.first_failure);
        CHECK(cert.first_failure->invariant == "MAP-8");
        CHECK(cert.first_failure->element == fhr::Element::boundary_position);
        CHECK(cert.first_failure->index == 2);
        CHECK_THAT(cert.first_failure->what, Catch::Contains("not on side 0"));
    }
    SECTION("two boundary vertices out of order along their side") {
        PatchMap bad = psi;
        std::swap(bad.beta[d.boundary[2]], bad.beta[d.boundary[3]]);
        const param::Certificate cert = param::certify(d, bad);
        CHECK_FALSE(cert.passed);
        CHECK(cert.boundary_violations >= 1);
    }
    SECTION("a corner off its triangle corner") {
        PatchMap bad = psi;
        bad.beta[d.boundary[d.corners[1]]] = {0.25, 0.75, 0};
        const param::Certificate cert = param::certify(d, bad);
        CHECK_FALSE(cert.passed);
        CHECK(cert.boundary_violations >= 1);
    }
    SECTION("β not summing to one, or missing") {
        PatchMap bad = psi;
        bad.beta[0][0] += 1e-9;
        const param::Certificate cert = param::certify(d, bad);
        REQUIRE(cert.first_failure);
        CHECK(cert.first_failure->invariant == "MAP-6");
        CHECK(cert.first_failure->element == fhr::Element::vertex);
        CHECK(cert.first_failure->index == 0);
        bad = psi;
        bad.beta[5][1] = std::numeric_limits<double>::quiet_NaN();
        const param::Certificate nan = param::certify(d, bad);
        REQUIRE(nan.first_failure);
        CHECK(nan.first_failure->invariant == "MAP-6");
        CHECK(nan.first_failure->index == 5);
        CHECK_THAT(nan.first_failure->what, Catch::Contains("vertex 5 has β (") && Catch::Contains("nan"));
        bad = psi;
        bad.beta.pop_back();
        CHECK_FALSE(param::certify(d, bad).passed);
    }
    SECTION("a map of a disk that breaks MAP-1: the disk's violation, nothing certified") {
        Disk broken = d;
        broken.corners = {0, broken.corners[2], broken.corners[1]};
        const param::Certificate cert = param::certify(broken, psi);
        CHECK_FALSE(cert.passed);
        REQUIRE(cert.first_failure);
        CHECK(cert.first_failure->invariant == "MAP-1");
        CHECK(cert.first_failure->element == fhr::Element::corners);
        CHECK(cert.triangles == 0);  // no orientation, boundary or area check ran
        CHECK(cert.boundary_violations == 0);
    }
}

TEST_CASE("MAP-10: Proposition 2 — a planar patch spanning its triangle maps affinely", "[property][param]") {
    rc::prop("jittered, flipped planar lattice triangles in random position", [] {
        const int n = *rc::gen::inRange(1, 16);
        std::mt19937_64 rng(*rc::gen::inRange<std::uint64_t>(0, 1u << 30));
        std::vector<std::array<double, 2>> st;
        Disk d = test::lattice_triangle(n, 0.2, rng, st);
        std::uniform_real_distribution<double> u(-10, 10);
        const std::array<Vec3, 3> abc{Vec3(u(rng), u(rng), u(rng)), Vec3(u(rng), u(rng), u(rng)),
                                      Vec3(u(rng), u(rng), u(rng))};
        RC_PRE((abc[1] - abc[0]).cross(abc[2] - abc[0]).norm() > 1e-2 * (abc[1] - abc[0]).squaredNorm());
        test::place(d, st, abc, 0, 0, 0, 0, 0);
        // A planar triangle has no dividing edge on one side (its boundary is straight).
        RC_ASSERT(param::split_dividing_edges(d) == 0);
        for (Weights kind : {Weights::shape_preserving, Weights::mean_value}) {
            const PatchMap psi = param::map_patch(d, {kind, Solver::sparse_lu});
            // φ linear ⇔ ψ(v) = v's barycentric coordinates (1 − s − t, s, t) in [A, B, C].
            // Positions carry the rounding of their construction (a few ε relative); the
            // weights reproduce lines to ≈ 1e-15; the system amplifies by κ ≲ #V ≤ 136: ≤ 1e-12.
            for (std::size_t v = 0; v < st.size(); ++v) {
                RC_ASSERT(std::abs(psi.beta[v][1] - st[v][0]) <= 1e-12);
                RC_ASSERT(std::abs(psi.beta[v][2] - st[v][1]) <= 1e-12);
            }
        }
    });
}

TEST_CASE("MAP-10: uniform weights are not linear on an irregular planar patch (the test has teeth)", "[unit][param]") {
    std::mt19937_64 rng(5);
    std::vector<std::array<double, 2>> st;
    Disk d = test::lattice_triangle(8, 0.2, rng, st);
    test::place(d, st, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, 0, 0, 0, 0, 0);
    const PatchMap psi = param::map_patch(d, {Weights::uniform, Solver::sparse_lu});
    double deviation = 0;
    for (std::size_t v = 0; v < st.size(); ++v) deviation = std::max(deviation, std::abs(psi.beta[v][1] - st[v][0]));
    CHECK(deviation > 1e-4);
    CHECK(param::certify(d, psi).passed);
}

namespace {

// The smallest image angle by brute force: every corner of every image triangle in the domain
// triangle, atan2(|u × w|, u · w) in degrees (MAP-8's statistic, computed here corner by corner).
double every_corner_min_angle(const Disk& d, const PatchMap& psi, const std::array<Vec3, 3>& abc) {
    double smallest = 180;
    for (const auto& f : d.triangles) {
        std::array<Vec3, 3> p;
        for (int k = 0; k < 3; ++k) {
            const auto& b = psi.beta[f[k]];
            p[k] = Vec3(b[0] * abc[0] + b[1] * abc[1] + b[2] * abc[2]);
        }
        for (int k = 0; k < 3; ++k) {
            const Vec3 u = p[(k + 1) % 3] - p[k], w = p[(k + 2) % 3] - p[k];
            smallest = std::min(smallest, std::atan2(u.cross(w).norm(), u.dot(w)) * 180 / std::numbers::pi);
        }
    }
    return smallest;
}

}  // namespace

TEST_CASE("MAP-8: the certificate's smallest image angle is the least of all corners' angles, bit for bit",
          "[property][param]") {
    // The certificate computes a corner's atan2 only where its tangent does not already show it
    // above the minimum; the value must be the one of computing every corner.
    rc::prop("maps of random disks, in the equilateral triangle and in a random one", [] {
        Disk d = *gen_disk();
        param::split_dividing_edges(d);
        const PatchMap psi = param::map_patch(d);
        const std::array<Vec3, 3> equilateral{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, std::sqrt(3.0) / 2, 0)};
        const param::Certificate cert = param::certify(d, psi);
        RC_ASSERT(cert.passed);
        RC_ASSERT(cert.min_image_angle_degrees == every_corner_min_angle(d, psi, equilateral));
        // Scaled by 10^-80, 10^-150 and 10^150 too: the tangent test's products of coordinates are
        // then subnormal, or round to 0, or overflow.
        const auto coordinate = [] { return *rc::gen::inRange(-1000, 1000) / 100.0; };
        std::array<Vec3, 3> abc;
        for (Vec3& p : abc) p = Vec3(coordinate(), coordinate(), coordinate());
        RC_PRE((abc[1] - abc[0]).cross(abc[2] - abc[0]).norm() > 1e-3);
        const double scale = *rc::gen::element(1.0, 1e-80, 1e-150, 1e150);
        for (Vec3& p : abc) p *= scale;
        RC_TAG(scale);
        RC_ASSERT(param::certify(d, psi, abc).min_image_angle_degrees == every_corner_min_angle(d, psi, abc));
    });
    rc::prop("a needle: one interior vertex at distance 10^-e of a side (e up to 15), in the equilateral triangle", [] {
        // Corners 0, 1, 2 and vertex 3 inside, near the side from corner 1 to corner 2.
        Disk d;
        d.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0.3, 0.3, 0.1)};
        d.triangles = {{0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
        d.boundary = {0, 1, 2};
        d.corners = {0, 1, 2};
        const double delta = std::pow(10.0, -*rc::gen::inRange(1, 16)) * (1 + *rc::gen::inRange(0, 1000) / 1000.0);
        // Halfway along, the needle's two small angles are equal but for rounding: the minimum
        // must still be the smaller of the two, to the last bit.
        const double along = *rc::gen::inRange(0, 2) == 0 ? 0.5 : *rc::gen::inRange(1, 1000) / 1000.0;
        PatchMap psi;
        psi.beta = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {delta, (1 - delta) * along, 0}};
        psi.beta[3][2] = 1 - psi.beta[3][0] - psi.beta[3][1];
        const std::array<Vec3, 3> equilateral{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, std::sqrt(3.0) / 2, 0)};
        const param::Certificate cert = param::certify(d, psi);
        RC_PRE(cert.passed);  // β3 summing to 1 within 2ε, and the needle still positively oriented
        RC_TAG(cert.min_image_angle_degrees < 1e-9 ? "below 1e-9 degrees" : "larger");
        RC_ASSERT(cert.min_image_angle_degrees == every_corner_min_angle(d, psi, equilateral));
        // The same needle in an equilateral triangle of side 10^-s, s in 76..84: the tangent test's
        // bound is subnormal there.
        const double side = std::pow(10.0, -*rc::gen::inRange(76, 85));
        std::array<Vec3, 3> small = equilateral;
        for (Vec3& p : small) p *= side;
        RC_ASSERT(param::certify(d, psi, small).min_image_angle_degrees == every_corner_min_angle(d, psi, small));
    });
}

TEST_CASE("MAP-8: three images that round to one point give the smallest angle 0, as computed at every corner",
          "[unit][param]") {
    // P, R, Q differ by an ulp in the β plane (positively oriented there, so certified) but their
    // points in the equilateral triangle round to one point: every corner of (P, R, Q) has
    // u · w = 0 and |u × w| = 0, atan2(0, 0) = 0. Triangle (0, 1, R) first sets a positive minimum.
    Disk d;
    const double px = 0.20000000000000004, py = 0.7000000000000004;
    const std::array<double, 2> plane[6] = {
        {0, 0}, {1, 0}, {0, 1}, {px, py}, {std::nextafter(px, 1.0), py}, {px, std::nextafter(py, 1.0)}};
    PatchMap psi;
    for (const auto& [b1, b2] : plane) {
        d.positions.emplace_back(b1, b2, 0);
        psi.beta.push_back({1 - b1 - b2, b1, b2});
    }
    d.triangles = {{0, 1, 4}, {3, 4, 5}, {0, 4, 3}, {0, 3, 2}, {2, 3, 5}, {1, 2, 5}, {1, 5, 4}};
    d.boundary = {0, 1, 2};
    d.corners = {0, 1, 2};
    const std::array<Vec3, 3> equilateral{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, std::sqrt(3.0) / 2, 0)};
    auto image = [&](std::uint32_t v) {
        const auto& b = psi.beta[v];
        return Vec3(b[0] * equilateral[0] + b[1] * equilateral[1] + b[2] * equilateral[2]);
    };
    REQUIRE(image(3) == image(4));
    REQUIRE(image(3) == image(5));
    const param::Certificate cert = param::certify(d, psi);
    CHECK(cert.passed);
    CHECK(cert.min_image_angle_degrees == 0);
    CHECK(every_corner_min_angle(d, psi, equilateral) == 0);
}
