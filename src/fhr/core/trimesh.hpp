// FHR core — TriMesh, the index-based halfedge triangulation T of the paper (§1: a manifold
// triangulation whose union Ω_T is an orientable 2-manifold).
//
// Layout: edge e owns halfedges 2e and 2e+1, so twin(h) = h ^ 1 and edge(h) = h >> 1. Per
// halfedge we store `to` (its head vertex), `next` (next halfedge of its face, or of its boundary
// loop) and `face` (invalid for a boundary halfedge). Per vertex one outgoing halfedge (a
// boundary one when the vertex is on the boundary), per face one of its halfedges. Positions are
// kept apart from connectivity. The invariants are spec/mesh.md INV-MESH-1..8; validate() checks
// every one of them and names the first that is broken.
//
// Topological edits (flip, split, half-edge collapse) keep all invariants. A collapse leaves
// its removed elements as garbage until compact(); algorithms other than the editors expect a
// mesh without garbage.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <fhr/core/ids.hpp>
#include <fhr/core/polygon_soup.hpp>

namespace fhr {

namespace detail {
struct EdgeTable;
}

using Triangle = std::array<std::uint32_t, 3>;

class TriMesh {
public:
    TriMesh() = default;

    /// Builds the halfedge structure of consistently oriented triangles.
    /// \pre (checked by build_trimesh, which is how input reaches this) every index is
    ///      < positions.size(); no triangle repeats a vertex; every undirected edge lies in at most
    ///      two triangles, which traverse it in opposite directions; every vertex is in one
    ///      triangle at least and its triangles form one fan.
    /// \throws ContractViolation naming the violated precondition.
    static TriMesh from_triangles(std::vector<Vec3> positions, std::span<const Triangle> triangles);
    /// The same, for a caller that has already checked that every index is in range, no triangle
    /// repeats a vertex and every vertex is manifold (build_trimesh), and built `table` =
    /// detail::build_edge_table(positions.size(), triangles): nothing is computed twice.
    static TriMesh from_triangles(std::vector<Vec3> positions, std::span<const Triangle> triangles,
                                  const detail::EdgeTable& table);

    /// The halfedge arrays themselves, slot for slot in the layout above: per halfedge `to`,
    /// `next` and `face` (invalid on the boundary), per vertex `out`, per face `face_halfedge`,
    /// and the positions. They name every element by its id, so they carry a mesh, edited or
    /// not, with all its ids (from_triangles numbers edges its own way).
    struct Arrays {
        std::vector<VertexId> to;
        std::vector<HalfedgeId> next;
        std::vector<FaceId> face;
        std::vector<HalfedgeId> out;
        std::vector<HalfedgeId> face_halfedge;
        std::vector<Vec3> positions;
        bool operator==(const Arrays&) const = default;
    };
    /// A copy of this mesh's arrays (garbage slots included: compact() first to pass them on).
    Arrays arrays() const;
    /// The mesh with exactly these arrays, so `from_arrays(m.arrays())` has every id of m.
    /// Arrays from outside are checked like input: INV-MESH-1..8 hold or nothing is built, and the
    /// checks themselves read no reference before knowing it is in range.
    /// \throws ContractViolation "INV-MESH-k: ..." as validate() does, naming the first broken invariant.
    static TriMesh from_arrays(Arrays arrays);

    // --- sizes (including garbage slots, see has_garbage) ---------------------------------
    std::size_t n_vertices() const { return out_.size(); }
    std::size_t n_halfedges() const { return to_.size(); }
    std::size_t n_edges() const { return to_.size() / 2; }
    std::size_t n_faces() const { return fh_.size(); }
    IdRange<VertexId> vertices() const { return IdRange<VertexId>(n_vertices()); }
    IdRange<HalfedgeId> halfedges() const { return IdRange<HalfedgeId>(n_halfedges()); }
    IdRange<EdgeId> edges() const { return IdRange<EdgeId>(n_edges()); }
    IdRange<FaceId> faces() const { return IdRange<FaceId>(n_faces()); }

