// FHR generate — the density family (beyond the paper): block meshes refined unevenly,
// as real meshes are (fine detail beside coarse flat parts, boundary layers of long thin
// triangles), with a longest/shortest edge ratio of at least `edge_ratio` (10^5 by default) in
// every component. Such meshes stress whatever depends on a length scale: §2's decimation
// priorities, §3's fast marching and ellipses, the tolerances of every stage. The construction
// and its guarantees are in paper_notes/generator.md ("The density family"); per component:
//
//   1. Band (anisotropic refinement). A straight chain of 1 to 4 interior crease edges of the
//      block and one of its two facets (the side). Each round splits, at their midpoints, the
//      edges that join a chain vertex to the apex of a chain triangle (the side face of a chain
//      edge). A chain triangle is split exactly once per round (its two new edges to the chain
//      are not split in the same round), and its new apex is the midpoint of an edge from the
//      chain line to the old apex: its height over the chain halves. The block's corners are
//      >= 20°, so at first height / chain edge <= tan(80°)/2 < 2.84, and after j rounds every
//      chain triangle has aspect (longest edge / height on it) >= 2^j / 2.84. Rounds stop when
//      every chain triangle reaches `anisotropy`; at most J = ⌈log2(3·anisotropy)⌉ + 1 rounds of
//      at most 2·4 splits.
//   2. Graded refinement. A vertex p is inserted at the middle of a median of a random face
//      without a chain vertex (valence 3), then each round splits p's three edges at their
//      midpoints (p keeps valence 3; its 1-ring halves; every angle of the fan is kept). The
//      component's longest edge is never split by these edits (it is no edge of p's star: p's
//      spokes are shorter than half the longest edge of the face p was put in), so the ratio at
//      least doubles per round; rounds stop when longest / shortest >= edge_ratio, after at most
//      K = ⌈log2(edge_ratio)⌉ + 1 rounds of 3 splits.
//   3. The budget reserved for 1 and 2 but not used: further graded foci (random faces, random
//      depths), and single face splits for the last 2, 4 or 6 faces.
//   4. Renumber component by component and rebuild from the triangles (GEN-3, GEN-5).
//
// Face count: F = F0 + C·R with R = 4·4·J + 2 + 6·K the reserve of a component, every edit a
// split of a face or of an interior edge (two faces each). Every point is a midpoint (of an edge,
// or of a median) on an axis-aligned facet, so every face stays exactly in its facet; every edit
// goes through the EmbeddingGuard (detail/editor.hpp), so the mesh stays embedded. Decisions use
// only +, −, ×, ÷, √ in a fixed order and the family's own random stream.
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
    if (!(k.edge_ratio >= 10 && k.edge_ratio <= 1e9))
        invalid("--edge-ratio must be in [10, 1e+09] (got " + shortest(k.edge_ratio) + ")");
    if (!(k.anisotropy >= 1 && k.anisotropy <= 1e6))
        invalid("--anisotropy must be in [1, 1e+06] (got " + shortest(k.anisotropy) + ")");
}

/// The least k with 2^k >= x (exact: doublings of 1 are exact).
int doublings(double x) {
    int k = 0;
    for (double p = 1; p < x; p *= 2) ++k;
    return k;
}

constexpr int max_chain_edges = 4;
/// The targets are aimed at with this relative margin, so that another evaluation order of the
/// same lengths (a test's, Eigen's) still finds them reached.
constexpr double margin = 1 + 0x1.0p-20;

int band_rounds(const FamilyKnobs& k) { return doublings(3 * k.anisotropy) + 1; }
int graded_rounds(const FamilyKnobs& k) { return doublings(k.edge_ratio) + 1; }
/// Faces reserved per component: the band's rounds of at most 2·max_chain_edges edge splits, the
/// focus and its rounds of 3 edge splits; two faces per split.
std::size_t component_reserve(const FamilyKnobs& k) {
    return static_cast<std::size_t>(4 * max_chain_edges * band_rounds(k) + 2 + 6 * graded_rounds(k));
}

double edge_length(const TriMesh& m, HalfedgeId h) { return length(m.position(m.to(h)) - m.position(m.from(h))); }

/// The facet of the face of h: axis of its normal times 2, plus 1 when it points the positive way.
/// Every face of this family lies in an axis-aligned facet (exactly: every new point is a
/// midpoint in one), so exactly one component of its normal is non-zero.
int facet(const TriMesh& m, HalfedgeId h) {
    const Vec3 n = normal(m.position(m.from(h)), m.position(m.to(h)), m.position(m.to(m.next(h))));
    const int axis = n[0] != 0 ? 0 : n[1] != 0 ? 1 : 2;
    return 2 * axis + (n[axis] > 0 ? 1 : 0);
}

