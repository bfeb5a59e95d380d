// Checks shared by the generator's tests (spec/generator.md GEN-1..8): what every generated mesh,
// of every family, must be, and small helpers the tests share. RapidCheck assertions.
#pragma once

#include <cstdint>
#include <vector>

#include <fhr/core/build.hpp>
#include <fhr/core/polygon_soup.hpp>
#include <fhr/core/topology.hpp>
#include <fhr/core/trimesh.hpp>
#include <fhr/generate/random_mesh.hpp>

namespace fhr::generate::checks {

/// The mesh as a polygon soup (what a reader would hand to build_trimesh).
fhr::PolygonSoup to_soup(const TriMesh& m);
/// Component c's share of a total over C components (spec/generator.md): ⌊total/C⌋, plus one
/// for c < total mod C.
int share(int total, int components, int c);
/// Volume of the block a component starts from (paper_notes/generator.md, step 1).
double block_volume(int genus, int holes = 0);
/// The smallest corner angle of m, radians.
double smallest_corner_angle(const TriMesh& m);
/// FNV-1a over the position bits and the triangles.
std::uint64_t mesh_hash(const TriMesh& m);
/// The vertices of the boundary loop through boundary halfedge h, in order.
std::vector<fhr::VertexId> loop_vertices(const TriMesh& m, HalfedgeId h);
/// 6 × the volume each component encloses with its holes closed by fans.
std::vector<double> filled_six_volumes(const TriMesh& m, const fhr::Components& comps);
/// Bitwise equality of two meshes' vertex positions and triangles.
bool identical(const TriMesh& a, const TriMesh& b);
/// GEN-1, GEN-2, GEN-3, GEN-6, the boundary loops and the order of the components; for the block
/// family also their placement and the 20° corners.
void check_generated(const RandomMeshOptions& o, const TriMesh& m);
/// GEN-5: the builder accepts m with these options, without a warning, and gives back the very
/// same mesh, as a reader of its written file would.
void check_builds_unchanged(const TriMesh& m, const fhr::BuildOptions& options);
/// GEN-8: check_generated, GEN-5 (with boundary and components allowed), and embedded — or, for
/// the immersed family, at least one improper intersection.
void check_family_mesh(const RandomMeshOptions& o, const TriMesh& m);

}  // namespace fhr::generate::checks
