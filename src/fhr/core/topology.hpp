// FHR core — topological invariants of T. The paper's domain D must have "the same topology"
// as T (§2); for closed orientable surfaces that is the Euler characteristic χ = V − E + F = 2 − 2g
// per component. With b boundary loops a connected orientable surface has χ = 2 − 2g − b.
#pragma once

#include <vector>

#include <fhr/core/trimesh.hpp>

namespace fhr {

/// χ = V − E + F. \pre !mesh.has_garbage().
long euler_characteristic(const TriMesh& mesh);

/// One halfedge per boundary loop (the lowest-numbered one of its loop), in increasing order.
std::vector<HalfedgeId> boundary_loops(const TriMesh& mesh);

struct Components {
    std::size_t count = 0;
    VertexData<std::uint32_t> vertex_component;  ///< #V, numbered by lowest vertex index
};
Components connected_components(const TriMesh& mesh);

/// Sum over the components of their genus g_c = (2 − b_c − χ_c) / 2.
long genus(const TriMesh& mesh);
/// The same, with mesh's components known (`components` is connected_components(mesh)).
long genus(const TriMesh& mesh, const Components& components);

}  // namespace fhr
