// FHR generate — the valence family (beyond the paper): block meshes with a vertex of
// very high valence in every component and a share of vertices of valence 3. Real meshes have
// both (poles of revolved surfaces, fans of CAD tessellations; vertices left by face insertions),
// and both stress the stages: a high-valence vertex has many thin wedges around it (§3's
// geodesics and §4's weights), a valence-3 vertex is the smallest star a decimation may meet (§2).
// The construction and its guarantees are in paper_notes/generator.md ("The valence family"):
//
//   1. Budget. F = F0 + 2·(S + n3): a block of F0 faces, S = C·(high_valence − 2) splits
//      reserved for the hubs, n3 = ⌊low_fraction · V⌋ insertions of valence-3 vertices, V the
//      final vertex count. Flips add no face, a split of a face or of an interior edge adds two.
//      V = χ + (F + B)/2 (B the
//      boundary edges, which no edit changes) is known before the block is made when there are no
//      holes; with holes the block is made once to learn B and, if that raises n3, once more with
//      fewer faces (fewer faces never give more boundary edges, so that n3 still suffices).
//   2. Hubs, one per component: a random vertex interior to a flat facet. While its valence is
//      below high_valence, flip the edge opposite it in one of its faces, nearest opposite vertex
//      first: each flip of the edge bc opposite v in (v, b, c) raises v's valence by one, and the
//      star grows into a fan within the hub's facet, wherever the guard accepts. When no flip is
//      accepted, split the link edge of the hub's wedge of largest angle where that angle's
//      bisector meets it (one more spoke per split), and restore the Delaunay property around the
//      new link vertex by flips away from the hub (Lawson), until the valence is reached: a fan
//      of about evenly spread, roughly isosceles wedges. The reserve's unused splits go to step 3.
//   3. Valence 3: n3 plus the unused reserve vertices, each inserted into a random face none of
//      whose vertices is a hub or an earlier such insertion, so that each keeps its three
//      neighbours and the fans stay as they are.
//   4. Renumber component by component and rebuild from the triangles (GEN-3, GEN-5).
//
// Every edit goes through the EmbeddingGuard (detail/editor.hpp): the block is embedded, so the
// result is. Every flip stays within a facet and every new point keeps its facet's (or crease's)
// constant coordinates exactly, so every face stays in the block's surface. Boundary edges are
// never flipped or split: the holes keep their outlines. Decisions use only +, −, ×, ÷, √ in a
// fixed order (detail::dot etc.) and the family's own random stream: bit-identical on every
// compiler.
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <fhr/core/errors.hpp>
#include <fhr/generate/detail/editor.hpp>
#include <fhr/generate/detail/family.hpp>

