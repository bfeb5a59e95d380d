// FHR §3 — d_a by Kimmel–Sethian fast marching (see fast_marching.hpp for the pseudocode and
// paper_notes/fast_marching.md for the decisions: planar update and causality test, unfolding of
// obtuse corners and its bound, early-stop semantics, measured accuracy).
#include <fhr/geodesic/detail/fast_marching.hpp>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>

#include <fhr/core/errors.hpp>
#include <fhr/geodesic/detail/scratch.hpp>

namespace fhr::geodesic {

// Kimmel & Sethian 1998, the triangle update, written with the Gram matrix G = [e_a e_b]^T [e_a e_b]
// instead of their angle θ and lengths a, b (the same quadratic). A plane wave with unit gradient
// n in the triangle's plane, taking value t at c: n·e_a = d_a − t, n·e_b = d_b − t. Writing
// n = [e_a e_b] k, G k = w with w = (d_a − t, d_b − t), and |n|² = k^T G k = w^T G^{-1} w = 1, i.e.
// w^T adj(G) w = det G. With t = d_a + s and u = d_b − d_a, w = (−s, u − s):
//   |e_b − e_a|² s² + 2 u (e_a·e_b − |e_a|²) s + |e_a|² u² − det G = 0,
// whose larger root is the wave that reaches c last (it is behind a and b). Causality: the
// characteristic −n = −[e_a e_b] k points from c into the triangle iff k <= 0, and
// k ∝ adj(G) w = (|e_b|² w_1 − (e_a·e_b) w_2, |e_a|² w_2 − (e_a·e_b) w_1), det G > 0.
double planar_update(const Vec3& e_a, const Vec3& e_b, double d_a, double d_b) {
    const double aa = e_a.squaredNorm(), bb = e_b.squaredNorm(), ab = e_a.dot(e_b);
    const double det = e_a.cross(e_b).squaredNorm();  // = aa·bb − ab², without the cancellation
    const double qa = (e_b - e_a).squaredNorm();
    if (!(det > 0) || !(qa > 0)) return INFINITY;
    const double u = d_b - d_a;
    const double half_qb = u * (ab - aa);
    const double qc = aa * u * u - det;
    const double disc = half_qb * half_qb - qa * qc;
    if (disc < 0) return INFINITY;  // |u| > |ab|: no unit-slope plane through both values
    // The larger root, in the form without cancellation (Vieta: s₁s₂ = qc/qa).
    const double root = std::sqrt(disc);
    const double s = half_qb <= 0 ? (-half_qb + root) / qa : qc / (-half_qb - root);
    const double w1 = -s, w2 = u - s;
    const bool causal = bb * w1 - ab * w2 <= 0 && aa * w2 - ab * w1 <= 0;
    return causal ? d_a + s : INFINITY;
}

namespace {

constexpr std::uint32_t no_link = std::numeric_limits<std::uint32_t>::max();
constexpr std::uint32_t not_in_heap = std::numeric_limits<std::uint32_t>::max();

// The narrow band: a binary heap of (d, v), smallest first (ties: lower v), with each vertex's
// place in it, so that a lowered value moves its entry up instead of adding one (with
// entries added again, half of all pops on the horse's fields were stale ones; the fields 0.34 →
// 0.28 s on one thread, the 10⁶ mesh's 2.8 → 2.2 s, every value the same bits).
struct HeapEntry {
    double d;
    std::uint32_t v;
    bool before(const HeapEntry& o) const { return d < o.d || (d == o.d && v < o.v); }
};

// The vertex found by unfolding for an obtuse corner, in the corner's plane: c at the origin,
// a on the positive x-axis, b above it (see unfold_corner).
struct VirtualVertex {
    VertexId p;
    Vec3 p2;  // z = 0
};

// The per-vertex arrays of a run, borrowed clean from the caller's workspace (workspace.hpp,
// detail/scratch.hpp) and handed back clean: `touched` lists the vertices whose dist (and final
// flag and heap place) changed, `linked` those whose link_head did.
struct MarchScratch final : detail::ScratchBase {
    std::vector<double> dist;
    std::vector<std::uint8_t> final;
    std::vector<std::uint32_t> link_head;
    std::vector<std::uint32_t> at;  // a vertex's place in the heap, or not_in_heap
    std::vector<std::uint32_t> touched, linked;
    std::vector<VertexId> finalized;
    std::vector<HeapEntry> heap;
    struct Link {
        HalfedgeId corner;
        std::uint32_t next;
    };
    std::vector<Link> links;

