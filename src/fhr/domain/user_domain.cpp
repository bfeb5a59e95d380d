// FHR §2/§3 Fig. 4 — attaching a user-given domain (see user_domain.hpp).
//
//   canonicalize every x_j (a barycentric weight below 1e−12 counts as 0, so a point that close to
//     an edge lies on it); refuse duplicates
//   face points, face by face: locate x_j among the pieces its face has been split into so far
//     (in the face's own barycentric coordinates), split that piece (or, on an inner edge of the
//     face, that edge)
//   edge points, edge by edge, in decreasing edge parameter: split the remaining piece of the edge
#include <fhr/domain/user_domain.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include <Eigen/Dense>

#include <fhr/core/errors.hpp>
#include <fhr/core/topology.hpp>

namespace fhr::domain {
namespace {

// Barycentric weights at most this are zero: the point is on the edge (DOM-13 in spec/domain.md).
constexpr double snap_to_edge = 1e-12;
// Within a face already split, coordinates this small come from rounding in the location solve.
constexpr double snap_in_piece = 1e-14;

std::string entry_name(std::size_t j, const NamedSurfacePoint& e) {
    return "entry " + std::to_string(j) + " (line " + std::to_string(e.line) + ")";
}

SurfacePoint snapped(const TriMesh& T, SurfacePoint p) {
    if (p.kind == SurfacePoint::Kind::face) {
        for (double& b : p.bary)
            if (b <= snap_to_edge) b = 0;
        const double sum = p.bary[0] + p.bary[1] + p.bary[2];
        for (double& b : p.bary) b /= sum;
    }
    return canonical(T, p);
}

using Key = std::tuple<int, std::uint32_t, double, double, double>;
Key key(const SurfacePoint& p) {
    switch (p.kind) {
        case SurfacePoint::Kind::vertex: return {0, p.vertex.idx(), 0, 0, 0};
        case SurfacePoint::Kind::edge: return {1, p.halfedge.idx(), p.t, 0, 0};
        case SurfacePoint::Kind::face: return {2, p.face.idx(), p.bary[0], p.bary[1], p.bary[2]};
    }
    return {};
}

// Inserts the points of one face of T, each given by its barycentric coordinates in that face.
class FaceInserter {
public:
    FaceInserter(TriMesh& T, FaceId root) : T_(T), pieces_{root} {
        const auto c = T.face_vertices(root);
        for (int k = 0; k < 3; ++k) {
            Eigen::Vector3d e = Eigen::Vector3d::Zero();
            e[k] = 1;
            bary_[c[k]] = e;
        }
    }