namespace fhr::generate::detail {
namespace {

std::string shortest(double x) {
    char buffer[32];
    return std::string(buffer, std::to_chars(buffer, buffer + sizeof buffer, x).ptr);
}

void check_knobs(const FamilyKnobs& k) {
    if (k.high_valence < 7 || k.high_valence > 1000)
        invalid("--high-valence must be in [7, 1000] (got " + std::to_string(k.high_valence) + ")");
    if (!(k.low_fraction >= 0 && k.low_fraction <= 0.2))
        invalid("--low-fraction must be in [0, 0.2] (got " + shortest(k.low_fraction) + ")");
}

/// χ summed over the components: 2C − 2g − b.
long euler_characteristic(const RandomMeshOptions& o) {
    return 2L * o.components - 2L * o.genus - static_cast<long>(o.holes);
}

/// Splits reserved for the hubs (two faces each): high_valence − 2 per component (a hub's valence
/// is at least 2 before, and each split raises it by one).
std::size_t hub_reserve(const RandomMeshOptions& o) {
    return static_cast<std::size_t>(o.components) * static_cast<std::size_t>(o.knobs.high_valence - 2);
}

/// ⌊low_fraction · V⌋ for the final vertex count V = χ + (F + B)/2 (2E = 3F + B, so F + B is even).
std::size_t valence3_count(const RandomMeshOptions& o, std::size_t boundary_edges) {
    const long V = euler_characteristic(o) + static_cast<long>((o.faces + boundary_edges) / 2);
    return V <= 0 ? 0 : static_cast<std::size_t>(std::floor(o.knobs.low_fraction * static_cast<double>(V)));
}

std::size_t count_boundary_edges(const TriMesh& m) {
    std::size_t b = 0;
    for (EdgeId e : m.edges()) b += m.is_boundary(e) ? 1 : 0;
    return b;
}

/// The facet of the face of h: axis of its normal (0, 1, 2) times 2, plus 1 when it points the
/// positive way. Exact: an axis-aligned face's normal has two exactly zero components. Every face
/// of this family is axis-aligned; −1 (a normal with more than one non-zero component) would only
/// make the flat-facet tests below fail safely.
int facet(const TriMesh& m, HalfedgeId h) {
    const Vec3 n = normal(m.position(m.from(h)), m.position(m.to(h)), m.position(m.to(m.next(h))));
    int axis = -1;
    for (int k = 0; k < 3; ++k)
        if (n[k] != 0) {
            if (axis >= 0) return -1;
            axis = k;
        }
    return axis < 0 ? -1 : 2 * axis + (n[axis] > 0 ? 1 : 0);
}

// sin and cos of 10°: a hub's flip is made only if the two new triangles have every corner but the
// hub's at least this large (a fan of thin wedges, as around a pole, not of slivers: in exact
// arithmetic on rounded lattice points a flip could otherwise make nearly collinear triangles).
constexpr double sin_flip_angle = 0.17364817766693033, cos_flip_angle = 0.984807753012208;

/// The corner of triangle (x, y, z) at x is at least 10°: |u × w| cos 10° − (u · w) sin 10° >= 0.
bool corner_ok(const Vec3& x, const Vec3& y, const Vec3& z) {
    const Vec3 u = y - x, w = z - x;
    return length(cross(u, w)) * cos_flip_angle - dot(u, w) * sin_flip_angle >= 0;
}

class ValenceBuilder {
public:
    ValenceBuilder(const RandomMeshOptions& o, TriMesh base, int random_draws)
        : o_(o), ed_(std::move(base)), rng_(family_seed(o.seed, Family::valence)), draws_(random_draws) {}

    TriMesh build(std::size_t valence3) {
        const TriMesh& m = ed_.mesh();
        // Each component's vertices are consecutive in the block (GEN-3): note where each begins.
        std::vector<std::size_t> first(ed_.components() + 1, m.n_vertices());
        for (std::size_t v = m.n_vertices(); v-- > 0;)
            first[ed_.component(VertexId(static_cast<VertexId::Index>(v)))] = v;
        std::size_t unused = hub_reserve(o_);
        std::vector<VertexId> hubs;
        for (std::size_t c = 0; c < ed_.components(); ++c) {
            hubs.push_back(choose_hub(first[c], first[c + 1]));
            grow_by_flips(hubs.back());
            unused -= grow_by_splits(hubs.back());
        }
        insert_valence3(valence3 + unused, hubs);
        return ed_.finish();
    }

private:
    const RandomMeshOptions& o_;
    GuardedEditor ed_;
    Random rng_;
    int draws_;  // random faces tried per valence-3 vertex before the scan

    std::size_t target() const { return static_cast<std::size_t>(o_.knobs.high_valence); }

    /// A random vertex of the component interior to a flat facet (not on the boundary, all its
    /// faces in one facet); failing that a random interior vertex; failing that (a component all
    /// of whose vertices lie on holes) a random vertex.
    VertexId choose_hub(std::size_t begin, std::size_t end) {
        const TriMesh& m = ed_.mesh();
        std::vector<VertexId> flat, interior;
        for (std::size_t i = begin; i < end; ++i) {
            const VertexId v(static_cast<VertexId::Index>(i));
            if (m.is_boundary(v)) continue;
            interior.push_back(v);
            const int f0 = facet(m, m.out(v));
            bool same = f0 >= 0;
            m.for_each_outgoing(v, [&](HalfedgeId h) { same = same && facet(m, h) == f0; });
            if (same) flat.push_back(v);
        }
        const std::vector<VertexId>& pool = !flat.empty() ? flat : interior;
        if (!pool.empty()) return pool[rng_.below(pool.size())];
        return VertexId(static_cast<VertexId::Index>(begin + rng_.below(end - begin)));
    }

