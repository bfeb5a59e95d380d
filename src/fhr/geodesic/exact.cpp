// FHR §3 — exact geodesics by window propagation (Chen–Han / Xin–Wang ICH). The pseudocode is at
// the top of exact.hpp; the invariants, the filtering rule's proof and the tolerances are in
// paper_notes/exact_geodesics.md.
#include <fhr/geodesic/exact.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include <fhr/core/geometry.hpp>
#include <fhr/geodesic/detail/scratch.hpp>

namespace fhr::geodesic {

namespace {

/// A window's filter comparisons keep the window unless it loses by more than this fraction of
/// its own distance: distances carry a relative rounding error of about k·2⁻⁵² after k unfoldings
/// (k ≤ 10⁴ here), so a smaller margin could discard the window that realizes a tie.
constexpr double filter_tolerance = 1e-11;
/// Windows narrower than this fraction of their edge are dropped: their end points carry an
/// absolute rounding error of about k·2⁻⁵²·|I| (|I| ≤ 10³·|edge| on our meshes), so such a
/// window is a single ray, and a single ray only matters where it hits a vertex, which the
/// neighbouring windows reach within cover_tolerance.
constexpr double width_tolerance = 1e-12;
/// Unfolded coordinates carry an absolute rounding error of about k·2⁻⁵² times their magnitude
/// after k unfoldings; this bounds it for k ≤ 4·10³. On the meshes the tolerances below were
/// first derived for (|I| ≤ 10³·|edge|) it is covered by them; a needle's short edge, 10⁻¹¹ of the
/// distances around it, needs it explicitly (notes, "Needles").
constexpr double unfolding_rounding = 1e-12;
/// An interior vertex is a saddle when its angle sum exceeds 2π by more than this. Each corner
/// angle is accurate to a few ulps of π (atan2 form), so a flat vertex (sum 2π) comes out within
/// ~valence·10⁻¹⁵ of 2π and is not a saddle: the windows on its two sides meet along the straight
/// continuation of their rays. A saddle with a smaller excess leaves a wedge of angle < 10⁻¹²
/// uncovered; at distance r ≤ 10³·|edge| its width is < 10⁻⁹·|edge|, inside cover_tolerance.
constexpr double saddle_tolerance = 1e-12;
/// A saddle's faces get windows when they come within this angle of the wedge where paths
/// through it continue: the arrival direction is computed from unfolded coordinates with a
/// relative error of ~k·2⁻⁵² (k ≤ 10⁴ unfoldings), far below 10⁻⁹ rad.
constexpr double wedge_tolerance = 1e-9;

struct P2 {
    double x, y;
};

}  // namespace

/// The face(h) of a window on h in h's frame: from(h) = (0, 0), to(h) = (len, 0), apex (cx, cy).
struct ExactGeodesic::Frame {
    double len, cx, cy;
};

namespace {

/// p turned about the line of h into h's frame, on the side y >= 0: its projection onto the line
/// (from(h) at 0) and its distance from the line. A difference of two positions is rounded
/// relative to itself, so the result is accurate to a few ulps of |p − from(h)| however short h
/// is (notes, "Needles").
P2 turned(const TriMesh& m, HalfedgeId h, const Vec3& p) {
    const Vec3& a = m.position(m.from(h));
    const Vec3 e = edge_vector(m, h), r = p - a;
    const double len = e.norm();
    return {e.dot(r) / len, e.cross(r).norm() / len};
}

}  // namespace

ExactGeodesic::Frame ExactGeodesic::frame(const TriMesh& m, HalfedgeId h) {
    const P2 c = turned(m, h, m.position(m.to(m.next(h))));
    return {edge_vector(m, h).norm(), c.x, c.y};
}

namespace {

/// The rigid motion from the frame of a window's edge h to the frame of a child edge g (the twin
/// of one of the two other edges of face(h)), and g's length. h and g share one vertex s; the
/// motion is fixed by s's place in g's frame (exact: g's start or end) and by the direction of h
/// there, taken from the 3-D vectors out of s, so it is accurate to a few ulps of the angle at s
/// (turned() is accurate relative to |h|) whatever the triangle's shape. A direction taken as the
/// difference of two points rounded by ε times the triangle's size (g's axis as to(h) − apex in
/// h's frame, or h's as the difference of its ends in g's frame) turns by ε·(size)/(short edge)
/// rad when that edge is a needle's short one: 10⁻⁸ rad at 10⁻⁹°, every window beyond it off by
/// that times |I| (notes, "Needles").
struct Motion {
    P2 o, a;  ///< where from(h) goes, and the unit vector h's x-axis becomes
    double len;
    P2 operator()(P2 p) const { return {o.x + p.x * a.x - p.y * a.y, o.y + p.x * a.y + p.y * a.x}; }
};

Motion motion(const TriMesh& m, HalfedgeId h, HalfedgeId g) {
    const double len = edge_vector(m, g).norm();
    if (m.from(g) == m.from(h)) {  // s = from(h) is g's start; to(h) lies below g
        const P2 u = turned(m, g, m.position(m.to(h)));
        const double n = std::hypot(u.x, u.y);
        return {{0, 0}, {u.x / n, -u.y / n}, len};
    }
    // s = to(h) is g's end; from(h), seen from s along g reversed, lies below g.
    const P2 u = turned(m, TriMesh::twin(g), m.position(m.from(h)));
    const double n = std::hypot(u.x, u.y);
    return {{len - u.x, -u.y}, {u.x / n, u.y / n}, len};
}

/// Where the line through i and q crosses y = 0. \pre q.y > i.y.
double intercept(P2 i, P2 q) { return (i.x * q.y - q.x * i.y) / (q.y - i.y); }

double longest_edge_at(const TriMesh& m, VertexId v) {
    double longest = 0;
    m.for_each_outgoing(
        v, [&](HalfedgeId h) { longest = std::max(longest, (m.position(m.to(h)) - m.position(v)).norm()); });
    return longest;
}

}  // namespace

struct ExactGeodesic::Scratch final : detail::ScratchBase {
    std::vector<double> dist;
    std::vector<Via> via;
    std::vector<std::uint8_t> kind;
    std::vector<std::uint32_t> touched;  ///< vertices whose dist, via or kind changed
    std::vector<Window> windows;
    std::vector<Event> heap;

