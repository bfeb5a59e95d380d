// FHR generate — the block, the base of every family (see random_mesh.hpp for the families): random
// orientable manifold meshes of genus g with an exact face count: closed
// and connected ones are the input class T of the paper (§1); boundary loops (holes) and several
// components are beyond the paper. For the property tests, the fuzzers and
// `fhr generate`. The full argument is in paper_notes/generator.md; in short, per component:
//
//   1. Block: the solid (2g+1) x 3 x 1 unit cells with g unit holes in a row (a unit cube for g = 0),
//      made longer when it has too few cells for its boundary loops. Hole j is the top (j even) or
//      bottom (j odd) face of the j/2-th cell with even coordinates: those faces are pairwise
//      vertex-disjoint. The block is cut into a lattice of nx x ny x nz boxes per unit cell, nx, ny,
//      nz in {r, r+1}; its surface without the holes has Q(nx, ny, nz) lattice rectangles.
//      Resolution: the largest (nx, ny, nz) on the chain (1,1,1) → (2,1,1) → (2,2,1) → (2,2,2) →
//      (3,2,2) → … with 2Q + t <= F (t = F mod 2 = 1 keeps one triangle of hole 0). One step
//      multiplies Q by at most 2, so F − t < 4Q.
//   2. Triangulate: k = (F − t)/2 − Q randomly chosen rectangles get a centre vertex (4 triangles),
//      the others a random diagonal (2 triangles): exactly 2(Q − k) + 4k + t = F faces, every
//      corner >= 26.5°.
//   3. Randomize the connectivity without changing the surface, in one sweep over the edges:
//      flips of coplanar pairs, and pairs "split an edge at its midpoint, then half-edge collapse
//      a nearby vertex interior to a flat facet" (face count unchanged; if no collapse is allowed
//      the split is undone). Every edit is kept only if all triangles it creates keep their
//      corners >= 20° and lie in the facet of the triangles they replace (normals unchanged), so
//      the surface stays the embedded polyhedron of step 1 and the face count never drifts.
//      Boundary edges and boundary vertices are never edited, so the holes keep their outlines.
//   4. Jitter (noise > 0): each vertex moves by at most noise × (mean length of its edges before
//      the jitter) in a random direction; a move is refused if a triangle would get a corner < 20°
//      or tilt by more than 60° from its un-jittered normal.
//   5. Components are made one after the other from the same random stream, component c ≥ 1
//      moved along +x to lie at least 1 beyond the ones before it; then the mesh is rebuilt from
//      the triangles: the result is exactly what reading its written file gives.
//
// Reproducibility: std::mt19937_64 is fully specified by the standard, our uniform mappings are
// our own (the std::uniform_*_distribution outputs differ between libraries), and every decision
// uses only +, −, ×, / and sqrt in a fixed order (correctly rounded in IEEE double arithmetic;
// the project builds with -ffp-contract=off, so no FMA changes a rounding), so the output is
// bit-identical on every conforming compiler.
#include <fhr/generate/detail/family.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <fhr/core/errors.hpp>

namespace fhr::generate {
namespace {

using detail::cross;
using detail::dot;
using detail::invalid;
using detail::length;
using detail::normal;
using detail::Random;

// sin and cos of min_corner_angle_degrees (20°), correctly rounded.
constexpr double sin_min_angle = 0.34202014332566873;
constexpr double cos_min_angle = 0.93969262078590838;

/// Every corner angle φ of (a, b, c) is >= 20°: sin(φ − 20°) >= 0, i.e.
/// |u × v| cos 20° − (u · v) sin 20° >= 0 for the two edge vectors u, v at the corner. A
/// triangle passing this is far from degenerate (its corners are not collinear).
bool well_shaped(const Vec3& a, const Vec3& b, const Vec3& c) {
    auto corner_ok = [](const Vec3& u, const Vec3& v) {
        const double s = length(cross(u, v));
        return s > 0 && s * cos_min_angle - dot(u, v) * sin_min_angle >= 0;
    };
    return corner_ok(b - a, c - a) && corner_ok(c - b, a - b) && corner_ok(a - c, b - c);
}

/// Angle between n and reference at most acos(cos_limit) (neither may be zero).
bool within_angle(const Vec3& n, const Vec3& reference, double cos_limit) {
    return dot(n, reference) >= cos_limit * length(n) * length(reference);
}

/// Before jitter every facet of the block is axis-aligned, and all edits keep its vertices'
/// constant coordinate exactly (midpoints of equal numbers are exact), so normals of coplanar
/// triangles have exactly the same direction and this test is exact for them; a tilt of more
/// than ~1.4e−6 rad fails it.
constexpr double cos_coplanar = 1 - 1e-12;
/// Jitter may tilt a triangle by at most 60° from its un-jittered normal (no fold-over).
constexpr double cos_max_tilt = 0.5;

// --- step 1: the block and its resolution ----------------------------------------------------

struct Block {
    int genus;
    int holes;                                // boundary loops cut into this block
    bool keep_half;                           // hole 0 keeps one triangle of its corner pixel: an odd face count
    std::uint64_t H, W;                       // unit cells along y and x; the block is 1 unit thick (z)
    std::array<std::uint64_t, 3> n{1, 1, 1};  // lattice boxes per unit cell along x, y, z