    /// Flips edges opposite the hub v, the one whose far vertex d is nearest to v first (the star
    /// grows like a disk), until v reaches the target valence or no such flip is accepted. Only
    /// for a hub interior to a flat facet, only flips within that facet (the star stays in its
    /// plane, exactly: new triangles across a crease would lie in tilted planes where the exact
    /// predicates of every later guarded edit near the hub need their slow path), and never a
    /// flip touching a boundary vertex (the holes are left as they are).
    void grow_by_flips(VertexId v) {
        const TriMesh& m = ed_.mesh();
        if (m.is_boundary(v)) return;
        const int f0 = facet(m, m.out(v));
        bool flat = f0 >= 0;
        m.for_each_outgoing(v, [&](HalfedgeId h) { flat = flat && facet(m, h) == f0; });
        if (!flat) return;
        const int axis = f0 / 2;  // the facet's constant coordinate
        struct Candidate {
            double distance2;
            EdgeId e;
        };
        std::vector<Candidate> candidates;
        while (m.valence(v) < target()) {
            candidates.clear();
            m.for_each_outgoing(v, [&](HalfedgeId h) {
                const HalfedgeId g = m.next(h);  // b -> c, opposite v
                const VertexId b = m.to(h), c = m.to(g);
                if (m.is_boundary(TriMesh::edge(g)) || m.is_boundary(b) || m.is_boundary(c)) return;
                const VertexId d = m.to(m.next(TriMesh::twin(g)));
                if (m.is_boundary(d) || m.position(d)[axis] != m.position(v)[axis]) return;
                // The new triangles (v, b, d) and (v, d, c): corners at b, d, c.
                const Vec3 &pv = m.position(v), &pb = m.position(b), &pc = m.position(c), &pd = m.position(d);
                if (!corner_ok(pb, pd, pv) || !corner_ok(pd, pv, pb) || !corner_ok(pd, pc, pv) ||
                    !corner_ok(pc, pv, pd))
                    return;
                const Vec3 vd = pd - pv;
                candidates.push_back({dot(vd, vd), TriMesh::edge(g)});
            });
            std::sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) {
                return x.distance2 != y.distance2 ? x.distance2 < y.distance2 : x.e < y.e;
            });
            bool flipped = false;
            for (const Candidate& k : candidates)
                if (ed_.flip(k.e)) {
                    flipped = true;
                    break;
                }
            if (!flipped) return;
        }
    }

