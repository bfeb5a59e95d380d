// Test support: CGAL's exact shortest paths (Surface_mesh_shortest_path, Epick kernel) as an
// independent oracle, behind a header without CGAL so that CGAL's headers stay in one translation
// unit (paper_notes/library.md: CGAL only in tests and benchmarks). Used by GEO-1 (src/fhr/geodesic)
// and PART-10 (restricted shortest paths).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <fhr/core/trimesh.hpp>

namespace fhr::test {

/// CGAL's exact single-source distances on the faces of `m` that the mask keeps (all without one).
/// Unreachable vertices (CGAL answers −1) get INFINITY. nullopt when CGAL refuses the sub-mesh (a
/// vertex where two fans of kept faces touch is not a manifold for Surface_mesh).
std::optional<std::vector<double>> cgal_distances(const TriMesh& m, VertexId source,
                                                  const FaceData<std::uint8_t>* mask = nullptr);

}  // namespace fhr::test
