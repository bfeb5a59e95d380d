// FHR core — from a polygon soup to a valid TriMesh: every input rule of spec/mesh.md
// (INV-IN-1..13), checked before any algorithm runs. The paper (§1) requires a manifold
// triangulation: triangles meeting only in common vertices or edges, whose union is an orientable
// 2-manifold. Its §3 takes a closed, connected surface; fhr goes beyond it (paper_notes/boundary.md)
// and accepts boundary loops and several components, unless a caller asks for closed or connected.
#pragma once

#include <string>
#include <vector>

#include <fhr/core/polygon_soup.hpp>
#include <fhr/core/trimesh.hpp>

namespace fhr {

struct BuildOptions {
    bool triangulate = false;        ///< fan-triangulate polygons with more than 3 vertices (INV-IN-3)
    bool require_closed = false;     ///< refuse boundary (INV-IN-10)
    bool require_connected = false;  ///< refuse several components (INV-IN-11)
    bool refuse_degenerate = true;   ///< refuse exactly degenerate triangles (INV-IN-5); `fhr info`
                                     ///< turns this off to still report the topology of such files
};

/// What the builder changed, for the report and the CLI's warnings.
struct BuildLog {
    std::vector<std::string> warnings;        ///< one line each, without "fhr: warning: "
    std::size_t dropped_vertices = 0;         ///< isolated vertices removed (INV-IN-12)
    std::size_t reoriented_faces = 0;         ///< faces turned to agree with their component (INV-IN-8)
    VertexData<std::uint32_t> vertex_origin;  ///< #V: index in the soup of each mesh vertex
};

/// Checks the soup against spec/mesh.md in a fixed order and builds the mesh.
/// \post the result passes TriMesh::validate(); each component is oriented so that its signed
///       volume is positive when it is closed (outward normals), and keeps the orientation of its
///       lowest face when it has boundary.
/// \throws InvalidInput naming the first broken rule with file, line (text formats) and element.
TriMesh build_trimesh(const PolygonSoup& soup, const BuildOptions& options, BuildLog& log);

}  // namespace fhr