/// A straight chain of crease edges c_0 … c_n and the facet on the side that is refined.
struct Chain {
    std::vector<VertexId> v;
    int side = -1;
};

class DensityBuilder {
public:
    DensityBuilder(const RandomMeshOptions& o, TriMesh base)
        : o_(o), ed_(std::move(base)), rng_(family_seed(o.seed, Family::density)) {}

    TriMesh build() {
        const TriMesh& m = ed_.mesh();
        const std::size_t C = ed_.components();
        // Each component's faces are consecutive in the block (GEN-3); faces keep their ids
        // through splits, so a random id in that range is always a face of the component.
        face_first_.assign(C + 1, m.n_faces());
        for (std::size_t f = m.n_faces(); f-- > 0;)
            face_first_[ed_.component(m.face_vertices(FaceId(static_cast<FaceId::Index>(f)))[0])] = f;
        std::vector<std::vector<EdgeId>> creases(C);
        for (EdgeId e : m.edges()) {
            const HalfedgeId h = TriMesh::halfedge(e, 0);
            if (!m.is_boundary(e) && facet(m, h) != facet(m, TriMesh::twin(h)))
                creases[ed_.component(m.from(h))].push_back(e);
        }
        std::vector<std::size_t> used(C, 0);
        on_chain_.assign(m.n_vertices(), 0);
        for (std::size_t c = 0; c < C; ++c) {
            const Chain chain = choose_chain(creases[c]);
            if (chain.v.empty())
                throw InternalError("density family: no crease chain in component " + std::to_string(c) + " (" +
                                    generate_command(o_) + ")");
            for (VertexId v : chain.v) on_chain_[v.idx()] = 1;
            used[c] += refine_band(chain);
        }
        // The longest and shortest edge of each component once the bands are made: later edits
        // split only edges they created, so the longest stays and the shortest can only shrink.
        std::vector<double> longest(C, 0), shortest_edge(C, INFINITY);
        for (EdgeId e : m.edges()) {
            const HalfedgeId h = TriMesh::halfedge(e, 0);
            const std::size_t c = ed_.component(m.from(h));
            const double l = edge_length(m, h);
            longest[c] = std::max(longest[c], l);
            shortest_edge[c] = std::min(shortest_edge[c], l);
        }
        const double target = o_.knobs.edge_ratio * margin;
        const std::size_t reserve = component_reserve(o_.knobs);
        for (std::size_t c = 0; c < C; ++c) {
            double shortest_c = shortest_edge[c];
            const VertexId focus = insert_focus(c, shortest_c);
            if (!focus.valid())
                throw InternalError("density family: no face for the focus (" + generate_command(o_) + ")");
            used[c] += 2;
            while (longest[c] / shortest_c < target) {
                if (graded_round(focus, shortest_c) != 3)
                    invalid("--edge-ratio " + shortest(o_.knobs.edge_ratio) +
                            " needs edges shorter than double precision resolves at this mesh's coordinates");
                used[c] += 6;
            }
            spend(c, reserve - used[c]);
        }
        return ed_.finish();
    }

private:
    const RandomMeshOptions& o_;
    GuardedEditor ed_;
    Random rng_;
    std::vector<std::size_t> face_first_;
    std::vector<char> on_chain_;  // the vertices of the components' chains

    bool touches_chain(FaceId f) const {
        for (VertexId v : ed_.mesh().face_vertices(f))
            if (v.idx() < on_chain_.size() && on_chain_[v.idx()]) return true;
        return false;
    }

    /// The halfedge of chain edge (a, b) whose face lies on the chain's side.
    HalfedgeId side_halfedge(VertexId a, VertexId b, int side) const {
        const TriMesh& m = ed_.mesh();
        const HalfedgeId h = m.find_halfedge(a, b);
        return !m.is_boundary(h) && facet(m, h) == side ? h : TriMesh::twin(h);
    }

    /// Tries the crease edges from a random one on, each with a random side first: the first that
    /// gives a chain whose every side triangle has an interior edge to its apex (so that the
    /// first round can split it) wins. Extends it along its line, alternately at both ends, while
    /// the next edge is a crease between the same two facets, up to max_chain_edges edges.
    Chain choose_chain(const std::vector<EdgeId>& creases) {
        const TriMesh& m = ed_.mesh();
        if (creases.empty()) return {};
        const std::size_t start = rng_.below(creases.size());
        const bool first_side = rng_.coin();
        for (std::size_t k = 0; k < creases.size(); ++k)
            for (int s = 0; s < 2; ++s) {
                const HalfedgeId h =
                    TriMesh::halfedge(creases[(start + k) % creases.size()], (s == 0) == first_side ? 0 : 1);
                Chain chain{{m.from(h), m.to(h)}, facet(m, h)};
                const int other = facet(m, TriMesh::twin(h));
                extend(chain, other);
                if (splittable(chain)) return chain;
            }
        return {};
    }

