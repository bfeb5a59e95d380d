// FHR §5 tests — what the wavelet suites share: closed meshes with a vertex of each valence 3..12
// (bipyramids), random domains from src/fhr/generate, and random functions in S^j.
#pragma once

#include <rapidcheck.h>

#include <cmath>
#include <numbers>
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

/// A random closed domain D: genus 0..2 (as far as `max_faces` allows: generate::min_faces), at
/// most `max_faces` faces (shown as its `fhr generate` command in a counterexample).
/// \pre max_faces ≥ 12.
inline rc::Gen<testing::GeneratedMesh> gen_domain(std::size_t max_faces) {
    int genus = 2;
    while (genus > 0 && generate::min_faces(genus) > max_faces) --genus;
    return testing::gen_closed_mesh(0, genus, max_faces);
}

/// n random points with coordinates uniform in [−1, 1] (scaled by `scale`, shifted by `offset`).
inline std::vector<Vec3> random_points(std::size_t n, std::uint64_t seed, double scale = 1, const Vec3& offset = Vec3::Zero()) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<Vec3> f(n);
    for (Vec3& x : f) x = offset + scale * Vec3(u(rng), u(rng), u(rng));
    return f;
}

}  // namespace fhr::test
