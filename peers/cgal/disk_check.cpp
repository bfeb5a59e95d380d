// cgal_uv's applicability check: CGAL's parameterizers map a topological disk, so every method
// first asks CGAL whether the mesh is one. Code 3 (not applicable) names what the mesh is instead.
//
// Decisions:
// - The order of the tests gives the most specific message: a face that uses a vertex twice, a
//   vertex in no face, then CGAL's PMP::is_polygon_soup_a_polygon_mesh (every edge in at most two
//   faces, consistently oriented, no pinched vertex), then CGAL's is_valid_polygon_mesh and
//   is_triangle_mesh on the Surface_mesh, then the counts: one component
//   (PMP::connected_components), one border cycle (PMP::extract_boundary_cycles) and Euler
//   characteristic V − E + F = 1, which together mean genus 0.
// - The soup is never repaired or reoriented: the map CGAL computes is of the mesh as given.
#include "cgal_mesh.hpp"

#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/version_macros.h>

#include <array>
#include <iterator>

namespace cgal_uv {

namespace PMP = CGAL::Polygon_mesh_processing;

const char* cgal_version() { return CGAL_VERSION_STR; }

namespace {

std::string plural(std::size_t n, const char* one, const char* many) {
    return std::to_string(n) + " " + (n == 1 ? one : many);
}

}  // namespace

Outcome check_disk(const TriangleSoup& soup) {
    const std::size_t nv = soup.vertex_count(), nf = soup.face_count();
    if (nf == 0) return {3, "not a disk: the mesh has no faces"};

    std::vector<std::array<std::size_t, 3>> polygons(nf);
    for (std::size_t f = 0; f < nf; ++f) {
        const std::uint32_t* t = &soup.tri[3 * f];
        if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
            return {3, "not a disk: face " + std::to_string(f) + " uses a vertex twice"};
        polygons[f] = {t[0], t[1], t[2]};
    }
    std::vector<char> used(nv, 0);
    for (std::uint32_t i : soup.tri) used[i] = 1;
    std::size_t unused = 0, first_unused = 0;
    for (std::size_t i = 0; i < nv; ++i)
        if (!used[i] && unused++ == 0) first_unused = i;
    if (unused != 0)
        return {3, "not a disk: " + plural(unused, "vertex is", "vertices are") + " in no face (the first: vertex " +
                       std::to_string(first_unused) + ")"};

    if (!PMP::is_polygon_soup_a_polygon_mesh(polygons))
        return {3,
                "not an oriented 2-manifold (CGAL's is_polygon_soup_a_polygon_mesh: an edge in more than two faces, "
                "two faces oriented inconsistently, or a pinched vertex)"};

    try {
        SurfaceMesh sm;
        if (const long f = build_surface_mesh(soup, sm); f >= 0)
            return {3, "not an oriented 2-manifold: CGAL's Surface_mesh refuses face " + std::to_string(f)};
        if (!CGAL::is_valid_polygon_mesh(sm)) return {3, "not a valid polygon mesh (CGAL's is_valid_polygon_mesh)"};
        if (!CGAL::is_triangle_mesh(sm)) return {3, "not a triangle mesh (CGAL's is_triangle_mesh)"};

        auto component = sm.add_property_map<face_descriptor, std::size_t>("f:component", 0).first;
        const std::size_t components = PMP::connected_components(sm, component);
        std::vector<halfedge_descriptor> cycles;
        PMP::extract_boundary_cycles(sm, std::back_inserter(cycles));
        const std::size_t loops = cycles.size();
        const long long chi = static_cast<long long>(sm.number_of_vertices()) -
                              static_cast<long long>(sm.number_of_edges()) +
                              static_cast<long long>(sm.number_of_faces());
        if (components == 1 && loops == 1 && chi == 1) return {};

        std::string what;
        if (components == 1) {
            // χ = 2 − 2g − b for one connected orientable surface.
            const long long twice_genus = 2 - chi - static_cast<long long>(loops);
            const std::string genus = twice_genus % 2 == 0 ? std::to_string(twice_genus / 2) : "?";
            if (loops == 0)
                what = "a closed surface of genus " + genus;
            else if (loops == 2 && twice_genus == 0)
                what = "an annulus (one component, 2 boundary loops, genus 0)";
            else
                what = "one component of genus " + genus + " with " + plural(loops, "boundary loop", "boundary loops");
        } else {
            what = plural(components, "component", "components") + ", " +
                   plural(loops, "boundary loop", "boundary loops") + " in all, Euler characteristic " +
                   std::to_string(chi);
        }
        return {3, "not a disk: " + what + "; a disk is one component with one boundary loop and genus 0"};
    } catch (const CGAL::Failure_exception& e) {
        return {4, one_line(e.what())};
    }
}

}  // namespace cgal_uv