    void fit(std::size_t n) {
        if (dist.size() >= n) return;
        dist.resize(n, INFINITY);
        via.resize(n, Via{});
        kind.resize(n, unknown);
    }
    void reset() noexcept {
        for (std::uint32_t v : touched) {
            dist[v] = INFINITY;
            via[v] = Via{};
            kind[v] = unknown;
        }
        detail::clear_buffer(touched);
        detail::clear_buffer(windows);
        detail::clear_buffer(heap);
    }
};

void ExactGeodesic::ScratchDeleter::operator()(Scratch* s) const noexcept {
    detail::WorkspaceAccess::release(workspace, std::unique_ptr<Scratch>(s));
}

namespace {

void check_source(const TriMesh& mesh, VertexId source, const ExactOptions& options) {
    if (!source.valid() || source.idx() >= mesh.n_vertices())
        throw std::invalid_argument("ExactGeodesic: source vertex out of range");
    if (options.face_mask && options.face_mask->size() != mesh.n_faces())
        throw std::invalid_argument("ExactGeodesic: face_mask needs one entry per face");
}

}  // namespace

ExactGeodesic::ExactGeodesic(const TriMesh& mesh, VertexId source, ExactOptions options)
    : mesh_((check_source(mesh, source, options), mesh)),
      options_(options),
      scratch_(detail::WorkspaceAccess::acquire<Scratch>(options.workspace, mesh.n_vertices()).release(),
               ScratchDeleter{options.workspace}),
      dist_(scratch_->dist),
      via_(scratch_->via),
      kind_(scratch_->kind),
      windows_(scratch_->windows),
      heap_(scratch_->heap) {
    scratch_->touched.push_back(source.idx());
    dist_[source.idx()] = 0;
    via_[source.idx()] = {Via::Kind::source, 0};
    push_vertex(source);
}

ExactGeodesic::~ExactGeodesic() = default;

bool ExactGeodesic::face_exists(FaceId f) const {
    return f.valid() && (!options_.face_mask || (*options_.face_mask)[f] != 0);
}

bool ExactGeodesic::masked_out(FaceId f) const {
    return f.valid() && options_.face_mask && (*options_.face_mask)[f] == 0;
}

// A window that would enter a masked-out face: its key over its interval (clamped to the edge,
// not filtered, so at most the key the window would have had) bounds from below every path that
// leaves the mask through it.
void ExactGeodesic::note_border(const Window& candidate) {
    Window w = candidate;
    const double len = edge_vector(mesh_, w.h).norm();
    const double lo = std::min(w.b0, w.b1), hi = std::max(w.b0, w.b1);
    w.b0 = std::clamp(lo, 0.0, len);
    w.b1 = std::clamp(hi, 0.0, len);
    stats_.border_key = std::min(stats_.border_key, window_key(w));
}

std::uint8_t ExactGeodesic::vertex_kind(VertexId v) {
    std::uint8_t& kind = kind_[v.idx()];
    if (kind == unknown) {
        if (dist_[v.idx()] == INFINITY) scratch_->touched.push_back(v.idx());
        bool boundary = false;
        double sum = 0;
        mesh_.for_each_outgoing(v, [&](HalfedgeId h) {
            if (!face_exists(mesh_.face(h)))
                boundary = true;
            else
                sum += corner_angle(mesh_, h);
        });
        kind = boundary ? boundary_vertex : sum > 2 * std::numbers::pi + saddle_tolerance ? saddle : plain;
    }
    return kind;
}

double ExactGeodesic::vertex_key(VertexId v, double d) const {
    double rest = goals_.empty() ? 0 : INFINITY;
    for (const Vec3& t : goals_) rest = std::min(rest, (mesh_.position(v) - t).norm());
    return d + rest;
}

// The smallest σ + |I x| + |x t| over the window's points x and the goals t. |x t| (3-D) equals
// the planar distance from x to t', t turned about the edge's line into the plane (y ≥ 0), and
// |I x| + |x t'| is convex in x with its minimum where the segment I t' crosses the edge.
double ExactGeodesic::window_key(const Window& w) const {
    const P2 s{w.sx, w.sy};
    const auto through = [&](double x, double tx, double ty) {
        return w.sigma + std::hypot(x - w.sx, w.sy) + std::hypot(x - tx, ty);
    };
    if (goals_.empty()) return w.sigma + std::hypot(std::clamp(w.sx, w.b0, w.b1) - w.sx, w.sy);
    double best = INFINITY;
    for (const Vec3& t : goals_) {
        const P2 tt = turned(mesh_, w.h, t);
        best = std::min(best, through(std::clamp(intercept(s, tt), w.b0, w.b1), tt.x, tt.y));
    }
    return best;
}

void ExactGeodesic::push_vertex(VertexId v) {
    const double key = vertex_key(v, dist_[v.idx()]);
    if (key > options_.prune_above) return;
    heap_.push_back({key, dist_[v.idx()], seq_++, v.idx(), true});
    std::push_heap(heap_.begin(), heap_.end(), std::greater<>());
}

void ExactGeodesic::relax(VertexId v, double d, Via via) {
    if (!(d < dist_[v.idx()])) return;
    if (dist_[v.idx()] == INFINITY && kind_[v.idx()] == unknown) scratch_->touched.push_back(v.idx());
    dist_[v.idx()] = d;
    via_[v.idx()] = via;
    if (vertex_kind(v) != plain) push_vertex(v);
}

// The filtering rule (notes, "Filtering"): w is useless when, at every point x of [b0, b1], some
// vertex u of the face w enters gives a shorter path d(u) + |u x|. For v1 and v2 the excess
// σ + |I x| − d(v) − |v x| is monotone along the edge, so its far end decides; for v3 we bound
// it from below by the nearest point of the window and the farthest end.
bool ExactGeodesic::useless(const Window& w, const Frame& f) const {
    const double d0 = std::hypot(w.b0 - w.sx, w.sy), d1 = std::hypot(w.b1 - w.sx, w.sy);
    const double margin = filter_tolerance * (w.sigma + std::max(d0, d1));
    if (w.sigma + d1 > dist_[mesh_.from(w.h).idx()] + w.b1 + margin) return true;
    if (w.sigma + d0 > dist_[mesh_.to(w.h).idx()] + (f.len - w.b0) + margin) return true;
    const double nearest = w.sx >= w.b0 && w.sx <= w.b1 ? -w.sy : std::min(d0, d1);
    const double farthest = std::max(std::hypot(f.cx - w.b0, f.cy), std::hypot(f.cx - w.b1, f.cy));
    const VertexId v3 = mesh_.to(mesh_.next(w.h));
    return w.sigma + nearest > dist_[v3.idx()] + farthest + margin;
}

void ExactGeodesic::push_window(const Window& candidate) {
    Window w = candidate;
    const Frame f = frame(mesh_, w.h);
    w.b0 = std::clamp(w.b0, 0.0, f.len);
    w.b1 = std::clamp(w.b1, 0.0, f.len);
    // sy < 0: a source image on the edge's own line sends rays along the edge only (zero width).
    if (!(w.b1 - w.b0 > width_tolerance * f.len) || !(w.sy < 0) || useless(w, f)) return;
    const double key = window_key(w);
    if (key > options_.prune_above) return;
    windows_.push_back(w);
    ++stats_.windows_created;
    heap_.push_back({key, 0, seq_++, static_cast<std::uint32_t>(windows_.size() - 1), false});
    std::push_heap(heap_.begin(), heap_.end(), std::greater<>());
}

// The fan of v, counter-clockwise from out(v): fan_[k] is the corner angle of face(g_k) at v.
// A shortest path through an interior saddle v leaves it at an angle of at least π from its
// arrival direction on both sides, so only the faces meeting that wedge get windows; the
// others are reached shorter by the windows that passed v (notes, "Pseudo-sources").
void ExactGeodesic::expand_vertex(VertexId v) {
    ++stats_.pseudo_sources;
    const double delta = dist_[v.idx()];
    const Vec3& pv = mesh_.position(v);
    const Via via = via_[v.idx()];
    const bool all_faces = via.kind == Via::Kind::source || vertex_kind(v) == boundary_vertex;
    double back = 0, total = 0;  // the arrival direction (towards the source) and the angle sum
    if (!all_faces) {
        fan_.clear();
        HalfedgeId g = mesh_.out(v);
        do {
            if (via.kind == Via::Kind::edge && mesh_.to(g) == VertexId(via.index)) back = total;
            if (via.kind == Via::Kind::window) {
                const Window& w = windows_[via.index];
                if (g == mesh_.next(mesh_.next(w.h))) {  // g = v -> v1 in the window's face
                    const Frame f = frame(mesh_, w.h);
                    const Vec3 to_v1(-f.cx, -f.cy, 0), to_source(w.sx - f.cx, w.sy - f.cy, 0);
                    back = total + std::atan2(to_v1.cross(to_source).norm(), to_v1.dot(to_source));
                }
            }
            fan_.push_back(corner_angle(mesh_, g));
            total += fan_.back();
            g = mesh_.ccw_rotated(g);
        } while (g != mesh_.out(v));
    }
    const double pi = std::numbers::pi;
    double theta = 0;
    std::size_t k = 0;
    HalfedgeId g = mesh_.out(v);
    do {
        if (face_exists(mesh_.face(g)) || face_exists(mesh_.face(TriMesh::twin(g))))
            relax(mesh_.to(g), delta + (mesh_.position(mesh_.to(g)) - pv).norm(), {Via::Kind::edge, v.idx()});
        // v is on the mask's border: a path may leave through v itself.
        if (masked_out(mesh_.face(g))) stats_.border_key = std::min(stats_.border_key, vertex_key(v, delta));
        bool emit = face_exists(mesh_.face(g));
        if (!all_faces) {
            // The face spans [a, a + fan_[k]] counted from the arrival direction; the wedge is
            // [π, total − π], widened by wedge_tolerance.
            const double a = std::fmod(theta - back + total, total), b = a + fan_[k];
            emit = emit && ((a <= total - pi + wedge_tolerance && b >= pi - wedge_tolerance) ||
                            b - total >= pi - wedge_tolerance);
            theta += fan_[k++];
        }
        if (emit) {
            // The edge opposite v in face(g), seen from the face beyond it: b -> a.
            const HalfedgeId beyond = TriMesh::twin(mesh_.next(g));
            if (face_exists(mesh_.face(beyond)) || masked_out(mesh_.face(beyond))) {
                const P2 image = turned(mesh_, beyond, pv);
                // v's image lies strictly below the edge: the face is not exactly degenerate
                // (INV-IN-5). When v lies on the edge's line within rounding (a cap with an angle of
                // π at v), |e × r| can round to 0; a zero height would read as "rays along the edge
                // only" and drop the window, hiding the face beyond from v (GEO-E4).
                const double below = std::min(-image.y, -std::numeric_limits<double>::min());
                const Window w{beyond, v, no_parent, 0, edge_vector(mesh_, beyond).norm(), image.x, below, delta};
                if (face_exists(mesh_.face(beyond)))
                    push_window(w);
                else
                    note_border(w);
            }
        }
        g = mesh_.ccw_rotated(g);
    } while (g != mesh_.out(v));
}

void ExactGeodesic::propagate_window(std::uint32_t index) {
    const Window w = windows_[index];  // a copy: push_window may reallocate windows_
    const Frame f = frame(mesh_, w.h);
    if (useless(w, f)) return;  // distances may have improved since w was queued
    ++stats_.windows_propagated;
    const HalfedgeId hn = mesh_.next(w.h), hp = mesh_.next(hn);
    const VertexId v3 = mesh_.to(hn);
    const P2 s{w.sx, w.sy}, c{f.cx, f.cy};
    // Where the ray from the source image to the apex v3 crosses the window's edge.
    const double xc = intercept(s, c);
    // Rounding moves xc and the interval by up to unfolding_rounding times the coordinates
    // involved (the edge, the source image, the apex), which on a needle's short edge is far more
    // than cover_tolerance·|edge| (notes, "Needles").
    const double scale = std::max({f.len, std::hypot(w.sx, w.sy), std::hypot(f.cx, f.cy)});
    const double tol = cover_tolerance * f.len + unfolding_rounding * scale;
    const double via_w = w.sigma + std::hypot(f.cx - w.sx, f.cy - w.sy);
    if (xc >= w.b0 - tol && xc <= w.b1 + tol) relax(v3, via_w, {Via::Kind::window, index});
    // Rays left of xc cross edge v1 -> v3, rays right of it edge v3 -> v2. When v3 is reached
    // shorter by a path whose last segment starts at x* on this edge, the rays between xc and x*
    // cross that segment and are dominated there (notes, "Splitting at the apex").
    double left_end = std::min(xc, w.b1), right_start = std::max(xc, w.b0);
    const Via known = via_[v3.idx()];
    if (via_w > dist_[v3.idx()] * (1 + filter_tolerance)) {
        double xs = NAN;
        if (known.kind == Via::Kind::window && windows_[known.index].h == w.h)
            xs = intercept({windows_[known.index].sx, windows_[known.index].sy}, c);
        else if (known.kind == Via::Kind::edge)
            xs = VertexId(known.index) == mesh_.from(w.h) ? 0 : VertexId(known.index) == mesh_.to(w.h) ? f.len : NAN;
        if (xs < xc) left_end = std::min(left_end, xs);
        if (xs > xc) right_start = std::max(right_start, xs);
    }
    if (left_end > w.b0) {
        const HalfedgeId child = TriMesh::twin(hp);
        if (face_exists(mesh_.face(child)) || masked_out(mesh_.face(child))) {
            const Motion to_child = motion(mesh_, w.h, child);
            const P2 si = to_child(s);
            const double b1 = left_end == xc ? to_child.len : intercept(si, to_child({left_end, 0}));
            const Window c{child, w.pseudo, index, intercept(si, to_child({w.b0, 0})), b1, si.x, si.y, w.sigma};
            if (face_exists(mesh_.face(child)))
                push_window(c);
            else
                note_border(c);
        }
    }
    if (right_start < w.b1) {
        const HalfedgeId child = TriMesh::twin(hn);
        if (face_exists(mesh_.face(child)) || masked_out(mesh_.face(child))) {
            const Motion to_child = motion(mesh_, w.h, child);
            const P2 si = to_child(s);
            const double b0 = right_start == xc ? 0 : intercept(si, to_child({right_start, 0}));
            const Window r{child, w.pseudo, index, b0, intercept(si, to_child({w.b1, 0})), si.x, si.y, w.sigma};
            if (face_exists(mesh_.face(child)))
                push_window(r);
            else
                note_border(r);
        }
    }
}

void ExactGeodesic::propagate(std::span<const VertexId> targets) {
    // The keys are lower bounds of the distance to the nearest target (A* with the Euclidean
    // distance, notes "Early stop"); new targets re-key the queue.
    std::vector<Vec3> goals;
    for (VertexId t : targets) goals.push_back(mesh_.position(t));
    if (goals != goals_) {
        goals_ = std::move(goals);
        for (Event& e : heap_)
            e.key = e.is_vertex ? vertex_key(VertexId(e.index), e.dist) : window_key(windows_[e.index]);
        std::make_heap(heap_.begin(), heap_.end(), std::greater<>());
    }
    while (!heap_.empty()) {
        stats_.stop_key = heap_.front().key;
        if (!targets.empty()) {
            double bound = 0;
            for (VertexId t : targets) bound = std::max(bound, dist_[t.idx()]);
            if (heap_.front().key >= bound) return;  // nothing left can lower a target's distance
        }
        if (heap_.front().key > options_.prune_above) return;  // keys from before a re-keying
        std::pop_heap(heap_.begin(), heap_.end(), std::greater<>());
        const Event e = heap_.back();
        heap_.pop_back();
        if (!e.is_vertex)
            propagate_window(e.index);
        else if (e.dist == dist_[e.index])  // else stale: the vertex was reached shorter since
            expand_vertex(VertexId(e.index));
    }
    stats_.stop_key = INFINITY;
}

GeodesicPath ExactGeodesic::path_to(VertexId target) const {
    GeodesicPath path;
    path.length = dist_[target.idx()];
    if (!(path.length < INFINITY)) return path;
    std::vector<SurfacePoint>& pts = path.points;
    const auto add = [&](const SurfacePoint& p) {
        const bool repeat = !pts.empty() && p.kind == SurfacePoint::Kind::vertex &&
                            pts.back().kind == SurfacePoint::Kind::vertex && pts.back().vertex == p.vertex;
        if (!repeat) pts.push_back(p);
    };
    VertexId cur = target;
    add(SurfacePoint::at_vertex(cur));
    while (via_[cur.idx()].kind != Via::Kind::source) {
        const Via via = via_[cur.idx()];
        if (via.kind == Via::Kind::edge) {
            cur = VertexId(via.index);
            add(SurfacePoint::at_vertex(cur));
            continue;
        }
        // Unfold backwards: P is the current path point in window w's frame; the straight segment
        // from P to the source image crosses w's edge, which is an edge of the parent's face.
        const Window* w = &windows_[via.index];
        Frame f = frame(mesh_, w->h);
        P2 p{f.cx, f.cy};
        for (;;) {
            const double dx = w->sx - p.x, dy = w->sy - p.y;
            const double x = p.x - dx * p.y / dy;
            const double t = std::clamp(x, 0.0, f.len) / f.len;
            // The line passes the nearer end of the edge at distance rho: the same for every edge
            // around that vertex, so a run of crossings around it snaps all or none (GEO-5). A
            // line that misses the edge (a vertex reached within cover_tolerance) passes that end.
            const VertexId end = t <= 0.5 ? mesh_.from(w->h) : mesh_.to(w->h);
            const double rho = std::abs(dx * p.y - dy * (p.x - (t <= 0.5 ? 0 : f.len))) / std::hypot(dx, dy);
            const bool at_end = !(x > 0 && x < f.len) || rho <= snap_tolerance * longest_edge_at(mesh_, end);
            add(at_end ? SurfacePoint::at_vertex(end) : SurfacePoint::on_edge(w->h, t));
            if (w->parent == no_parent) {
                cur = w->pseudo;
                add(SurfacePoint::at_vertex(cur));
                break;
            }
            const Window* parent = &windows_[w->parent];
            const Frame pf = frame(mesh_, parent->h);
            // w lies on twin(prev) (edge v1 -> v3) or twin(next) (edge v3 -> v2) of the parent's face.
            if (w->h == TriMesh::twin(mesh_.next(mesh_.next(parent->h))))
                p = {t * pf.cx, t * pf.cy};
            else
                p = {pf.cx + t * (pf.len - pf.cx), (1 - t) * pf.cy};
            w = parent;
            f = pf;
        }
    }
    std::reverse(pts.begin(), pts.end());
    return path;
}

}  // namespace fhr::geodesic
