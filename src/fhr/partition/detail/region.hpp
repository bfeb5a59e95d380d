// Beyond the paper (§3, keeping the domain): a region of T′ cut out on its own.
//
// Keeping D (partition/detail/keep.hpp) changes the network one small region at a time: a flip or a
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
// Curves the caller took as given (the kept geodesics of the direct start) may not enclose what
// they promised: each step that can find so returns why (core/detail/outcome.hpp) rather than a region.
// Decisions and their reasons: paper_notes/partition.md, "Keeping the domain".
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <variant>
#include <vector>

#include <fhr/core/detail/outcome.hpp>
#include <fhr/core/trimesh.hpp>
#include <fhr/geodesic/exact.hpp>
#include <fhr/partition/embed.hpp>
#include <fhr/partition/patches.hpp>

namespace fhr::partition {

/// A curve of the network, on T, from its first point to its last.
struct RegionCurve {
    const geodesic::GeodesicPath* path = nullptr;
    bool snapped = false;  ///< placed as embed() places a geodesic (snapped); else exactly as given
};

class Region {
public:
    /// The region of `touched`, the faces of T that it meets, cut along `curves`, which include
    /// every curve on its boundary; or why not: a curve leaves those faces, or two curves cross.
    static Outcome<Region> cut_out(const TriMesh& T, std::span<const FaceId> touched,
                                   std::span<const RegionCurve> curves);

    /// Adds a curve inside the region (the new curve of a flip or a tightening) and cuts again;
    /// or why not (as cut_out).
    Outcome<std::monostate> add(const RegionCurve& curve);

    const TriMesh& sub() const { return sub_; }          ///< T_S
    const Network& cut() const { return cut_.network; }  ///< T′_S; curve i labels halfedges 2i, 2i + 1

    /// The faces of T′_S on the left (or right) of curve i, as a mask over T′_S's faces; or why
    /// not: the curves do not enclose that side.
    Outcome<FaceData<std::uint8_t>> side(std::size_t curve, bool left) const;
    /// The patch of the masked faces of T′_S bounded by three of the curves (curve index, and
    /// whether the loop runs against it), the first curve's start its corner 0; or why not
    /// (partition/detail/cut_disk.hpp).
    Outcome<Patch> patch(const FaceData<std::uint8_t>& mask,
                         const std::array<std::pair<std::size_t, bool>, 3>& sides) const;
    /// The faces of T holding the masked faces of T′_S, in increasing order.
    std::vector<FaceId> t_faces(const FaceData<std::uint8_t>& mask) const;

    std::optional<VertexId> find_sub(VertexId v) const;  ///< the vertex of T_S at vertex v of T, if any
    VertexId in_sub(VertexId v) const;  ///< the vertex of T_S at vertex v of T; InternalError when there is none
    VertexId in_t(VertexId v) const { return t_vertex_[v.idx()]; }
    SurfacePoint in_t(const SurfacePoint& p) const;  ///< a vertex or edge point of T_S, on T

private:
    const TriMesh& T_;
    std::vector<VertexId> t_vertex_;                                   // vertex of T_S -> vertex of T
    std::vector<FaceId> t_face_;                                       // face of T_S -> face of T
    std::vector<std::pair<VertexId::Index, VertexId::Index>> sub_of_;  // (vertex of T, of T_S), sorted
    TriMesh sub_;
    std::vector<geodesic::GeodesicPath> curves_;  // on T_S
    std::vector<std::uint8_t> unsnapped_;
    Embedding cut_;

    explicit Region(const TriMesh& T) : T_(T) {}
    Outcome<std::monostate> convert(const RegionCurve& curve);
    Outcome<std::monostate> recut();
};

}  // namespace fhr::partition
