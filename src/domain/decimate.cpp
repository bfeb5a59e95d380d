// FHR §2 — half-edge-collapse decimation (see decimate.hpp for the pseudocode and
// paper_notes/domain.md for the choices: quadric error of the surviving vertex, link condition,
// normal-deviation and minimum-angle rules).
#include "domain/decimate.hpp"

#include <algorithm>
#include <cmath>
#include <queue>
#include <string>

#include <Eigen/Core>

#include "core/errors.hpp"
#include "core/geometry.hpp"
#include "core/predicates.hpp"
#include "core/topology.hpp"

namespace fhr::domain {
namespace {

using Quadric = Eigen::Matrix4d;

// Garland & Heckbert 1997: the squared distance to the plane n·x + d = 0 is [x 1] K [x 1]^T
// with K = [n d][n d]^T; weighting by area makes the error an integral over the surface.
Quadric face_quadric(const TriMesh& m, FaceId f) {
    const auto v = m.face_vertices(f);
    const Vec3 n = face_normal(m, f);
    const Eigen::Vector4d plane(n.x(), n.y(), n.z(), -n.dot(m.position(v[0])));
    return face_area(m, f) * plane * plane.transpose();
}

double evaluate(const Quadric& q, const Vec3& p) {
    const Eigen::Vector4d x(p.x(), p.y(), p.z(), 1.0);
    return std::max(0.0, x.dot(q * x));  // ≥ 0 in exact arithmetic; clamp round-off
}

// The smallest corner angle of triangle (a, b, c), in radians (atan2 form, see geometry.hpp).
double min_corner_angle(const Vec3& a, const Vec3& b, const Vec3& c) {
    auto angle = [](const Vec3& p, const Vec3& q, const Vec3& r) {
        const Vec3 u = q - p, w = r - p;
        return std::atan2(u.cross(w).norm(), u.dot(w));
    };
    return std::min({angle(a, b, c), angle(b, c, a), angle(c, a, b)});
}

struct Candidate {
    double cost;
    std::uint32_t halfedge;
    std::uint32_t stamp;
    bool operator>(const Candidate& o) const {
        return cost != o.cost ? cost > o.cost : halfedge > o.halfedge;  // deterministic ties
    }
};

class Decimator {
public:
    Decimator(const TriMesh& T, const DecimateOptions& o)
        : m_(T), options_(o), quadric_(T.n_vertices(), Quadric::Zero()), stamp_(T.n_halfedges(), 0),
          rejected_(T.n_halfedges(), false) {
        cos_max_turn_ = std::cos(o.max_normal_deviation_deg * M_PI / 180.0);
        min_angle_ = o.min_angle_deg * M_PI / 180.0;
        for (FaceId f : m_.faces()) {
            const Quadric q = face_quadric(m_, f);
            for (VertexId v : m_.face_vertices(f)) quadric_[v.idx()] += q;
        }
        for (HalfedgeId h : m_.halfedges()) push(h);
    }

    Domain run() {
        std::size_t faces = m_.n_faces();
        Domain d;
        while (faces > options_.target_faces) {
            if (queue_.empty()) {
                throw InvalidInput("", 0, "decimation stopped at " + std::to_string(faces) + " faces (target " +
                                              std::to_string(options_.target_faces) +
                                              "): no further half-edge collapse keeps the domain valid under "
                                              "min angle " + fmt(options_.min_angle_deg) + "° and normal deviation " +
                                              fmt(options_.max_normal_deviation_deg) + "°; ask for more faces");
            }
            const Candidate c = queue_.top();
            queue_.pop();
            const HalfedgeId h(c.halfedge);
            if (c.stamp != stamp_[h.idx()] || m_.is_deleted(TriMesh::edge(h))) continue;
            if (!valid(h)) {
                rejected_[h.idx()] = true;
                continue;
            }
            const VertexId v0 = m_.from(h), v1 = m_.to(h);
            d.history.push_back({v0, v1, m_.to(m_.next(h)), m_.to(m_.next(TriMesh::twin(h)))});
            m_.collapse(h);
            faces -= 2;
            quadric_[v1.idx()] += quadric_[v0.idx()];
            refresh_around(v1);
        }
        for (VertexId v : m_.vertices())
            if (!m_.is_deleted(v)) d.t_vertex.push_back(v);
        m_.compact();  // keeps the survivors' order, so D's vertex j is d.t_vertex[j]
        d.mesh = std::move(m_);
        return d;
    }

private:
    TriMesh m_;
    const DecimateOptions& options_;
    std::vector<Quadric> quadric_;
    std::vector<std::uint32_t> stamp_;
    std::vector<bool> rejected_;  // popped, found invalid, and not queued since
    std::priority_queue<Candidate, std::vector<Candidate>, std::greater<>> queue_;
    double cos_max_turn_ = 0, min_angle_ = 0;

