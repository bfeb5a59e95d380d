// FHR generate — the degenerate family (beyond the paper): every coordinate on a coarse
// grid, so that many neighbouring triangles are exactly coplanar and many vertices lie exactly on
// the lines of other triangles' edges — as in meshes of CAD models and quantized scans — yet no
// triangle has zero area (that would be invalid input, spec/mesh.md). Such meshes are valid but
// hard for geometric predicates: every orient2d/orient3d zero is a real tie, not a rounding.
// The argument in full is paper_notes/generator.md, "The degenerate family"; in short:
//
//   1. Grid. The block of the recipe with exactly F faces; the grid spacing h is the largest power
//      of two not above min(1/2, ℓ/G), ℓ the block's mean edge length and G = grid_cells: every
//      grid coordinate is an exact dyadic number, and the block's facet planes (at multiples of
//      1/2) lie on the grid.
//   2. Snap. Every vertex to its nearest grid point (each coordinate rounded to a multiple of h,
//      exactly; a facet's constant coordinate is one already, so each vertex stays in its facets
//      and on its creases). This one edit of all vertices is checked as a whole with
//      find_self_intersection (exact, like the guard); if the snapped block is not embedded, the
//      snap starts again with h halved. It ends: once every vertex moves by less than half the
//      smallest altitude of the block's triangles, each facet stays triangulated by positively
//      oriented triangles, i.e. the surface stays the block's polyhedron (the notes).
//   3. Jitter by whole grid steps. Each vertex, in order, with probability 1/4, draws an axis and
//      a move of 1 to max(1, ⌊G/4⌋) grid steps either way along it, made if the vertex may move
//      along that axis (crease vertices only slide along their crease, the block's corners and a
//      few kept vertices stay) and EmbeddingGuard accepts it: moves within a facet keep its
//      triangles exactly coplanar and put vertices on grid lines, moves across it tilt them by
//      small integer slopes, so neighbours that were collinear become exactly coplanar tilted
//      faces.
//   4. Flips. Each edge, with probability 1/4, is flipped if its two faces are exactly coplanar
//      (orient3d = 0), TriMesh::is_flip_ok holds and the guard accepts the two new triangles.
//   5. Rebuild from the triangles, as the block does.
//
// Vertex moves and flips keep the face count, the topology and the order of the components; the
// guard keeps the mesh embedded and refuses zero-area triangles, so the result is embedded with no
// zero area by construction. Kept features (kept_features below) give every mesh an exactly
// coplanar pair of faces and, when its block has three vertices on an axis-parallel lattice line,
// a vertex exactly on the line of another face's edge. Exactness: h is a power of two and every
// coordinate a multiple of it far below 2^53·h, so the rounding to the grid, the moves and their
// sums are exact.
#include <fhr/generate/detail/family.hpp>

#include <array>
#include <cmath>
#include <optional>
#include <vector>

#include <fhr/core/detail/predicates.hpp>
#include <fhr/generate/embedding.hpp>