    // --- navigation -----------------------------------------------------------------------
    // Index arithmetic, the same in every TriMesh: also for the ids of D or T where they meet
    // other meshes' (ids.hpp), keeping their mesh.
    template <class M>
    static Id<HalfedgeTag, M> twin(Id<HalfedgeTag, M> h) {
        return Id<HalfedgeTag, M>(h.idx() ^ 1u);
    }
    template <class M>
    static Id<EdgeTag, M> edge(Id<HalfedgeTag, M> h) {
        return Id<EdgeTag, M>(h.idx() >> 1);
    }
    template <class M>
    static Id<HalfedgeTag, M> halfedge(Id<EdgeTag, M> e, unsigned side) {
        return Id<HalfedgeTag, M>(2 * e.idx() + side);
    }
    VertexId to(HalfedgeId h) const { return to_[h.idx()]; }
    VertexId from(HalfedgeId h) const { return to_[h.idx() ^ 1u]; }
    HalfedgeId next(HalfedgeId h) const { return next_[h.idx()]; }
    /// Previous halfedge of h's face or boundary loop (a boundary loop is walked: O(loop length)).
    HalfedgeId prev(HalfedgeId h) const;
    FaceId face(HalfedgeId h) const { return face_[h.idx()]; }
    HalfedgeId out(VertexId v) const { return out_[v.idx()]; }
    HalfedgeId halfedge(FaceId f) const { return fh_[f.idx()]; }
    /// The next outgoing halfedge of from(h), turning counter-clockwise: twin(prev(h)).
    HalfedgeId ccw_rotated(HalfedgeId h) const { return twin(prev(h)); }
    /// The next outgoing halfedge of from(h), turning clockwise: next(twin(h)).
    HalfedgeId cw_rotated(HalfedgeId h) const { return next(twin(h)); }

    bool is_boundary(HalfedgeId h) const { return !face_[h.idx()].valid(); }
    bool is_boundary(EdgeId e) const { return is_boundary(halfedge(e, 0)) || is_boundary(halfedge(e, 1)); }
    bool is_boundary(VertexId v) const { return is_boundary(out(v)); }
    bool is_closed() const;

    std::array<VertexId, 3> face_vertices(FaceId f) const;
    std::size_t valence(VertexId v) const;
    /// The halfedge from a to b, or an invalid id when a and b are not adjacent.
    HalfedgeId find_halfedge(VertexId a, VertexId b) const;

    /// Calls f(h) for every outgoing halfedge h of v, clockwise, starting at out(v).
    template <class F>
    void for_each_outgoing(VertexId v, F&& f) const {
        const HalfedgeId start = out(v);
        HalfedgeId h = start;
        do {
            f(h);
            h = cw_rotated(h);
        } while (h != start);
    }

    // --- geometry -------------------------------------------------------------------------
    const Vec3& position(VertexId v) const { return pos_[v.idx()]; }
    Vec3& position(VertexId v) { return pos_[v.idx()]; }
    const std::vector<Vec3>& positions() const { return pos_; }

    /// Faces as vertex triples in their orientation (garbage faces are skipped).
    std::vector<Triangle> triangles() const;