    Block(int g, int b, bool half) : genus(g), holes(b), keep_half(half), H(g == 0 ? 1 : 3), W(width(g, b, H)) {}

    /// Rows of cells with an even y coordinate (1 or 2): the cells that can hold holes.
    static std::uint64_t even_rows(std::uint64_t h) { return (h + 1) / 2; }
    /// 2g + 1 cells for the genus (1 for g = 0), or more when the cells with even coordinates,
    /// two holes each (top and bottom), are too few for b holes.
    static std::uint64_t width(int g, int b, std::uint64_t h) {
        const std::uint64_t cells = (static_cast<std::uint64_t>(b) + 1) / 2;
        const std::uint64_t columns = (cells + even_rows(h) - 1) / even_rows(h);
        return std::max(g == 0 ? 1 : 2 * static_cast<std::uint64_t>(g) + 1, columns == 0 ? 1 : 2 * columns - 1);
    }

    // The g holes of the genus are the cells (1, 1), (3, 1), …, (2g − 1, 1).
    bool solid_cell(std::uint64_t cx, std::uint64_t cy) const {
        return cx < W && cy < H && !(genus > 0 && cy == 1 && cx % 2 == 1 && cx < 2 * static_cast<std::uint64_t>(genus));
    }
    /// Boundary loop j is the top (j even) or bottom (j odd) face of cell j/2 in the list (0, 0),
    /// (0, 2), (2, 0), (2, 2), … of the cells with even coordinates, column by column. Two such
    /// faces share no vertex: different cells are at least one cell apart, and top and bottom
    /// are one unit apart.
    bool hole_cell(std::uint64_t cx, std::uint64_t cy, bool top) const {
        if (cx % 2 != 0 || cy % 2 != 0) return false;
        const std::uint64_t index = 2 * ((cx / 2) * even_rows(H) + cy / 2) + (top ? 0 : 1);
        return index < static_cast<std::uint64_t>(holes);
    }
    std::uint64_t px() const { return W * n[0]; }  // pixels of the footprint along x
    std::uint64_t py() const { return H * n[1]; }
    bool solid_pixel(std::int64_t i, std::int64_t j) const {
        return i >= 0 && j >= 0 &&
               solid_cell(static_cast<std::uint64_t>(i) / n[0], static_cast<std::uint64_t>(j) / n[1]);
    }
    /// Lattice rectangles on the surface, holes excluded: top and bottom, outer walls, hole walls.
    /// A sum of monomials of degree <= 1 in each of m[0], m[1], m[2] with non-negative
    /// coefficients (the b holes lie in the 2(WH − g) top and bottom cells).
    std::uint64_t quad_count(const std::array<std::uint64_t, 3>& m) const {
        const std::uint64_t g = static_cast<std::uint64_t>(genus), b = static_cast<std::uint64_t>(holes);
        return m[0] * m[1] * (2 * (W * H - g) - b) + 2 * m[2] * (W * m[0] + H * m[1]) + 2 * g * m[2] * (m[0] + m[1]);
    }
    std::uint64_t quad_count() const { return quad_count(n); }

