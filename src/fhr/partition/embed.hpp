// FHR §3 — embedding the geodesic network into T, giving the refined triangulation T′ (eq. 1,
// Fig. 3), and checking the paper's conditions (1) and (2) on it.
//
// Paper §3: "we can therefore insert all segments of these geodesic curves into the triangulation
// T, yielding a refined triangulation T′. All points u_p will become vertices in T′ and the
// segments [u_p, u_{p+1}] will become edges of T′. The geometry of T′ is the same as that of T";
// each segment cuts a triangle into a triangle and a quadrilateral, split by either diagonal. The
// curves partition Ω_T into patches when (1) they meet only at common endpoints and (2) their
// cyclic order around each x_j is that of D's edges around v_j.
//
// Pseudocode (all paths at once, face by face, so several paths in one triangle are no special case):
//   for each path Γ_e (D edge e, from x_j to x_k): its nodes as vertices of T or points (edge, t)
//       of T, a node within snap_fraction of an edge's end moved to that end; each node becomes a
//       vertex of T′ (T's own vertices keep their numbers); a node visited by two paths, or a
//       corner x_m inside a path, breaks (1)
//   each segment is either a piece of an edge of T or a chord of the face of T holding both ends
//   for each face of T: its boundary polygon (corners, then the nodes on its edges in order);
//       two chords that interleave along it cross, breaking (1); otherwise the chords cut the
//       polygon into convex pieces, each triangulated with the largest smallest angle (dynamic
//       programming; a triangle with its three corners on one side of the face is never chosen)
//   T′ <- all these triangles; every segment is an edge of T′ and carries its D halfedge
//   (2): around each x_j, the D halfedges on T′'s edges in turning order equal D's around v_j
// Decisions and their reasons: paper_notes/partition.md.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <fhr/core/executor.hpp>

#include <fhr/core/trimesh.hpp>
#include <fhr/domain/domain.hpp>
#include <fhr/geodesic/exact.hpp>

namespace fhr::partition {

/// A node of a path closer than snap_fraction · |edge| to an end of its edge of T is moved to that
/// end (a vertex of T). This keeps every triangle of T′ at least that far from degenerate along
/// T's edges; the path moves by at most snap_fraction · |edge| per node (paper_notes/partition.md).
inline constexpr double snap_fraction = 1e-6;

/// Where a vertex of T′ lies on T: every vertex of T′ is a vertex of T or a point of an edge of T.
struct Origin {
    TVertexId vertex;  ///< valid: this vertex of T
    TEdgeId edge;      ///< otherwise: the point (1 − t)·from + t·to of T's halfedge(edge, 0)
    double t = 0;
};

/// A vertex of T′ inside a path: the D edge of the path and the node's index along it.
struct PathPosition {
    DEdgeId d_edge;  ///< invalid: not inside any path
    std::uint32_t index = 0;
};

/// A violation of condition (1) or (2), naming the D edges whose paths are involved.
struct Conflict {
    enum class Kind {
        shared_node,     ///< (1): two paths (or one path twice) pass through the same point
        crossing,        ///< (1): two paths cross inside a face of T
        through_corner,  ///< (1): a path passes through a corner x_m that is not its end
        order,           ///< (2): the cyclic order of the paths at x_j differs from D's
    };
    Kind kind;
    DEdgeId d_edge_a, d_edge_b;  ///< the D edges (equal when only one is involved), a <= b
    DVertexId d_vertex;          ///< through_corner and order: the D vertex v_m / v_j, else invalid
    /// Vertices of T at the place (unused ones invalid), each the one nearest to a node of T′
    /// (the node itself, or the nearer end of its edge of T): shared_node: the shared node;
    /// through_corner: the curve's nodes just before and after x_m; order: the curve's first node
    /// after x_j; crossing: the face of T where the curves cross.
    std::array<TVertexId, 3> near{};
    std::string describe() const;
};

/// The refined triangulation T′ with the geodesic network embedded in it.
struct Network {
    TriMesh mesh;                                   ///< T′; vertices 0..#V(T)−1 are T's vertices
    VertexData<Origin> origin;                      ///< #V(T′)
    VertexData<PathPosition> on_path;               ///< #V(T′)
    VertexData<DVertexId> corner;                   ///< #V(T′): the D vertex v_j at x_j, else invalid
    IdVector<DEdgeId, std::vector<VertexId>> path;  ///< #E(D): vertices of T′ from x_j to x_k along Γ_e
                                                    ///< (direction of D's halfedge (e, 0))
    HalfedgeData<DHalfedgeId> d_halfedge;           ///< #H(T′): the D halfedge it runs along, else invalid
    FaceData<TFaceId> t_face;                       ///< #F(T′): the face of T that holds it
    double max_snap_distance = 0;                   ///< the farthest a node was moved by snapping
};

struct Embedding {
    std::vector<Conflict> conflicts;  ///< empty: (1) and (2) hold and `network` is complete
    Network network;                  ///< complete only when there are no conflicts
};

/// Embeds one path per edge of D into T.
/// \pre T valid (T̂ closed by cones, or T with boundary: then D's boundary edges carry T's boundary
///      arcs, PART-12); paths[e] runs from x_j to x_k for D's halfedge (e, 0) and is a
///      polyline with consecutive nodes in a common face of T (GeodesicPath's contract).
/// \post when no conflict: network.mesh is valid with T's topology (χ, loops, components), Ω_T′ = Ω_T, and
///       every segment of every (snapped) path is an edge of T′ labelled with its D halfedge.
/// `unsnapped` (empty, or one flag per path): a path flagged 1 is placed exactly as given, without
/// snapping — a restricted path whose separation points lie closer to a vertex of T than
/// snap_fraction on purpose (partition/restricted.hpp).
/// \throws ContractViolation when a path breaks its contract (not a caller's input error).
/// The faces of T are cut and triangulated in parallel on `executor` (default_executor() when
/// null): the result is the same on any number of threads.
Embedding embed(const TriMesh& T, const domain::Domain& D, std::span<const geodesic::GeodesicPath> paths,
                std::span<const std::uint8_t> unsnapped = {}, Executor* executor = nullptr);

/// Embeds curves that are not (yet) a whole domain's network — the few curves around a region of
/// T′ (partition/region.hpp) — into T, which may have a boundary: as embed(), with the curves'
/// ends as the corners (numbered in order of first appearance), curve i labelling halfedges 2i
/// (along it) and 2i + 1, and no condition (2) (there is no D to compare with).
Embedding embed_curves(const TriMesh& T, std::span<const geodesic::GeodesicPath> curves,
                       std::span<const std::uint8_t> unsnapped = {}, Executor* executor = nullptr);

/// Condition (2) at one vertex v_j of D: in_d holds D's halfedges out of v_j in D's cyclic order,
/// in_t the D halfedges of the curves leaving x_j in T′'s cyclic order. Flag k is 1 when D's edge
/// in_d[k] or its predecessor around v_j has another successor around x_j than around v_j, so
/// that exactly the curves on either side of a misplaced pair are reported; every flag is 1 when
/// the curves at x_j are not exactly D's edges there.
std::vector<std::uint8_t> out_of_order(std::span<const DHalfedgeId> in_d, std::span<const DHalfedgeId> in_t);

}  // namespace fhr::partition
