// FHR §2 — half-edge-collapse decimation (see decimate.hpp for the pseudocode and
// paper_notes/domain.md for the choices: quadric error of the surviving vertex, link condition,
// normal-deviation and minimum-angle rules).
#include <fhr/core/detail/contract.hpp>
#include <fhr/domain/decimate.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <queue>
#include <stdexcept>
#include <string>

#include <array>

#include <fhr/core/errors.hpp>
#include <fhr/core/geometry.hpp>
#include <fhr/core/predicates.hpp>
#include <fhr/core/topology.hpp>

namespace fhr::domain {
namespace {

// Garland & Heckbert 1997: the squared distance of x to the plane n·x + d = 0 is the quadric
// [x 1] K [x 1]^T with K = [n d][n d]^T; weighting by area makes the error an integral over the
// surface. K is symmetric, so 10 numbers hold it: the upper triangle, row by row.
struct Quadric {
    std::array<double, 10> k{};
    Quadric& operator+=(const Quadric& o) {
        for (int i = 0; i < 10; ++i) k[i] += o.k[i];
        return *this;
    }
    friend Quadric operator+(Quadric a, const Quadric& b) { return a += b; }
    // [x 1] K [x 1]^T, clamped at 0 (it is ≥ 0 in exact arithmetic; round-off can dip below).
    double operator()(const Vec3& p) const {
        const double x = p.x(), y = p.y(), z = p.z();
        const double e = k[0] * x * x + 2 * k[1] * x * y + 2 * k[2] * x * z + 2 * k[3] * x + k[4] * y * y +
                         2 * k[5] * y * z + 2 * k[6] * y + k[7] * z * z + 2 * k[8] * z + k[9];
        return std::max(0.0, e);
    }
};

Quadric face_quadric(const TriMesh& m, FaceId f) {
    const Vec3 n = face_normal(m, f);
    const double a = n.x(), b = n.y(), c = n.z(), d = -n.dot(m.position(m.face_vertices(f)[0]));
    const double w = face_area(m, f);
    return {{w * a * a, w * a * b, w * a * c, w * a * d, w * b * b, w * b * c, w * b * d, w * c * c, w * c * d, w * d * d}};
}

// True when every corner angle of triangle (a, b, c) is at least `min_angle` (< 90°), where
// tan_min = tan(min_angle). A corner with edge vectors u, w has tan(angle) = |u × w| / (u · w), and
// |u × w| = 2·area is the same at all three corners, so no trigonometry is needed.
bool corners_at_least(const Vec3& a, const Vec3& b, const Vec3& c, double tan_min) {
    const double twice_area = (b - a).cross(c - a).norm();
    const double dots[3] = {(b - a).dot(c - a), (c - b).dot(a - b), (a - c).dot(b - c)};
    for (double d : dots)
        if (d > 0 && twice_area < tan_min * d) return false;  // an acute corner below the minimum
    return true;
}

struct Candidate {
    double cost;
    std::uint32_t halfedge;
    std::uint32_t stamp;
    bool operator>(const Candidate& o) const {
        return cost != o.cost ? cost > o.cost : halfedge > o.halfedge;  // deterministic ties
    }
};

// Six times the signed volume enclosed by m (the sum over its faces of a · (b × c)).
double volume6_of(const TriMesh& m) {
    double v = 0;
    for (FaceId f : m.faces()) {
        const auto [a, b, c] = m.face_vertices(f);
        v += m.position(a).dot(m.position(b).cross(m.position(c)));
    }
    return v;
}

// Each vertex's quadric: the area-weighted plane quadrics of its faces.
std::vector<Quadric> vertex_quadrics(const TriMesh& T) {
    std::vector<Quadric> q(T.n_vertices());
    for (FaceId f : T.faces()) {
        const Quadric k = face_quadric(T, f);
        for (VertexId v : T.face_vertices(f)) q[v.idx()] += k;
    }
    return q;
}

// Decimates `start`, a decimation of T after the collapses `start.history` (T itself with none),
// whose vertex j is T's vertex start.t_vertex[j] with quadric quadrics[j].
class Decimator {
public:
    Decimator(const Domain& start, std::vector<Quadric> quadrics, double t_volume6, const DecimateOptions& o)
        : m_(start.mesh), t_of_(start.t_vertex), history_(start.history), options_(o), quadric_(std::move(quadrics)),
          stamp_(m_.n_edges(), 0), rejected_(m_.n_halfedges(), false), keep_(m_.n_vertices(), 0) {
        std::vector<std::uint8_t> kept(std::max_element(t_of_.begin(), t_of_.end())->idx() + 1, 0);
        for (VertexId v : o.keep)
            if (v.idx() < kept.size()) kept[v.idx()] = 1;
        for (VertexId v : m_.vertices()) keep_[v.idx()] = kept[t_of_[v].idx()];
        cos_max_turn_ = std::cos(o.max_normal_deviation_deg * M_PI / 180.0);
        tan_min_angle_ = std::tan(o.min_angle_deg * M_PI / 180.0);
        volume_ = volume6_of(m_);
        min_volume_ = 1e-6 * t_volume6;
        std::vector<Candidate> all;
        all.reserve(m_.n_edges());
        for (EdgeId e : m_.edges()) all.push_back(edge_candidate(e));
        queue_ = Queue(std::greater<>(), std::move(all));  // heapified in O(n)
    }