    /// The largest resolution on the chain (1,1,1) → (2,1,1) → (2,2,1) → (2,2,2) → … with
    /// 2Q + t <= faces (t = keep_half). Theorem: Q is a sum of monomials of degree <= 1 in each
    /// of nx, ny, nz, so raising one of them from r to r + 1 multiplies Q by at most
    /// (r + 1)/r <= 2; hence the next resolution's 2Q' + t > faces gives faces − t < 4Q, i.e.
    /// fewer than Q centre splits are needed.
    void choose_resolution(std::uint64_t faces) {
        for (std::size_t axis = 0;; axis = (axis + 1) % 3) {
            std::array<std::uint64_t, 3> next = n;
            ++next[axis];
            if (2 * quad_count(next) + (keep_half ? 1 : 0) > faces) return;
            n = next;
        }
    }
};

/// The surface vertices of the block, numbered column by column: lattice column (i, j) holds
/// the bottom and top vertex when it touches a solid pixel, and every layer's vertex when it is
/// on the footprint's outline (touching solid and empty pixels), where the walls are.
class Lattice {
public:
    explicit Lattice(const Block& b) : b_(b), first_((b.px() + 1) * (b.py() + 1) + 1, 0) {
        const std::uint64_t nz = b.n[2];
        for (std::uint64_t i = 0; i <= b.px(); ++i)
            for (std::uint64_t j = 0; j <= b.py(); ++j) {
                int solid = 0;
                for (std::int64_t di = -1; di <= 0; ++di)
                    for (std::int64_t dj = -1; dj <= 0; ++dj)
                        solid += b.solid_pixel(static_cast<std::int64_t>(i) + di, static_cast<std::int64_t>(j) + dj);
                const std::uint64_t count = solid == 0 ? 0 : solid == 4 ? 2 : nz + 1;
                first_[column(i, j) + 1] = first_[column(i, j)] + count;
            }
    }
    std::uint64_t size() const { return first_.back(); }
    std::uint32_t index(std::uint64_t i, std::uint64_t j, std::uint64_t k) const {
        const std::uint64_t c = column(i, j);
        const std::uint64_t count = first_[c + 1] - first_[c];
        return static_cast<std::uint32_t>(first_[c] + (count == 2 ? (k == 0 ? 0 : 1) : k));
    }
    /// The block, centred at the origin; a vertex's constant coordinate on its facet depends
    /// only on that lattice index, so facets are exactly planar.
    Vec3 position(std::uint64_t i, std::uint64_t j, std::uint64_t k) const {
        return Vec3(static_cast<double>(i) / static_cast<double>(b_.n[0]) - 0.5 * static_cast<double>(b_.W),
                    static_cast<double>(j) / static_cast<double>(b_.n[1]) - 0.5 * static_cast<double>(b_.H),
                    static_cast<double>(k) / static_cast<double>(b_.n[2]) - 0.5);
    }

private:
    const Block& b_;
    std::vector<std::uint64_t> first_;  // first vertex of each column, and the total at the end
    std::uint64_t column(std::uint64_t i, std::uint64_t j) const { return i * (b_.py() + 1) + j; }
};

using Corner = std::array<std::uint64_t, 3>;

/// A surface rectangle of the block is solid, or lies in a hole: wholly (no triangle), or as
/// hole 0's corner pixel when that hole keeps one triangle (keep_half).
enum class QuadKind { solid, hole, half };

/// Calls quad(p, u, v, kind) for every surface rectangle p, p+u, p+u+v, p+v of the block, with
/// u × v its outward normal, so the corners run counter-clockwise seen from outside.
template <class F>
void for_each_quad(const Block& b, F&& quad) {
    const Corner X{1, 0, 0}, Y{0, 1, 0}, Z{0, 0, 1};
    const std::uint64_t nz = b.n[2];
    for (std::uint64_t i = 0; i < b.px(); ++i)
        for (std::uint64_t j = 0; j < b.py(); ++j) {
            const auto si = static_cast<std::int64_t>(i), sj = static_cast<std::int64_t>(j);
            if (!b.solid_pixel(si, sj)) continue;
            const std::uint64_t cx = i / b.n[0], cy = j / b.n[1];
            const QuadKind top = !b.hole_cell(cx, cy, true)        ? QuadKind::solid
                                 : b.keep_half && i == 0 && j == 0 ? QuadKind::half
                                                                   : QuadKind::hole;
            quad(Corner{i, j, nz}, X, Y, top);                                                           // top, +z
            quad(Corner{i, j, 0}, Y, X, b.hole_cell(cx, cy, false) ? QuadKind::hole : QuadKind::solid);  // bottom, −z
            const bool wall[4] = {!b.solid_pixel(si + 1, sj), !b.solid_pixel(si - 1, sj), !b.solid_pixel(si, sj + 1),
                                  !b.solid_pixel(si, sj - 1)};
            for (std::uint64_t k = 0; k < nz && (wall[0] || wall[1] || wall[2] || wall[3]); ++k) {
                if (wall[0]) quad(Corner{i + 1, j, k}, Y, Z, QuadKind::solid);  // +x
                if (wall[1]) quad(Corner{i, j, k}, Z, Y, QuadKind::solid);      // −x
                if (wall[2]) quad(Corner{i, j + 1, k}, Z, X, QuadKind::solid);  // +y
                if (wall[3]) quad(Corner{i, j, k}, X, Z, QuadKind::solid);      // −y
            }
        }
}

// --- step 2: triangulate --------------------------------------------------------------------

/// Drops the vertices no triangle uses (the lattice vertices inside a hole), keeping the order
/// of the others; without holes every vertex is used and nothing changes.
void drop_unused_vertices(std::vector<Vec3>& positions, std::vector<Triangle>& triangles) {
    constexpr std::uint32_t unused = UINT32_MAX;
    std::vector<std::uint32_t> renumbered(positions.size(), unused);
    for (const Triangle& t : triangles)
        for (std::uint32_t v : t) renumbered[v] = 0;
    std::uint32_t kept = 0;
    for (std::size_t v = 0; v < positions.size(); ++v)
        if (renumbered[v] != unused) {
            renumbered[v] = kept;
            positions[kept++] = positions[v];
        }
    positions.resize(kept);
    for (Triangle& t : triangles)
        for (std::uint32_t& v : t) v = renumbered[v];
}

TriMesh triangulated_block(const Block& b, std::uint64_t faces, Random& rng) {
    const Lattice lattice(b);
    const std::uint64_t n_quads = b.quad_count();                            // the solid ones
    std::uint64_t to_split = (faces - (b.keep_half ? 1 : 0)) / 2 - n_quads;  // centre splits still to place
    std::uint64_t quads_left = n_quads;
    std::vector<Vec3> positions;
    positions.reserve(lattice.size() + to_split);
    positions.resize(lattice.size());
    std::vector<Triangle> triangles;
    triangles.reserve(faces);
    for_each_quad(b, [&](const Corner& p, const Corner& u, const Corner& v, QuadKind kind) {
        if (kind == QuadKind::hole) return;
        std::array<std::uint32_t, 4> c;
        for (std::size_t q = 0; q < 4; ++q) {
            const std::uint64_t su = q == 1 || q == 2, sv = q >= 2;
            const Corner l{p[0] + su * u[0] + sv * v[0], p[1] + su * u[1] + sv * v[1], p[2] + su * u[2] + sv * v[2]};
            c[q] = lattice.index(l[0], l[1], l[2]);
            positions[c[q]] = lattice.position(l[0], l[1], l[2]);
        }
        if (kind == QuadKind::half) {
            // The triangle at the cell's corner p: p becomes interior, the loop cuts across.
            triangles.push_back({c[0], c[1], c[3]});
            return;
        }
        // Selection sampling (Knuth, TAOCP 3.4.2, Algorithm S): a uniform k-subset of the quads.
        if (rng.below(quads_left--) < to_split) {
            --to_split;
            const auto m = static_cast<std::uint32_t>(positions.size());
            positions.push_back(0.5 * (positions[c[0]] + positions[c[2]]));
            for (std::size_t q = 0; q < 4; ++q) triangles.push_back({c[q], c[(q + 1) % 4], m});
        } else if (rng.coin()) {
            triangles.push_back({c[0], c[1], c[2]});
            triangles.push_back({c[0], c[2], c[3]});
        } else {
            triangles.push_back({c[1], c[2], c[3]});
            triangles.push_back({c[1], c[3], c[0]});
        }
    });
    drop_unused_vertices(positions, triangles);
    return TriMesh::from_triangles(std::move(positions), triangles);
}

// --- step 3: random connectivity edits on the fixed surface ----------------------------------

class Randomizer {
public:
    Randomizer(TriMesh& m, Random& rng) : m_(m), rng_(rng) {}

