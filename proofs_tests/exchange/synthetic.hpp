// FHR tests — valid `fhr-param 1` files built without any parameterization code, so that the
// oracle (src/fhr/exchange/verify.hpp) is tested independently of what it judges (spec/param.md).
//
// Take a closed mesh D as the domain and let T′ be D with every face subdivided k-to-k² along
// the lattice of points with barycentric coordinates (r, p, q)/k, r + p + q = k. Then ψ is the
// identity of Ω_D written in barycentric terms: each vertex of T′ has the exact lattice β in its
// face; a vertex on an edge of D gets the same two non-zero numbers, (k − m)/k and m/k, from both
// faces (continuity, PARAM-7, exactly) and 0 at the opposite corner (PARAM-9); the points of a
// side are equally spaced, so chord length holds (PARAM-10) up to rounding; T′ has D's vertices
// bit for bit and lies on D (PARAM-11 with T = D). k = 1 gives T′ = D.
//
// D may have boundary and several components: then a vertex of T′ on a boundary edge
// of D lies in one patch only, on T′'s boundary, and each component of T′ subdivides one of D.
// The domains below make such D without any parameterization code: small planar pieces (a disk,
// an annulus), random closed meshes with holes cut out, and disjoint unions.
#pragma once

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>
#include <utility>
#include <vector>

#include <fhr/core/trimesh.hpp>
#include <fhr/exchange/fhr_param.hpp>

namespace fhr::test {

/// The k-to-k² subdivision of `domain` (closed or not, one or several components) as a valid
/// parameterization file. \pre k >= 1.
inline exchange::ParamFile subdivided_param(const TriMesh& domain, int k) {
    exchange::ParamFile file;
    file.domain_vertices = domain.positions();
    file.domain_faces = domain.triangles();
    file.surface_vertices = domain.positions();  // the corners keep their numbers and coordinates
    const double kd = k;
    // The k − 1 points inside edge (a, b), a < b, ordered from a; computed once, from a to b.
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> edge_first;
    auto edge_point = [&](std::uint32_t a, std::uint32_t b, int m) {  // m steps from a, 0 < m < k
        const auto key = std::minmax(a, b);
        auto it = edge_first.find(key);
        if (it == edge_first.end()) {
            it = edge_first.emplace(key, static_cast<std::uint32_t>(file.surface_vertices.size())).first;
            const Vec3 xa = file.domain_vertices[key.first], xb = file.domain_vertices[key.second];
            for (int s = 1; s < k; ++s) file.surface_vertices.push_back((double(k - s) * xa + double(s) * xb) / kd);
        }
        return it->second + static_cast<std::uint32_t>(a < b ? m - 1 : k - m - 1);
    };
    for (std::uint32_t d = 0; d < file.domain_faces.size(); ++d) {
        const Triangle& c = file.domain_faces[d];
        std::vector<std::uint32_t> lattice((k + 1) * (k + 1));
        auto at = [&](int p, int q) -> std::uint32_t& { return lattice[p * (k + 1) + q]; };
        for (int p = 0; p <= k; ++p)
            for (int q = 0; p + q <= k; ++q) {
                const int r = k - p - q;
                if (r == k)
                    at(p, q) = c[0];
                else if (p == k)
                    at(p, q) = c[1];
                else if (q == k)
                    at(p, q) = c[2];
                else if (q == 0)
                    at(p, q) = edge_point(c[0], c[1], p);
                else if (p == 0)
                    at(p, q) = edge_point(c[0], c[2], q);
                else if (r == 0)
                    at(p, q) = edge_point(c[1], c[2], q);
                else {
                    at(p, q) = static_cast<std::uint32_t>(file.surface_vertices.size());
                    file.surface_vertices.push_back((double(r) * file.domain_vertices[c[0]] +
                                                     double(p) * file.domain_vertices[c[1]] +
                                                     double(q) * file.domain_vertices[c[2]]) /
                                                    kd);
                }
            }
        auto beta = [&](int p, int q) {
            return exchange::Beta{double(k - p - q) / kd, double(p) / kd, double(q) / kd};
        };
        auto add = [&](int p0, int q0, int p1, int q1, int p2, int q2) {
            exchange::ParamFace face;
            face.v = {at(p0, q0), at(p1, q1), at(p2, q2)};
            face.patch = d;
            face.beta = {beta(p0, q0), beta(p1, q1), beta(p2, q2)};
            file.surface_faces.push_back(face);
        };
        // Counter-clockwise in the (β1, β2) = (p, q)/k plane, hence in the face's orientation.
        for (int p = 0; p < k; ++p)
            for (int q = 0; p + q < k; ++q) {
                add(p, q, p + 1, q, p, q + 1);
                if (p + q + 2 <= k) add(p + 1, q, p + 1, q + 1, p, q + 1);
            }
    }
    return file;
}

/// A hexagonal disk in the plane z = 0: centre 0, rim 1..6 counter-clockwise seen from +z; six
/// triangles, one boundary loop, χ = 1.
inline TriMesh hexagon_disk() {
    std::vector<Vec3> p{Vec3(0, 0, 0)};
    for (int i = 0; i < 6; ++i)
        p.emplace_back(std::cos(i * std::numbers::pi / 3), std::sin(i * std::numbers::pi / 3), 0);
    std::vector<Triangle> t;
    for (std::uint32_t i = 0; i < 6; ++i) t.push_back({0, 1 + i, 1 + (i + 1) % 6});
    return TriMesh::from_triangles(std::move(p), t);
}

/// A planar square annulus: inner square 0..3 (side 2), outer square 4..7 (side 4), eight
/// triangles, two boundary loops, χ = 0.
inline TriMesh square_annulus() {
    std::vector<Vec3> p{Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0),
                        Vec3(-2, -2, 0), Vec3(2, -2, 0), Vec3(2, 2, 0), Vec3(-2, 2, 0)};
    std::vector<Triangle> t;
    for (std::uint32_t i = 0; i < 4; ++i) {
        const std::uint32_t j = (i + 1) % 4;
        t.push_back({i, 4 + i, 4 + j});
        t.push_back({i, 4 + j, j});
    }
    return TriMesh::from_triangles(std::move(p), t);
}