    /// Adds spokes to the hub v until it has the target valence: the wedge (v, b, c) of largest
    /// angle at v has its link edge bc split where the bisector of that angle meets it,
    /// q = b + |vb| / (|vb| + |vc|) · (c − b) (on an axis-aligned facet or crease exactly in it:
    /// c − b is zero in the constant coordinates), so the spokes stay about evenly spread, each
    /// wedge roughly isosceles; then the edges around q away from v are made locally Delaunay by
    /// flips (Lawson's insertion), so that the new link vertex does not leave needles outside the
    /// fan. When no link edge can be split (all on the boundary, or refused), the wedge gets an
    /// inner vertex instead. \return the number of splits (one spoke each).
    std::size_t grow_by_splits(VertexId v) {
        const TriMesh& m = ed_.mesh();
        std::size_t splits = 0;
        struct Candidate {
            double cosine;
            HalfedgeId h;
        };
        std::vector<Candidate> candidates;
        while (m.valence(v) < target()) {
            candidates.clear();
            m.for_each_outgoing(v, [&](HalfedgeId h) {
                if (m.is_boundary(h)) return;
                const Vec3 u = m.position(m.to(h)) - m.position(v), w = m.position(m.to(m.next(h))) - m.position(v);
                candidates.push_back({dot(u, w) / (length(u) * length(w)), h});
            });
            std::sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) {
                return x.cosine != y.cosine ? x.cosine < y.cosine : x.h < y.h;
            });
            VertexId added;
            for (std::size_t k = 0; k < candidates.size() && !added.valid(); ++k) {
                const HalfedgeId h = candidates[k].h, g = m.next(h);  // g: b -> c, opposite v
                if (m.is_boundary(TriMesh::edge(g))) continue;
                const Vec3 &b = m.position(m.to(h)), &c = m.position(m.to(g));
                const double lb = length(b - m.position(v)), lc = length(c - m.position(v));
                added = ed_.split_edge(TriMesh::edge(g), b + (lb / (lb + lc)) * (c - b));
            }
            if (added.valid()) {
                legalize_around(added, v);
            } else {
                for (std::size_t k = 0; k < candidates.size() && !added.valid(); ++k) {
                    const HalfedgeId h = candidates[k].h;
                    added = ed_.split_face(
                        m.face(h), median_point(m.position(v), m.position(m.to(h)), m.position(m.to(m.next(h)))));
                }
            }
            if (!added.valid())
                throw InternalError("valence family: no wedge of hub vertex " + std::to_string(v.idx()) +
                                    " could be split (" + generate_command(o_) + ")");
            ++splits;
        }
        return splits;
    }

    /// Lawson's flips after inserting q: an edge ab opposite q, in face (q, a, b), whose far
    /// vertex x sees it with an angle that, added to q's, exceeds π, is flipped to qx, and the two
    /// edges then opposite q are checked in turn. Only edges whose two faces lie in one facet
    /// (the quadrilateral is planar, exactly), never an edge of the hub or on the boundary.
    void legalize_around(VertexId q, VertexId hub) {
        const TriMesh& m = ed_.mesh();
        std::vector<std::array<VertexId, 2>> stack;  // edges ab opposite q, as vertex pairs
        m.for_each_outgoing(q, [&](HalfedgeId h) {
            if (!m.is_boundary(h)) stack.push_back({m.to(h), m.to(m.next(h))});
        });
        // Every flip gives q one more neighbour, and only edges opposite q are ever flipped, so
        // this ends after fewer flips than there are vertices.
        while (!stack.empty()) {
            const auto [a, b] = stack.back();
            stack.pop_back();
            const HalfedgeId h = m.find_halfedge(a, b);        // in the face (a, b, q)
            if (!h.valid() || m.to(m.next(h)) != q) continue;  // no longer opposite q
            if (m.is_boundary(TriMesh::edge(h)) || a == hub || b == hub) continue;
            // Both faces in one facet (same axis-aligned normal through a and b: one plane).
            const int f = facet(m, h);
            if (f < 0 || f != facet(m, TriMesh::twin(h))) continue;
            const VertexId x = m.to(m.next(TriMesh::twin(h)));
            const Vec3 &pq = m.position(q), &pa = m.position(a), &pb = m.position(b), &px = m.position(x);
            // angle(q) + angle(x) > π  ⇔  sin(q + x) < 0, with both sines and cosines scaled by
            // positive lengths.
            const Vec3 qa = pa - pq, qb = pb - pq, xa = pa - px, xb = pb - px;
            if (length(cross(qa, qb)) * dot(xa, xb) + dot(qa, qb) * length(cross(xa, xb)) >= 0) continue;
            if (!ed_.flip(TriMesh::edge(h))) continue;
            stack.push_back({a, x});
            stack.push_back({x, b});
        }
    }

    /// Inserts `count` vertices of valence 3, each into a random face none of whose vertices is an
    /// earlier one (so each keeps its three neighbours) or a hub (whose fan stays as it is), at
    /// the middle of the median from the face's largest corner (opposite its longest edge).
    void insert_valence3(std::size_t count, const std::vector<VertexId>& hubs) {
        const TriMesh& m = ed_.mesh();
        constexpr char hub = 1, inserted = 2;
        std::vector<char> kept(m.n_vertices(), 0);  // the hubs and the valence-3 vertices so far
        for (VertexId h : hubs) kept[h.idx()] = hub;
        const auto eligible = [&](FaceId f, bool hubs_too) {
            for (VertexId v : m.face_vertices(f))
                if (v.idx() < kept.size() && (kept[v.idx()] == inserted || (kept[v.idx()] == hub && !hubs_too)))
                    return false;
            return true;
        };
        const auto insert = [&](FaceId f) {
            const auto v = m.face_vertices(f);
            std::array<double, 3> opposite;  // squared length of the edge opposite corner k
            for (int k = 0; k < 3; ++k) {
                const Vec3 e = m.position(v[(k + 1) % 3]) - m.position(v[(k + 2) % 3]);
                opposite[k] = dot(e, e);
            }
            int a = 0;
            for (int k = 1; k < 3; ++k)
                if (opposite[k] > opposite[a]) a = k;
            const VertexId added = ed_.split_face(
                f, median_point(m.position(v[a]), m.position(v[(a + 1) % 3]), m.position(v[(a + 2) % 3])));
            if (!added.valid()) return false;
            kept.resize(m.n_vertices(), 0);
            kept[added.idx()] = inserted;
            return true;
        };
        // Every insertion makes 3 faces ineligible and adds 2: with F0 >= the insertions, an
        // eligible face always remains, if need be in a hub's fan. A few random draws, then a
        // scan from a random face, then the same scan with the fans.
        for (std::size_t i = 0; i < count; ++i) {
            bool done = false;
            for (int t = 0; t < draws_ && !done; ++t) {
                const FaceId f(static_cast<FaceId::Index>(rng_.below(m.n_faces())));
                done = eligible(f, false) && insert(f);
            }
            const std::size_t start = rng_.below(m.n_faces()), n = m.n_faces();
            for (int pass = 0; pass < 2 && !done; ++pass)
                for (std::size_t k = 0; k < n && !done; ++k) {
                    const FaceId f(static_cast<FaceId::Index>((start + k) % n));
                    done = eligible(f, pass == 1) && insert(f);
                }
            if (!done)
                throw InternalError("valence family: no face left for a valence-3 vertex (" + generate_command(o_) +
                                    ")");
        }
    }
};

}  // namespace

