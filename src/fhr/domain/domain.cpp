// FHR §2 — the domain's own queries and operations (see domain.hpp): an edge's ends in T, the
// closure of D by the cones of T̂ (core/detail/cones.hpp) and its opening, and undoing collapses.
#include <fhr/domain/domain.hpp>

#include <algorithm>
#include <cstdint>
#include <string>

#include <fhr/core/detail/cones.hpp>
#include <fhr/core/detail/contract.hpp>
#include <fhr/core/detail/outcome.hpp>
#include <fhr/core/errors.hpp>
#include <fhr/core/topology.hpp>

namespace fhr::domain {

std::vector<std::pair<VertexId, VertexId>> edge_endpoints(const Domain& d) {
    std::vector<std::pair<VertexId, VertexId>> pairs;
    pairs.reserve(d.mesh.n_edges());
    for (EdgeId e : d.mesh.edges()) {
        const HalfedgeId h = TriMesh::halfedge(e, 0);
        pairs.emplace_back(d.t_vertex[d.mesh.from(h)], d.t_vertex[d.mesh.to(h)]);
    }
    return pairs;
}

namespace {

// undo_collapses on a closed T, or why the history does not describe d.mesh: a split whose two
// neighbours are not neighbours of the kept vertex there (d.mesh changed after its decimation).
Outcome<Domain> replay_collapses(const Domain& d, const TriMesh& T, std::size_t count) {
    Domain r;
    r.by_cells = d.by_cells;
    r.cell_collapses = std::min(d.cell_collapses, d.history.size() - count);
    r.mesh = d.mesh;
    r.t_vertex = d.t_vertex;
    r.history.assign(d.history.begin(), d.history.end() - static_cast<std::ptrdiff_t>(count));
    std::vector<VertexId> current(T.n_vertices());  // T vertex -> vertex of r.mesh
    for (VertexId j : r.t_vertex.ids()) current[r.t_vertex[j].idx()] = j;
    for (std::size_t i = d.history.size(); i-- > d.history.size() - count;) {
        const Collapse& c = d.history[i];
        const VertexId kept = current[c.kept.idx()], left = current[c.left.idx()], right = current[c.right.idx()];
        if (left == right || !r.mesh.find_halfedge(kept, left).valid() || !r.mesh.find_halfedge(kept, right).valid())
            return Outcome<Domain>::failure("collapse " + std::to_string(i) +
                                            " cannot be undone: its neighbours are not there");
        current[c.removed.idx()] = r.mesh.split_vertex(kept, left, right, T.position(c.removed));
        r.t_vertex.push_back(c.removed);
    }
    return r;
}

}  // namespace

Domain undo_collapses(const Domain& d, const TriMesh& T, std::size_t count) {
    FHR_DCHECK(count <= d.history.size());
    if (!T.is_closed())
        return open_domain(undo_collapses(close_domain(d, T), add_cones(T).mesh, count), T.n_vertices());
    Outcome<Domain> r = replay_collapses(d, T, count);
    if (!r) throw ContractViolation("undo_collapses: the history does not describe the domain: " + r.why());
    return std::move(r).value();
}

bool history_describes(const Domain& d, const TriMesh& T) {
    if (!T.is_closed()) {
        try {
            return history_describes(close_domain(d, T), add_cones(T).mesh);
        } catch (const InvalidInput&) {
            return false;  // D's boundary does not follow T's
        }
    }
    Outcome<Domain> replayed = replay_collapses(d, T, d.history.size());
    if (!replayed) return false;  // D changed after its decimation
    const Domain& back = *replayed;
    if (back.mesh.n_vertices() != T.n_vertices()) return false;
    // The same faces, each from its smallest vertex (orientation kept), in any order.
    auto canonical = [](std::vector<Triangle> faces) {
        for (Triangle& f : faces) std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());
        std::sort(faces.begin(), faces.end());
        return faces;
    };
    std::vector<Triangle> faces = back.mesh.triangles();
    for (Triangle& f : faces)
        for (std::uint32_t& v : f) v = back.t_vertex[VertexId(v)].idx();
    return canonical(std::move(faces)) == canonical(T.triangles());
}

