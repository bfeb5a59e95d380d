// FHR generate — the immersed family (beyond the paper): surfaces that are
// combinatorially manifold and consistently, outwardly oriented, but meet themselves: for code
// that must not assume an embedding. Drawn only when asked for by name. The argument
// (paper_notes/generator.md, "The immersed family"), per component, from the block mesh of the
// recipe with 8 faces fewer per component:
//
//   1. The facet. A genus-0 block's −y wall (y = −1/2; the +y wall, one unit away, covers the
//      same x and z), a block with genus its first genus hole's −x wall (the +x face of cell
//      (0, 1); the hole's other wall, one unit away, is the same unit square). Walls are never
//      holes, so both always exist. Pushing along +y, or +x, goes through the slab (inward), or
//      across the hole (outward).
//   2. The finger. A random face f of that facet is split at its centroid c (the tip, 2 faces
//      more), and the tip's three spokes at a quarter of their length (6 more): the tip's star is
//      f shrunk by 4 about c. The tip moves by depth along the push, and every vertex interior
//      to the facet whose star lies within R = 0.15 of c by depth·(1 − S(|v − c|/R)) (S the
//      quintic smoothstep). Every moved vertex has its whole star in the facet and moves along
//      the facet's normal, so no triangle's projection onto the facet changes: none becomes
//      degenerate, none flips.
//   3. Why it meets itself. The moved faces form a graph over the facet, zero on its border and
//      depth > 1 at the tip: it crosses the plane one unit away within the facet's projection,
//      which the facing wall's triangles tile; a crossing point lies on a finger triangle and a
//      wall triangle without a common vertex: an improper intersection, in every component.
//   4. Outward. Across a genus hole the finger adds volume; through a genus-0 block it removes at
//      most depth·(A(f)/48 + πR²) <= 4·(W/96 + 0.071) < W, the block's volume.
//   5. Curved when possible. The same vertices are also given the smooth family's targets (its
//      default roundness and amplitude), the finger added after the rounding; that mesh is kept
//      when find_self_intersection (exact) finds two faces that meet — so, in particular, no
//      degenerate face — otherwise the flat one of steps 1–4, which is proven.
//   6. Renumbered component by component (the finger's new vertices and faces after the others of
//      their component) and rebuilt from its triangles, as random_mesh's meshes are.
#include <fhr/generate/detail/smooth_map.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include <fhr/core/topology.hpp>
#include <fhr/generate/embedding.hpp>