    Domain run() {
        std::size_t faces = m_.n_faces();
        Domain d;
        d.history = std::move(history_);
        while (faces > options_.target_faces) {
            if (queue_.empty()) {
                if (options_.best_effort) break;
                throw InvalidInput("", 0, "decimation stopped at " + std::to_string(faces) + " faces (target " +
                                              std::to_string(options_.target_faces) +
                                              "): no further half-edge collapse keeps the domain valid under "
                                              "min angle " + fmt(options_.min_angle_deg) + "° and normal deviation " +
                                              fmt(options_.max_normal_deviation_deg) + "°; ask for more faces");
            }
            const Candidate c = queue_.top();
            queue_.pop();
            const HalfedgeId h(c.halfedge);
            if (c.stamp != stamp_[TriMesh::edge(h).idx()] || m_.is_deleted(TriMesh::edge(h))) continue;
            if (!valid(h)) {  // try the edge's other direction at its own cost
                rejected_[h.idx()] = true;
                if (!rejected_[TriMesh::twin(h).idx()]) queue_.push(candidate(TriMesh::twin(h)));
                continue;
            }
            const VertexId v0 = m_.from(h), v1 = m_.to(h);
            d.history.push_back({t_of_[v0], t_of_[v1], t_of_[m_.to(m_.next(h))],
                                 t_of_[m_.to(m_.next(TriMesh::twin(h)))]});
            m_.collapse(h);
            volume_ += change_;
            faces -= 2;
            quadric_[v1.idx()] += quadric_[v0.idx()];
            refresh_around(v1);
        }
        for (VertexId v : m_.vertices())
            if (!m_.is_deleted(v)) d.t_vertex.push_back(t_of_[v]);
        m_.compact();  // keeps the survivors' order, so D's vertex j is d.t_vertex[j]
        d.mesh = std::move(m_);
        return d;
    }

private:
    TriMesh m_;
    VertexData<VertexId> t_of_;       // vertex of m_ -> vertex of T
    std::vector<Collapse> history_;   // the collapses that made `start` from T
    const DecimateOptions& options_;
    std::vector<Quadric> quadric_;
    std::vector<std::uint32_t> stamp_;  // per edge
    std::vector<bool> rejected_;        // per halfedge: popped, found invalid, and not queued since
    std::vector<std::uint8_t> keep_;    // per vertex: never removed (DecimateOptions::keep)
    using Queue = std::priority_queue<Candidate, std::vector<Candidate>, std::greater<>>;
    Queue queue_;
    double cos_max_turn_ = 0, tan_min_angle_ = 0;
    // D's signed volume, kept above min_volume_ (a small part of T's) so that D stays outward
    // oriented like T: per-face normal rules alone let a coarse domain turn inside out.
    double volume_ = 0, min_volume_ = 0;
    mutable double change_ = 0;  // the volume change of the collapse last found valid