    /// The next vertex after `last` on the crease line through `before` and `last` between facets
    /// side and other, if any.
    VertexId next_on_line(VertexId before, VertexId last, int side, int other) const {
        const TriMesh& m = ed_.mesh();
        const Vec3 &p = m.position(before), &q = m.position(last);
        const int a = side / 2, b = other / 2;  // the two coordinates constant along the crease
        VertexId found;
        m.for_each_outgoing(last, [&](HalfedgeId g) {
            const VertexId w = m.to(g);
            const Vec3& r = m.position(w);
            if (w == before || m.is_boundary(TriMesh::edge(g)) || r[a] != q[a] || r[b] != q[b]) return;
            const int k = 3 - a - b;  // the crease's direction: continue the same way
            if ((q[k] - p[k] > 0) != (r[k] - q[k] > 0)) return;
            const int f0 = facet(m, g), f1 = facet(m, TriMesh::twin(g));
            if ((f0 == side && f1 == other) || (f0 == other && f1 == side)) found = w;
        });
        return found;
    }

    void extend(Chain& chain, int other) const {
        bool grew = true;
        while (grew && static_cast<int>(chain.v.size()) - 1 < max_chain_edges) {
            grew = false;
            const std::size_t n = chain.v.size();
            if (const VertexId w = next_on_line(chain.v[n - 2], chain.v[n - 1], chain.side, other); w.valid()) {
                chain.v.push_back(w);
                grew = true;
            }
            if (static_cast<int>(chain.v.size()) - 1 >= max_chain_edges) break;
            if (const VertexId w = next_on_line(chain.v[1], chain.v[0], chain.side, other); w.valid()) {
                chain.v.insert(chain.v.begin(), w);
                grew = true;
            }
        }
    }

    /// Every chain triangle has an interior edge from a chain vertex to its apex.
    bool splittable(const Chain& chain) const {
        const TriMesh& m = ed_.mesh();
        for (std::size_t i = 0; i + 1 < chain.v.size(); ++i) {
            const HalfedgeId h = side_halfedge(chain.v[i], chain.v[i + 1], chain.side);
            if (m.is_boundary(h) || facet(m, h) != chain.side) return false;
            if (m.is_boundary(TriMesh::edge(m.next(h))) && m.is_boundary(TriMesh::edge(m.next(m.next(h)))))
                return false;
        }
        return true;
    }

    /// The smallest aspect (longest edge² / twice the area = longest edge / height on it) of the
    /// chain triangles.
    double band_aspect(const Chain& chain) const {
        const TriMesh& m = ed_.mesh();
        double smallest = INFINITY;
        for (std::size_t i = 0; i + 1 < chain.v.size(); ++i) {
            const HalfedgeId h = side_halfedge(chain.v[i], chain.v[i + 1], chain.side);
            const Vec3 &a = m.position(m.from(h)), &b = m.position(m.to(h)), &c = m.position(m.to(m.next(h)));
            const Vec3 ab = b - a, bc = c - b, ca = a - c;
            const double longest2 = std::max({dot(ab, ab), dot(bc, bc), dot(ca, ca)});
            smallest = std::min(smallest, longest2 / length(cross(ab, c - a)));
        }
        return smallest;
    }

    /// Step 1: rounds of splits of the chain triangles' edges to their apex. \return faces added.
    std::size_t refine_band(const Chain& chain) {
        const TriMesh& m = ed_.mesh();
        const double target = o_.knobs.anisotropy * margin;
        std::size_t added = 0;
        std::vector<std::array<VertexId, 2>> edges;
        for (int round = 0; band_aspect(chain) < target; ++round) {
            if (round == band_rounds(o_.knobs))
                throw InternalError("density family: the band did not reach its aspect (" + generate_command(o_) + ")");
            // The edges to split, gathered before any is split, along the chain one way in even
            // rounds and the other way in odd ones (the apexes zigzag rather than drift).
            edges.clear();
            const std::size_t n = chain.v.size() - 1;
            for (std::size_t j = 0; j < n; ++j) {
                const std::size_t i = round % 2 == 0 ? j : n - 1 - j;
                const HalfedgeId h = side_halfedge(chain.v[i], chain.v[i + 1], chain.side);
                const VertexId apex = m.to(m.next(h));
                for (VertexId u : {m.from(h), m.to(h)}) {
                    const std::array<VertexId, 2> e{u, apex};
                    if (!m.is_boundary(TriMesh::edge(m.find_halfedge(u, apex))) &&
                        std::find(edges.begin(), edges.end(), e) == edges.end())
                        edges.push_back(e);
                }
            }
            for (const auto& [u, apex] : edges) {
                const HalfedgeId g = m.find_halfedge(u, apex);
                if (!ed_.split_edge(TriMesh::edge(g), midpoint(m.position(u), m.position(apex))).valid())
                    invalid("--anisotropy " + shortest(o_.knobs.anisotropy) +
                            " needs triangles thinner than double precision resolves at this mesh's coordinates");
                added += 2;
            }
        }
        return added;
    }

