// FHR §2/§3 — a parameter domain given by the user: D and, for each vertex v_j of D, its point
// x_j on Ω_T (paper §2: "a correspondence between the vertices v_j of D and some suitable points
// on Ω_T"). A point inside a face or on an edge of T is inserted into T first, splitting the face
// into three triangles or the edge's two triangles into four (paper §3, Fig. 4), so that from
// then on every x_j is a vertex of T, exactly as after decimation.
#pragma once

#include <string>
#include <vector>

#include <fhr/core/surface_point.hpp>
#include <fhr/domain/decimate.hpp>

namespace fhr::domain {

/// Names for messages: the domain file and the correspondence file.
struct DomainSources {
    std::string domain_file, correspondence_file;
};

/// Attaches D to T. T gains one vertex per x_j that is not a vertex (its geometry Ω_T does not
/// change); the result's t_vertex[j] is x_j's vertex of the modified T; history is empty.
/// \pre T and D are valid meshes (build_trimesh; boundary loops and several components allowed);
///      x was parsed against the unmodified T.
/// \throws InvalidInput (DOM-10..13, 21 of spec/domain.md): entry count differs from D's vertex
///         count; D's Euler characteristic, boundary loops or components differ from T's; two
///         entries name the same point (or points closer than 1e−12 in barycentric terms within a
///         face); D's boundary does not follow T's (close_domain).
Domain attach_domain(TriMesh& T, TriMesh D, const std::vector<NamedSurfacePoint>& x, const DomainSources& sources);

}  // namespace fhr::domain
