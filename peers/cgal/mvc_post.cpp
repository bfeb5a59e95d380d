// cgal_uv's post-processed method: LSCM (LSCM_parameterizer_3, two pinned vertices), then
// MVC_post_processor_3 (Karni, Gotsman and Gortler 2005, "free boundary linear
// parameterization"): the LSCM border becomes a constraint of a 2D triangulation of its convex
// hull, the hull's border is fixed, and a mean value system over the mesh and the added
// triangles moves every vertex that is not on the hull.
//
// Decisions:
// - The post-processor runs on LSCM because LSCM is the free-border map it is built to repair
//   (ARAP calls it the same way on its own result); after a fixed-border map with a convex border
//   it would only reproduce a mean value map.
// - It runs unconditionally, also when LSCM's map is already one-to-one, so the method is one
//   well-defined map.
// - What it does, read from CGAL 5.5's code: the mean value weights come from the UV positions
//   (LSCM's), not from the surface, and mean value coordinates reproduce the positions they are
//   computed from, so where LSCM's border is convex the result is LSCM's map again (flipped
//   triangles included); only vertices near a concave stretch of the border move.
// - CGAL refuses (ERROR_NON_CONVEX_BORDER) when the LSCM border is not a simple polygon.
//   MVC_post_processor_3 in CGAL 5.5 ignores a failed solve of its own system and returns OK;
//   cgal_uv then catches non-finite UVs (code 4) but cannot see any other consequence.
#include "cgal_mesh.hpp"

#include <CGAL/Surface_mesh_parameterization/LSCM_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/MVC_post_processor_3.h>

namespace cgal_uv {

Outcome run_lscm_mvc_post(const TriangleSoup& soup, std::vector<double>& uv) {
    return run_on_mesh(soup, uv, [](SurfaceMesh& sm, halfedge_descriptor bhd, UvMap uvmap) {
        SMP::Error_code status = SMP::parameterize(sm, SMP::LSCM_parameterizer_3<SurfaceMesh>(), bhd, uvmap);
        if (status != SMP::OK) return status;
        // The post-processor numbers the unknowns by this map: the Surface_mesh's own vertex indices,
        // 0..V−1, since every vertex is in the one component.
        auto vimap = sm.add_property_map<vertex_descriptor, int>("v:index", 0).first;
        for (vertex_descriptor v : sm.vertices()) vimap[v] = static_cast<int>(v.idx());
        SMP::MVC_post_processor_3<SurfaceMesh> post;
        return post.parameterize(sm, bhd, uvmap, vimap);
    });
}

}  // namespace cgal_uv
