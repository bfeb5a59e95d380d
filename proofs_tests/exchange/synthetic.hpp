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
#pragma once

#include <map>
#include <utility>
#include <vector>

#include <fhr/core/trimesh.hpp>
#include <fhr/exchange/fhr_param.hpp>

namespace fhr::test {

/// The k-to-k² subdivision of `domain` as a valid parameterization file. \pre k >= 1.
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
                if (r == k) at(p, q) = c[0];
                else if (p == k) at(p, q) = c[1];
                else if (q == k) at(p, q) = c[2];
                else if (q == 0) at(p, q) = edge_point(c[0], c[1], p);
                else if (p == 0) at(p, q) = edge_point(c[0], c[2], q);
                else if (r == 0) at(p, q) = edge_point(c[1], c[2], q);
                else {
                    at(p, q) = static_cast<std::uint32_t>(file.surface_vertices.size());
                    file.surface_vertices.push_back((double(r) * file.domain_vertices[c[0]] +
                                                     double(p) * file.domain_vertices[c[1]] +
                                                     double(q) * file.domain_vertices[c[2]]) / kd);
                }
            }
        auto beta = [&](int p, int q) { return exchange::Beta{double(k - p - q) / kd, double(p) / kd, double(q) / kd}; };
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

}  // namespace fhr::test