    /// One sweep over the edges in index order (neighbouring edges have close indices, so the
    /// sweep walks the memory in order): each edge is flipped with probability 1/2, or split
    /// and paired with a collapse nearby with probability 1/8, when the edit keeps the shape.
    /// Every live edge draws its number, a boundary edge too, but a boundary edge is never edited.
    void run() {
        const std::size_t n = m_.n_edges();
        for (std::size_t i = 0; i < n; ++i) {
            const EdgeId e(static_cast<EdgeId::Index>(i));
            if (m_.is_deleted(e)) continue;
            const std::uint64_t pick = rng_.below(8);
            if (pick < 4 && flip_keeps_shape(e)) m_.flip(e);
            if (pick == 4) split_then_collapse(e);
        }
    }

private:
    static constexpr int max_attempts = 16;  // collapse candidates tried around a split
    TriMesh& m_;
    Random& rng_;

    const Vec3& pos(VertexId v) const { return m_.position(v); }

    HalfedgeId random_outgoing(VertexId v) {
        std::uint64_t steps = rng_.below(m_.valence(v));
        HalfedgeId h = m_.out(v);
        while (steps-- > 0) h = m_.cw_rotated(h);
        return h;
    }

    // Faces (a, b, c) and (b, a, d) of e become (a, d, c) and (d, b, c): allowed when the four
    // points are coplanar and the quadrilateral is strictly convex (new normals unchanged).
    bool flip_keeps_shape(EdgeId e) const {
        if (m_.is_boundary(e)) return false;
        const HalfedgeId h = TriMesh::halfedge(e, 0), o = TriMesh::halfedge(e, 1);
        const Vec3 &a = pos(m_.from(h)), &b = pos(m_.to(h)), &c = pos(m_.to(m_.next(h))), &d = pos(m_.to(m_.next(o)));
        const Vec3 n = normal(a, b, c);
        return within_angle(normal(b, a, d), n, cos_coplanar) && within_angle(normal(a, d, c), n, cos_coplanar) &&
               within_angle(normal(d, b, c), n, cos_coplanar) && well_shaped(a, d, c) && well_shaped(d, b, c) &&
               m_.is_flip_ok(e);
    }

