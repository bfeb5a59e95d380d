// Beyond the paper (§3, keeping the domain): a region of T′ cut out on its own.
//
// Keeping D (partition/keep.hpp) changes the network one small region at a time: a flip or a
// tightening replaces the curve inside the union of two patches. Embedding the whole network into
// T again after every such round costs O(|T|) a round and hundreds of rounds (femur, man: most of
// the run). The region, its boundary curves and the faces of T around it are all a change needs,
// so the region is cut out on its own, at a cost proportional to its size.
//
// Pseudocode:
//   S <- the faces of T the region touches, and every face around their vertices (so that every
//        vertex of T′ in the closed region has all its faces); a vertex whose faces in S form
//        more than one fan gets all its faces, until none does
//   T_S <- S as a mesh of its own: a piece of T with boundary, vertices renumbered
//   T′_S <- T_S cut along the given curves (embed_curves): around the region it is T′
//   a side of a curve: the faces of T′_S reached from the face on that side of its first segment
//       without crossing a curve (the region when the curves enclose it: checked, the fill never
//       reaches the border of T_S)
// Decisions and their reasons: paper_notes/partition.md, "Keeping the domain".
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <fhr/core/trimesh.hpp>
#include <fhr/geodesic/exact.hpp>
#include <fhr/partition/embed.hpp>

namespace fhr::partition {

/// A curve of the network, on T, from its first point to its last.
struct RegionCurve {
    const geodesic::GeodesicPath* path = nullptr;
    bool snapped = false;  ///< placed as embed() places a geodesic (snapped); else exactly as given
};

class Region {
public:
    /// \pre `touched` are the faces of T that the region meets; `curves` include every curve on
    ///      the region's boundary, lie in those faces and do not cross one another.
    /// \throws std::logic_error when the curves cross (not a caller's input error).
    Region(const TriMesh& T, std::span<const FaceId> touched, std::span<const RegionCurve> curves);

    /// Adds a curve inside the region (the new curve of a flip or a tightening) and cuts again.
    void add(const RegionCurve& curve);

    const TriMesh& sub() const { return sub_; }            ///< T_S
    const Network& cut() const { return cut_.network; }    ///< T′_S; curve i labels halfedges 2i, 2i + 1

    /// The faces of T′_S on the left (or right) of curve i, as a mask over T′_S's faces.
    /// \throws std::logic_error when the curves do not enclose that side.
    FaceData<std::uint8_t> side(std::size_t curve, bool left) const;
    /// The faces of T holding the masked faces of T′_S, in increasing order.
    std::vector<FaceId> t_faces(const FaceData<std::uint8_t>& mask) const;

    VertexId in_sub(VertexId v) const;             ///< the vertex of T_S at vertex v of T
    VertexId in_t(VertexId v) const { return t_vertex_[v.idx()]; }
    SurfacePoint in_t(const SurfacePoint& p) const;  ///< a vertex or edge point of T_S, on T

private:
    const TriMesh& T_;
    std::vector<VertexId> t_vertex_;  // vertex of T_S -> vertex of T
    std::vector<FaceId> t_face_;      // face of T_S -> face of T
    std::vector<std::pair<VertexId::Index, VertexId::Index>> sub_of_;  // (vertex of T, of T_S), sorted
    TriMesh sub_;
    std::vector<geodesic::GeodesicPath> curves_;  // on T_S
    std::vector<std::uint8_t> unsnapped_;
    Embedding cut_;

    void convert(const RegionCurve& curve);
    void recut();
};

}  // namespace fhr::partition