    void fit(std::size_t n) {
        if (dist.size() >= n) return;
        dist.resize(n, INFINITY);
        final.resize(n, 0);
        link_head.resize(n, no_link);
        at.resize(n, not_in_heap);
    }
    void reset() noexcept {
        for (std::uint32_t v : touched) {
            dist[v] = INFINITY;
            final[v] = 0;
            at[v] = not_in_heap;
        }
        for (std::uint32_t p : linked) link_head[p] = no_link;
        detail::clear_buffer(touched);
        detail::clear_buffer(linked);
        detail::clear_buffer(finalized);
        detail::clear_buffer(heap);
        detail::clear_buffer(links);
    }
};

}  // namespace

struct FastMarching::State {
public:
    State(const TriMesh& m, bool unfold, Workspace* workspace)
        : m_(m),
          unfold_(unfold),
          s_(detail::borrow<MarchScratch>(workspace, m.n_vertices())),
          dist_(s_->dist),
          final_(s_->final),
          link_head_(s_->link_head),
          finalized_(s_->finalized),
          heap_(s_->heap),
          at_(s_->at),
          links_(s_->links) {}

    void start(std::span<const VertexId> sources) {
        for (VertexId s : sources) {
            if (dist_[s.idx()] == 0) continue;
            set_dist(s.idx(), 0);
            push(0, s.idx());
        }
    }

    // The main loop of the full run, stopped before a vertex beyond max_distance is accepted,
    // or right after `target` is accepted.
    void run(double max_distance, VertexId target) {
        while (!heap_.empty()) {
            const HeapEntry top = heap_.front();
            if (top.d > max_distance) break;
            pop();
            accept(top.v);
            if (top.v == target.idx()) break;
        }
    }

    double distance(VertexId v) const { return final_[v.idx()] ? dist_[v.idx()] : INFINITY; }
    const TriMesh& mesh() const { return m_; }
    std::span<const VertexId> finalized() const { return finalized_; }

private:
    const TriMesh& m_;
    const bool unfold_;
    detail::Borrowed<MarchScratch> s_;
    std::vector<double>& dist_;  // tentative in the band, final where final_ is set
    std::vector<std::uint8_t>& final_;
    // Obtuse corners waiting for their virtual vertex p to become final: singly linked lists,
    // one per p, of the corners' opposite halfedges.
    std::vector<std::uint32_t>& link_head_;
    std::vector<VertexId>& finalized_;
    std::vector<HeapEntry>& heap_;
    std::vector<std::uint32_t>& at_;
    std::vector<MarchScratch::Link>& links_;
    double front_ = 0;  // distance of the vertex being accepted

    void set_dist(std::uint32_t v, double d) {
        if (dist_[v] == INFINITY) s_->touched.push_back(v);
        dist_[v] = d;
    }

    void place(std::uint32_t i, const HeapEntry& e) {
        heap_[i] = e;
        at_[e.v] = i;
    }
    void sift_up(std::uint32_t i, const HeapEntry e) {
        while (i > 0) {
            const std::uint32_t parent = (i - 1) / 2;
            if (!e.before(heap_[parent])) break;
            place(i, heap_[parent]);
            i = parent;
        }
        place(i, e);
    }
    // v's tentative distance d, lower than before: a new entry, or v's entry moved up.
    void push(double d, std::uint32_t v) {
        std::uint32_t i = at_[v];
        if (i == not_in_heap) {
            i = static_cast<std::uint32_t>(heap_.size());
            heap_.push_back({d, v});
        }
        sift_up(i, {d, v});
    }
    // Removes the smallest entry: the last one takes its place and sinks through the n entries
    // left; its old place is dropped at the end.
    void pop() {
        at_[heap_.front().v] = not_in_heap;
        const HeapEntry last = heap_.back();
        const auto n = static_cast<std::uint32_t>(heap_.size() - 1);
        std::uint32_t i = 0;
        for (;;) {
            std::uint32_t child = 2 * i + 1;
            if (child >= n) break;
            if (child + 1 < n && heap_[child + 1].before(heap_[child])) ++child;
            if (!heap_[child].before(last)) break;
            place(i, heap_[child]);
            i = child;
        }
        if (n > 0) place(i, last);
        heap_.pop_back();
    }