Domain close_domain(const Domain& D, const TriMesh& T) {
    if (T.is_closed()) {
        if (!D.mesh.is_closed()) throw InvalidInput("the domain has a boundary but the mesh has none");
        return D;
    }
    // Each boundary vertex of T: its loop and its place along it.
    const std::vector<HalfedgeId> t_loops = boundary_loops(T);
    const std::vector<Vec3> apexes = cone_apexes(T);
    std::vector<std::uint32_t> loop_of(T.n_vertices(), UINT32_MAX), place(T.n_vertices(), 0);
    std::vector<std::uint32_t> length(t_loops.size(), 0);
    for (std::uint32_t i = 0; i < t_loops.size(); ++i)
        for (HalfedgeId g = t_loops[i]; loop_of[T.from(g).idx()] == UINT32_MAX; g = T.next(g)) {
            loop_of[T.from(g).idx()] = i;
            place[T.from(g).idx()] = length[i]++;
        }
    auto vertex = [&](VertexId v) {
        return "domain vertex " + std::to_string(v.idx()) + " (mesh vertex " + std::to_string(D.t_vertex[v].idx()) +
               ")";
    };
    // Each loop of D: on one loop of T, its boundary halfedges (which run as T's do) stepping
    // forward along it, once around in all.
    std::vector<HalfedgeId> d_loop_of(t_loops.size());
    for (HalfedgeId h : boundary_loops(D.mesh)) {
        const std::uint32_t loop = loop_of[D.t_vertex[D.mesh.from(h)].idx()];
        std::size_t steps = 0;
        for (HalfedgeId g = h; steps == 0 || g != h; g = D.mesh.next(g)) {
            const VertexId a = D.mesh.from(g), b = D.mesh.to(g);
            for (VertexId v : {a, b})
                if (loop_of[D.t_vertex[v].idx()] != loop)
                    throw InvalidInput(vertex(v) + " is on the domain's boundary but " +
                                       (loop_of[D.t_vertex[v].idx()] == UINT32_MAX
                                            ? std::string("not on the mesh's boundary")
                                            : "on another boundary loop of the mesh than its neighbour"));
            steps += (place[D.t_vertex[b].idx()] + length[loop] - place[D.t_vertex[a].idx()]) % length[loop];
        }
        if (steps != length[loop] || d_loop_of[loop].valid())
            throw InvalidInput("the domain's boundary loop through " + vertex(D.mesh.from(h)) +
                               " does not go once around the mesh's boundary loop in the mesh's orientation");
        d_loop_of[loop] = h;
    }
    Domain out = D;
    for (std::uint32_t i = 0; i < t_loops.size(); ++i) {
        if (!d_loop_of[i].valid())
            throw InvalidInput("the mesh's boundary loop through mesh vertex " +
                               std::to_string(T.from(t_loops[i]).idx()) +
                               " has no boundary loop of the domain along it");
        out.mesh.fill_hole(d_loop_of[i], apexes[i]);
        out.t_vertex.emplace_back(static_cast<VertexId::Index>(T.n_vertices() + i));
    }
    return out;
}

bool on_cone(const TriMesh& closed, const VertexData<VertexId>& t_vertex, EdgeId e, std::size_t real_vertices) {
    for (unsigned side = 0; side < 2; ++side)
        for (VertexId v : closed.face_vertices(closed.face(TriMesh::halfedge(e, side))))
            if (t_vertex[v].idx() >= real_vertices) return true;
    return false;
}

Domain open_domain(const Domain& closed, std::size_t real_vertices) {
    Domain out;
    out.history = closed.history;
    out.by_cells = closed.by_cells;
    out.cell_collapses = closed.cell_collapses;
    std::vector<std::uint32_t> index(closed.mesh.n_vertices(), UINT32_MAX);
    std::vector<Vec3> positions;
    for (VertexId v : closed.mesh.vertices()) {
        if (closed.t_vertex[v].idx() >= real_vertices) continue;
        index[v.idx()] = static_cast<std::uint32_t>(positions.size());
        positions.push_back(closed.mesh.position(v));
        out.t_vertex.push_back(closed.t_vertex[v]);
    }
    std::vector<Triangle> faces;
    for (const Triangle& f : closed.mesh.triangles())
        if (index[f[0]] != UINT32_MAX && index[f[1]] != UINT32_MAX && index[f[2]] != UINT32_MAX)
            faces.push_back({index[f[0]], index[f[1]], index[f[2]]});
    out.mesh = TriMesh::from_triangles(std::move(positions), faces);
    return out;
}

}  // namespace fhr::domain