namespace fhr::generate::detail {
namespace {

/// Faces the finger adds to each component: a face split (2) and three edge splits (2 each).
constexpr std::size_t finger_faces = 8;
/// The radius of the finger around its tip, in unit cells.
constexpr double finger_radius = 0.15;

/// A vertex the finger moves, by `height` along +axis.
struct Lift {
    VertexId v;
    int axis;
    double height;
};

/// All of v's faces lie in the plane coordinate[axis] = plane (and v is not on the boundary).
bool interior_to_facet(const TriMesh& m, VertexId v, int axis, double plane) {
    bool inside = true;
    m.for_each_outgoing(v, [&](HalfedgeId h) {
        inside = inside && !m.is_boundary(h) && m.position(m.to(h))[axis] == plane &&
                 m.position(m.to(m.next(h)))[axis] == plane;
    });
    return inside;
}

/// Steps 1 and 2 for the component with slab `slab` and faces `faces`: splits a random face of
/// the facet and appends the finger's moves to `lifts`.
void add_finger(TriMesh& m, const Slab& slab, const std::vector<FaceId>& faces, double depth, Random& rng,
                std::vector<Lift>& lifts) {
    // The facet: the −y wall (genus 0), or the first genus hole's −x wall, x = x0 + 1.
    const int axis = slab.genus == 0 ? 1 : 0;
    std::vector<FaceId> facet;
    for (FaceId f : faces) {
        const auto v = m.face_vertices(f);
        const double a = m.position(v[0])[axis];
        if (a == m.position(v[1])[axis] && a == m.position(v[2])[axis] &&
            (axis == 1 ? a == -0.5 * static_cast<double>(slab.H) : std::abs(a - (slab.x0 + 1)) < 0.25))
            facet.push_back(f);
    }
    const FaceId f = facet[rng.below(facet.size())];
    const auto corner = m.face_vertices(f);
    const double plane = m.position(corner[0])[axis];
    Vec3 c;
    for (int k = 0; k < 3; ++k)
        c[k] = (m.position(corner[0])[k] + m.position(corner[1])[k] + m.position(corner[2])[k]) / 3;
    c[axis] = plane;
    const VertexId tip = m.split_face(f, c);
    for (VertexId a : corner) {
        Vec3 q = c + 0.25 * (m.position(a) - c);
        q[axis] = plane;
        m.split_edge(TriMesh::edge(m.find_halfedge(tip, a)), q);
    }
    lifts.push_back({tip, axis, depth});
    // The vertices interior to the facet whose stars lie within the radius (step 2). Candidates
    // are found by walking out from the tip over vertices within the radius.
    std::vector<VertexId> stack{tip}, seen{tip};
    std::vector<char> visited(m.n_vertices(), 0);
    visited[tip.idx()] = 1;
    while (!stack.empty()) {
        const VertexId v = stack.back();
        stack.pop_back();
        m.for_each_outgoing(v, [&](HalfedgeId h) {
            const VertexId u = m.to(h);
            if (visited[u.idx()] || length(m.position(u) - c) >= finger_radius) return;
            visited[u.idx()] = 1;
            seen.push_back(u);
            stack.push_back(u);
        });
    }
    std::sort(seen.begin(), seen.end());
    for (VertexId v : seen) {
        if (v == tip || !interior_to_facet(m, v, axis, plane)) continue;
        bool star_inside = true;
        m.for_each_outgoing(
            v, [&](HalfedgeId h) { star_inside = star_inside && length(m.position(m.to(h)) - c) < finger_radius; });
        if (star_inside)
            lifts.push_back({v, axis, depth * (1 - smoothstep(length(m.position(v) - c) / finger_radius))});
    }
}

/// Step 6: m renumbered component by component, keeping the order within each, and rebuilt.
TriMesh in_component_order(const TriMesh& m) {
    const Components comps = connected_components(m);
    std::vector<std::uint32_t> order(m.n_vertices());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
        return comps.vertex_component[VertexId(a)] < comps.vertex_component[VertexId(b)];
    });
    std::vector<std::uint32_t> renumbered(m.n_vertices());
    std::vector<Vec3> positions(m.n_vertices());
    for (std::uint32_t k = 0; k < order.size(); ++k) {
        renumbered[order[k]] = k;
        positions[k] = m.position(VertexId(order[k]));
    }
    std::vector<Triangle> triangles = m.triangles();
    for (Triangle& t : triangles)
        for (std::uint32_t& v : t) v = renumbered[v];
    std::stable_sort(triangles.begin(), triangles.end(), [&](const Triangle& a, const Triangle& b) {
        return comps.vertex_component[VertexId(order[a[0]])] < comps.vertex_component[VertexId(order[b[0]])];
    });
    return TriMesh::from_triangles(std::move(positions), triangles);
}

}  // namespace

std::size_t immersed_min_faces(const RandomMeshOptions& o) {
    const std::size_t least = min_faces(o.genus, o.holes, o.components);
    if (!(o.knobs.depth >= 1.1 && o.knobs.depth <= 4))
        invalid("--depth must be in [1.1, 4] (got " + std::to_string(o.knobs.depth) + ")");
    return least + finger_faces * static_cast<std::size_t>(o.components);
}

TriMesh immersed_mesh(const RandomMeshOptions& o) {
    TriMesh m = base_block(o, o.faces - finger_faces * static_cast<std::size_t>(o.components));
    const Components comps = connected_components(m);
    const std::vector<Slab> slabs = block_slabs(m, o, comps.vertex_component);
    std::vector<std::vector<FaceId>> faces(slabs.size());
    for (FaceId f : m.faces()) faces[comps.vertex_component[m.face_vertices(f)[0]]].push_back(f);
    Random rng(family_seed(o.seed, Family::immersed));
    const FamilyKnobs smooth_defaults{};
    const Deformation deform(rng, smooth_defaults.amplitude);
    std::vector<Lift> lifts;
    for (std::size_t c = 0; c < slabs.size(); ++c) add_finger(m, slabs[c], faces[c], o.knobs.depth, rng, lifts);

    // Step 5: the curved mesh, kept when the exact check finds two faces that meet.
    const Components after = connected_components(m);
    std::vector<Vec3> flat = m.positions(), curved(m.n_vertices());
    std::vector<Vec3> offset(m.n_vertices(), Vec3::Zero());
    for (const Lift& l : lifts) {
        flat[l.v.idx()][l.axis] += l.height;
        offset[l.v.idx()][l.axis] = l.height;
    }
    for (VertexId v : m.vertices())
        curved[v.idx()] = deform(rounded(slabs[after.vertex_component[v]], smooth_defaults.roundness, m.position(v)) +
                                 offset[v.idx()]);
    for (VertexId v : m.vertices()) m.position(v) = curved[v.idx()];
    const auto pair = find_self_intersection(m);
    if (!pair || (*pair)[0] == (*pair)[1])
        for (VertexId v : m.vertices()) m.position(v) = flat[v.idx()];
    return in_component_order(m);
}

}  // namespace fhr::generate::detail
