// Checks shared by the generator's tests (spec/generator.md GEN-1..8): one place that states what
// every generated mesh, of every family, must be.
#include "generate/generated_checks.hpp"

#include <rapidcheck.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>

#include <fhr/core/build.hpp>
#include <fhr/core/geometry.hpp>
#include <fhr/core/topology.hpp>
#include <fhr/generate/embedding.hpp>

namespace fhr::generate::checks {

using fhr::HalfedgeId;
using fhr::TriMesh;
using fhr::Vec3;

fhr::PolygonSoup to_soup(const TriMesh& m) {
    fhr::PolygonSoup soup;
    soup.points = m.positions();
    for (const fhr::Triangle& t : m.triangles()) soup.add_polygon(t.data(), 3);
    return soup;
}

int share(int total, int components, int c) { return total / components + (c < total % components ? 1 : 0); }

double block_volume(int genus, int holes) {
    const long h = genus == 0 ? 1 : 3, even_rows = (h + 1) / 2;
    const long columns = ((holes + 1) / 2 + even_rows - 1) / even_rows;
    const long w = std::max<long>(genus == 0 ? 1 : 2 * genus + 1, 2 * columns - 1);
    return static_cast<double>(w * h - genus);
}

double smallest_corner_angle(const TriMesh& m) {
    double smallest = std::numbers::pi;
    for (HalfedgeId h : m.halfedges())
        if (!m.is_boundary(h)) smallest = std::min(smallest, fhr::corner_angle(m, h));
    return smallest;
}

std::uint64_t mesh_hash(const TriMesh& m) {
    std::uint64_t hash = 14695981039346656037ull;
    auto mix = [&](std::uint64_t x) {
        for (int byte = 0; byte < 8; ++byte) {
            hash ^= (x >> (8 * byte)) & 0xff;
            hash *= 1099511628211ull;
        }
    };
    for (const Vec3& p : m.positions())
        for (int k = 0; k < 3; ++k) mix(std::bit_cast<std::uint64_t>(p[k]));
    for (const fhr::Triangle& t : m.triangles())
        for (auto i : t) mix(i);
    return hash;
}

std::vector<fhr::VertexId> loop_vertices(const TriMesh& m, HalfedgeId h) {
    std::vector<fhr::VertexId> loop;
    HalfedgeId g = h;
    do {
        loop.push_back(m.from(g));
        g = m.next(g);
    } while (g != h && loop.size() <= m.n_vertices());
    return loop;
}

std::vector<double> filled_six_volumes(const TriMesh& m, const fhr::Components& comps) {
    std::vector<double> six_volume(comps.count, 0);
    std::vector<Vec3> origin(comps.count);
    for (fhr::VertexId v : m.vertices())
        if (v.idx() == 0 || comps.vertex_component[v] != comps.vertex_component[fhr::VertexId(v.idx() - 1)])
            origin[comps.vertex_component[v]] = m.position(v);
    auto add = [&](fhr::VertexId a, fhr::VertexId b, fhr::VertexId d) {
        const std::size_t c = comps.vertex_component[a];
        six_volume[c] += (m.position(a) - origin[c]).dot((m.position(b) - origin[c]).cross(m.position(d) - origin[c]));
    };
    for (fhr::FaceId f : m.faces()) {
        const auto v = m.face_vertices(f);
        add(v[0], v[1], v[2]);
    }
    for (HalfedgeId h : fhr::boundary_loops(m)) {
        const std::vector<fhr::VertexId> loop = loop_vertices(m, h);
        for (std::size_t i = 1; i + 1 < loop.size(); ++i) add(loop[0], loop[i], loop[i + 1]);
    }
    return six_volume;
}

bool identical(const TriMesh& a, const TriMesh& b) {
    if (a.n_vertices() != b.n_vertices() || a.triangles() != b.triangles()) return false;
    for (fhr::VertexId v : a.vertices())
        for (int k = 0; k < 3; ++k)
            if (std::bit_cast<std::uint64_t>(a.position(v)[k]) != std::bit_cast<std::uint64_t>(b.position(v)[k]))
                return false;
    return true;
}

void check_generated(const RandomMeshOptions& o, const TriMesh& m) {
    // GEN-1: a valid, compact halfedge mesh (INV-MESH-0..8: every vertex one fan).
    RC_ASSERT(!m.has_garbage());
    m.validate();
    // GEN-2: exactly the requested face count; 2E = 3F + (boundary edges).
    std::size_t boundary_edges = 0;
    for (HalfedgeId h : m.halfedges()) boundary_edges += m.is_boundary(h);
    RC_ASSERT(m.n_faces() == o.faces);
    RC_ASSERT(2 * m.n_edges() == 3 * o.faces + boundary_edges);
    // Every boundary loop is a simple closed curve, and no two loops share a vertex.
    const std::vector<HalfedgeId> loops = fhr::boundary_loops(m);
    std::vector<char> on_a_loop(m.n_vertices(), 0);
    std::size_t loop_edges = 0;
    for (HalfedgeId h : loops)
        for (fhr::VertexId v : loop_vertices(m, h)) {
            RC_ASSERT(!on_a_loop[v.idx()]);
            on_a_loop[v.idx()] = 1;
            ++loop_edges;
        }
    RC_ASSERT(loop_edges == boundary_edges);
    // GEN-3, per component: χ_c = 2 − 2g_c − b_c with g_c, b_c the component's share of the
    // totals; components numbered in order (component c's vertices before component c + 1's).
    const fhr::Components comps = fhr::connected_components(m);
    RC_ASSERT(comps.count == static_cast<std::size_t>(o.components));
    RC_ASSERT(loops.size() == static_cast<std::size_t>(o.holes));
    RC_ASSERT(m.is_closed() == (o.holes == 0));
    RC_ASSERT(fhr::genus(m) == o.genus);
    const std::size_t C = comps.count;
    auto component = [&](fhr::VertexId v) { return comps.vertex_component[v]; };
    std::vector<long> chi(C, 0), n_loops(C, 0);
    std::vector<double> min_x(C, INFINITY), max_x(C, -INFINITY);
    for (fhr::VertexId v : m.vertices()) {
        ++chi[component(v)];
        if (v.idx() > 0) RC_ASSERT(component(v) >= component(fhr::VertexId(v.idx() - 1)));
        min_x[component(v)] = std::min(min_x[component(v)], m.position(v).x());
        max_x[component(v)] = std::max(max_x[component(v)], m.position(v).x());
    }
    for (fhr::EdgeId e : m.edges()) --chi[component(m.from(TriMesh::halfedge(e, 0)))];
    for (fhr::FaceId f : m.faces()) {
        ++chi[component(m.face_vertices(f)[0])];
        if (f.idx() > 0)
            RC_ASSERT(component(m.face_vertices(f)[0]) >= component(m.face_vertices(fhr::FaceId(f.idx() - 1))[0]));
    }
    for (HalfedgeId h : loops) ++n_loops[component(m.from(h))];
    // GEN-6: outward: each component, its holes filled, encloses a positive volume.
    const std::vector<double> six_volume = filled_six_volumes(m, comps);
    for (std::size_t c = 0; c < C; ++c) {
        const int g = share(o.genus, o.components, static_cast<int>(c)),
                  b = share(o.holes, o.components, static_cast<int>(c));
        RC_ASSERT(chi[c] == 2 - 2 * g - b);
        RC_ASSERT(n_loops[c] == b);
        RC_ASSERT(six_volume[c] > 0);
        // Block: component c lies at least 1 beyond the ones before it along x (up to rounding).
        if (o.family == fhr::generate::Family::block && c > 0)
            RC_ASSERT(min_x[c] - *std::max_element(max_x.begin(), max_x.begin() + c) >= 1 - 1e-9);
    }
    // Block shape: every corner at least 20°, up to the rounding of the two angle evaluations.
    if (o.family == fhr::generate::Family::block)
        RC_ASSERT(smallest_corner_angle(m) >= fhr::generate::min_corner_angle_degrees * std::numbers::pi / 180 - 1e-9);
}

void check_builds_unchanged(const TriMesh& m, const fhr::BuildOptions& options) {
    fhr::BuildLog log;
    const TriMesh built = fhr::build_trimesh(to_soup(m), options, log);
    RC_ASSERT(log.warnings.empty());
    RC_ASSERT(log.reoriented_faces == 0u);
    RC_ASSERT(log.dropped_vertices == 0u);
    RC_ASSERT(identical(built, m));
    RC_ASSERT(built.n_halfedges() == m.n_halfedges());
    for (HalfedgeId h : m.halfedges()) RC_ASSERT(built.to(h) == m.to(h) && built.next(h) == m.next(h));
}

void check_family_mesh(const RandomMeshOptions& o, const TriMesh& m) {
    check_generated(o, m);
    fhr::BuildOptions build;
    build.require_closed = build.require_connected = false;
    check_builds_unchanged(m, build);
    const auto pair = find_self_intersection(m);
    if (o.family == Family::immersed) {
        RC_ASSERT(pair.has_value());
        RC_ASSERT((*pair)[0] != (*pair)[1]);  // an intersection, not a degenerate triangle
    } else if (pair) {
        RC_FAIL(generate_command(o) + ": faces " + std::to_string((*pair)[0].idx()) + " and " +
                std::to_string((*pair)[1].idx()) + " meet improperly (or one is degenerate)");
    }
}

}  // namespace fhr::generate::checks
