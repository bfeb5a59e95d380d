// FHR core — geometry helpers on T: lengths, angles, areas, normals, bounding box, volume.
// Used by §2 (decimation quality), §3 (edge lengths for geodesics), §4 (the 3-D angles of
// Floater's shape-preserving weights) and the reports.
#pragma once

#include <fhr/core/trimesh.hpp>

namespace fhr {

double edge_length(const TriMesh& m, EdgeId e);
Vec3 edge_vector(const TriMesh& m, HalfedgeId h);  ///< position(to(h)) − position(from(h))
double face_area(const TriMesh& m, FaceId f);
/// Unit normal of a face, counter-clockwise orientation; zero vector for a degenerate face.
Vec3 face_normal(const TriMesh& m, FaceId f);
/// The same for the triangle (a, b, c): face_normal is triangle_normal of face_vertices' positions.
Vec3 triangle_normal(const Vec3& a, const Vec3& b, const Vec3& c);
/// The interior angle of h's face at from(h), in [0, π] (atan2 form, accurate for small angles).
double corner_angle(const TriMesh& m, HalfedgeId h);
/// Angle-weighted unit vertex normal.
Vec3 vertex_normal(const TriMesh& m, VertexId v);
/// Sum of the angles at v of its faces (2π at a flat interior vertex).
double angle_sum(const TriMesh& m, VertexId v);

struct BoundingBox {
    Vec3 min, max;
    double diagonal() const { return (max - min).norm(); }
};
BoundingBox bounding_box(const TriMesh& m);

/// Signed volume enclosed by a closed mesh (positive for outward orientation).
double signed_volume(const TriMesh& m);

struct EdgeLengthStats {
    double min = 0, max = 0, mean = 0, median = 0;
};
EdgeLengthStats edge_length_stats(const TriMesh& m);

/// How hard a mesh is for numerical code (`fhr info` and bench/generator_stats.py compare
/// generated meshes with real ones by these): the smallest and largest corner angle (radians,
/// atan2 of |u × v| and u · v, accurate
/// for needles and caps alike) and the smallest and largest vertex valence (boundary vertices
/// count their edges too). All zero for a mesh without faces.
struct ShapeStats {
    double min_angle = 0, max_angle = 0;
    std::size_t min_valence = 0, max_valence = 0;
};
ShapeStats shape_stats(const TriMesh& m);

/// The squared distance from p to the box [lo, hi] (0 inside), without branches: which side p is
/// on is as good as random, and mispredicted branches were most of a Hausdorff query's time.
/// closest_point_on_triangle's rounded squared distance to p is never below its triangle's
/// box's: a search may skip boxes no nearer than its best so far (§5's tree, the oracle's PARAM-11).
double box_distance2(const Vec3& p, const Vec3& lo, const Vec3& hi);

/// An upper bound, within 10⁻¹² relative, of max over the points p of triangle abc of min_k |p − x_k|:
/// how far a point of the triangle can be from every corner (§5's Lipschitz bound, WAV-9). Not
/// obtuse: the circumradius; obtuse: where the perpendicular bisectors of the two shorter sides
/// meet the longest; never above ℓ/√3 (ℓ the longest side).
double corner_cover_radius(const Vec3& a, const Vec3& b, const Vec3& c);

/// The point of triangle abc closest to p: p's projection onto the plane when it falls inside,
/// else the nearest point of the edges; within a few u·(diameter) of the exact one also on needles
/// (geometry.cpp). Shared by the oracle's PARAM-11 (src/fhr/exchange) and the Hausdorff distance
/// of §5 (src/fhr/wavelet).
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace fhr