    // --- topological edits (closed surfaces; each keeps INV-MESH-1..8) ----------------------
    /// True when the interior edge e can be flipped: its opposite vertices differ, are not yet
    /// adjacent, and both ends keep valence >= 3.
    bool is_flip_ok(EdgeId e) const;
    /// Replaces the diagonal of the two triangles at e by the other diagonal. \pre is_flip_ok(e).
    void flip(EdgeId e);
    /// Inserts a vertex at `p` on edge e, splitting its one or two triangles; halfedge(e, 0) keeps
    /// its tail and now ends at the new vertex. \return the new vertex; out(new) points to the old
    /// to(halfedge(e, 0)), or on the boundary is its boundary halfedge.
    VertexId split_edge(EdgeId e, const Vec3& p);
    /// Link condition for the half-edge collapse from(h) -> to(h) on a closed mesh: the two
    /// ends share exactly the two opposite vertices as common neighbours, and the mesh keeps
    /// more than 4 vertices. Theorem (Dey et al. 1999): then the result is again a closed
    /// 2-manifold of the same topology.
    bool is_collapse_ok(HalfedgeId h) const;
    /// Removes from(h) by moving its edges to to(h) (half-edge collapse, paper §2), removing the
    /// two faces at h. Removed elements become garbage until compact(). \pre is_collapse_ok(h).
    void collapse(HalfedgeId h);
    /// The inverse of collapse(): splits v1 into v1 and a new vertex v0 at `p`, joined by an edge,
    /// with the new triangles (v0, v1, va) and (v1, v0, vb). The faces of v1 strictly inside the
    /// counter-clockwise wedge from va to vb move to v0. Undoing collapse(h) is
    /// split_vertex(to(h), to(next(h)), to(next(twin(h))), old position of from(h)).
    /// \pre va and vb are distinct neighbours of v1. \return v0 (a new, last vertex).
    VertexId split_vertex(VertexId v1, VertexId va, VertexId vb, const Vec3& p);
    /// Inserts a vertex at `p` inside face f, splitting it into three triangles (paper §3, Fig. 4).
    /// \return the new vertex.
    VertexId split_face(FaceId f, const Vec3& p);
    /// Closes the boundary loop of the boundary halfedge h by a cone: a new vertex at `apex`
    /// joined to every vertex of the loop, one new triangle (from(g), to(g), apex) per boundary
    /// halfedge g of the loop. Every existing element keeps its id; the new vertex, edges and faces
    /// come after them (core/detail/cones.hpp). \pre is_boundary(h). \return the new vertex.
    VertexId fill_hole(HalfedgeId h, const Vec3& apex);
    bool has_garbage() const { return deleted_vertices_ != 0; }
    bool is_deleted(VertexId v) const { return !out_[v.idx()].valid(); }
    bool is_deleted(FaceId f) const { return !fh_[f.idx()].valid(); }
    bool is_deleted(EdgeId e) const { return !to_[2 * e.idx()].valid(); }
    /// Renumbers the surviving elements densely, keeping their relative order.
    void compact();

    /// Checks INV-MESH-1..8 of spec/mesh.md. \throws ContractViolation "INV-MESH-k: ..." naming
    /// the first broken invariant and the element where it breaks.
    void validate() const;

private:
    std::vector<VertexId> to_;
    std::vector<HalfedgeId> next_;
    std::vector<FaceId> face_;
    std::vector<HalfedgeId> out_;
    std::vector<HalfedgeId> fh_;
    std::vector<Vec3> pos_;
    std::size_t deleted_vertices_ = 0;  ///< garbage left by collapse() until compact()

    void set_face_loop(FaceId f, HalfedgeId a, HalfedgeId b, HalfedgeId c);
    void take_place(HalfedgeId keep, HalfedgeId gone);
    VertexId new_vertex(const Vec3& p);
    FaceId new_face();
    EdgeId new_edge(VertexId a, VertexId b);
};

/// The number of elements of the kind an id names, in `m` (whatever mesh the id type is for: the
/// domain's ids count D's elements in D's TriMesh): what IdVector(mesh, value) sizes its data by.
template <class Mesh>
std::size_t element_count(const TriMesh& m, Id<struct VertexTag, Mesh>) {
    return m.n_vertices();
}
template <class Mesh>
std::size_t element_count(const TriMesh& m, Id<struct HalfedgeTag, Mesh>) {
    return m.n_halfedges();
}
template <class Mesh>
std::size_t element_count(const TriMesh& m, Id<struct EdgeTag, Mesh>) {
    return m.n_edges();
}
template <class Mesh>
std::size_t element_count(const TriMesh& m, Id<struct FaceTag, Mesh>) {
    return m.n_faces();
}

}  // namespace fhr
