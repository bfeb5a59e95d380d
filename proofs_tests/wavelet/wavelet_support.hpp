// FHR §5 tests — what the wavelet suites share: closed meshes with a vertex of each valence 3..12
// (bipyramids), open fans with a boundary vertex of t = 1..12 triangles, random closed domains
// from src/fhr/generate, random domains with boundary and several components made from them
// (holes punched at disjoint vertex 1-rings, disjoint unions), and random functions in S^j.
#pragma once

#include <rapidcheck.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <ostream>
#include <random>
#include <vector>

#include <fhr/core/trimesh.hpp>
#include <fhr/testing/rapidcheck.hpp>
#include <fhr/wavelet/refine.hpp>

namespace fhr::test {

/// The n-gonal bipyramid: equator 0..n−1, apexes n (top) and n+1 (bottom) of valence n; the
/// equator vertices have valence 4. \pre n ≥ 3.
inline TriMesh bipyramid(unsigned n) {
    std::vector<Vec3> p;
    for (unsigned k = 0; k < n; ++k) {
        const double a = 2 * std::numbers::pi * k / n;
        p.emplace_back(std::cos(a), std::sin(a), 0);
    }
    p.emplace_back(0, 0, 1);
    p.emplace_back(0, 0, -1);
    std::vector<Triangle> t;
    for (unsigned k = 0; k < n; ++k) {
        t.push_back({k, (k + 1) % n, n});
        t.push_back({(k + 1) % n, k, n + 1});
    }
    return TriMesh::from_triangles(std::move(p), t);
}

/// The open fan of t triangles (v, r_k, r_{k+1}), k = 0..t−1: v = vertex 0 (a boundary vertex with
/// t triangles and t + 1 neighbours), the rim r_k = vertex k + 1 on an arc below it (the ends with
/// one triangle, the others with two). \pre t ≥ 1.
inline TriMesh open_fan(unsigned t) {
    std::vector<Vec3> p{{0, 0, 1}};
    for (unsigned k = 0; k <= t; ++k) {
        const double a = 1.5 * std::numbers::pi * k / t;  // the rim spans 270°: the fan is no half disk
        p.emplace_back(std::cos(a), std::sin(a), 0);
    }
    std::vector<Triangle> f;
    for (unsigned k = 0; k < t; ++k) f.push_back({0, k + 1, k + 2});
    return TriMesh::from_triangles(std::move(p), f);
}

/// A random closed domain D: genus 0..2 (as far as `max_faces` allows: generate::min_faces), at
/// most `max_faces` faces (shown as its `fhr generate` command in a counterexample).
/// \pre max_faces ≥ 12.
inline rc::Gen<testing::GeneratedMesh> gen_domain(std::size_t max_faces) {
    int genus = 2;
    while (genus > 0 && generate::min_faces(genus) > max_faces) --genus;
    return testing::gen_closed_mesh(0, genus, max_faces);
}

/// A domain with boundary and possibly several components: the disjoint union of generated
/// closed meshes (component c translated by 4c along x, its vertices numbered after those of the
/// components before it), each without the triangles at its `holes` vertices; those vertices are
/// dropped and the others renumbered in order. The removed 1-rings are vertex-disjoint closed
/// disks, so every hole is one boundary loop and every vertex stays manifold.
struct OpenDomain : TriMesh {
    std::vector<generate::RandomMeshOptions> components;
    std::vector<std::vector<std::uint32_t>> holes;  ///< per component: the vertices whose triangles were removed
    std::size_t hole_count() const {
        std::size_t n = 0;
        for (const auto& h : holes) n += h.size();
        return n;
    }
};

inline void showValue(const OpenDomain& d, std::ostream& os) {
    for (std::size_t c = 0; c < d.components.size(); ++c) {
        os << "[" << testing::generate_command(d.components[c]) << "] without the triangles at vertices {";
        for (std::uint32_t v : d.holes[c]) os << " " << v;
        os << " }  ";
    }
    os << "(" << d.n_vertices() << " vertices, " << d.n_faces() << " faces)";
}

/// Up to `wanted` vertices of the closed mesh `m` whose closed 1-rings are pairwise vertex-disjoint,
/// tried in an order shuffled by `seed` (the first one always fits: never empty when wanted ≥ 1).
/// Removing their triangles takes two consecutive triangles from each neighbour (valence ≥ 3), so
/// each keeps one fan.
inline std::vector<std::uint32_t> disjoint_rings(const TriMesh& m, std::size_t wanted, std::uint64_t seed) {
    std::vector<std::uint32_t> order(m.n_vertices());
    for (std::uint32_t v = 0; v < order.size(); ++v) order[v] = v;
    std::shuffle(order.begin(), order.end(), std::mt19937_64(seed));
    std::vector<char> taken(m.n_vertices(), 0);
    std::vector<std::uint32_t> centres;
    for (std::uint32_t c : order) {
        if (centres.size() == wanted) break;
        bool fits = !taken[c];
        m.for_each_outgoing(VertexId(c), [&](HalfedgeId h) { fits = fits && !taken[m.to(h).idx()]; });
        if (!fits) continue;
        centres.push_back(c);
        taken[c] = 1;
        m.for_each_outgoing(VertexId(c), [&](HalfedgeId h) { taken[m.to(h).idx()] = 1; });
    }
    return centres;
}

/// Builds the OpenDomain of these components and holes (see OpenDomain).
/// \pre holes.size() == components.size(); the holes of each component from disjoint_rings.
inline OpenDomain open_domain(std::vector<generate::RandomMeshOptions> components,
                              std::vector<std::vector<std::uint32_t>> holes) {
    std::vector<Vec3> points;
    std::vector<Triangle> triangles;
    for (std::size_t c = 0; c < components.size(); ++c) {
        const TriMesh m = generate::random_closed_mesh(components[c]);
        std::vector<char> gone(m.n_vertices(), 0);
        for (std::uint32_t v : holes[c]) gone[v] = 1;
        std::vector<std::uint32_t> id(m.n_vertices());
        for (VertexId v : m.vertices()) {
            if (gone[v.idx()]) continue;
            id[v.idx()] = static_cast<std::uint32_t>(points.size());
            points.push_back(m.position(v) + Vec3(4.0 * static_cast<double>(c), 0, 0));
        }
        for (const Triangle& t : m.triangles())
            if (!gone[t[0]] && !gone[t[1]] && !gone[t[2]]) triangles.push_back({id[t[0]], id[t[1]], id[t[2]]});
    }
    OpenDomain d{TriMesh::from_triangles(std::move(points), triangles), std::move(components), std::move(holes)};
    return d;
}

/// A random domain with 1..max_holes boundary loops (as many as fit, at least one) and
/// 1..max_components components of genus 0..2, each with at most `max_faces` faces before the holes.
/// \pre max_faces ≥ 12, max_holes ≥ 1, max_components ≥ 1.
inline rc::Gen<OpenDomain> gen_open_domain(std::size_t max_faces, std::size_t max_holes = 5,
                                           std::size_t max_components = 3) {
    return rc::gen::exec([=] {
        int genus = 2;
        while (genus > 0 && generate::min_faces(genus) > max_faces) --genus;
        const std::size_t k = *rc::gen::inRange<std::size_t>(1, max_components + 1);
        std::size_t wanted = *rc::gen::inRange<std::size_t>(1, max_holes + 1);
        std::vector<generate::RandomMeshOptions> components;
        std::vector<std::vector<std::uint32_t>> holes;
        for (std::size_t c = 0; c < k; ++c) {
            components.push_back(*testing::gen_mesh_options(0, genus, max_faces));
            // The first component takes at least one hole; the others a random share of the rest.
            const std::size_t here = c + 1 == k ? wanted : *rc::gen::inRange<std::size_t>(c == 0 ? 1 : 0, wanted + 1);
            const TriMesh m = generate::random_closed_mesh(components.back());
            holes.push_back(disjoint_rings(m, here, *rc::gen::inRange<std::uint64_t>(0, 1u << 30)));
            wanted -= std::min(wanted, holes.back().size());
        }
        return open_domain(std::move(components), std::move(holes));
    });
}

/// A random domain drawn in a property: closed (genus 0..2, at most `max_faces` faces) or, when
/// `open`, with 1..5 boundary loops and 1..3 components of at most `max_faces` faces each. The
/// counterexample shows the recipe of either kind.
inline TriMesh draw_domain(bool open, std::size_t max_faces) {
    if (open) return *gen_open_domain(max_faces);
    return *gen_domain(max_faces);
}

/// n random points with coordinates uniform in [−1, 1] (scaled by `scale`, shifted by `offset`).
inline std::vector<Vec3> random_points(std::size_t n, std::uint64_t seed, double scale = 1,
                                       const Vec3& offset = Vec3::Zero()) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<Vec3> f(n);
    for (Vec3& x : f) x = offset + scale * Vec3(u(rng), u(rng), u(rng));
    return f;
}

}  // namespace fhr::test
