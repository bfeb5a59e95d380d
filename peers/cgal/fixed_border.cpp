// cgal_uv's fixed-border methods: CGAL's four Fixed_border_parameterizer_3 methods, each with the
// circular and with the square border. The border is mapped first, then one sparse linear system
// per coordinate puts every interior vertex at the weighted mean of its neighbours.
//
//   tutte      Barycentric_mapping_parameterizer_3      uniform weights (Tutte 1963)
//   conformal  Discrete_conformal_map_parameterizer_3   cotangent weights (Eck et al. 1995)
//   authalic   Discrete_authalic_parameterizer_3        authalic weights (Desbrun et al. 2002)
//   mvc        Mean_value_coordinates_parameterizer_3   mean value weights (Floater 2003)
//
// Decisions:
// - Borders by arc length: Circular_border_arc_length_parameterizer_3 (CGAL's default for these
//   methods) and Square_border_arc_length_parameterizer_3 with the corners CGAL chooses (the
//   border's first vertex, then the vertices nearest to a quarter, a half and three quarters of
//   its length). Both place the border on [0, 1]². CGAL walks the border halfedges clockwise
//   round the circle but counter-clockwise round the square, so the square-border maps are mirror
//   images (every triangle clockwise in UV; the oracle reports a mirrored chart). A triangle with
//   its three vertices on one side of the square is degenerate in UV.
// - The linear solver is CGAL's default for these methods (Eigen's BiCGSTAB with an incomplete
//   LUT preconditioner): the map is CGAL's as a user of CGAL gets it.
// - CGAL does not check the result of these methods (Fixed_border_parameterizer_3 never calls
//   is_one_to_one_mapping); cgal_uv writes what CGAL returns and leaves the judgement to the oracle.
#include "cgal_mesh.hpp"

#include <CGAL/Surface_mesh_parameterization/Barycentric_mapping_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Circular_border_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Discrete_authalic_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Discrete_conformal_map_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Mean_value_coordinates_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Square_border_parameterizer_3.h>

namespace cgal_uv {

namespace {

template <class Parameterizer>
Outcome run(const TriangleSoup& soup, std::vector<double>& uv) {
    return run_on_mesh(soup, uv, [](SurfaceMesh& sm, halfedge_descriptor bhd, UvMap uvmap) {
        return SMP::parameterize(sm, Parameterizer(), bhd, uvmap);
    });
}

template <class BorderParameterizer>
Outcome run_with_border(FixedWeights weights, const TriangleSoup& soup, std::vector<double>& uv) {
    switch (weights) {
        case FixedWeights::tutte:
            return run<SMP::Barycentric_mapping_parameterizer_3<SurfaceMesh, BorderParameterizer>>(soup, uv);
        case FixedWeights::conformal:
            return run<SMP::Discrete_conformal_map_parameterizer_3<SurfaceMesh, BorderParameterizer>>(soup, uv);
        case FixedWeights::authalic:
            return run<SMP::Discrete_authalic_parameterizer_3<SurfaceMesh, BorderParameterizer>>(soup, uv);
        case FixedWeights::mean_value:
            return run<SMP::Mean_value_coordinates_parameterizer_3<SurfaceMesh, BorderParameterizer>>(soup, uv);
    }
    return {4, "unknown fixed-border method"};
}

}  // namespace

Outcome run_fixed_border(FixedWeights weights, Border border, const TriangleSoup& soup, std::vector<double>& uv) {
    if (border == Border::circle)
        return run_with_border<SMP::Circular_border_arc_length_parameterizer_3<SurfaceMesh>>(weights, soup, uv);
    return run_with_border<SMP::Square_border_arc_length_parameterizer_3<SurfaceMesh>>(weights, soup, uv);
}

}  // namespace cgal_uv