namespace fhr::generate::detail {
namespace {

/// The mean edge length, summed in edge order.
double mean_edge_length(const TriMesh& m) {
    double sum = 0;
    for (EdgeId e : m.edges()) {
        const HalfedgeId h = TriMesh::halfedge(e, 0);
        sum += length(m.position(m.to(h)) - m.position(m.from(h)));
    }
    return sum / static_cast<double>(m.n_edges());
}

/// Step 1: the largest power of two not above min(1/2, ℓ/G).
double grid_spacing(const TriMesh& m, int grid_cells) {
    const double target = mean_edge_length(m) / grid_cells;
    double h = 0.5;
    while (h > target) h *= 0.5;
    return h;
}

/// Moves vertex v to p if the guard accepts the new triangles of its faces.
void guarded_move(TriMesh& m, EmbeddingGuard& guard, VertexId v, const Vec3& p) {
    std::vector<FaceId> faces;
    std::vector<TriangleAt> added;
    m.for_each_outgoing(v, [&](HalfedgeId h) {
        if (m.is_boundary(h)) return;
        faces.push_back(m.face(h));
        TriangleAt t = triangle_at(m, m.face(h));
        for (int k = 0; k < 3; ++k)
            if (t.v[k] == v) t.p[k] = p;
        added.push_back(t);
    });
    if (!guard.accepts(m, faces, added)) return;
    for (FaceId f : faces) guard.remove(m, f);
    m.position(v) = p;
    for (FaceId f : faces) guard.insert(m, f);
}

/// Step 2: the block with every vertex at its nearest grid point (each coordinate rounded to a
/// multiple of h, exactly: h is a power of two), if that is still embedded.
std::optional<TriMesh> snapped(const TriMesh& block, double h) {
    TriMesh m = block;
    for (VertexId v : m.vertices())
        for (int k = 0; k < 3; ++k) m.position(v)[k] = std::round(m.position(v)[k] / h) * h;
    if (find_self_intersection(m)) return std::nullopt;
    return m;
}

/// Step 3's fixed features of the snapped block, which every mesh of the family then has: the
/// four vertices of the first pair of exactly coplanar faces (in edge order: every facet of the
/// block has one), and the first edge ab parallel to an axis with a neighbour w of b, not a
/// vertex of ab's faces, on its line (a lattice line of the block: snapping keeps equal
/// coordinates equal, so the three stay collinear). Their vertices never move, and ab is never
/// flipped: the coplanar pair stays coplanar (a flip only ever joins coplanar faces), and w stays
/// on the line of ab, whose faces cannot contain w (they would have zero area).
struct Kept {
    std::vector<char> vertex;
    EdgeId edge;
};

Kept kept_features(const TriMesh& m) {
    Kept kept{std::vector<char>(m.n_vertices(), 0), EdgeId()};
    for (EdgeId e : m.edges()) {
        if (m.is_boundary(e)) continue;
        const HalfedgeId h0 = TriMesh::halfedge(e, 0), h1 = TriMesh::halfedge(e, 1);
        const VertexId quad[4] = {m.from(h0), m.to(h0), m.to(m.next(h0)), m.to(m.next(h1))};
        if (orient3d(m.position(quad[0]), m.position(quad[1]), m.position(quad[2]), m.position(quad[3])) != 0) continue;
        for (VertexId v : quad) kept.vertex[v.idx()] = 1;
        break;
    }
    const auto equal_coordinates = [&](VertexId a, VertexId b) {
        int equal = 0;
        for (int k = 0; k < 3; ++k) equal += m.position(a)[k] == m.position(b)[k];
        return equal;
    };
    for (EdgeId e : m.edges()) {
        const HalfedgeId h = TriMesh::halfedge(e, 0);
        const VertexId a = m.from(h), b = m.to(h);
        if (equal_coordinates(a, b) != 2) continue;
        const VertexId c = m.is_boundary(h) ? VertexId() : m.to(m.next(h));
        const VertexId d = m.is_boundary(TriMesh::twin(h)) ? VertexId() : m.to(m.next(TriMesh::twin(h)));
        VertexId w;
        m.for_each_outgoing(b, [&](HalfedgeId g) {
            const VertexId x = m.to(g);
            if (!w.valid() && x != a && x != c && x != d && equal_coordinates(a, x) == 2 &&
                equal_coordinates(b, x) == 2 && collinear(m.position(a), m.position(b), m.position(x)))
                w = x;
        });
        if (!w.valid()) continue;
        for (VertexId v : {a, b, w}) kept.vertex[v.idx()] = 1;
        kept.edge = e;
        break;
    }
    return kept;
}

/// The axes along which each vertex of the snapped block may move (its faces are still in the
/// block's axis-aligned facets): any axis when all its faces lie in one facet, else the axes no
/// normal of its faces has, so crease vertices only slide along their crease (the block's creases
/// stay straight lines of collinear vertices) and the block's corners stay; kept vertices none.
std::vector<std::array<bool, 3>> free_axes(const TriMesh& m, const Kept& kept) {
    std::vector<std::array<bool, 3>> free(m.n_vertices());
    for (VertexId v : m.vertices()) {
        std::array<bool, 3> normal_axis{false, false, false};
        m.for_each_outgoing(v, [&](HalfedgeId g) {
            if (m.is_boundary(g)) return;
            const auto t = m.face_vertices(m.face(g));
            const Vec3 n = normal(m.position(t[0]), m.position(t[1]), m.position(t[2]));
            for (int k = 0; k < 3; ++k) normal_axis[k] = normal_axis[k] || n[k] != 0;
        });
        const int count = normal_axis[0] + normal_axis[1] + normal_axis[2];
        for (int k = 0; k < 3; ++k) free[v.idx()][k] = !kept.vertex[v.idx()] && (count == 1 || !normal_axis[k]);
    }
    return free;
}

void check_knobs(const FamilyKnobs& k) {
    if (k.grid_cells < 2 || k.grid_cells > 1024)
        invalid("--grid-cells must be in [2, 1024] (got " + std::to_string(k.grid_cells) + ")");
}

}  // namespace

std::size_t degenerate_min_faces(const RandomMeshOptions& options) {
    check_knobs(options.knobs);
    return min_faces(options.genus, options.holes, options.components);
}

TriMesh degenerate_mesh(const RandomMeshOptions& options) {
    const TriMesh block = base_block(options, options.faces);
    double h = grid_spacing(block, options.knobs.grid_cells);
    std::optional<TriMesh> snap = snapped(block, h);
    while (!snap) snap = snapped(block, h *= 0.5);
    TriMesh& m = *snap;
    Random rng(family_seed(options.seed, Family::degenerate));
    EmbeddingGuard guard(m, 0);
    // Step 3: jitter by whole grid steps along one axis, where the vertex is free to move.
    const Kept kept = kept_features(m);
    const std::vector<std::array<bool, 3>> free = free_axes(m, kept);
    const std::uint64_t steps = static_cast<std::uint64_t>(std::max(1, options.knobs.grid_cells / 4));
    for (VertexId v : m.vertices()) {
        if (rng.below(4) != 0) continue;
        const auto axis = static_cast<int>(rng.below(3));
        const double step = static_cast<double>(1 + rng.below(steps)) * h;
        const bool down = rng.coin();
        if (!free[v.idx()][axis]) continue;
        Vec3 p = m.position(v);
        p[axis] += down ? -step : step;
        guarded_move(m, guard, v, p);
    }
    // Step 4: flips of exactly coplanar pairs.
    for (EdgeId e : m.edges()) {
        if (rng.below(4) != 0 || e == kept.edge || !m.is_flip_ok(e)) continue;
        const HalfedgeId h0 = TriMesh::halfedge(e, 0), h1 = TriMesh::halfedge(e, 1);
        const VertexId a = m.from(h0), b = m.to(h0), c = m.to(m.next(h0)), d = m.to(m.next(h1));
        if (orient3d(m.position(a), m.position(b), m.position(c), m.position(d)) != 0) continue;
        // flip makes (a, d, c) and (d, b, c).
        const std::array<FaceId, 2> removed{m.face(h0), m.face(h1)};
        const std::array<TriangleAt, 2> added{TriangleAt{{a, d, c}, {m.position(a), m.position(d), m.position(c)}},
                                              TriangleAt{{d, b, c}, {m.position(d), m.position(b), m.position(c)}}};
        if (!guard.accepts(m, removed, added)) continue;
        for (FaceId f : removed) guard.remove(m, f);
        m.flip(e);
        for (FaceId f : removed) guard.insert(m, f);
    }
    // Step 5: rebuilt from its triangles (the flips changed the halfedges' order).
    return TriMesh::from_triangles(m.positions(), m.triangles());
}

}  // namespace fhr::generate::detail
