// FHR core — SurfacePoint evaluation and canonical form (see surface_point.hpp).
#include <fhr/core/surface_point.hpp>

#include <algorithm>
#include <vector>

namespace fhr {

Vec3 position(const TriMesh& m, const SurfacePoint& p) {
    switch (p.kind) {
        case SurfacePoint::Kind::vertex: return m.position(p.vertex);
        case SurfacePoint::Kind::edge:
            return (1 - p.t) * m.position(m.from(p.halfedge)) + p.t * m.position(m.to(p.halfedge));
        case SurfacePoint::Kind::face: {
            const auto v = m.face_vertices(p.face);
            return p.bary[0] * m.position(v[0]) + p.bary[1] * m.position(v[1]) + p.bary[2] * m.position(v[2]);
        }
    }
    return Vec3::Zero();
}

SurfacePoint canonical(const TriMesh& m, const SurfacePoint& p) {
    switch (p.kind) {
        case SurfacePoint::Kind::vertex: return p;
        case SurfacePoint::Kind::edge: {
            if (p.t == 0) return SurfacePoint::at_vertex(m.from(p.halfedge));
            if (p.t == 1) return SurfacePoint::at_vertex(m.to(p.halfedge));
            // The edge's even halfedge carries the point, so both sides name it alike.
            if (p.halfedge.idx() & 1u) return SurfacePoint::on_edge(TriMesh::twin(p.halfedge), 1 - p.t);
            return p;
        }
        case SurfacePoint::Kind::face: {
            const HalfedgeId h0 = m.halfedge(p.face);
            const HalfedgeId h[3] = {h0, m.next(h0), m.next(m.next(h0))};  // h[k] leaves corner k
            for (int k = 0; k < 3; ++k) {
                if (p.bary[k] != 0) continue;
                // On the edge opposite corner k: from corner k+1 to corner k+2.
                const int a = (k + 1) % 3, b = (k + 2) % 3;
                return canonical(m, SurfacePoint::on_edge(h[a], p.bary[b]));
            }
            return p;
        }
    }
    return p;
}

bool same_location(const TriMesh& m, const SurfacePoint& a, const SurfacePoint& b) {
    const SurfacePoint x = canonical(m, a), y = canonical(m, b);
    if (x.kind != y.kind) return false;
    switch (x.kind) {
        case SurfacePoint::Kind::vertex: return x.vertex == y.vertex;
        case SurfacePoint::Kind::edge: return x.halfedge == y.halfedge && x.t == y.t;
        case SurfacePoint::Kind::face: return x.face == y.face && x.bary == y.bary;
    }
    return false;
}

namespace {

// The faces of a mesh at a vertex or an edge point (an edge of the boundary has one).
std::vector<FaceId> faces_at(const TriMesh& mesh, const SurfacePoint& p) {
    std::vector<FaceId> faces;
    if (p.kind == SurfacePoint::Kind::vertex) {
        mesh.for_each_outgoing(p.vertex, [&](HalfedgeId h) {
            if (mesh.face(h).valid()) faces.push_back(mesh.face(h));
        });
    } else {
        for (HalfedgeId h : {p.halfedge, TriMesh::twin(p.halfedge)})
            if (mesh.face(h).valid()) faces.push_back(mesh.face(h));
    }
    return faces;
}

}  // namespace

bool share_face(const TriMesh& mesh, const SurfacePoint& a, const SurfacePoint& b) {
    const std::vector<FaceId> fa = faces_at(mesh, a), fb = faces_at(mesh, b);
    return std::any_of(fa.begin(), fa.end(), [&](FaceId f) { return std::find(fb.begin(), fb.end(), f) != fb.end(); });
}

}  // namespace fhr