std::size_t valence_min_faces(const RandomMeshOptions& o) {
    check_knobs(o.knobs);
    const std::size_t block = min_faces(o.genus, o.holes, o.components), reserve = hub_reserve(o);
    // The block of F0 = F − 2(S + n3) faces must exist. n3 is at most its value for B = F
    // (a block face has at most one edge on a hole, so B <= F0 <= F; B = 0 without holes).
    const auto fits = [&](std::size_t F) {
        RandomMeshOptions at = o;
        at.faces = F;
        const std::size_t n3 = valence3_count(at, o.holes > 0 ? F : 0);
        return F >= block + 2 * reserve + 2 * n3;
    };
    // The deficit F' − F of an infeasible F is a lower bound of how far the next feasible F' is
    // (n3 never decreases as F grows), so jumping by it skips none. Without holes F − 2·n3(F)
    // never decreases in steps of 2; with holes a step of 1 may lower it by 1, so a face count
    // is accepted when it and the next one fit (then every larger one does).
    const std::size_t step = o.holes > 0 ? 1 : 2;
    std::size_t F = block + 2 * reserve;
    for (;;) {
        RandomMeshOptions at = o;
        at.faces = F;
        const std::size_t need = block + 2 * reserve + 2 * valence3_count(at, o.holes > 0 ? F : 0);
        if (need > F) {
            F += (need - F + step - 1) / step * step;
        } else if (step == 1 && !fits(F + 1)) {
            F += 1;
        } else {
            return F;
        }
    }
}

TriMesh valence_mesh(const RandomMeshOptions& o, int random_draws) {
    const std::size_t reserve = hub_reserve(o);
    std::size_t n3 = valence3_count(o, 0);
    TriMesh base = base_block(o, o.faces - 2 * (reserve + n3));
    if (o.holes > 0) {
        // V depends on the boundary: a second block with fewer faces when the first one's raises n3.
        const std::size_t needed = valence3_count(o, count_boundary_edges(base));
        if (needed > n3) {
            n3 = needed;
            base = base_block(o, o.faces - 2 * (reserve + n3));
        }
    }
    return ValenceBuilder(o, std::move(base), random_draws).build(n3);
}

}  // namespace fhr::generate::detail