    void accept(std::uint32_t v) {
        final_[v] = 1;
        finalized_.push_back(VertexId(v));
        front_ = dist_[v];
        const Vec3& pv = m_.position(VertexId(v));
        m_.for_each_outgoing(VertexId(v), [&](HalfedgeId h) {
            const VertexId w = m_.to(h);
            if (!final_[w.idx()]) relax(w.idx(), front_ + (m_.position(w) - pv).norm());  // edge update
            if (m_.is_boundary(h)) return;
            update_corner(h, true);                    // the corner at to(next(h)), opposite v -> w
            update_corner(m_.next(m_.next(h)), true);  // the corner at w, opposite to(next(h)) -> v
        });
        if (!unfold_) return;
        for (std::uint32_t l = link_head_[v]; l != no_link; l = links_[l].next) update_corner(links_[l].corner, false);
    }

    void relax(std::uint32_t c, double t) {
        t = std::max(t, front_);  // rounding must not let a value fall below the accepted front
        if (t < dist_[c]) {
            set_dist(c, t);
            push(t, c);
        }
    }

    // The triangle updates of the corner at c = to(next(h)), opposite h = (a -> b), called when
    // a or b (from_edge_end) or the corner's virtual vertex p has just become final. The edge
    // updates from a, b are made in accept (each final neighbour's once, when it becomes final).
    void update_corner(HalfedgeId h, bool from_edge_end) {
        const VertexId a = m_.from(h), b = m_.to(h), c = m_.to(m_.next(h));
        if (final_[c.idx()]) return;
        const bool fa = final_[a.idx()] != 0, fb = final_[b.idx()] != 0;
        const bool acute = [&] {  // the angle at c is at most 90°
            const Vec3& pc = m_.position(c);
            return (m_.position(a) - pc).dot(m_.position(b) - pc) >= 0;
        }();
        if (acute && !(fa && fb)) return;  // the common case: only the edge update applies
        if (!acute && !unfold_) return;
        const Vec3& pc = m_.position(c);
        const Vec3 e_a = m_.position(a) - pc, e_b = m_.position(b) - pc;
        const double d_a = dist_[a.idx()], d_b = dist_[b.idx()];
        if (acute) {
            relax(c.idx(), planar_update(e_a, e_b, d_a, d_b));
            return;
        }
        const std::optional<VirtualVertex> p = unfold_corner(h, e_a, e_b);
        if (!p) return;
        const std::uint32_t pi = p->p.idx();
        // The corner is first met when the first of a, b becomes final (exactly once); from
        // then on it must also hear about p.
        if (from_edge_end && !(fa && fb) && !final_[pi]) {
            if (link_head_[pi] == no_link) s_->linked.push_back(pi);
            links_.push_back({h, link_head_[pi]});
            link_head_[pi] = static_cast<std::uint32_t>(links_.size() - 1);
        }
        if (!final_[pi]) return;
        const double d_p = dist_[pi];
        double t = d_p + p->p2.norm();
        if (fa) t = std::min(t, planar_update(Vec3(e_a.norm(), 0, 0), p->p2, d_a, d_p));
        if (fb) t = std::min(t, planar_update(p->p2, unfolded_b(e_a, e_b), d_p, d_b));
        relax(c.idx(), t);
    }

    // b in the corner's plane: c at the origin, a = (|e_a|, 0, 0), b with y > 0.
    static Vec3 unfolded_b(const Vec3& e_a, const Vec3& e_b) {
        const double la = e_a.norm();
        return Vec3(e_a.dot(e_b) / la, e_a.cross(e_b).norm() / la, 0);
    }

