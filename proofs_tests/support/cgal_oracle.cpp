// Test support: CGAL's exact shortest paths as an oracle (see cgal_oracle.hpp).
#include "support/cgal_oracle.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_shortest_path.h>

#include <cmath>

namespace fhr::test {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalMesh = CGAL::Surface_mesh<K::Point_3>;
using CgalShortestPath = CGAL::Surface_mesh_shortest_path<CGAL::Surface_mesh_shortest_path_traits<K, CgalMesh>>;

}  // namespace

std::optional<std::vector<double>> cgal_distances(const TriMesh& m, VertexId source,
                                                  const FaceData<std::uint8_t>* mask) {
    CgalMesh cm;
    std::vector<CgalMesh::Vertex_index> vid;
    for (VertexId v : m.vertices()) {
        const Vec3& p = m.position(v);
        vid.push_back(cm.add_vertex(K::Point_3(p.x(), p.y(), p.z())));
    }
    for (FaceId f : m.faces()) {
        if (mask && !(*mask)[f]) continue;
        const auto t = m.face_vertices(f);
        if (cm.add_face(vid[t[0].idx()], vid[t[1].idx()], vid[t[2].idx()]) == CgalMesh::null_face())
            return std::nullopt;
    }
    std::vector<double> d(m.n_vertices(), INFINITY);
    d[source.idx()] = 0;
    if (cm.is_isolated(vid[source.idx()])) return d;
    CgalShortestPath sp(cm);
    sp.add_source_point(vid[source.idx()]);
    sp.build_sequence_tree();
    for (VertexId v : m.vertices()) {
        if (cm.is_isolated(vid[v.idx()])) continue;
        const double dv = sp.shortest_distance_to_source_points(vid[v.idx()]).first;
        if (dv >= 0) d[v.idx()] = dv;
    }
    return d;
}

}  // namespace fhr::test