    static std::string fmt(double x) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%g", x);
        return buf;
    }

    void push(HalfedgeId h) {
        rejected_[h.idx()] = false;
        const double cost = evaluate(quadric_[m_.from(h).idx()] + quadric_[m_.to(h).idx()], m_.position(m_.to(h)));
        queue_.push({cost, h.idx(), ++stamp_[h.idx()]});
    }

    // Costs change for the halfedges at v1 (its quadric grew): they are queued again. Validity
    // can change for every halfedge whose link or faces touch v1's star, so a candidate found
    // invalid earlier (and dropped) near v1 is queued again too.
    void refresh_around(VertexId v1) {
        m_.for_each_outgoing(v1, [&](HalfedgeId g) {
            push(g);
            push(TriMesh::twin(g));
            m_.for_each_outgoing(m_.to(g), [&](HalfedgeId k) {
                for (HalfedgeId x : {k, TriMesh::twin(k)})
                    if (rejected_[x.idx()]) push(x);
            });
        });
    }

    // The collapse from(h) -> to(h) is allowed when it keeps D a closed 2-manifold of the same
    // topology (Theorem, Dey et al. 1999: the link condition suffices) and every face that moves
    // with from(h) stays well shaped and does not turn over.
    bool valid(HalfedgeId h) const {
        if (!m_.is_collapse_ok(h)) return false;
        const VertexId v0 = m_.from(h), v1 = m_.to(h);  // v0 disappears into v1
        const FaceId gone0 = m_.face(h), gone1 = m_.face(TriMesh::twin(h));
        const Vec3& p1 = m_.position(v1);
        bool ok = true;
        m_.for_each_outgoing(v0, [&](HalfedgeId g) {
            const FaceId f = m_.face(g);
            if (!ok || f == gone0 || f == gone1) return;
            // Face (v0, a, b) becomes (v1, a, b).
            const Vec3& a = m_.position(m_.to(g));
            const Vec3& b = m_.position(m_.to(m_.next(g)));
            if (collinear(p1, a, b)) {
                ok = false;
                return;
            }
            const Vec3 n_new = (a - p1).cross(b - p1).normalized();
            if (n_new.dot(face_normal(m_, f)) < cos_max_turn_ || min_corner_angle(p1, a, b) < min_angle_) ok = false;
        });
        return ok;
    }
};

}  // namespace

std::size_t min_closed_faces(long genus) {
    const long chi = 2 - 2 * genus;
    long v = static_cast<long>(std::ceil((7.0 + std::sqrt(1.0 + 48.0 * static_cast<double>(genus))) / 2.0));
    if (genus == 2) v = 10;  // Jungerman & Ringel: the genus-2 surface has no 9-vertex triangulation
    return static_cast<std::size_t>(2 * (v - chi));
}

Domain decimate(const TriMesh& T, const DecimateOptions& options) {
    const std::size_t target = options.target_faces;
    const long g = genus(T);
    if (target % 2 != 0)
        throw InvalidInput("", 0, "--faces " + std::to_string(target) + " is odd: a closed triangulation has an even number of faces");
    if (target > T.n_faces())
        throw InvalidInput("", 0, "--faces " + std::to_string(target) + " is more than the mesh has (" +
                                      std::to_string(T.n_faces()) + ")");
    if (target < min_closed_faces(g))
        throw InvalidInput("", 0, "--faces " + std::to_string(target) + " is fewer than a closed surface of genus " +
                                      std::to_string(g) + " needs (at least " + std::to_string(min_closed_faces(g)) + ")");
    return Decimator(T, options).run();
}

Domain undo_collapses(const Domain& d, const TriMesh& T, std::size_t count) {
    Domain r;
    r.mesh = d.mesh;
    r.t_vertex = d.t_vertex;
    r.history.assign(d.history.begin(), d.history.end() - static_cast<std::ptrdiff_t>(count));
    std::vector<VertexId> current(T.n_vertices());  // T vertex -> vertex of r.mesh
    for (std::size_t j = 0; j < r.t_vertex.size(); ++j) current[r.t_vertex[j].idx()] = VertexId(static_cast<VertexId::Index>(j));
    for (std::size_t i = d.history.size(); i-- > d.history.size() - count;) {
        const Collapse& c = d.history[i];
        const VertexId v = r.mesh.split_vertex(current[c.kept.idx()], current[c.left.idx()], current[c.right.idx()],
                                               T.position(c.removed));
        current[c.removed.idx()] = v;
        r.t_vertex.push_back(c.removed);
    }
    return r;
}

}  // namespace fhr::domain
