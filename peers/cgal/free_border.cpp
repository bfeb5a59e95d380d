// cgal_uv's free-border methods: the border is not fixed in advance.
//
//   lscm  LSCM_parameterizer_3 (Lévy et al. 2002): least squares conformal map with two pinned
//         vertices (Two_vertices_parameterizer_3: the extreme vertices along the longest axis of
//         the bounding box, pinned at (0, 0.5) and (1, 0.5)); CGAL promises no one-to-one map.
//   arap  ARAP_parameterizer_3 (Liu et al. 2008, local/global): starts from CGAL's mean value map
//         on a circle (the mesh has one border), iterates the local/global steps, and when the
//         result has flipped triangles runs MVC_post_processor_3 on it; CGAL promises no
//         one-to-one map. (The post-processor takes its weights from the UV positions
//         themselves, so flips inside a convex border survive it: see mvc_post.cpp.)
//
// Decisions:
// - Every parameter is CGAL's default: for ARAP λ = 1000 (close to as-rigid-as-possible),
//   at most 50 iterations, relative energy tolerance 1e-6; the solvers CGAL picks by default
//   (for LSCM, OpenNL's least squares front end over Eigen's SimplicialLDLT; for ARAP, Eigen's
//   SparseLU — SuiteSparse is not used).
// - The result is written as CGAL returns it, whatever its validity.
#include "cgal_mesh.hpp"

#include <CGAL/Surface_mesh_parameterization/ARAP_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/LSCM_parameterizer_3.h>

namespace cgal_uv {

Outcome run_free_border(FreeMethod method, const TriangleSoup& soup, std::vector<double>& uv) {
    if (method == FreeMethod::lscm)
        return run_on_mesh(soup, uv, [](SurfaceMesh& sm, halfedge_descriptor bhd, UvMap uvmap) {
            return SMP::parameterize(sm, SMP::LSCM_parameterizer_3<SurfaceMesh>(), bhd, uvmap);
        });
    return run_on_mesh(soup, uv, [](SurfaceMesh& sm, halfedge_descriptor bhd, UvMap uvmap) {
        return SMP::parameterize(sm, SMP::ARAP_parameterizer_3<SurfaceMesh>(), bhd, uvmap);
    });
}

}  // namespace cgal_uv
