// FHR core — SurfacePoint: a point of Ω_T given combinatorially. The paper's
// geodesic Γ(x_j, x_k) (§3, eq. 1) is a polyline u_1 … u_r whose nodes lie on edges of T or at
// its vertices, and a domain vertex may correspond to a point inside a face or on an edge (§3,
// Fig. 4); a SurfacePoint names exactly such a location without rounding it to coordinates.
#pragma once

#include <array>
#include <cstdint>

#include <fhr/core/trimesh.hpp>

namespace fhr {

struct SurfacePoint {
    enum class Kind { vertex, edge, face };
    Kind kind = Kind::vertex;
    VertexId vertex;               ///< kind == vertex
    HalfedgeId halfedge;           ///< kind == edge: the point (1 − t)·from + t·to of this halfedge
    double t = 0;                  ///< kind == edge, in [0, 1]
    FaceId face;                   ///< kind == face
    std::array<double, 3> bary{};  ///< kind == face: weights of face_vertices(face), summing to 1

    static SurfacePoint at_vertex(VertexId v) {
        SurfacePoint p;
        p.vertex = v;
        return p;
    }
    static SurfacePoint on_edge(HalfedgeId h, double t) {
        SurfacePoint p;
        p.kind = Kind::edge;
        p.halfedge = h;
        p.t = t;
        return p;
    }
    static SurfacePoint in_face(FaceId f, const std::array<double, 3>& bary) {
        SurfacePoint p;
        p.kind = Kind::face;
        p.face = f;
        p.bary = bary;
        return p;
    }
};

/// A point of a surface as an input named it: the point, and the 1-based line of the text file
/// that gave it (0 when it came from memory). What §2 attaches a user's domain with
/// (domain::attach_domain) and the correspondence file holds (io/correspondence.hpp).
struct NamedSurfacePoint {
    SurfacePoint point;      ///< Kind::vertex or Kind::face, as written
    std::uint64_t line = 0;  ///< 1-based line in the file; 0: not from a file
};

/// The point's coordinates in R^3.
Vec3 position(const TriMesh& mesh, const SurfacePoint& p);

/// The same point in its simplest form: an edge point with t = 0 or 1 becomes a vertex, a face
/// point with a zero weight becomes an edge point (or a vertex), so that equal locations compare
/// equal. Exact: no tolerance is applied.
SurfacePoint canonical(const TriMesh& mesh, const SurfacePoint& p);

/// Whether two vertices or edge points lie in one face of the mesh (consecutive nodes of a curve
/// on it do). A vertex lies in its faces, an edge point in its edge's one or two.
/// \pre neither is a face point.
bool share_face(const TriMesh& mesh, const SurfacePoint& a, const SurfacePoint& b);

/// True when both name the same location (after canonical()).
bool same_location(const TriMesh& mesh, const SurfacePoint& a, const SurfacePoint& b);

}  // namespace fhr