/// `mesh` with `holes` faces removed, pairwise without a common vertex (so every vertex keeps one
/// fan): each hole adds a boundary loop and lowers χ by 1. The faces are taken greedily from
/// face `seed mod F` on. \pre mesh is closed, and has that many such faces.
inline TriMesh with_holes(const TriMesh& mesh, std::size_t holes, std::uint64_t seed) {
    const std::vector<Triangle> all = mesh.triangles();
    std::vector<bool> used(mesh.n_vertices(), false), removed(all.size(), false);
    for (std::size_t i = 0; i < all.size() && holes > 0; ++i) {
        const std::size_t f = (seed + i) % all.size();
        const Triangle& t = all[f];
        if (used[t[0]] || used[t[1]] || used[t[2]]) continue;
        for (std::uint32_t v : t) used[v] = true;
        removed[f] = true;
        --holes;
    }
    if (holes > 0) throw std::logic_error("with_holes: not enough vertex-disjoint faces");
    std::vector<Triangle> kept;
    for (std::size_t f = 0; f < all.size(); ++f)
        if (!removed[f]) kept.push_back(all[f]);
    return TriMesh::from_triangles(mesh.positions(), kept);
}

/// The disjoint union of a and b: b's vertices and faces follow a's, b moved along x to lie
/// beyond a, 1 apart.
inline TriMesh disjoint_union(const TriMesh& a, const TriMesh& b) {
    double a_max = -1e300, b_min = 1e300;
    for (const Vec3& x : a.positions()) a_max = std::max(a_max, x.x());
    for (const Vec3& x : b.positions()) b_min = std::min(b_min, x.x());
    const Vec3 offset(a_max - b_min + 1, 0, 0);
    std::vector<Vec3> p = a.positions();
    std::vector<Triangle> t = a.triangles();
    const auto n = static_cast<std::uint32_t>(p.size());
    for (const Vec3& x : b.positions()) p.push_back(x + offset);
    for (Triangle f : b.triangles()) t.push_back({f[0] + n, f[1] + n, f[2] + n});
    return TriMesh::from_triangles(std::move(p), t);
}

}  // namespace fhr::test