    // Six times the signed volume of the tetrahedron (0, a, b, c).
    static double volume6(const Vec3& a, const Vec3& b, const Vec3& c) { return a.dot(b.cross(c)); }

    static std::string fmt(double x) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%g", x);
        return buf;
    }

    double cost(HalfedgeId h) const {
        return (quadric_[m_.from(h).idx()] + quadric_[m_.to(h).idx()])(m_.position(m_.to(h)));
    }
    // The queue holds one entry per edge, for one of its directions; a new entry supersedes the
    // edge's older ones (stamp).
    Candidate candidate(HalfedgeId h) { return {cost(h), h.idx(), ++stamp_[TriMesh::edge(h).idx()]}; }
    // The cheaper direction of e, both directions counting as untried again.
    Candidate edge_candidate(EdgeId e) {
        const HalfedgeId h0 = TriMesh::halfedge(e, 0), h1 = TriMesh::halfedge(e, 1);
        rejected_[h0.idx()] = rejected_[h1.idx()] = false;
        return candidate(cost(h1) < cost(h0) ? h1 : h0);
    }
    void push_edge(EdgeId e) { queue_.push(edge_candidate(e)); }

    // Costs change for the edges at v1 (its quadric grew): they are queued again. Validity can
    // change for every halfedge whose link or faces touch v1's star, so an edge with a direction
    // found invalid earlier near v1 is queued again too.
    void refresh_around(VertexId v1) {
        m_.for_each_outgoing(v1, [&](HalfedgeId g) {
            push_edge(TriMesh::edge(g));
            m_.for_each_outgoing(m_.to(g), [&](HalfedgeId k) {
                if (rejected_[k.idx()] || rejected_[TriMesh::twin(k).idx()]) push_edge(TriMesh::edge(k));
            });
        });
    }

    // The collapse from(h) -> to(h) is allowed when it keeps D a closed 2-manifold of the same
    // topology (Theorem, Dey et al. 1999: the link condition suffices) and every face that moves
    // with from(h) stays well shaped and does not turn over.
    bool valid(HalfedgeId h) const {
        if (keep_[m_.from(h).idx()] || !m_.is_collapse_ok(h)) return false;
        const VertexId v0 = m_.from(h), v1 = m_.to(h);  // v0 disappears into v1
        const FaceId gone0 = m_.face(h), gone1 = m_.face(TriMesh::twin(h));
        const Vec3 &p0 = m_.position(v0), &p1 = m_.position(v1);
        bool ok = true;
        double change = 0;
        m_.for_each_outgoing(v0, [&](HalfedgeId g) {
            const FaceId f = m_.face(g);
            // Face (v0, a, b) becomes (v1, a, b); the two faces at h go.
            const Vec3& a = m_.position(m_.to(g));
            const Vec3& b = m_.position(m_.to(m_.next(g)));
            change += (f == gone0 || f == gone1 ? 0.0 : volume6(p1, a, b)) - volume6(p0, a, b);
            if (!ok || f == gone0 || f == gone1) return;
            if (collinear(p1, a, b)) {
                ok = false;
                return;
            }
            const Vec3 n_new = (a - p1).cross(b - p1).normalized();
            if (n_new.dot(face_normal(m_, f)) < cos_max_turn_ || !corners_at_least(p1, a, b, tan_min_angle_)) ok = false;
        });
        if (!ok || volume_ + change <= min_volume_) return false;
        change_ = change;
        return true;
    }
};

}  // namespace

std::vector<std::pair<VertexId, VertexId>> edge_endpoints(const Domain& d) {
    std::vector<std::pair<VertexId, VertexId>> pairs;
    pairs.reserve(d.mesh.n_edges());
    for (EdgeId e : d.mesh.edges()) {
        const HalfedgeId h = TriMesh::halfedge(e, 0);
        pairs.emplace_back(d.t_vertex[d.mesh.from(h)], d.t_vertex[d.mesh.to(h)]);
    }
    return pairs;
}

std::size_t min_closed_faces(long genus) {
    const long chi = 2 - 2 * genus;
    long v = static_cast<long>(std::ceil((7.0 + std::sqrt(1.0 + 48.0 * static_cast<double>(genus))) / 2.0));
    if (genus == 2) v = 10;  // Jungerman & Ringel: the genus-2 surface has no 9-vertex triangulation
    return static_cast<std::size_t>(2 * (v - chi));
}