    /// The vertex inserted at `b` (position p), or an invalid id when b is an existing vertex.
    VertexId insert(const std::array<double, 3>& b, const Vec3& p) {
        const Eigen::Vector3d target(b[0], b[1], b[2]);
        FaceId best;
        Eigen::Vector3d best_coords = Eigen::Vector3d::Constant(-INFINITY);
        for (FaceId f : pieces_) {
            const auto c = T_.face_vertices(f);
            Eigen::Matrix3d m;
            for (int k = 0; k < 3; ++k) m.col(k) = bary_.at(c[k]);
            const Eigen::Vector3d coords = m.colPivHouseholderQr().solve(target);
            if (coords.minCoeff() > best_coords.minCoeff()) {
                best = f;
                best_coords = coords;
            }
        }
        const auto c = T_.face_vertices(best);
        int zeros = 0, zero_at = 0;
        for (int k = 0; k < 3; ++k)
            if (best_coords[k] <= snap_in_piece) ++zeros, zero_at = k;
        VertexId v;
        if (zeros == 0) {
            v = T_.split_face(best, p);
        } else if (zeros == 1) {  // on the inner edge opposite corner zero_at
            const HalfedgeId h = T_.find_halfedge(c[(zero_at + 1) % 3], c[(zero_at + 2) % 3]);
            v = T_.split_edge(TriMesh::edge(h), p);
        } else {
            return VertexId();
        }
        pieces_.push_back(FaceId(static_cast<FaceId::Index>(T_.n_faces() - 2)));
        pieces_.push_back(FaceId(static_cast<FaceId::Index>(T_.n_faces() - 1)));
        bary_[v] = target;
        return v;
    }

private:
    TriMesh& T_;
    std::vector<FaceId> pieces_;                // the faces the root face is split into
    std::map<VertexId, Eigen::Vector3d> bary_;  // root-face barycentric coordinates of their corners
};

}  // namespace

Domain attach_domain(TriMesh& T, TriMesh D, const std::vector<NamedSurfacePoint>& x, const DomainSources& sources) {
    if (x.size() != D.n_vertices())
        throw InvalidInput(sources.correspondence_file, 0,
                           "has " + std::to_string(x.size()) + " entries but the domain " + sources.domain_file +
                               " has " + std::to_string(D.n_vertices()) + " vertices");
    if (euler_characteristic(D) != euler_characteristic(T))
        throw InvalidInput(sources.domain_file, 0,
                           "the domain has Euler characteristic " + std::to_string(euler_characteristic(D)) +
                               " (genus " + std::to_string(genus(D)) + ") but the mesh has " +
                               std::to_string(euler_characteristic(T)) + " (genus " + std::to_string(genus(T)) +
                               "): they must have the same topology");
    const std::size_t loops_d = boundary_loops(D).size(), loops_t = boundary_loops(T).size();
    const std::size_t parts_d = connected_components(D).count, parts_t = connected_components(T).count;
    if (loops_d != loops_t || parts_d != parts_t)
        throw InvalidInput(sources.domain_file, 0,
                           "the domain has " + std::to_string(loops_d) + " boundary loops in " +
                               std::to_string(parts_d) + " components but the mesh has " + std::to_string(loops_t) +
                               " in " + std::to_string(parts_t) + ": they must have the same topology");
    const std::size_t n = x.size();
    std::vector<SurfacePoint> p(n);
    std::vector<Vec3> pos(n);
    for (std::size_t j = 0; j < n; ++j) {
        p[j] = snapped(T, x[j].point);
        pos[j] = position(T, p[j]);
    }
    // DOM-12: no two domain vertices on one point.
    std::vector<std::size_t> order(n);
    for (std::size_t j = 0; j < n; ++j) order[j] = j;
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return std::pair(key(p[a]), a) < std::pair(key(p[b]), b); });
    for (std::size_t i = 1; i < n; ++i)
        if (key(p[order[i]]) == key(p[order[i - 1]]))
            throw InvalidInput(sources.correspondence_file, x[order[i]].line,
                               entry_name(order[i], x[order[i]]) + " names the same point of the mesh as " +
                                   entry_name(order[i - 1], x[order[i - 1]]));
    Domain d;
    d.mesh = std::move(D);
    d.t_vertex.resize(n);
    auto v_of = [](std::size_t j) { return VertexId(static_cast<VertexId::Index>(j)); };  // entry j is D's vertex j
    // Face points first (face splits keep every edge of T, so edge points stay valid), grouped
    // by face in `order`, which sorts them by face.
    for (std::size_t i = 0; i < n;) {
        const std::size_t j0 = order[i];
        if (p[j0].kind != SurfacePoint::Kind::face) {
            if (p[j0].kind == SurfacePoint::Kind::vertex) d.t_vertex[v_of(j0)] = p[j0].vertex;
            ++i;
            continue;
        }
        FaceInserter inserter(T, p[j0].face);
        for (; i < n && p[order[i]].kind == SurfacePoint::Kind::face && p[order[i]].face == p[j0].face; ++i) {
            const std::size_t j = order[i];
            const VertexId v = inserter.insert(p[j].bary, pos[j]);
            if (!v.valid())
                throw InvalidInput(sources.correspondence_file, x[j].line,
                                   entry_name(j, x[j]) + " is within 1e-14 (barycentric) of another entry's point");
            d.t_vertex[v_of(j)] = v;
        }
    }
    // Edge points, edge by edge, from the far end: split_edge keeps the edge's first halfedge
    // on the piece from its tail, where the remaining points are.
    for (std::size_t i = 0; i < n;) {
        const std::size_t j0 = order[i];
        if (p[j0].kind != SurfacePoint::Kind::edge) {
            ++i;
            continue;
        }
        std::size_t end = i;
        while (end < n && p[order[end]].kind == SurfacePoint::Kind::edge && p[order[end]].halfedge == p[j0].halfedge)
            ++end;
        for (std::size_t k = end; k-- > i;)
            d.t_vertex[v_of(order[k])] = T.split_edge(TriMesh::edge(p[j0].halfedge), pos[order[k]]);
        i = end;
    }
    // DOM-21: D's boundary follows T's (each boundary edge of D an arc of T's boundary between its ends).
    try {
        close_domain(d, T);
    } catch (const InvalidInput& e) {
        throw InvalidInput(sources.domain_file, 0, e.problem());
    }
    return d;
}

}  // namespace fhr::domain