    // The midpoint of (a, b) lies exactly on the facet (or on the crease) of both faces of e,
    // so the four new triangles keep their faces' normals; only their shape is checked.
    bool split_keeps_shape(EdgeId e, const Vec3& mid) const {
        const HalfedgeId h = TriMesh::halfedge(e, 0), o = TriMesh::halfedge(e, 1);
        const Vec3 &a = pos(m_.from(h)), &b = pos(m_.to(h)), &c = pos(m_.to(m_.next(h))), &d = pos(m_.to(m_.next(o)));
        return well_shaped(a, mid, c) && well_shaped(mid, b, c) && well_shaped(b, mid, d) && well_shaped(mid, a, d);
    }

    // from(h) must be interior to a flat facet (not on the boundary, all its faces coplanar), and
    // its faces other than the two removed ones, moved to to(h), must stay in that facet and be
    // well shaped: then the collapse only re-triangulates the facet. The link condition keeps the
    // topology (to(h) may be on the boundary: the collapse only moves an interior vertex).
    // Boundary vertices are recognised by their halfedges, not by out(): collapse() does not keep
    // a boundary vertex's out() on its boundary halfedge.
    bool collapse_keeps_shape(HalfedgeId h) const {
        const VertexId v0 = m_.from(h);
        const Vec3& target = pos(m_.to(h));
        const Vec3 n = normal(pos(v0), target, pos(m_.to(m_.next(h))));
        const FaceId gone0 = m_.face(h), gone1 = m_.face(TriMesh::twin(h));
        bool ok = true;
        m_.for_each_outgoing(v0, [&](HalfedgeId g) {
            const Vec3 &b = pos(m_.to(g)), &c = pos(m_.to(m_.next(g)));
            ok = ok && !m_.is_boundary(g) && within_angle(normal(pos(v0), b, c), n, cos_coplanar);
            if (ok && m_.face(g) != gone0 && m_.face(g) != gone1)
                ok = within_angle(normal(target, b, c), n, cos_coplanar) && well_shaped(target, b, c);
        });
        return ok && m_.is_collapse_ok(h);
    }