    // Kimmel & Sethian 1998 §4, for the obtuse corner at c opposite h = (a -> b): unfold the
    // triangles beyond ab into the plane of (c, a, b), following the section S = {x : x·a >= 0,
    // x·b >= 0} (the directions within 90° of both ca and cb), until a vertex falls into S.
    // Invariant: the current edge (p -> q) has p on a's side of S and q on b's side, c on its left,
    // so every ray of S crosses it; the next triangle lies on its right. A vertex r not in S is on
    // a's side iff r·b < 0 (all candidates lie in the half-plane beyond the edge, an angular range
    // below 180° that contains S), and then the rays of S leave the triangle through (r, q).
    // The straight segment c -> p crosses the unfolded triangles, so it is a path on the surface
    // and |p2| an upper bound of the distance from c to p.
    std::optional<VirtualVertex> unfold_corner(HalfedgeId h, const Vec3& e_a, const Vec3& e_b) const {
        const VertexId c = m_.to(m_.next(h));
        const Vec3 a2(e_a.norm(), 0, 0), b2 = unfolded_b(e_a, e_b);
        Vec3 p2 = a2, q2 = b2;
        HalfedgeId cur = h;
        for (int step = 0; step < max_unfold_steps; ++step) {
            const HalfedgeId t = TriMesh::twin(cur);
            if (m_.is_boundary(t)) return std::nullopt;
            const VertexId p = m_.from(cur), q = m_.to(cur), r = m_.to(m_.next(t));
            if (r == c) return std::nullopt;  // the strip wound around to c itself
            const double l_pr = (m_.position(r) - m_.position(p)).norm();
            const double l_qr = (m_.position(r) - m_.position(q)).norm();
            const Vec3 u = q2 - p2;
            const double l = u.norm();
            if (!(l > 0)) return std::nullopt;
            const double x = (l * l + l_pr * l_pr - l_qr * l_qr) / (2 * l);
            const double y = std::sqrt(std::max(0.0, l_pr * l_pr - x * x));
            const Vec3 r2 = p2 + (x / l) * u + (y / l) * Vec3(u.y(), -u.x(), 0);  // right of p -> q
            const bool a_side = r2.dot(b2) < 0, b_side = r2.dot(a2) < 0;
            if (!a_side && !b_side) return VirtualVertex{r, r2};
            if (a_side) {
                cur = m_.next(m_.next(t));  // r -> q
                p2 = r2;
            } else {
                cur = m_.next(t);  // p -> r
                q2 = r2;
            }
        }
        return std::nullopt;
    }
};

namespace {

void check_sources(const TriMesh& mesh, std::span<const VertexId> sources) {
    for (VertexId s : sources)
        if (!s.valid() || s.idx() >= mesh.n_vertices())
            throw InvalidInput("fast marching: source " + std::to_string(s.idx()) + " is not a vertex of the mesh (" +
                               std::to_string(mesh.n_vertices()) + " vertices)");
}

}  // namespace

FastMarching::FastMarching(const TriMesh& mesh, std::span<const VertexId> sources, bool unfold, Workspace* workspace) {
    check_sources(mesh, sources);
    state_ = std::make_unique<State>(mesh, unfold, workspace);
    state_->start(sources);
}

FastMarching::~FastMarching() = default;

void FastMarching::advance(double max_distance) {
    if (std::isnan(max_distance)) throw InvalidInput("fast marching: max_distance is NaN");
    state_->run(max_distance, VertexId());
}

double FastMarching::advance_to(VertexId target) {
    check_sources(state_->mesh(), std::span(&target, 1));
    if (const double d = state_->distance(target); d < INFINITY) return d;  // final already: nothing to do
    state_->run(INFINITY, target);
    return state_->distance(target);
}

double FastMarching::distance(VertexId v) const { return state_->distance(v); }

std::span<const VertexId> FastMarching::finalized() const { return state_->finalized(); }

DistanceField fast_marching(const TriMesh& mesh, std::span<const VertexId> sources,
                            const FastMarchingOptions& options) {
    if (std::isnan(options.max_distance)) throw InvalidInput("fast marching: max_distance is NaN");
    FastMarching run(mesh, sources, options.unfold, options.workspace);
    run.advance(options.max_distance);
    DistanceField field{VertexData<double>(mesh.n_vertices(), INFINITY), {}};
    const std::span<const VertexId> done = run.finalized();
    field.finalized.assign(done.begin(), done.end());
    for (VertexId v : done) field.distance[v] = run.distance(v);
    return field;
}

}  // namespace fhr::geodesic
