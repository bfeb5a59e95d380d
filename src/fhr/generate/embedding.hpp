// FHR generate — is a triangle mesh embedded? Beyond the paper: the generator's
// families promise embedded surfaces ("no two non-adjacent triangles intersect") and the immersed
// family promises the opposite, so both the whole-mesh check and an incremental guard that keeps
// a mesh embedded edit by edit decide with the exact predicates of core/detail/predicates.hpp. The
// argument (paper_notes/generator.md, "Embedding"):
//
//   A mesh is embedded when every triangle is non-degenerate and any two triangles meet exactly
//   in what they share: nothing (no common vertex), their common vertex, or their common edge.
//   Two closed triangles A, B meet iff an edge of one meets the other (their intersection is
//   convex, its relative boundary lies on their boundaries). With one common vertex v,
//   A = (v, a1, a2) and B = (v, b1, b2) meet elsewhere iff a1a2 meets B or b1b2 meets A (a ray
//   from v through another common point leaves A through a1a2 and B through b1b2, and the nearer
//   of those two exits lies in both). With a common edge uv, A = (u, v, a) and B = (u, v, b) meet
//   elsewhere iff they are coplanar with a and b on the same side of uv (a third common point
//   spans the plane of both).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <unordered_map>
#include <vector>

#include <fhr/core/trimesh.hpp>

namespace fhr::generate {

/// A triangle as an edit would make it: its vertices (ids of the mesh, or new ids not yet in it,
/// e.g. n_vertices() for the vertex a split will add) and their positions.
struct TriangleAt {
    std::array<VertexId, 3> v;
    std::array<Vec3, 3> p;
};

/// The triangle of face f as it is in m.
TriangleAt triangle_at(const TriMesh& m, FaceId f);

/// True iff the closed triangle is degenerate (its corners are collinear, or two coincide). Exact.
bool is_degenerate(const TriangleAt& t);

/// True iff the two closed non-degenerate triangles meet in more than what their common vertex ids
/// say they share (nothing, one vertex, one edge): the header's argument. Exact.
bool meet_improperly(const TriangleAt& a, const TriangleAt& b);

/// The first degenerate face (as {f, f}) or the first pair of faces that meet improperly, if any:
/// none means m is embedded. Uniform-grid broad phase; about linear in the face count.
std::optional<std::array<FaceId, 2>> find_self_intersection(const TriMesh& m);

/// Keeps a mesh embedded edit by edit: for a mesh that is embedded when the guard is made, an
/// edit (faces removed, triangles added) that `accepts` and is then applied with `remove` before
/// and `insert` after leaves it embedded. The guard holds a uniform grid of the faces' bounding
/// boxes; its answers depend only on the mesh, never on the order of the grid's buckets.
class EmbeddingGuard {
public:
    /// \pre m is embedded (find_self_intersection(m) is empty). cell: the grid's cell size (> 0);
    ///      about twice the mean edge length is a good choice.
    EmbeddingGuard(const TriMesh& m, double cell);
    /// True iff the added triangles are non-degenerate, and meet neither each other nor any face
    /// of m other than `removed` improperly.
    bool accepts(const TriMesh& m, std::span<const FaceId> removed, std::span<const TriangleAt> added) const;
    /// Forget face f (call before an edit changes it, with m as it still is).
    void remove(const TriMesh& m, FaceId f);
    /// Record face f (call after an edit made or changed it).
    void insert(const TriMesh& m, FaceId f);

private:
    using Key = std::uint64_t;
    double cell_;
    std::unordered_map<Key, std::vector<std::uint32_t>> buckets_;
    template <typename F>
    void for_each_cell(const std::array<Vec3, 3>& p, F&& f) const;
};

}  // namespace fhr::generate