    // Splits e at its midpoint, then collapses a random halfedge leaving a random neighbour of
    // the new vertex, so that the face count and the local vertex density stay the same.
    void split_then_collapse(EdgeId e) {
        if (m_.is_boundary(e)) return;  // a split would add one face, a collapse then remove two
        const HalfedgeId h = TriMesh::halfedge(e, 0);
        const Vec3 mid = 0.5 * (pos(m_.from(h)) + pos(m_.to(h)));
        if (!split_keeps_shape(e, mid)) return;
        const VertexId added = m_.split_edge(e, mid);
        for (int t = 0; t < max_attempts; ++t) {
            const HalfedgeId g = random_outgoing(m_.to(random_outgoing(added)));
            if (collapse_keeps_shape(g)) {
                m_.collapse(g);
                return;
            }
        }
        // No candidate found: undo the split by collapsing the new vertex onto the old end of its
        // outgoing halfedge. Theorem: its only common neighbours with that end are the two opposite
        // vertices (link condition), and the collapse restores the two original triangles exactly.
        m_.collapse(m_.out(added));
    }
};

// --- step 4: jitter ---------------------------------------------------------------------------

void jitter(TriMesh& m, double noise, Random& rng) {
    // Normals and step lengths of the un-jittered mesh, so no move depends on an earlier one's size.
    std::vector<Vec3> reference(m.n_faces());
    for (FaceId f : m.faces()) {
        const auto v = m.face_vertices(f);
        reference[f.idx()] = normal(m.position(v[0]), m.position(v[1]), m.position(v[2]));
    }
    std::vector<double> step(m.n_vertices());
    for (VertexId v : m.vertices()) {
        double sum = 0;
        std::size_t count = 0;
        m.for_each_outgoing(v, [&](HalfedgeId h) {
            sum += length(m.position(m.to(h)) - m.position(v));
            ++count;
        });
        step[v.idx()] = noise * sum / static_cast<double>(count);
    }
    for (VertexId v : m.vertices()) {
        Vec3 direction;  // uniform in the unit ball (rejection from the cube)
        do {
            for (int k = 0; k < 3; ++k) direction[k] = rng.symmetric();  // in order (not as arguments)
        } while (dot(direction, direction) > 1);
        const Vec3 moved = m.position(v) + step[v.idx()] * direction;
        bool ok = true;
        m.for_each_outgoing(v, [&](HalfedgeId h) {
            if (m.is_boundary(h)) return;  // no triangle on the left of h: a hole
            const Vec3 &b = m.position(m.to(h)), &c = m.position(m.to(m.next(h)));
            ok = ok && well_shaped(moved, b, c) &&
                 within_angle(normal(moved, b, c), reference[m.face(h).idx()], cos_max_tilt);
        });
        if (ok) m.position(v) = moved;
    }
}

// --- components -------------------------------------------------------------------------------

/// Component c's share of a total over C components: ⌊total/C⌋, plus one for the first total mod C.
int share(int total, int components, int c) { return total / components + (c < total % components ? 1 : 0); }

/// 2Q at the coarsest resolution: the fewest faces of a component (always even).
std::uint64_t component_min_faces(int genus, int holes) { return 2 * Block(genus, holes, false).quad_count(); }

void check_counts(int genus, int holes, int components) {
    if (genus < 0) invalid("the genus must be >= 0 (got " + std::to_string(genus) + ")");
    if (holes < 0 || holes > max_holes)
        invalid("the number of holes must be in [0, " + std::to_string(max_holes) + "] (got " + std::to_string(holes) +
                ")");
    if (components < 1 || components > max_components)
        invalid("the number of components must be in [1, " + std::to_string(max_components) + "] (got " +
                std::to_string(components) + ")");
}

/// Steps 1–4 for one component with an exact face count (odd only when it has holes).
TriMesh component_mesh(int genus, int holes, std::uint64_t faces, double noise, Random& rng) {
    Block block(genus, holes, faces % 2 == 1);
    block.choose_resolution(faces);
    TriMesh mesh = triangulated_block(block, faces, rng);
    Randomizer(mesh, rng).run();
    mesh.compact();
    if (noise > 0) jitter(mesh, noise, rng);
    return mesh;
}

}  // namespace

/// The block family (steps 1–5 above), the options checked by check_recipe.
TriMesh detail::block_mesh(const RandomMeshOptions& options) {
    const std::size_t faces = options.faces, least = min_faces(options.genus, options.holes, options.components);
    // Faces: every component gets its minimum, then the pairs of faces left over are dealt out
    // as evenly as possible (the first ones get one pair more), and an odd last face goes to
    // component 0, which has a hole whenever F may be odd.
    const int components = options.components;
    const std::uint64_t surplus = faces - least, pairs = surplus / 2, count = static_cast<std::uint64_t>(components);
    Random rng(options.seed);
    std::vector<Vec3> positions;
    std::vector<Triangle> triangles;
    double right = -std::numeric_limits<double>::infinity();  // the largest x of the components so far
    for (int c = 0; c < components; ++c) {
        const int genus = share(options.genus, components, c), holes = share(options.holes, components, c);
        const std::uint64_t extra =
            2 * (pairs / count + (static_cast<std::uint64_t>(c) < pairs % count ? 1 : 0)) + (c == 0 ? surplus % 2 : 0);
        const TriMesh part =
            component_mesh(genus, holes, component_min_faces(genus, holes) + extra, options.noise, rng);
        // Component 0 stays centred at the origin; component c >= 1 is moved along +x so that its
        // smallest x is right + 1: bounding boxes 1 apart (up to a rounding), so no two
        // components meet.
        double shift = 0;
        if (c > 0) {
            double left = part.positions().front().x();
            for (const Vec3& p : part.positions()) left = std::min(left, p.x());
            shift = (right + 1) - left;
        }
        const auto first = static_cast<std::uint32_t>(positions.size());
        for (Vec3 p : part.positions()) {
            if (c > 0) p.x() += shift;  // not for c = 0: −0 + 0 would change a bit
            right = std::max(right, p.x());
            positions.push_back(p);
        }
        for (Triangle t : part.triangles()) {
            for (std::uint32_t& v : t) v += first;
            triangles.push_back(t);
        }
    }
    // Step 5: rebuilt from its own triangles, the mesh is exactly the one a reader gives for its
    // written file (same halfedge numbering), so a failing test reproduces from the file.
    return TriMesh::from_triangles(std::move(positions), triangles);
}

std::size_t min_faces(int genus, int holes, int components) {
    check_counts(genus, holes, components);
    std::uint64_t sum = 0;
    for (int c = 0; c < components; ++c)
        sum += component_min_faces(share(genus, components, c), share(holes, components, c));
    return sum;
}

std::size_t detail::block_min_faces(const RandomMeshOptions& options) {
    return min_faces(options.genus, options.holes, options.components);
}

void detail::check_recipe(const RandomMeshOptions& options, std::size_t (*least_faces)(const RandomMeshOptions&)) {
    if (!(options.noise >= 0 && options.noise < 0.5))
        invalid("the noise must be in [0, 0.5) (got " + std::to_string(options.noise) + ")");
    if (options.noise != 0 && options.family != Family::block)
        invalid(std::string("the noise is a knob of the block family only (the ") + family_name(options.family) +
                " family starts from a block without noise)");
    const std::size_t faces = options.faces, least = least_faces(options);
    if (faces % 2 != 0 && options.holes == 0)
        invalid("the face count must be even without holes (got " + std::to_string(faces) +
                "): a closed triangle mesh has 3F/2 edges");
    if (faces < least) {
        std::string what = "genus " + std::to_string(options.genus);
        if (options.holes > 0) what += " with " + std::to_string(options.holes) + " holes";
        if (options.components > 1) what += " in " + std::to_string(options.components) + " components";
        if (options.family != Family::block) what += std::string(" in the ") + family_name(options.family) + " family";
        invalid(what + " needs at least " + std::to_string(least) + " faces (got " + std::to_string(faces) + ")");
    }
    if (faces > max_faces)
        invalid("at most " + std::to_string(max_faces) + " faces can be generated (got " + std::to_string(faces) + ")");
}

TriMesh detail::base_block(const RandomMeshOptions& options, std::size_t faces) {
    RandomMeshOptions block = options;
    block.family = Family::block;
    block.faces = faces;
    block.noise = 0;
    check_recipe(block, block_min_faces);
    return block_mesh(block);
}

}  // namespace fhr::generate
