// FHR core — TriMesh construction, navigation, edits and invariant checks (spec/mesh.md
// INV-MESH-1..8). Pictures of the edits use the names of the code:
//
//   flip(e):   c            c          split_edge(e):  c               collapse(h: v0 -> v1):
//             / \          /|\                        /|\                   vA          vA
//            a-h->b  ==>  a | b                      a-m-b                 /  \          |
//             \ /          \|/                        \|/               v0-h->v1  ==>   v1
//              d            d                          d                   \  /          |
//                                                                           vB          vB
#include <fhr/core/detail/contract.hpp>
#include <fhr/core/trimesh.hpp>

#include <algorithm>
#include <array>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>

#include <fhr/core/detail/edge_table.hpp>
#include <fhr/core/errors.hpp>

namespace fhr {
namespace {

[[noreturn]] void broken(const std::string& what) { throw ContractViolation(what); }

std::string vname(VertexId v) { return "vertex " + std::to_string(v.idx()); }
std::string hname(HalfedgeId h) { return "halfedge " + std::to_string(h.idx()); }

}  // namespace

TriMesh TriMesh::from_triangles(std::vector<Vec3> positions, std::span<const Triangle> triangles) {
    const std::size_t nv = positions.size();
    for (std::size_t f = 0; f < triangles.size(); ++f) {
        const Triangle& t = triangles[f];
        for (auto i : t)
            if (i >= nv) broken("from_triangles: face " + std::to_string(f) + " has index out of range");
        if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
            broken("from_triangles: face " + std::to_string(f) + " repeats a vertex");
    }
    const detail::EdgeTable table = detail::build_edge_table(nv, triangles);
    TriMesh m = from_triangles(std::move(positions), triangles, table);
    if (const std::uint32_t v = detail::first_non_manifold_vertex(m, triangles); v != UINT32_MAX)
        broken("from_triangles: " + vname(VertexId(v)) + " has more than one fan");
    return m;
}

TriMesh TriMesh::from_triangles(std::vector<Vec3> positions, std::span<const Triangle> triangles,
                                const detail::EdgeTable& table) {
    const std::size_t nv = positions.size();
    TriMesh m;
    m.pos_ = std::move(positions);
    const std::size_t ne = table.n_edges();
    m.to_.assign(2 * ne, VertexId());
    m.next_.assign(2 * ne, HalfedgeId());
    m.face_.assign(2 * ne, FaceId());
    m.out_.assign(nv, HalfedgeId());
    m.fh_.assign(triangles.size(), HalfedgeId());
    // Corner c of the table becomes halfedge 2e (first corner of its edge) or 2e+1 (second).
    std::vector<HalfedgeId> corner_he(3 * triangles.size());
    for (std::uint32_t e = 0; e < ne; ++e) {
        const std::uint32_t deg = table.edge_degree(e);
        const std::uint32_t* c = &table.edge_corners[table.edge_offsets[e]];
        if (deg > 2) broken("from_triangles: edge in more than two faces (corner " + std::to_string(c[0]) + ")");
        corner_he[c[0]] = HalfedgeId(2 * e);
        m.to_[2 * e] = VertexId(detail::corner_head(triangles, c[0]));
        m.to_[2 * e + 1] = VertexId(detail::corner_tail(triangles, c[0]));
        if (deg == 2) {
            if (detail::corner_tail(triangles, c[1]) != detail::corner_head(triangles, c[0]))
                broken("from_triangles: faces " + std::to_string(c[0] / 3) + " and " + std::to_string(c[1] / 3) +
                       " are inconsistently oriented");
            corner_he[c[1]] = HalfedgeId(2 * e + 1);
        }
    }
    for (std::uint32_t f = 0; f < triangles.size(); ++f) {
        const HalfedgeId h[3] = {corner_he[3 * f], corner_he[3 * f + 1], corner_he[3 * f + 2]};
        m.set_face_loop(FaceId(f), h[0], h[1], h[2]);
        for (int k = 0; k < 3; ++k) m.out_[m.from(h[k]).idx()] = h[k];
    }
    // Boundary halfedges: link each into its loop; a boundary vertex's out() is its boundary halfedge.
    for (HalfedgeId h : m.halfedges()) {
        if (m.is_boundary(h)) m.out_[m.from(h).idx()] = h;
    }
    for (HalfedgeId h : m.halfedges()) {
        if (m.is_boundary(h)) m.next_[h.idx()] = m.out_[m.to(h).idx()];
    }
    for (VertexId v : m.vertices())
        if (!m.out_[v.idx()].valid()) broken("from_triangles: " + vname(v) + " is in no face");
    return m;
}

TriMesh::Arrays TriMesh::arrays() const { return {to_, next_, face_, out_, fh_, pos_}; }

TriMesh TriMesh::from_arrays(Arrays arrays) {
    TriMesh m;
    m.to_ = std::move(arrays.to);
    m.next_ = std::move(arrays.next);
    m.face_ = std::move(arrays.face);
    m.out_ = std::move(arrays.out);
    m.fh_ = std::move(arrays.face_halfedge);
    m.pos_ = std::move(arrays.positions);
    m.validate();
    return m;
}

void TriMesh::set_face_loop(FaceId f, HalfedgeId a, HalfedgeId b, HalfedgeId c) {
    next_[a.idx()] = b;
    next_[b.idx()] = c;
    next_[c.idx()] = a;
    face_[a.idx()] = face_[b.idx()] = face_[c.idx()] = f;
    fh_[f.idx()] = a;
}

HalfedgeId TriMesh::prev(HalfedgeId h) const {
    if (!is_boundary(h)) return next(next(h));
    HalfedgeId p = h;
    while (next(p) != h) p = next(p);
    return p;
}

bool TriMesh::is_closed() const {
    for (HalfedgeId h : halfedges())
        if (to(h).valid() && is_boundary(h)) return false;
    return true;
}

std::array<VertexId, 3> TriMesh::face_vertices(FaceId f) const {
    const HalfedgeId h = halfedge(f);
    return {from(h), to(h), to(next(h))};
}

std::size_t TriMesh::valence(VertexId v) const {
    std::size_t n = 0;
    for_each_outgoing(v, [&](HalfedgeId) { ++n; });
    return n;
}

HalfedgeId TriMesh::find_halfedge(VertexId a, VertexId b) const {
    HalfedgeId found;
    for_each_outgoing(a, [&](HalfedgeId h) {
        if (to(h) == b) found = h;
    });
    return found;
}

std::vector<Triangle> TriMesh::triangles() const {
    std::vector<Triangle> t;
    t.reserve(n_faces());
    for (FaceId f : faces()) {
        if (is_deleted(f)) continue;
        const auto v = face_vertices(f);
        t.push_back({v[0].idx(), v[1].idx(), v[2].idx()});
    }
    return t;
}

// --- edits ---------------------------------------------------------------------------------

bool TriMesh::is_flip_ok(EdgeId e) const {
    if (is_boundary(e)) return false;
    const HalfedgeId h = halfedge(e, 0), o = halfedge(e, 1);
    const VertexId c = to(next(h)), d = to(next(o));
    if (c == d || find_halfedge(c, d).valid()) return false;
    return valence(to(h)) > 3 && valence(from(h)) > 3;
}

void TriMesh::flip(EdgeId e) {
    FHR_DCHECK(is_flip_ok(e));
    const HalfedgeId h = halfedge(e, 0), h1 = next(h), h2 = next(h1);
    const HalfedgeId o = halfedge(e, 1), o1 = next(o), o2 = next(o1);
    const VertexId a = from(h), b = to(h), c = to(h1), d = to(o1);
    const FaceId f0 = face(h), f1 = face(o);
    // New triangles (a, d, c) = o1 h h2 and (d, b, c) = o2 h1 o.
    to_[h.idx()] = c;
    to_[o.idx()] = d;
    set_face_loop(f0, o1, h, h2);
    set_face_loop(f1, o2, h1, o);
    if (out_[a.idx()] == h) out_[a.idx()] = o1;
    if (out_[b.idx()] == o) out_[b.idx()] = h1;
}

VertexId TriMesh::fill_hole(HalfedgeId h, const Vec3& apex) {
    FHR_DCHECK(h.valid() && h.idx() < n_halfedges() && is_boundary(h));
    std::vector<HalfedgeId> loop;
    for (HalfedgeId g = h; loop.empty() || g != h; g = next(g)) loop.push_back(g);
    const VertexId c = new_vertex(apex);
    // spoke[i]: the edge from from(loop[i]) to the apex; its halfedge 0 leaves the loop.
    std::vector<EdgeId> spoke;
    spoke.reserve(loop.size());
    for (HalfedgeId g : loop) spoke.push_back(new_edge(from(g), c));
    for (std::size_t i = 0; i < loop.size(); ++i) {
        const std::size_t j = (i + 1) % loop.size();  // to(loop[i]) = from(loop[j])
        set_face_loop(new_face(), loop[i], halfedge(spoke[j], 0), halfedge(spoke[i], 1));
    }
    out_[c.idx()] = halfedge(spoke[0], 1);
    return c;
}

EdgeId TriMesh::new_edge(VertexId a, VertexId b) {
    const EdgeId e(static_cast<EdgeId::Index>(n_edges()));
    to_.push_back(b);
    to_.push_back(a);
    next_.resize(to_.size());
    face_.resize(to_.size());
    return e;
}

VertexId TriMesh::split_edge(EdgeId e, const Vec3& p) {
    const HalfedgeId h = halfedge(e, 0), o = halfedge(e, 1);
    const bool side_h = !is_boundary(h), side_o = !is_boundary(o);  // the sides that have a face
    const HalfedgeId before_o = side_o ? HalfedgeId() : prev(o);    // o's predecessor along its boundary loop
    const HalfedgeId h1 = next(h);
    const VertexId b = to(h);
    const VertexId m = new_vertex(p);
    const FaceId f2 = side_h ? new_face() : FaceId(), f3 = side_o ? new_face() : FaceId();
    const HalfedgeId x = halfedge(new_edge(m, b), 0);  // m -> b; twin b -> m
    to_[h.idx()] = m;                                  // h: a -> m, o: m -> a
    if (side_h) {                                      // (a, b, c) -> (a, m, c), (m, b, c)
        const HalfedgeId h2 = next(h1);
        const HalfedgeId y = halfedge(new_edge(m, to(h1)), 0);
        set_face_loop(face(h), h, y, h2);
        set_face_loop(f2, x, h1, twin(y));
    } else {  // h stays on the boundary, followed by x
        next_[x.idx()] = next(h);
        next_[h.idx()] = x;
        face_[x.idx()] = FaceId();
    }
    if (side_o) {  // (b, a, d) -> (b, m, d), (m, a, d)
        const HalfedgeId o1 = next(o), o2 = next(o1);
        const HalfedgeId z = halfedge(new_edge(m, to(o1)), 0);
        set_face_loop(face(o), twin(x), z, o2);
        set_face_loop(f3, o, o1, twin(z));
    } else {  // twin(x) then o along the boundary
        next_[before_o.idx()] = twin(x);
        next_[twin(x).idx()] = o;
        face_[twin(x).idx()] = FaceId();
    }
    // On the boundary, out(m) and out(b) are their boundary halfedges (INV-MESH-7).
    out_[m.idx()] = side_o ? x : o;
    if (!side_h) out_[m.idx()] = x;
    if (out_[b.idx()] == o) out_[b.idx()] = side_o ? h1 : twin(x);
    return m;
}

bool TriMesh::is_collapse_ok(HalfedgeId h) const {
    if (is_boundary(edge(h))) return false;
    const VertexId v0 = from(h), v1 = to(h), va = to(next(h)), vb = to(next(twin(h)));
    if (va == vb) return false;
    if (n_vertices() - deleted_vertices_ <= 4) return false;
    // Link condition: the common neighbours of v0 and v1 are exactly va and vb. v1's neighbours
    // are gathered once into a small contiguous buffer on the stack, then each neighbour of v0 is
    // looked up there. Valences are small; past the buffer's size (a vertex of valence > 64) each
    // lookup walks v1's ring instead. No scratch outside the call, so several readers
    // of one mesh stay safe (spec/library.md, "Thread safety").
    std::array<VertexId, 64> ring;
    std::size_t valence = 0;
    for_each_outgoing(v1, [&](HalfedgeId g) {
        if (valence < ring.size()) ring[valence] = to(g);
        ++valence;
    });
    const std::span<const VertexId> gathered(ring.data(), std::min(valence, ring.size()));
    const auto adjacent_to_v1 = [&](VertexId w) {
        return valence <= ring.size() ? std::find(gathered.begin(), gathered.end(), w) != gathered.end()
                                      : find_halfedge(v1, w).valid();
    };
    bool ok = true;
    for_each_outgoing(v0, [&](HalfedgeId g) {
        const VertexId w = to(g);
        if (w != v1 && w != va && w != vb && adjacent_to_v1(w)) ok = false;
    });
    return ok;
}

void TriMesh::collapse(HalfedgeId h) {
    FHR_DCHECK(is_collapse_ok(h));
    const HalfedgeId h1 = next(h), h2 = next(h1), o = twin(h), o1 = next(o), o2 = next(o1);
    const HalfedgeId t2 = twin(h2), s1 = twin(o1);  // outer halfedges that lose their faces' partners
    const VertexId v0 = from(h), v1 = to(h), va = to(h1), vb = to(o1);
    // Everything that pointed at v0 now points at v1.
    for_each_outgoing(v0, [&](HalfedgeId g) { to_[twin(g).idx()] = v1; });
    // h1 (v1 -> va) takes the place of t2 (v1 -> va) in t2's face; o2 (vb -> v1) that of s1.
    take_place(h1, t2);
    take_place(o2, s1);
    out_[v1.idx()] = h1;
    out_[va.idx()] = twin(h1);
    out_[vb.idx()] = o2;
    fh_[face(h).idx()] = HalfedgeId();
    fh_[face(o).idx()] = HalfedgeId();
    out_[v0.idx()] = HalfedgeId();
    ++deleted_vertices_;
    for (HalfedgeId g : {h, o, h2, t2, o1, s1}) {
        to_[g.idx()] = VertexId();
        face_[g.idx()] = FaceId();
        next_[g.idx()] = HalfedgeId();
    }
}

void TriMesh::take_place(HalfedgeId keep, HalfedgeId gone) {
    next_[prev(gone).idx()] = keep;
    next_[keep.idx()] = next(gone);
    face_[keep.idx()] = face(gone);
    fh_[face(gone).idx()] = keep;
}

VertexId TriMesh::new_vertex(const Vec3& p) {
    pos_.push_back(p);
    out_.push_back(HalfedgeId());
    return VertexId(static_cast<VertexId::Index>(n_vertices() - 1));
}

FaceId TriMesh::new_face() {
    fh_.push_back(HalfedgeId());
    return FaceId(static_cast<FaceId::Index>(n_faces() - 1));
}

VertexId TriMesh::split_vertex(VertexId v1, VertexId va, VertexId vb, const Vec3& p) {
    const HalfedgeId ha = find_halfedge(v1, va), hb = find_halfedge(v1, vb);
    if (!ha.valid() || !hb.valid() || va == vb)
        broken("split_vertex: vertices " + std::to_string(va.idx()) + " and " + std::to_string(vb.idx()) +
               " are not two neighbours of " + vname(v1));
    const VertexId v0 = new_vertex(p);
    // Outgoing halfedges of v1 strictly inside the wedge (ha, hb) now leave v0.
    for (HalfedgeId g = ccw_rotated(ha); g != hb; g = ccw_rotated(g)) to_[twin(g).idx()] = v0;
    const HalfedgeId h = halfedge(new_edge(v0, v1), 0);   // h: v0 -> v1, twin: v1 -> v0
    const HalfedgeId na = halfedge(new_edge(v0, va), 0);  // v0 -> va
    const HalfedgeId nb = halfedge(new_edge(v0, vb), 0);  // v0 -> vb
    // In the wedge, v0 -> va replaces v1 -> va, and vb -> v0 replaces vb -> v1.
    const HalfedgeId hb_twin = twin(hb);
    take_place(na, ha);
    take_place(twin(nb), hb_twin);
    set_face_loop(new_face(), h, ha, twin(na));       // (v0, v1, va)
    set_face_loop(new_face(), twin(h), nb, hb_twin);  // (v1, v0, vb)
    out_[v0.idx()] = na;
    out_[v1.idx()] = ha;
    out_[vb.idx()] = hb_twin;
    return v0;
}

VertexId TriMesh::split_face(FaceId f, const Vec3& p) {
    const HalfedgeId a = halfedge(f), b = next(a), c = next(b);
    const VertexId va = from(a), vb = from(b), vc = from(c);
    const VertexId m = new_vertex(p);
    const HalfedgeId ma = halfedge(new_edge(m, va), 0), mb = halfedge(new_edge(m, vb), 0),
                     mc = halfedge(new_edge(m, vc), 0);
    set_face_loop(f, a, twin(mb), ma);           // (va, vb, m)
    set_face_loop(new_face(), b, twin(mc), mb);  // (vb, vc, m)
    set_face_loop(new_face(), c, twin(ma), mc);  // (vc, va, m)
    out_[m.idx()] = ma;
    return m;
}

void TriMesh::compact() {
    if (!has_garbage()) return;
    std::vector<VertexId> vmap(n_vertices());
    std::vector<EdgeId> emap(n_edges());
    std::vector<FaceId> fmap(n_faces());
    std::uint32_t nv = 0, ne = 0, nf = 0;
    for (VertexId v : vertices()) vmap[v.idx()] = is_deleted(v) ? VertexId() : VertexId(nv++);
    for (EdgeId e : edges()) emap[e.idx()] = is_deleted(e) ? EdgeId() : EdgeId(ne++);
    for (FaceId f : faces()) fmap[f.idx()] = is_deleted(f) ? FaceId() : FaceId(nf++);
    auto mh = [&](HalfedgeId h) { return HalfedgeId(2 * emap[edge(h).idx()].idx() + (h.idx() & 1u)); };
    TriMesh m;
    m.pos_.resize(nv);
    m.out_.resize(nv);
    m.fh_.resize(nf);
    m.to_.resize(2 * ne);
    m.next_.resize(2 * ne);
    m.face_.resize(2 * ne);
    for (VertexId v : vertices())
        if (vmap[v.idx()].valid()) {
            m.pos_[vmap[v.idx()].idx()] = pos_[v.idx()];
            m.out_[vmap[v.idx()].idx()] = mh(out(v));
        }
    for (FaceId f : faces())
        if (fmap[f.idx()].valid()) m.fh_[fmap[f.idx()].idx()] = mh(halfedge(f));
    for (HalfedgeId h : halfedges()) {
        if (is_deleted(edge(h))) continue;
        const HalfedgeId n = mh(h);
        m.to_[n.idx()] = vmap[to(h).idx()];
        m.next_[n.idx()] = mh(next(h));
        m.face_[n.idx()] = is_boundary(h) ? FaceId() : fmap[face(h).idx()];
    }
    *this = std::move(m);
}

// --- invariants (spec/mesh.md) --------------------------------------------------------------

void TriMesh::validate() const {
    if (has_garbage()) broken("INV-MESH-0: mesh has garbage from collapses (call compact())");
    if (pos_.size() != out_.size() || next_.size() != to_.size() || face_.size() != to_.size() || to_.size() % 2)
        broken("INV-MESH-1: array sizes disagree");
    const std::size_t nv = n_vertices(), nh = n_halfedges(), nf = n_faces();
    for (HalfedgeId h : halfedges()) {
        if (!to(h).valid() || to(h).idx() >= nv || !next(h).valid() || next(h).idx() >= nh)
            broken("INV-MESH-1: " + hname(h) + " has an out-of-range reference");
        if (face(h).valid() && face(h).idx() >= nf) broken("INV-MESH-1: " + hname(h) + " has an out-of-range face");
        if (to(h) == from(h)) broken("INV-MESH-2: " + hname(h) + " is a loop at " + vname(to(h)));
        if (from(next(h)) != to(h)) broken("INV-MESH-3: next of " + hname(h) + " does not start where it ends");
        if (face(next(h)) != face(h)) broken("INV-MESH-4: next of " + hname(h) + " lies in another face");
        if (is_boundary(h) && is_boundary(twin(h)))
            broken("INV-MESH-5: edge " + std::to_string(edge(h).idx()) + " has no face on either side");
    }
    for (FaceId f : faces()) {
        const HalfedgeId h = halfedge(f);
        if (!h.valid() || h.idx() >= nh || face(h) != f)
            broken("INV-MESH-4: face " + std::to_string(f.idx()) + " does not own its halfedge");
        if (next(next(next(h))) != h) broken("INV-MESH-4: face " + std::to_string(f.idx()) + " is not a triangle");
    }
    std::vector<std::uint32_t> degree(nv, 0);
    for (HalfedgeId h : halfedges()) ++degree[from(h).idx()];
    for (VertexId v : vertices()) {
        const HalfedgeId h = out(v);
        if (!h.valid() || h.idx() >= nh || from(h) != v)
            broken("INV-MESH-6: out of " + vname(v) + " does not leave it");
        std::uint32_t n = 0, boundary = 0;
        HalfedgeId g = h;
        do {
            if (++n > degree[v.idx()]) break;
            boundary += is_boundary(g);
            g = cw_rotated(g);
        } while (g != h);
        if (n != degree[v.idx()]) broken("INV-MESH-7: " + vname(v) + " is not a single fan (non-manifold vertex)");
        if (boundary > 1 || (boundary == 1 && !is_boundary(h)))
            broken("INV-MESH-7: " + vname(v) + " has several boundary fans, or out() is not its boundary halfedge");
    }
    // INV-MESH-8: no two edges join the same pair of vertices.
    for (VertexId v : vertices()) {
        for_each_outgoing(v, [&](HalfedgeId g) {
            for_each_outgoing(v, [&](HalfedgeId k) {
                if (g < k && to(g) == to(k)) broken("INV-MESH-8: two edges join " + vname(v) + " and " + vname(to(g)));
            });
        });
    }
}

}  // namespace fhr
