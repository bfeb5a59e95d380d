// Beyond the paper — surfaces with boundary closed by virtual cones (see cones.hpp).
#include <fhr/core/detail/cones.hpp>

#include <fhr/core/detail/contract.hpp>
#include <fhr/core/topology.hpp>

namespace fhr {

std::vector<Vec3> cone_apexes(const TriMesh& T) {
    std::vector<Vec3> apexes;
    for (HalfedgeId h : boundary_loops(T)) {
        Vec3 sum = Vec3::Zero();
        std::size_t n = 0;
        for (HalfedgeId g = h; n == 0 || g != h; g = T.next(g), ++n) sum += T.position(T.from(g));
        apexes.push_back(sum / static_cast<double>(n));
    }
    return apexes;
}

Coned add_cones(const TriMesh& T) {
    Coned out{T, T.n_vertices(), T.n_faces()};
    const std::vector<HalfedgeId> loops = boundary_loops(T);
    const std::vector<Vec3> apexes = cone_apexes(T);
    for (std::size_t i = 0; i < loops.size(); ++i) out.mesh.fill_hole(loops[i], apexes[i]);
    return out;
}

std::vector<VertexId> boundary_arc(const TriMesh& closed, std::size_t real_vertices, VertexId a, VertexId b) {
    FHR_DCHECK(a != b && a.idx() < real_vertices && b.idx() < real_vertices);
    auto cone = [&](FaceId f) {
        for (VertexId v : closed.face_vertices(f))
            if (v.idx() >= real_vertices) return true;
        return false;
    };
    std::vector<VertexId> arc{a};
    while (arc.back() != b) {
        // The edge leaving the current vertex with a face of T on its left and a cone face on its right.
        HalfedgeId step;
        closed.for_each_outgoing(arc.back(), [&](HalfedgeId h) {
            if (!cone(closed.face(h)) && cone(closed.face(TriMesh::twin(h)))) step = h;
        });
        FHR_DCHECK(step.valid() && arc.size() <= real_vertices);
        arc.push_back(closed.to(step));
    }
    return arc;
}

}  // namespace fhr
