// Beyond the paper (§4) — T refined around the vertices of D (see corners.hpp).
#include <fhr/pipeline/detail/corners.hpp>

#include <array>
#include <cstdint>
#include <utility>

#include <fhr/core/detail/contract.hpp>

namespace fhr::pipeline {
namespace {

constexpr std::uint32_t none = UINT32_MAX;

// The collapses that take the cuts back into their vertices of D, in T*'s numbering: for each
// corner (group[v]: the corner that vertex v of T* is or is a cut of), each of its cuts s in the
// order made, s -> x with the third vertices of the faces at s -> x (left) and x -> s (right), the
// faces around x followed as each collapse changes them.
std::vector<domain::Collapse> collapses_of_cuts(const std::vector<Triangle>& faces,
                                                const std::vector<std::uint32_t>& group,
                                                const std::vector<std::uint32_t>& corner,
                                                const std::vector<std::vector<std::uint32_t>>& cuts) {
    std::vector<std::vector<Triangle>> fan(corner.size());  // per corner: the faces at it or at its cuts
    for (const Triangle& t : faces)
        for (std::uint32_t v : t)
            if (group[v] != none) {  // a face at a cut has no other corner: one fan each
                fan[group[v]].push_back(t);
                break;
            }
    std::vector<domain::Collapse> out;
    for (std::size_t c = 0; c < corner.size(); ++c) {
        const std::uint32_t x = corner[c];
        for (std::uint32_t s : cuts[c]) {
            domain::Collapse collapse{VertexId(s), VertexId(x), VertexId(), VertexId()};
            std::vector<Triangle> kept;
            for (Triangle t : fan[c]) {
                int at_s = -1, at_x = -1;
                for (int k = 0; k < 3; ++k) {
                    if (t[k] == s) at_s = k;
                    if (t[k] == x) at_x = k;
                }
                if (at_s >= 0 && at_x >= 0) {  // a face at the edge [s, x]: gone
                    if ((at_s + 1) % 3 == at_x)
                        collapse.left = VertexId(t[(at_x + 1) % 3]);
                    else
                        collapse.right = VertexId(t[(at_s + 1) % 3]);
                    continue;
                }
                if (at_s >= 0) t[at_s] = x;
                kept.push_back(t);
            }
            FHR_DCHECK(collapse.left.valid() && collapse.right.valid());
            fan[c] = std::move(kept);
            out.push_back(collapse);
        }
    }
    return out;
}

}  // namespace

std::optional<CornerRefinement> refine_corners(const TriMesh& T, const domain::Domain& D, double cut) {
    FHR_DCHECK(cut > 0 && cut < 1);
    if (D.by_cells || !domain::history_describes(D, T)) return std::nullopt;
    const std::size_t n = T.n_vertices();
    std::vector<std::uint32_t> group(n, none), corner;
    for (VertexId v : D.t_vertex) {
        group[v.idx()] = static_cast<std::uint32_t>(corner.size());
        corner.push_back(v.idx());
    }
    auto corners_of = [&](FaceId f) {
        int count = 0;
        for (VertexId v : T.face_vertices(f)) count += group[v.idx()] != none;
        return count;
    };
    // The cuts, edge by edge.
    std::vector<Vec3> positions = T.positions();
    std::vector<std::uint32_t> edge_cut(T.n_edges(), none);
    std::vector<std::vector<std::uint32_t>> cuts(corner.size());
    for (EdgeId e : T.edges()) {
        if (T.is_boundary(e)) continue;
        const HalfedgeId h = TriMesh::halfedge(e, 0);
        VertexId x = T.from(h), a = T.to(h);
        if ((group[x.idx()] != none) == (group[a.idx()] != none)) continue;
        if (corners_of(T.face(h)) != 1 || corners_of(T.face(TriMesh::twin(h))) != 1) continue;
        if (group[x.idx()] == none) std::swap(x, a);
        edge_cut[e.idx()] = static_cast<std::uint32_t>(positions.size());
        cuts[group[x.idx()]].push_back(edge_cut[e.idx()]);
        positions.push_back(T.position(x) + cut * (T.position(a) - T.position(x)));
        group.push_back(group[x.idx()]);
    }
    const std::size_t added = positions.size() - n;
    if (added == 0) return std::nullopt;
    // Each face of T with one corner split at its cuts, in its orientation.
    std::vector<Triangle> faces;
    CornerRefinement out;
    for (FaceId f : T.faces()) {
        const std::array<VertexId, 3> v = T.face_vertices(f);
        auto keep = [&](const Triangle& t) {
            faces.push_back(t);
            out.parent.push_back(TFaceId(f));
        };
        int k = 0;
        while (k < 3 && group[v[k].idx()] == none) ++k;
        if (k == 3 || corners_of(f) != 1) {
            keep({v[0].idx(), v[1].idx(), v[2].idx()});
            continue;
        }
        const std::uint32_t x = v[k].idx(), a = v[(k + 1) % 3].idx(), b = v[(k + 2) % 3].idx();
        const std::uint32_t sa = edge_cut[TriMesh::edge(T.find_halfedge(v[k], v[(k + 1) % 3])).idx()];
        const std::uint32_t sb = edge_cut[TriMesh::edge(T.find_halfedge(v[k], v[(k + 2) % 3])).idx()];
        if (sa != none && sb != none) {
            keep({x, sa, sb});
            keep({sa, a, b});
            keep({sa, b, sb});
        } else if (sa != none) {
            keep({x, sa, b});
            keep({sa, a, b});
        } else if (sb != none) {
            keep({x, a, sb});
            keep({sb, a, b});
        } else {
            keep({x, a, b});
        }
    }
    out.domain = D;
    out.domain.history = collapses_of_cuts(faces, group, corner, cuts);
    for (domain::Collapse c : D.history) {  // a cone's apex of T̂ (core/detail/cones.hpp) comes after the cuts
        for (VertexId* v : {&c.removed, &c.kept, &c.left, &c.right})
            if (v->idx() >= n) *v = VertexId(static_cast<VertexId::Index>(v->idx() + added));
        out.domain.history.push_back(c);
    }
    out.mesh = TriMesh::from_triangles(std::move(positions), faces);
    FHR_DCHECK(domain::history_describes(out.domain, out.mesh));
    return out;
}

}  // namespace fhr::pipeline