namespace {

void check_target(const TriMesh& T, const DecimateOptions& options) {
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
}

}  // namespace

Domain decimate(const TriMesh& T, const DecimateOptions& options) {
    check_target(T, options);
    Domain start{T, {}, {}};
    for (VertexId v : T.vertices()) start.t_vertex.push_back(v);
    return Decimator(start, vertex_quadrics(T), volume6_of(T), options).run();
}

Domain decimate_again(const TriMesh& T, const Domain& previous, const DecimateOptions& options) {
    check_target(T, options);
    // The collapses of `previous` before its first that removes a vertex kept now, and leaving at
    // least the target's faces, are the ones a new decimation makes first.
    std::vector<std::uint8_t> kept(T.n_vertices(), 0);
    for (VertexId v : options.keep) kept[v.idx()] = 1;
    std::size_t reuse = std::min(previous.history.size(), (T.n_faces() - options.target_faces) / 2);
    for (std::size_t i = 0; i < reuse; ++i)
        if (kept[previous.history[i].removed.idx()]) reuse = i;
    const Domain start = undo_collapses(previous, T, previous.history.size() - reuse);
    std::vector<Quadric> merged = vertex_quadrics(T);  // summed in the order decimate summed them
    for (std::size_t i = 0; i < reuse; ++i) merged[previous.history[i].kept.idx()] += merged[previous.history[i].removed.idx()];
    std::vector<Quadric> quadrics;
    for (VertexId x : start.t_vertex) quadrics.push_back(merged[x.idx()]);
    Domain d = Decimator(start, std::move(quadrics), volume6_of(T), options).run();
    // Number D's vertices in T's order, as decimate does (DOM-4): the undone prefix appended its
    // vertices at the end.
    std::vector<std::uint32_t> order(d.t_vertex.size()), rank(d.t_vertex.size());
    for (std::uint32_t j = 0; j < order.size(); ++j) order[j] = j;
    std::sort(order.begin(), order.end(),
              [&](std::uint32_t a, std::uint32_t b) { return d.t_vertex[VertexId(a)] < d.t_vertex[VertexId(b)]; });
    std::vector<Vec3> positions(order.size());
    VertexData<VertexId> t_vertex(order.size());
    for (std::uint32_t r = 0; r < order.size(); ++r) {
        rank[order[r]] = r;
        positions[r] = d.mesh.position(VertexId(order[r]));
        t_vertex[VertexId(r)] = d.t_vertex[VertexId(order[r])];
    }
    std::vector<Triangle> faces = d.mesh.triangles();
    for (Triangle& f : faces)
        for (std::uint32_t& v : f) v = rank[v];
    d.mesh = TriMesh::from_triangles(std::move(positions), faces);
    d.t_vertex = std::move(t_vertex);
    return d;
}

Domain undo_collapses(const Domain& d, const TriMesh& T, std::size_t count) {
    FHR_DCHECK(count <= d.history.size());
    Domain r;
    r.mesh = d.mesh;
    r.t_vertex = d.t_vertex;
    r.history.assign(d.history.begin(), d.history.end() - static_cast<std::ptrdiff_t>(count));
    std::vector<VertexId> current(T.n_vertices());  // T vertex -> vertex of r.mesh
    for (VertexId j : r.t_vertex.ids()) current[r.t_vertex[j].idx()] = j;
    for (std::size_t i = d.history.size(); i-- > d.history.size() - count;) {
        const Collapse& c = d.history[i];
        const VertexId v = r.mesh.split_vertex(current[c.kept.idx()], current[c.left.idx()], current[c.right.idx()],
                                               T.position(c.removed));
        current[c.removed.idx()] = v;
        r.t_vertex.push_back(c.removed);
    }
    return r;
}

bool history_describes(const Domain& d, const TriMesh& T) {
    Domain back;
    try {
        back = undo_collapses(d, T, d.history.size());
    } catch (const std::logic_error&) {
        return false;  // a split whose neighbours are not there: D changed after its decimation
    }
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

}  // namespace fhr::domain
