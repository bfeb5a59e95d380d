// FHR §4 tests — patches S_i to parameterize: triangulated disks cut from the random closed
// meshes of src/fhr/generate (paper §1's inputs T), and jittered, flipped triangle lattices that are
// planar (Proposition 2) or lifted onto a bumpy height field (Proposition 1).
#pragma once

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

#include <fhr/core/detail/predicates.hpp>
#include <fhr/core/trimesh.hpp>
#include <fhr/param/disk.hpp>

namespace fhr::test {

/// Random corner positions 0 < c1 < c2 < n on a boundary loop of n ≥ 3 vertices.
inline std::array<std::size_t, 3> random_corners(std::size_t n, std::mt19937_64& rng) {
    const std::size_t c1 = std::uniform_int_distribution<std::size_t>(1, n - 2)(rng);
    const std::size_t c2 = std::uniform_int_distribution<std::size_t>(c1 + 1, n - 1)(rng);
    return {0, c1, c2};
}

/// A disk of about `faces` faces of the closed mesh m, grown face by face from a random face so
/// that it stays a disk (a face joins across a boundary edge when its third vertex is new, or
/// when it fills a notch of two consecutive boundary edges); its boundary loop starts at a random
/// boundary vertex, with random corners. Deterministic in (m, seed, faces).
/// \pre m closed, faces ≥ 1.
inline param::Disk disk_from_mesh(const TriMesh& m, std::uint64_t seed, std::size_t faces) {
    std::mt19937_64 rng(seed);
    std::vector<char> in(m.n_faces(), 0);
    std::vector<std::uint32_t> vertex_faces(m.n_vertices(), 0);
    std::vector<FaceId> region;
    auto add = [&](FaceId f) {
        in[f.idx()] = 1;
        region.push_back(f);
        for (VertexId v : m.face_vertices(f)) ++vertex_faces[v.idx()];
    };
    add(FaceId(std::uniform_int_distribution<std::uint32_t>(0, static_cast<std::uint32_t>(m.n_faces() - 1))(rng)));
    std::size_t boundary_edges = 3;
    while (region.size() < faces) {
        // Candidates: (face outside, halfedge of it on the region's boundary), in region order.
        std::vector<std::pair<FaceId, HalfedgeId>> candidates;
        for (FaceId f : region) {
            HalfedgeId h = m.halfedge(f);
            for (int k = 0; k < 3; ++k, h = m.next(h)) {
                const HalfedgeId o = TriMesh::twin(h);
                if (!in[m.face(o).idx()]) candidates.emplace_back(m.face(o), o);
            }
        }
        std::shuffle(candidates.begin(), candidates.end(), rng);
        bool grown = false;
        for (const auto& [f, h] : candidates) {
            const HalfedgeId h1 = m.next(h), h2 = m.next(h1);
            const VertexId w = m.to(h1);
            const int shared =
                int(in[m.face(TriMesh::twin(h1)).idx()] != 0) + int(in[m.face(TriMesh::twin(h2)).idx()] != 0);
            if (vertex_faces[w.idx()] == 0 && shared == 0) {
                boundary_edges += 1;
            } else if (vertex_faces[w.idx()] != 0 && shared == 1 && boundary_edges > 3) {
                boundary_edges -= 1;
            } else {
                continue;
            }
            add(f);
            grown = true;
            break;
        }
        if (!grown) break;
    }

    param::Disk disk;
    std::map<std::uint32_t, std::uint32_t> local;
    auto id = [&](VertexId v) {
        const auto [it, fresh] = local.try_emplace(v.idx(), static_cast<std::uint32_t>(disk.positions.size()));
        if (fresh) disk.positions.push_back(m.position(v));
        return it->second;
    };
    std::map<std::uint32_t, std::uint32_t> boundary_next;
    for (FaceId f : region) {
        const auto v = m.face_vertices(f);
        disk.triangles.push_back({id(v[0]), id(v[1]), id(v[2])});
        HalfedgeId h = m.halfedge(f);
        for (int k = 0; k < 3; ++k, h = m.next(h))
            if (!in[m.face(TriMesh::twin(h)).idx()]) boundary_next[id(m.from(h))] = id(m.to(h));
    }
    auto it = boundary_next.begin();
    std::advance(it, std::uniform_int_distribution<std::size_t>(0, boundary_next.size() - 1)(rng));
    std::uint32_t v = it->first;
    do {
        disk.boundary.push_back(v);
        v = boundary_next.at(v);
    } while (v != disk.boundary.front());
    disk.corners = random_corners(disk.boundary.size(), rng);
    return disk;
}

/// The lattice triangle of level n with corners A (s = t = 0), B (s = 1), C (t = 1): vertices at
/// parameters (s, t) = (i, j)/n, i + j ≤ n, jittered by up to `jitter`/n (boundary vertices along
/// their side only), then every interior edge flipped with probability 1/3 when both new
/// triangles stay positive in the (s, t) plane. Triangles are counter-clockwise in (s, t); the
/// boundary runs A → B → C with the corners at 0, n, 2n. `st` receives each vertex's (s, t).
/// Flips never join two boundary vertices (on a side whose computed (s, t) are collinear only up
/// to rounding, that could make a sliver with three vertices on one side). `side1`, when not
/// empty, gives the (s, t) of the n + 1 vertices of side B → C (boundary positions n..2n) instead
/// of jittering them: two patches can then share that side's vertices bit for bit.
/// \pre n ≥ 1, 0 ≤ jitter < 0.25 (so no jitter can reorder a side; a fold throws logic_error).
inline param::Disk lattice_triangle(int n, double jitter, std::mt19937_64& rng, std::vector<std::array<double, 2>>& st,
                                    const std::vector<std::array<double, 2>>& side1 = {}) {
    std::map<std::pair<int, int>, std::uint32_t> index;
    st.clear();
    std::uniform_real_distribution<double> shake(-jitter / n, jitter / n);
    for (int i = 0; i <= n; ++i)
        for (int j = 0; i + j <= n; ++j) {
            double s = double(i) / n, t = double(j) / n;
            const bool corner = (i == 0 && j == 0) || i == n || j == n;
            if (corner) {
            } else if (j == 0) {
                s += shake(rng);
            } else if (i == 0) {
                t += shake(rng);
            } else if (i + j == n && !side1.empty()) {
                s = side1[j][0];
                t = side1[j][1];
            } else if (i + j == n) {
                s += shake(rng);
                t = 1 - s;
            } else {
                s += 0.6 * shake(rng);
                t += 0.6 * shake(rng);
            }
            index[{i, j}] = static_cast<std::uint32_t>(st.size());
            st.push_back({s, t});
        }
    param::Disk disk;
    disk.positions.assign(st.size(), Vec3::Zero());
    for (int i = 0; i < n; ++i)
        for (int j = 0; i + j < n; ++j) {
            disk.triangles.push_back({index[{i, j}], index[{i + 1, j}], index[{i, j + 1}]});
            if (i + j < n - 1) disk.triangles.push_back({index[{i + 1, j}], index[{i + 1, j + 1}], index[{i, j + 1}]});
        }
    auto point = [&](std::uint32_t v) { return Eigen::Vector2d(st[v][0], st[v][1]); };
    auto positive = [&](const std::array<std::uint32_t, 3>& f) {
        return orient2d(point(f[0]), point(f[1]), point(f[2])) > 0;
    };
    for (const auto& f : disk.triangles)
        if (!positive(f)) throw std::logic_error("lattice_triangle: jitter folded a triangle");
    std::vector<char> boundary_vertex(st.size(), 0);
    for (const auto& [ij, v] : index) boundary_vertex[v] = ij.first == 0 || ij.second == 0 || ij.first + ij.second == n;
    auto on_boundary = [&](std::uint32_t v) { return boundary_vertex[v] != 0; };
    // Random flips of interior edges (a, b) with triangles (a, b, c), (b, a, d) -> (c, d, b), (d, c, a).
    std::bernoulli_distribution flip(1.0 / 3);
    for (std::size_t t = 0; t < disk.triangles.size(); ++t)
        for (int k = 0; k < 3; ++k) {
            const auto f = disk.triangles[t];
            const std::uint32_t a = f[k], b = f[(k + 1) % 3], c = f[(k + 2) % 3];
            std::size_t other = disk.triangles.size();
            std::uint32_t d = 0;
            for (std::size_t u = 0; u < disk.triangles.size(); ++u)
                for (int l = 0; l < 3; ++l)
                    if (disk.triangles[u][l] == b && disk.triangles[u][(l + 1) % 3] == a) {
                        other = u;
                        d = disk.triangles[u][(l + 2) % 3];
                    }
            if (other == disk.triangles.size() || !flip(rng)) continue;
            bool cd_exists = false;
            for (const auto& g : disk.triangles)
                for (int l = 0; l < 3; ++l)
                    if ((g[l] == c && g[(l + 1) % 3] == d) || (g[l] == d && g[(l + 1) % 3] == c)) cd_exists = true;
            const std::array<std::uint32_t, 3> f1{c, d, b}, f2{d, c, a};
            if (cd_exists || (on_boundary(c) && on_boundary(d)) || !positive(f1) || !positive(f2)) continue;
            disk.triangles[t] = f1;
            disk.triangles[other] = f2;
        }
    for (int i = 0; i <= n; ++i) disk.boundary.push_back(index[{i, 0}]);
    for (int i = n - 1; i >= 0; --i) disk.boundary.push_back(index[{i, n - i}]);
    for (int j = n - 1; j >= 1; --j) disk.boundary.push_back(index[{0, j}]);
    disk.corners = {0, static_cast<std::size_t>(n), static_cast<std::size_t>(2 * n)};
    return disk;
}

/// Places a lattice disk in space: x(s, t) = A + s (B − A) + t (C − A) + h(s, t) N with the
/// height field h = amplitude · sin(fs·s + p) · cos(ft·t + q) along the unit normal N of ABC.
inline void place(param::Disk& disk, const std::vector<std::array<double, 2>>& st, const std::array<Vec3, 3>& abc,
                  double amplitude, double fs, double ft, double p, double q) {
    const Vec3 normal = (abc[1] - abc[0]).cross(abc[2] - abc[0]).normalized();
    for (std::size_t v = 0; v < st.size(); ++v) {
        const double s = st[v][0], t = st[v][1];
        disk.positions[v] = abc[0] + s * (abc[1] - abc[0]) + t * (abc[2] - abc[0]) +
                            amplitude * std::sin(fs * s + p) * std::cos(ft * t + q) * normal;
    }
}

/// A bumpy square cut along its diagonal: patch 1 = A B C with (x, y) = (s, t), patch 2 = D C B
/// with (x, y) = (1 − s, 1 − t) (a half turn, both counter-clockwise), sharing the curve B–C,
/// which patch 1 runs B → C and patch 2 C → B. Boundary position n + i of patch 1 (from B) and
/// 2n − i of patch 2 (from its C2 = B) are the same lattice point, with bit-identical square
/// coordinates; `lift` maps square coordinates to 3-D positions.
struct DiagonalPair {
    param::Disk p1, p2;
};
template <class Lift>
inline DiagonalPair diagonal_pair(int n, std::mt19937_64& rng, Lift&& lift) {
    std::vector<std::array<double, 2>> st1, st2;
    DiagonalPair pair{lattice_triangle(n, 0.2, rng, st1), {}};
    std::vector<std::array<double, 2>> side1;  // patch 2's side B2 → C2 is patch 1's C → B, turned
    for (int k = 0; k <= n; ++k) {
        const auto& q = st1[pair.p1.boundary[static_cast<std::size_t>(2 * n - k)]];
        side1.push_back({1 - q[0], 1 - q[1]});
    }
    pair.p2 = lattice_triangle(n, 0.2, rng, st2, side1);
    std::vector<std::array<double, 2>> xy2(st2.size());
    for (std::size_t v = 0; v < st2.size(); ++v) xy2[v] = {1 - st2[v][0], 1 - st2[v][1]};
    for (int i = 0; i <= n; ++i)
        xy2[pair.p2.boundary[static_cast<std::size_t>(2 * n - i)]] =
            st1[pair.p1.boundary[static_cast<std::size_t>(n + i)]];
    for (std::size_t v = 0; v < st1.size(); ++v) pair.p1.positions[v] = lift(st1[v]);
    for (std::size_t v = 0; v < xy2.size(); ++v) pair.p2.positions[v] = lift(xy2[v]);
    return pair;
}

}  // namespace fhr::test