    /// A random face of component c without a chain vertex (a few draws, then a scan).
    FaceId random_face(std::size_t c) {
        const std::size_t begin = face_first_[c], count = face_first_[c + 1] - begin;
        for (int t = 0; t < 16; ++t) {
            const FaceId f(static_cast<FaceId::Index>(begin + rng_.below(count)));
            if (!touches_chain(f)) return f;
        }
        const std::size_t start = rng_.below(count);
        for (std::size_t k = 0; k < count; ++k) {
            const FaceId f(static_cast<FaceId::Index>(begin + (start + k) % count));
            if (!touches_chain(f)) return f;
        }
        return FaceId();
    }

    /// Inserts a vertex at the middle of the median from the largest corner of a random face of
    /// component c without a chain vertex, updating `shortest` with its three edges.
    VertexId insert_focus(std::size_t c, double& shortest_c) {
        const TriMesh& m = ed_.mesh();
        for (int t = 0; t < 16; ++t) {
            const FaceId f = random_face(c);
            if (!f.valid()) return VertexId();
            const auto v = m.face_vertices(f);
            std::array<double, 3> opposite;
            for (int k = 0; k < 3; ++k) {
                const Vec3 e = m.position(v[(k + 1) % 3]) - m.position(v[(k + 2) % 3]);
                opposite[k] = dot(e, e);
            }
            int a = 0;
            for (int k = 1; k < 3; ++k)
                if (opposite[k] > opposite[a]) a = k;
            const VertexId p = ed_.split_face(
                f, median_point(m.position(v[a]), m.position(v[(a + 1) % 3]), m.position(v[(a + 2) % 3])));
            if (!p.valid()) continue;
            m.for_each_outgoing(p, [&](HalfedgeId h) { shortest_c = std::min(shortest_c, edge_length(m, h)); });
            return p;
        }
        return VertexId();
    }

    /// Splits the focus's edges (three: p keeps valence 3) at their midpoints, updating
    /// `shortest` with the edges made. \return the number of splits made: fewer than all when
    /// the guard refused one (a triangle degenerate in doubles).
    std::size_t graded_round(VertexId p, double& shortest_c) {
        const TriMesh& m = ed_.mesh();
        std::vector<VertexId> ring;
        m.for_each_outgoing(p, [&](HalfedgeId h) { ring.push_back(m.to(h)); });
        std::size_t splits = 0;
        for (VertexId s : ring) {
            const VertexId mid =
                ed_.split_edge(TriMesh::edge(m.find_halfedge(p, s)), midpoint(m.position(p), m.position(s)));
            if (!mid.valid()) break;
            ++splits;
            m.for_each_outgoing(mid, [&](HalfedgeId h) { shortest_c = std::min(shortest_c, edge_length(m, h)); });
        }
        return splits;
    }

    /// Step 3: spends the `faces` left of component c's reserve (even) on further foci refined
    /// to random depths, and single face splits for what is left below one focus and round.
    void spend(std::size_t c, std::size_t faces) {
        double ignored = INFINITY;
        const std::size_t depth = static_cast<std::size_t>(graded_rounds(o_.knobs));
        while (faces >= 8) {
            const VertexId p = insert_focus(c, ignored);
            if (!p.valid()) break;
            faces -= 2;
            const std::size_t rounds = std::min<std::size_t>(1 + rng_.below(depth), faces / 6);
            for (std::size_t r = 0; r < rounds; ++r) {
                const std::size_t splits = graded_round(p, ignored);
                faces -= 2 * splits;
                if (splits < 3) break;
            }
        }
        while (faces >= 2) {
            if (!insert_focus(c, ignored).valid())
                throw InternalError("density family: no face left to split (" + generate_command(o_) + ")");
            faces -= 2;
        }
    }
};

}  // namespace

std::size_t density_min_faces(const RandomMeshOptions& o) {
    check_knobs(o.knobs);
    return min_faces(o.genus, o.holes, o.components) +
           static_cast<std::size_t>(o.components) * component_reserve(o.knobs);
}

TriMesh density_mesh(const RandomMeshOptions& o) {
    const std::size_t reserve = static_cast<std::size_t>(o.components) * component_reserve(o.knobs);
    return DensityBuilder(o, base_block(o, o.faces - reserve)).build();
}

}  // namespace fhr::generate::detail
