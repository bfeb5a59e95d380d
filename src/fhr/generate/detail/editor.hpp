// FHR generate — guarded local edits shared by the valence and density families (beyond the paper).
// Both start from a block mesh (embedded, proven) and only ever flip edges, split faces
// and split interior edges; every edit is first offered to an EmbeddingGuard (exact predicates) and
// applied only if accepted, so the mesh stays embedded edit by edit and never gets a degenerate
// triangle. Each edit's effect on the face count is fixed (flip 0, split of a face or of an
// interior edge +2), which is what the families' exact face budgets rest on. The editor also
// remembers each vertex's component, so that the finished mesh can be renumbered component by
// component as GEN-3 requires (new vertices and faces are appended at the end by TriMesh).
// Internal to libfhr_generate.
#pragma once

#include <cstdint>
#include <vector>

#include <fhr/core/trimesh.hpp>
#include <fhr/generate/embedding.hpp>

namespace fhr::generate::detail {

class GuardedEditor {
public:
    /// \pre m is embedded (a block mesh without noise, as base_block makes).
    explicit GuardedEditor(TriMesh m);

    const TriMesh& mesh() const { return m_; }
    /// Component of vertex v: the connected component of the mesh it was given (numbered by their
    /// lowest vertex), inherited by the vertices the edits add.
    std::uint32_t component(VertexId v) const { return component_[v.idx()]; }
    std::size_t components() const { return components_; }

    /// Flips the interior edge e if TriMesh::is_flip_ok(e) and the guard accepts the two new
    /// triangles. \return whether it did.
    bool flip(EdgeId e);
    /// Inserts a vertex at p inside face f (TriMesh::split_face: f keeps one of the three
    /// triangles, two faces are added) if the guard accepts. \return the new vertex, or an
    /// invalid id when refused.
    VertexId split_face(FaceId f, const Vec3& p);
    /// Splits the interior edge e at p (TriMesh::split_edge: two faces are added) if the guard
    /// accepts. \pre !mesh().is_boundary(e). \return the new vertex, or an invalid id when refused.
    VertexId split_edge(EdgeId e, const Vec3& p);

    /// The mesh renumbered component by component (vertices and faces, each in their order of
    /// creation within their component) and rebuilt from its triangles: what reading its written
    /// file gives (GEN-3, GEN-5). Leaves the editor empty.
    TriMesh finish();

private:
    TriMesh m_;
    std::vector<std::uint32_t> component_;
    std::size_t components_ = 0;
    EmbeddingGuard guard_;
};

/// The midpoint of a and b: on an axis-aligned facet or crease it keeps the constant coordinates
/// exactly (0.5 · (x + x) = x).
inline Vec3 midpoint(const Vec3& a, const Vec3& b) { return 0.5 * (a + b); }

/// The point of triangle (a, b, c) halfway along its median from a, barycentric (1/2, 1/4, 1/4):
/// strictly inside, and on an axis-aligned facet exactly in its plane.
inline Vec3 median_point(const Vec3& a, const Vec3& b, const Vec3& c) { return midpoint(a, midpoint(b, c)); }

}  // namespace fhr::generate::detail
