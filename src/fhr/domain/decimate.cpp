// FHR §2 — half-edge-collapse decimation (see decimate.hpp for the pseudocode and
// paper_notes/domain.md for the choices: quadric error of the surviving vertex, link condition,
// normal-deviation and minimum-angle rules). Beyond the paper: a surface with boundary is
// decimated as T̂, closed by cones (core/detail/cones.hpp), with a boundary vertex collapsed only along
// the boundary; several components each to their share of the faces (paper_notes/boundary.md).
#include <fhr/core/detail/contract.hpp>
#include <fhr/domain/decimate.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include <array>

#include <fhr/core/detail/cones.hpp>
#include <fhr/core/errors.hpp>
#include <fhr/core/detail/outcome.hpp>
#include <fhr/core/geometry.hpp>
#include <fhr/core/detail/predicates.hpp>
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
    return {
        {w * a * a, w * a * b, w * a * c, w * a * d, w * b * b, w * b * c, w * b * d, w * c * c, w * c * d, w * d * d}};
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

// Ties of cost go to the shorter edge, then to the lower halfedge index (deterministic). On a flat
// region every collapse costs 0 (exactly, once rounding clamps at 0): by index alone, collapses swept
// along the numbering into one vertex whose star then refused collapse after collapse (the fandisk
// subdivided to 828,544 faces popped 17 candidates per collapse); shortest first spreads them, as an
// infinitesimal length term in the cost would (1.3 pops per collapse). The squared length
// is rounded to float so that a candidate stays 16 bytes; rounding is exact IEEE, the same on any
// compiler.
struct Candidate {
    double cost;
    float length2;
    std::uint32_t halfedge;
    bool operator<(const Candidate& o) const {
        if (cost != o.cost) return cost < o.cost;
        return length2 != o.length2 ? length2 < o.length2 : halfedge < o.halfedge;
    }
};
static_assert(sizeof(Candidate) == 16);

// The queue: at most one candidate per edge of D (one of its two directions), each edge's place
// known, so that a new candidate for an edge replaces the old one where it stands (a
// queue that left superseded candidates in place to be skipped made the same collapses, but at 10⁶
// faces popped 5 million for 495,000 collapses).
// Two tiers: a binary min-heap holds only the candidates at or below `bound_`, the others
// wait unsorted in `rest_`. A heap of every candidate (1.5 million at 10⁶ faces, 24 MB) made each
// pop a walk of twenty levels, the lower ones cache misses, and was a third of §2's loop; most
// candidates are replaced or removed long before they are the least. When the heap runs out, the
// least sixteenth or so of the rest (bounded by a quantile of an evenly spaced sample) moves into it.
// The order of pops is that of a single heap: every candidate in the heap is below every one in
// the rest, and (cost, halfedge) orders all candidates totally.
class CandidateQueue {
public:
    explicit CandidateQueue(std::size_t edges) : place_(edges, none) { FHR_DCHECK(edges < in_rest); }
    /// No candidate left. Refills the heap from the rest when it ran out.
    bool empty() {
        if (heap_.empty() && !rest_.empty()) refill();
        return heap_.empty();
    }
    /// The queue of these candidates, one per edge, and nothing else.
    void assign(std::vector<Candidate> candidates) {
        heap_.clear();
        rest_ = std::move(candidates);
        for (std::size_t i = 0; i < rest_.size(); ++i)
            place_[rest_[i].halfedge / 2] = in_rest | static_cast<std::uint32_t>(i);
        bound_ = Candidate{-INFINITY, -INFINITY, 0};
    }
    /// The least candidate. \pre !empty()
    const Candidate& top() const { return heap_.front(); }
    /// Puts c in as its edge's candidate, replacing the edge's earlier one.
    void put(const Candidate& c) {
        const std::uint32_t at = place_[c.halfedge / 2];
        const bool low = !(bound_ < c);
        if (at != none && !(at & in_rest) && low) {  // from the heap to the heap: in place
            const bool earlier = c < heap_[at];
            heap_[at] = c;
            earlier ? up(at) : down(at);
            return;
        }
        if (at != none && (at & in_rest) && !low) {  // from the rest to the rest: in place
            rest_[at & ~in_rest] = c;
            return;
        }
        if (at != none) remove_placed(at);
        low ? push_heap(c) : push_rest(c);
    }
    void pop() { remove_from_heap(0); }
    /// Takes every candidate out.
    void clear() {
        for (const Candidate& c : heap_) place_[c.halfedge / 2] = none;
        for (const Candidate& c : rest_) place_[c.halfedge / 2] = none;
        heap_.clear();
        rest_.clear();
    }
    /// Takes edge e's candidate out, if it has one.
    void remove(std::uint32_t e) {
        if (place_[e] != none) remove_placed(place_[e]);
    }

private:
    static constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
    static constexpr std::uint32_t in_rest = 1u << 31;  // place_ of a candidate in rest_
    std::vector<Candidate> heap_;                       // a binary min-heap of the candidates ≤ bound_
    std::vector<Candidate> rest_;                       // the candidates > bound_, in no order
    Candidate bound_{};
    std::vector<std::uint32_t>
        place_;  // per edge: its candidate's index in heap_, or in_rest | index in rest_, or none

    // The least part of the rest into the (empty) heap: those at or below the 1/16-quantile of 1,024
    // evenly spaced samples (all of them when few are left), found in one pass from the back, each
    // taken out by moving the last into its place.
    void refill() {
        const std::size_t n = rest_.size(), samples = 1024;
        if (n <= 8 * samples) {
            bound_ = Candidate{INFINITY, INFINITY, UINT32_MAX};  // above every candidate
        } else {
            std::vector<Candidate> sample(samples);
            for (std::size_t i = 0; i < samples; ++i) sample[i] = rest_[i * (n / samples)];
            std::nth_element(sample.begin(), sample.begin() + samples / 16, sample.end());
            bound_ = sample[samples / 16];
        }
        for (std::size_t i = n; i-- > 0;)
            if (!(bound_ < rest_[i])) {
                heap_.push_back(rest_[i]);
                remove_from_rest(i);
            }
        for (std::size_t i = heap_.size() / 2; i-- > 0;) down(i);
        for (std::size_t i = 0; i < heap_.size(); ++i) place_[heap_[i].halfedge / 2] = static_cast<std::uint32_t>(i);
    }
    void push_heap(const Candidate& c) {
        heap_.push_back(c);
        up(heap_.size() - 1);
    }
    void push_rest(const Candidate& c) {
        place_[c.halfedge / 2] = in_rest | static_cast<std::uint32_t>(rest_.size());
        rest_.push_back(c);
    }
    void remove_placed(std::uint32_t at) { at& in_rest ? remove_from_rest(at & ~in_rest) : remove_from_heap(at); }
    void remove_from_rest(std::size_t i) {
        place_[rest_[i].halfedge / 2] = none;
        if (i + 1 < rest_.size()) {
            rest_[i] = rest_.back();
            place_[rest_[i].halfedge / 2] = in_rest | static_cast<std::uint32_t>(i);
        }
        rest_.pop_back();
    }
    void remove_from_heap(std::size_t i) {
        place_[heap_[i].halfedge / 2] = none;
        const Candidate last = heap_.back();
        heap_.pop_back();
        if (i == heap_.size()) return;
        const bool earlier = last < heap_[i];
        move_to(i, last);
        earlier ? up(i) : down(i);
    }
    void move_to(std::size_t i, const Candidate& c) {
        heap_[i] = c;
        place_[c.halfedge / 2] = static_cast<std::uint32_t>(i);
    }
    void up(std::size_t i) {
        const Candidate c = heap_[i];
        for (; i > 0 && c < heap_[(i - 1) / 2]; i = (i - 1) / 2) move_to(i, heap_[(i - 1) / 2]);
        move_to(i, c);
    }
    void down(std::size_t i) {
        const Candidate c = heap_[i];
        const std::size_t n = heap_.size();
        for (std::size_t child = 2 * i + 1; child < n; child = 2 * i + 1) {
            if (child + 1 < n && heap_[child + 1] < heap_[child]) ++child;
            if (!(heap_[child] < c)) break;
            move_to(i, heap_[child]);
            i = child;
        }
        move_to(i, c);
    }
};

// Six times the signed volume enclosed by each component of m (numbered as `comps` numbers them):
// the sum over its faces of a · (b × c).
std::vector<double> volume6_per_component(const TriMesh& m, const Components& comps) {
    std::vector<double> v(comps.count, 0);
    for (FaceId f : m.faces()) {
        const auto [a, b, c] = m.face_vertices(f);
        v[comps.vertex_component[a]] += m.position(a).dot(m.position(b).cross(m.position(c)));
    }
    return v;
}

// Each vertex's quadric: the area-weighted plane quadrics of its faces — on T̂ the faces of T only
// (the first real_faces) — and at a boundary edge of T the plane through it perpendicular to its
// face, weighted by its squared length, so that the boundary keeps its shape (Garland & Heckbert
// 1997, §6.1).
std::vector<Quadric> vertex_quadrics(const TriMesh& T, std::size_t real_faces) {
    std::vector<Quadric> q(T.n_vertices());
    for (FaceId f : T.faces()) {
        if (f.idx() >= real_faces) break;
        const Quadric k = face_quadric(T, f);
        for (VertexId v : T.face_vertices(f)) q[v.idx()] += k;
        HalfedgeId h = T.halfedge(f);
        for (int i = 0; i < 3; ++i, h = T.next(h)) {
            const FaceId across = T.face(TriMesh::twin(h));
            if (across.valid() && across.idx() < real_faces) continue;
            const Vec3 &a = T.position(T.from(h)), &b = T.position(T.to(h));
            const Vec3 n = (b - a).cross(face_normal(T, f)).normalized();
            const double d = -n.dot(a), w = (b - a).squaredNorm();
            const Quadric side{{w * n.x() * n.x(), w * n.x() * n.y(), w * n.x() * n.z(), w * n.x() * d,
                                w * n.y() * n.y(), w * n.y() * n.z(), w * n.y() * d, w * n.z() * n.z(), w * n.z() * d,
                                w * d * d}};
            q[T.from(h).idx()] += side;
            q[T.to(h).idx()] += side;
        }
    }
    return q;
}

std::size_t reachable_request(const TriMesh& T, const std::vector<std::size_t>& reached, std::size_t from);

// decimate's regime for a request of `faces` faces: the pass over the cells first, or not.
bool cells_first(const TriMesh& T, std::size_t faces, const DecimateOptions& o) {
    return T.n_faces() > o.cells_from && 4 * faces <= T.n_faces();
}

// Decimates `start`, a decimation of T̂ (T with cones; T itself when closed) after the collapses
// `start.history` (T̂ itself with none),
// whose vertex j is T̂'s vertex start.t_vertex[j] with quadric quadrics[j]. Vertices of T̂ from
// `real_vertices` on are the apexes of its cones; component c of start.mesh (`comps`, its
// connected_components) is decimated to targets[c] faces of T (cone faces not counted).
class Decimator {
public:
    Decimator(const TriMesh& T, Domain start, const Components& comps, const TriMesh& t_hat,
              std::vector<Quadric> quadrics, const DecimateOptions& o, std::size_t real_vertices,
              std::vector<std::size_t> targets)
        : T_(T),
          m_(std::move(start.mesh)),
          history_(std::move(start.history)),
          options_(o),
          rejected_(m_.n_halfedges(), false),
          rejection_(m_.n_halfedges()),
          real_(real_vertices),
          target_(std::move(targets)),
          queue_(m_.n_edges()) {
        // One pass over the vertices and one over the faces fill the records and the counts
        // (at 10⁶ faces each pass over the records is some 15 ms).
        std::vector<std::uint8_t> kept(std::max_element(start.t_vertex.begin(), start.t_vertex.end())->idx() + 1, 0);
        for (VertexId v : o.keep)
            if (v.idx() < kept.size()) kept[v.idx()] = 1;
        faces_.assign(comps.count, 0);
        open_.assign(comps.count, 0);
        std::vector<VertexId> some(comps.count);  // a vertex of each component
        // A fresh start (decimate's identity(T̂): no history, every vertex its own) is T̂ itself,
        // face for face: the same components and the same volumes, summed in the same order.
        bool fresh = history_.empty() && m_.n_faces() == t_hat.n_faces();
        FHR_DCHECK(!m_.has_garbage());
        vertex_.reserve(m_.n_vertices());
        for (VertexId v : m_.vertices()) {
            VertexState& s = vertex_.emplace_back();
            s.position = m_.position(v);
            s.quadric = quadrics[v.idx()];
            s.t = start.t_vertex[v];
            s.component = comps.vertex_component[v];
            s.keep = kept[s.t.idx()] || apex(v);
            cones_ = cones_ || apex(v);
            open_[s.component] |= apex(v);
            fresh = fresh && s.t == v;
            if (!some[s.component].valid()) some[s.component] = v;
        }
        quadrics = {};
        for (FaceId f : m_.faces()) {
            const auto corners = m_.face_vertices(f);
            for (VertexId v : corners) {
                std::uint32_t& cell = vertex_[v.idx()].cell;
                cell = std::min(cell, static_cast<std::uint32_t>(f.idx() / o.cell_faces));
            }
            if (!cone_face(f)) ++faces_[component(corners[0])];
        }
        for (std::size_t c = 0; c < comps.count; ++c) excess_ += faces_[c] > target_[c] ? faces_[c] - target_[c] : 0;
        set_rules(first_normal_rule(),
                  o.first_min_angle_deg > o.min_angle_deg ? o.first_min_angle_deg : o.min_angle_deg);
        // The volume rule, per closed component (a sum over components would let a small one turn
        // inside out beside a large one); a component with boundary has no rule: T̂'s cones are no
        // part of the surface.
        volume_ = volume6_per_component(m_, comps);
        min_volume_.assign(comps.count, -INFINITY);
        const Components t_comps = fresh ? Components{} : connected_components(t_hat);
        const std::vector<double> t_volume = fresh ? volume_ : volume6_per_component(t_hat, t_comps);
        for (std::size_t c = 0; c < comps.count; ++c)
            if (!open_[c]) min_volume_[c] = 1e-6 * t_volume[fresh ? c : t_comps.vertex_component[t_of(some[c])]];
    }

    // by_cells: first the pass over T̂'s cells (reduce_cells), then the greedy loop over all edges.
    Domain run(bool by_cells) {
        Domain d;
        d.history = std::move(history_);
        d.by_cells = by_cells;
        if (by_cells) {
            FHR_DCHECK(d.history.empty());  // a fresh start (decimate_from_t)
            reduce_cells(d.history);
            d.cell_collapses = d.history.size();
            drop_garbage();
        }
        queue_every_edge();
        while (excess_ > 0) {
            if (queue_.empty() && relax_rules()) continue;
            if (queue_.empty()) {
                // A component with boundary may stop above its share (its loops and corners may need
                // more faces); a closed one may not, unless best_effort.
                bool closed_above = false;
                for (std::size_t c = 0; c < faces_.size(); ++c)
                    closed_above = closed_above || (!open_[c] && faces_[c] > target_[c]);
                if (options_.best_effort || !closed_above) break;
                std::size_t faces = 0;
                for (std::size_t f : faces_) faces += f;
                // The theorem behind the named request holds within one regime (reachable_request).
                std::size_t reachable = reachable_request(T_, faces_, faces);
                if (cells_first(T_, reachable, options_) != d.by_cells) reachable = 0;
                throw InvalidInput(
                    "decimation stopped at " + std::to_string(faces) + " faces (target " +
                    std::to_string(options_.target_faces) +
                    "): no further half-edge collapse keeps the domain valid under "
                    "min angle " +
                    fmt(options_.min_angle_deg) + "° and normal deviation " + fmt(options_.max_normal_deviation_deg) +
                    "°; ask for more faces" +
                    (reachable ? " (--faces " + std::to_string(reachable) + " succeeds)" : std::string()));
            }
            step(d.history);
        }
        for (VertexId v : m_.vertices())
            if (!m_.is_deleted(v)) d.t_vertex.push_back(t_of(v));
        m_.compact();  // keeps the survivors' order, so D's vertex j is d.t_vertex[j]
        d.mesh = std::move(m_);
        return d;
    }

private:
    // The graded rules (DOM-24, DOM-25): the normal rule's first angle, or the plain rule's maximum.
    double first_normal_rule() const {
        const DecimateOptions& o = options_;
        return o.first_normal_deviation_deg > 0 && o.first_normal_deviation_deg < o.max_normal_deviation_deg
                   ? o.first_normal_deviation_deg
                   : o.max_normal_deviation_deg;
    }
    // Where no collapse is left valid: the normal rule one step looser, or, at its maximum, the
    // angle rule one step looser with the normal rule from its first angle again; false when both
    // are at their plain values.
    bool relax_rules() {
        const DecimateOptions& o = options_;
        if (normal_rule_deg_ < o.max_normal_deviation_deg) {
            set_rules(std::min(normal_rule_deg_ + DecimateOptions::graded_step_deg, o.max_normal_deviation_deg),
                      angle_rule_deg_);
        } else if (angle_rule_deg_ > o.min_angle_deg) {
            set_rules(first_normal_rule(),
                      std::max(angle_rule_deg_ - DecimateOptions::graded_angle_step_deg, o.min_angle_deg));
        } else {
            return false;
        }
        std::fill(rejected_.begin(), rejected_.end(), false);
        std::fill(rejection_.begin(), rejection_.end(), Rejection{});
        queue_every_edge();  // what was rejected was rejected under the tighter rules
        return true;
    }
    void set_rules(double normal_deg, double angle_deg) {
        normal_rule_deg_ = normal_deg;
        angle_rule_deg_ = angle_deg;
        cos_max_turn_ = std::cos(normal_deg * M_PI / 180.0);
        tan_min_angle_ = std::tan(angle_deg * M_PI / 180.0);
    }

    // Every edge queued, with both directions untried: no edge has a rejected direction.
    void queue_every_edge() {
        std::vector<Candidate> all;
        all.reserve(m_.n_edges());
        for (EdgeId e : m_.edges())
            if (!m_.is_deleted(e)) all.push_back(edge_candidate(e));
        queue_.assign(std::move(all));
        for (VertexState& s : vertex_) s.suspect = false;
    }

    // Pops the cheapest candidate and collapses it if it is valid; true when it did.
    bool step(std::vector<Collapse>& history) {
        const Candidate c = queue_.top();
        queue_.pop();
        const HalfedgeId h(c.halfedge);
        FHR_DCHECK(!m_.is_deleted(TriMesh::edge(h)));
        const std::uint32_t comp = component(m_.from(h));
        if (faces_[comp] <= target_[comp]) return false;          // this component is done
        if (cell_ != no_cell && quota_[comp] == 0) return false;  // or done with this cell
        if (!valid(h)) {                                          // try the edge's other direction at its own cost
            rejected_[h.idx()] = true;
            vertex_[m_.from(h).idx()].suspect = vertex_[m_.to(h).idx()].suspect = true;
            // A twin known to be invalid as things stand is rejected at once: queued, it would
            // be popped and rejected, or, if a star it reads changed first, that collapse
            // would queue the edge again.
            const HalfedgeId t = TriMesh::twin(h);
            if (!rejected_[t.idx()]) {
                if (known_invalid(t))
                    rejected_[t.idx()] = true;
                else
                    queue_.put(candidate(t));
            }
            return false;
        }
        const VertexId v0 = m_.from(h), v1 = m_.to(h);
        const VertexId va = m_.to(m_.next(h)), vb = m_.to(m_.next(TriMesh::twin(h)));
        history.push_back({t_of(v0), t_of(v1), t_of(va), t_of(vb)});
        const std::size_t removed = apex(va) || apex(vb) ? 1 : 2;  // faces of T
        // The collapse merges (v0, va) into (v1, va) and (v0, vb) into (v1, vb), and TriMesh
        // deletes the first of each pair: their candidates leave the queue now. Left in, they
        // were two thirds of all pops at 10⁶ faces, each a walk down the whole heap to skip it.
        const EdgeId merged_a = TriMesh::edge(m_.next(m_.next(h))), merged_b = TriMesh::edge(m_.next(TriMesh::twin(h)));
        // The stars the collapse changes: those of v0's neighbours (v1, va and vb among them).
        m_.for_each_outgoing(v0, [&](HalfedgeId g) { vertex_[m_.to(g).idx()].changed = collapses_ + 1; });
        m_.collapse(h);
        ++collapses_;
        if (vertex_[v0.idx()].suspect) vertex_[v1.idx()].suspect = true;  // v0's edges are v1's now
        FHR_DCHECK(m_.is_deleted(merged_a) && m_.is_deleted(merged_b));
        queue_.remove(merged_a.idx());
        queue_.remove(merged_b.idx());
        volume_[comp] += change_;
        faces_[comp] -= removed;
        excess_ -= removed;
        vertex_[v1.idx()].quadric += vertex_[v0.idx()].quadric;
        refresh_around(v1);
        if (cell_ != no_cell) --quota_[comp];
        return true;
    }

    // m_ without the removed elements, for the greedy loop after the pass over the cells: its data
    // a quarter of T̂'s (at 10⁶ faces a collapse of that loop then takes about half the time). compact() keeps the survivors'
    // order, so the halfedges' order, which breaks ties, is the same. What was remembered of
    // rejections is forgotten (DOM-22: it only spares checks).
    void drop_garbage() {
        std::vector<VertexState> live;
        live.reserve(m_.n_vertices());
        for (VertexId v : m_.vertices())
            if (!m_.is_deleted(v)) live.push_back(vertex_[v.idx()]);
        m_.compact();
        vertex_ = std::move(live);
        rejected_.assign(m_.n_halfedges(), false);
        rejection_.assign(m_.n_halfedges(), Rejection{});
        queue_ = CandidateQueue(m_.n_edges());
    }

    // The pass over the cells (decimate.hpp): cell after cell, in order, the greedy loop over the
    // edges whose ends both lie in the cell, until a quarter of each component's vertices in the
    // cell are left (or no such collapse is valid). A collapse there reads and writes the stars of the cell's
    // vertices and of their neighbours: its data stays in cache. Only the cell's vertices are
    // removed, so at its turn a cell has all its vertices. Why: past some 10⁵ faces
    // the data of T (some 300 bytes per face) outgrows the last-level cache, and the greedy loop
    // makes a collapse in 3.6 µs at 10⁶ faces against 1.3 µs at 10⁵. A vertex lies in the cell
    // of its first face (cells of 2^14 faces by default, some 8,000 vertices: 2^14 to 2^16
    // measured alike, 2^17 slower) — by faces, not vertex ids: a subdivided mesh appends each
    // level's new vertices after the old ones, but numbers a face's four children together.
    void reduce_cells(std::vector<Collapse>& history) {
        const std::size_t cells = (m_.n_faces() + options_.cell_faces - 1) / options_.cell_faces;
        std::vector<std::size_t> first(cells + 1, 0);  // the vertices of each cell, by counting sort
        for (VertexId v : m_.vertices()) ++first[cell_of(v) + 1];
        for (std::size_t c = 0; c < cells; ++c) first[c + 1] += first[c];
        std::vector<VertexId> by_cell(first[cells]);
        std::vector<std::size_t> next(first.begin(), first.end() - 1);
        for (VertexId v : m_.vertices()) by_cell[next[cell_of(v)]++] = v;
        for (std::size_t c = 0; c < cells && excess_ > 0; ++c) {
            cell_ = static_cast<std::uint32_t>(c);
            std::vector<Candidate> inside;
            for (std::size_t i = first[c]; i < first[c + 1]; ++i)
                m_.for_each_outgoing(by_cell[i], [&](HalfedgeId g) {
                    if (m_.to(g).idx() > m_.from(g).idx() && in_cell(TriMesh::edge(g)))
                        inside.push_back(edge_candidate(TriMesh::edge(g)));
                });
            queue_.assign(std::move(inside));
            // Per component, so that a component's collapses depend on it alone (reachable_request).
            quota_.assign(faces_.size(), 0);
            for (std::size_t i = first[c]; i < first[c + 1]; ++i) ++quota_[component(by_cell[i])];
            std::size_t quota = 0;
            for (std::size_t& q : quota_) quota += q -= q / 4;
            while (quota > 0 && excess_ > 0 && !queue_.empty()) quota -= step(history);
            queue_.clear();
        }
        cell_ = no_cell;
    }

    const TriMesh& T_;  // the input, whose components' shares the targets are
    TriMesh m_;
    std::vector<Collapse> history_;  // the collapses that made `start` from T̂
    const DecimateOptions& options_;
    // What the collapse loop reads of a vertex, in one record of two cache lines: each
    // collapse reads it for every neighbour of the survivor, at random places in arrays of T's
    // size; in separate arrays (quadrics, positions, flags) that was three to five cache misses
    // per neighbour at 10⁶ faces, here two. The position is m_'s, which no collapse moves.
    struct alignas(64) VertexState {
        Vec3 position;
        Quadric quadric;
        std::uint32_t changed = 0;     // the collapses made when its star last changed (valid())
        std::uint32_t component = 0;   // of connected_components(m_)
        VertexId t;                    // its vertex of T̂
        bool keep = false;             // never removed (DecimateOptions::keep, apexes)
        bool suspect = false;          // false when no edge at it has a rejected direction
        std::uint32_t cell = no_cell;  // of the pass over the cells: that of its first face in m_
    };
    static_assert(sizeof(VertexState) == 128);
    std::vector<VertexState> vertex_;
    std::vector<bool> rejected_;  // per halfedge: popped, found invalid, and not queued since
    // For valid(): per halfedge, 1 + the collapses made when it was last found invalid by the
    // local rules (0: not so) and a halfedge whose face failed its rule then (none_: not so); per
    // vertex (VertexState::changed), the collapses made when its star last changed.
    static constexpr std::uint32_t none_ = std::numeric_limits<std::uint32_t>::max();
    struct Rejection {
        std::uint32_t since = 0, witness = none_;
    };
    std::vector<Rejection> rejection_;
    std::uint32_t collapses_ = 0;
    std::size_t real_;                         // vertices of T̂ from here on are apexes
    bool cones_ = false;                       // T has boundary: m_ is a decimation of T̂
    std::vector<std::size_t> faces_, target_;  // per component: faces of T now, and asked
    std::vector<std::uint8_t> open_;           // per component: 1 when it has boundary (an apex of T̂)
    std::size_t excess_ = 0;                   // Σ over the components of the faces above their target
    CandidateQueue queue_;
    double cos_max_turn_ = 0, tan_min_angle_ = 0;
    // The rules now: max_normal_deviation_deg and min_angle_deg, or a graded rule's step.
    double normal_rule_deg_ = 0, angle_rule_deg_ = 0;
    // Per component: D's signed volume, kept above min_volume_ (a small part of T's) so that a
    // closed component stays outward oriented like T's: per-face normal rules alone let a coarse
    // domain turn inside out.
    std::vector<double> volume_, min_volume_;
    double change_ = 0;  // the volume change of the collapse last found valid
    // The cell being reduced (reduce_cells), or no_cell, and per component the collapses still
    // to make in it.
    static constexpr std::uint32_t no_cell = std::numeric_limits<std::uint32_t>::max();
    std::uint32_t cell_ = no_cell;
    std::vector<std::size_t> quota_;

    VertexId t_of(VertexId v) const { return vertex_[v.idx()].t; }
    std::uint32_t component(VertexId v) const { return vertex_[v.idx()].component; }
    const Vec3& position(VertexId v) const { return vertex_[v.idx()].position; }
    bool apex(VertexId v) const { return t_of(v).idx() >= real_; }
    std::uint32_t cell_of(VertexId v) const { return vertex_[v.idx()].cell; }
    // e may be queued now: no cell is being reduced, or both its ends lie in that cell.
    bool in_cell(EdgeId e) const {
        const HalfedgeId h = TriMesh::halfedge(e, 0);
        return cell_ == no_cell || (cell_of(m_.from(h)) == cell_ && cell_of(m_.to(h)) == cell_);
    }
    // face_normal(m_, f), from the records' positions.
    Vec3 normal(FaceId f) const {
        const auto v = m_.face_vertices(f);
        return triangle_normal(position(v[0]), position(v[1]), position(v[2]));
    }
    bool cone_face(FaceId f) const {
        const auto v = m_.face_vertices(f);
        return cones_ && (apex(v[0]) || apex(v[1]) || apex(v[2]));
    }

    // Six times the signed volume of the tetrahedron (0, a, b, c).
    static double volume6(const Vec3& a, const Vec3& b, const Vec3& c) { return a.dot(b.cross(c)); }

    static std::string fmt(double x) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%g", x);
        return buf;
    }

    double cost(HalfedgeId h) const {
        return (vertex_[m_.from(h).idx()].quadric + vertex_[m_.to(h).idx()].quadric)(position(m_.to(h)));
    }
    // The queue holds one candidate per edge, for one of its directions; a new one replaces the
    // edge's earlier one.
    // The cheaper direction of e, both directions counting as untried again. One sum of the two
    // quadrics serves both: floating-point addition commutes, so it is cost()'s, bit for bit.
    Candidate edge_candidate(EdgeId e) {
        const HalfedgeId h0 = TriMesh::halfedge(e, 0), h1 = TriMesh::halfedge(e, 1);
        rejected_[h0.idx()] = rejected_[h1.idx()] = false;
        const VertexId a = m_.from(h0), b = m_.to(h0);
        const Quadric q = vertex_[a.idx()].quadric + vertex_[b.idx()].quadric;
        const double to_b = q(position(b)), to_a = q(position(a));
        const float length2 = static_cast<float>((position(b) - position(a)).squaredNorm());
        return to_a < to_b ? Candidate{to_a, length2, h1.idx()} : Candidate{to_b, length2, h0.idx()};
    }
    Candidate candidate(HalfedgeId h) const {
        const float length2 = static_cast<float>((position(m_.to(h)) - position(m_.from(h))).squaredNorm());
        return {cost(h), length2, h.idx()};
    }
    void push_edge(EdgeId e) {
        if (in_cell(e)) queue_.put(edge_candidate(e));
    }

    // Costs change for the edges at v1 (its quadric grew): they are queued again. Validity can
    // change for every halfedge whose link or faces touch v1's star, so an edge with a direction
    // found invalid earlier near v1 is queued again too — unless both its directions were found
    // invalid by the local rules and neither end's star has changed since (valid()): queued, it
    // would only be popped and rejected twice more, and should a star change later, that
    // collapse queues it again.
    // A neighbour's star is walked only when an edge at it may have a rejected direction
    // (`suspect`; queued again, no edge at it has one): the same edges are queued as by walking
    // the two-ring of every collapse, at 10⁶ faces the most scattered reads of §2.
    void refresh_around(VertexId v1) {
        m_.for_each_outgoing(v1, [&](HalfedgeId g) {
            push_edge(TriMesh::edge(g));
            const VertexId w = m_.to(g);
            if (!vertex_[w.idx()].suspect) return;
            bool left = false;  // an edge at w stays rejected
            m_.for_each_outgoing(w, [&](HalfedgeId k) {
                if (!rejected_[k.idx()] && !rejected_[TriMesh::twin(k).idx()]) return;
                if (!in_cell(TriMesh::edge(k)) || still_invalid(TriMesh::edge(k)))
                    left = true;
                else
                    push_edge(TriMesh::edge(k));
            });
            vertex_[w.idx()].suspect = left;
        });
    }

    // Both directions of e were rejected by the local rules, and the stars of its ends are as
    // they were then.
    bool still_invalid(EdgeId e) const {
        const HalfedgeId h0 = TriMesh::halfedge(e, 0), h1 = TriMesh::halfedge(e, 1);
        if (!rejected_[h0.idx()] || !rejected_[h1.idx()]) return false;
        return unchanged_since(std::min(rejection_[h0.idx()].since, rejection_[h1.idx()].since), h0);
    }
    // h is invalid by the local rules as things stand, known without checking them all: neither
    // star changed since it was found so, or its witness still fails. Remembered as found now.
    bool known_invalid(HalfedgeId h) {
        Rejection& r = rejection_[h.idx()];
        if (!unchanged_since(r.since, h) && !still_witnessed(h, r.witness)) return false;
        r.since = collapses_ + 1;
        return true;
    }
    // Neither end of h's edge changed its star since `found` (1 + the collapses made then; 0:
    // never found invalid).
    bool unchanged_since(std::uint32_t found, HalfedgeId h) const {
        return !options_.recheck_rejected && found > vertex_[m_.from(h).idx()].changed &&
               found > vertex_[m_.to(h).idx()].changed;
    }

    // The collapse from(h) -> to(h) is allowed when it keeps D a closed 2-manifold of the same
    // topology (Theorem, Dey et al. 1999: the link condition suffices) and every face that moves
    // with from(h) stays well shaped and does not turn over. On T̂ the link condition keeps every
    // cone a cone when a boundary vertex moves only along a boundary edge (one of the edge's two
    // faces is a cone face) and each loop keeps three vertices (its apex a valence above 3); the
    // faces of T then stay a surface with the same boundary loops.
    // A collapse found invalid by the rules that read only the stars of its two vertices (all but
    // the volume rule; the count rules only ever forbid more as faces go) stays invalid until one
    // of those stars changes, or while its witness still fails (still_witnessed): it is not
    // checked again before (DOM-22). On a flat CAD region, where every collapse costs
    // 0, each collapse queues the rejected edges around it again and they come straight back to
    // the top: the subdivided fandisk popped 25 candidates per collapse, nearly all rejected as
    // before.
    bool valid(HalfedgeId h) {
        if (known_invalid(h)) return false;
        Rejection& r = rejection_[h.idx()];
        double change = 0;
        if (!locally_valid(h, change, r.witness)) {
            r.since = collapses_ + 1;
            return false;
        }
        const std::uint32_t comp = component(m_.from(h));
        if (volume_[comp] + change <= min_volume_[comp]) return false;
        change_ = change;
        return true;
    }
    // All rules but the volume rule; `change` becomes six times the collapse's change of volume.
    // A face that fails its rule is kept as the collapse's witness (still_witnessed).
    bool locally_valid(HalfedgeId h, double& change, std::uint32_t& witness) const {
        if (vertex_[m_.from(h).idx()].keep) return false;
        const VertexId v0 = m_.from(h), v1 = m_.to(h);
        const std::uint32_t comp = component(v0);
        const FaceId gone0 = m_.face(h), gone1 = m_.face(TriMesh::twin(h));
        if (cones_) {
            const VertexId va = m_.to(m_.next(h)), vb = m_.to(m_.next(TriMesh::twin(h)));
            const bool along = apex(va) || apex(vb);
            bool on_boundary = false;
            m_.for_each_outgoing(v0, [&](HalfedgeId g) { on_boundary = on_boundary || apex(m_.to(g)); });
            if (on_boundary && !along) return false;
            if (along && m_.valence(apex(va) ? va : vb) <= 3) return false;
            // Exactly the target: with one face to go, only a collapse along the boundary.
            if (faces_[comp] - target_[comp] < (along ? 1u : 2u)) return false;
        }
        const Vec3 &p0 = position(v0), &p1 = position(v1);
        bool ok = true;
        m_.for_each_outgoing(v0, [&](HalfedgeId g) {
            const FaceId f = m_.face(g);
            // Face (v0, a, b) becomes (v1, a, b); the two faces at h go.
            const Vec3& a = position(m_.to(g));
            const Vec3& b = position(m_.to(m_.next(g)));
            change += (f == gone0 || f == gone1 ? 0.0 : volume6(p1, a, b)) - volume6(p0, a, b);
            if (!ok || f == gone0 || f == gone1 || cone_face(f)) return;
            if (face_rule_fails(g, p1)) {
                ok = false;
                witness = g.idx();
            }
        });
        return ok && m_.is_collapse_ok(h);
    }
    // Face (v0, a, b) of g = v0 -> a, its corner v0 moved to p1: degenerate, turned by more than
    // the maximum, or with a corner below the minimum.
    bool face_rule_fails(HalfedgeId g, const Vec3& p1) const {
        const Vec3& a = position(m_.to(g));
        const Vec3& b = position(m_.to(m_.next(g)));
        if (collinear(p1, a, b)) return true;
        const Vec3 n_new = (a - p1).cross(b - p1).normalized();
        return n_new.dot(normal(m_.face(g))) < cos_max_turn_ || !corners_at_least(p1, a, b, tan_min_angle_);
    }
    // The face that last made h invalid still lies at from(h), is not one of the two faces the
    // collapse removes, and still fails its rule: h is invalid whatever else changed (all rules
    // must hold). On a flat region a vertex that took in many collapses keeps most of its faces,
    // and the edges at it, queued again after each collapse, fail on the same face as before.
    bool still_witnessed(HalfedgeId h, std::uint32_t witness) const {
        if (options_.recheck_rejected || witness == none_) return false;
        const HalfedgeId g(witness);
        if (m_.is_deleted(TriMesh::edge(g)) || m_.from(g) != m_.from(h) || m_.is_boundary(g)) return false;
        const FaceId f = m_.face(g);
        if (f == m_.face(h) || f == m_.face(TriMesh::twin(h)) || cone_face(f)) return false;
        return face_rule_fails(g, position(m_.to(h)));
    }
};

}  // namespace

std::size_t min_closed_faces(long genus) {
    const long chi = 2 - 2 * genus;
    long v = static_cast<long>(std::ceil((7.0 + std::sqrt(1.0 + 48.0 * static_cast<double>(genus))) / 2.0));
    if (genus == 2) v = 10;  // Jungerman & Ringel: the genus-2 surface has no 9-vertex triangulation
    return static_cast<std::size_t>(2 * (v - chi));
}

namespace {

// What the shares of the faces depend on, per component of T.
struct ComponentMeasures {
    std::vector<double> area;
    std::vector<std::size_t> own;  // T's faces
    std::vector<long> chi, loops;
};

ComponentMeasures measure_components(const TriMesh& T) {
    const Components comps = connected_components(T);
    const std::size_t n = comps.count;
    std::vector<double> area(n, 0);
    std::vector<std::size_t> own(n, 0);
    std::vector<long> chi(n, 0), loops(n, 0);
    for (FaceId f : T.faces()) {
        const std::uint32_t c = comps.vertex_component[T.face_vertices(f)[0]];
        area[c] += face_area(T, f);
        ++own[c];
        ++chi[c];
    }
    for (VertexId v : T.vertices()) ++chi[comps.vertex_component[v]];
    for (EdgeId e : T.edges()) --chi[comps.vertex_component[T.from(TriMesh::halfedge(e, 0))]];
    for (HalfedgeId h : boundary_loops(T)) ++loops[comps.vertex_component[T.from(h)]];
    return {std::move(area), std::move(own), std::move(chi), std::move(loops)};
}

ComponentTargets shares_of(const ComponentMeasures& m, std::size_t faces) {
    const auto& [area, own, chi, loops] = m;
    const std::size_t n = area.size();
    ComponentTargets out;
    out.faces.assign(n, 0);
    if (n == 1) {
        out.faces[0] = faces;
        return out;
    }
    double total = 0;
    for (double a : area) total += a;
    // Shares in steps (2 faces closed, 1 with boundary); the remaining steps by largest remainder,
    // ties to the lower component, in rounds until the request is met.
    std::vector<double> remainder(n);
    std::size_t given = 0;
    for (std::size_t c = 0; c < n; ++c) {
        const double step = loops[c] ? 1.0 : 2.0, share = static_cast<double>(faces) * area[c] / total;
        out.faces[c] = static_cast<std::size_t>(std::floor(share / step)) * static_cast<std::size_t>(step);
        remainder[c] = share - static_cast<double>(out.faces[c]);
        given += out.faces[c];
    }
    std::vector<std::size_t> order(n);
    for (std::size_t c = 0; c < n; ++c) order[c] = c;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return remainder[a] > remainder[b]; });
    const bool any_boundary = std::any_of(loops.begin(), loops.end(), [](long b) { return b > 0; });
    if (!any_boundary && faces % 2 != 0)
        throw InvalidInput("--faces " + std::to_string(faces) +
                           " is odd: closed triangulations have an even number of faces");
    while (given < faces) {
        for (std::size_t c : order) {
            const std::size_t step = loops[c] ? 1 : 2;
            if (given + step > faces) continue;
            out.faces[c] += step;
            given += step;
            if (given == faces) break;
        }
    }
    for (std::size_t c = 0; c < n; ++c) {
        const long g = (2 - loops[c] - chi[c]) / 2;
        const std::size_t least =
            loops[c] ? static_cast<std::size_t>(std::max(1L, 5 * loops[c] + 4 * g - 4)) : min_closed_faces(g);
        const std::size_t want = std::min(own[c], std::max(out.faces[c], least));
        if (want > out.faces[c]) out.raised += want - out.faces[c];
        out.faces[c] = want;
    }
    return out;
}

}  // namespace

ComponentTargets component_targets(const TriMesh& T, std::size_t faces) {
    if (faces == 0 || faces > T.n_faces())
        throw InvalidInput("--faces " + std::to_string(faces) + " must be between 1 and the mesh's " +
                           std::to_string(T.n_faces()));
    return shares_of(measure_components(T), faces);
}

namespace {

// The targets per component, after the range checks of decimate.
std::vector<std::size_t> targets_of(const TriMesh& T, const Components& comps, std::size_t target) {
    if (T.is_closed() && comps.count == 1) {
        const long g = genus(T, comps);
        if (target % 2 != 0)
            throw InvalidInput("--faces " + std::to_string(target) +
                               " is odd: a closed triangulation has an even number of faces");
        if (target > T.n_faces())
            throw InvalidInput("--faces " + std::to_string(target) + " is more than the mesh has (" +
                               std::to_string(T.n_faces()) + ")");
        if (target < min_closed_faces(g))
            throw InvalidInput("--faces " + std::to_string(target) + " is fewer than a closed surface of genus " +
                               std::to_string(g) + " needs (at least " + std::to_string(min_closed_faces(g)) + ")");
        return {target};
    }
    return component_targets(T, target).faces;
}

// The least request from `from` faces on whose shares (targets_of) every component reaches, 0 when
// none is: each share at least the faces `reached` the component has where decimation stopped.
// Theorem: a component's collapses are chosen and checked within it alone (its costs, its
// validity rules, its volume), so decimating it to any count between its own faces and where it
// stopped passes that count (closed: in steps of 2; with boundary the share may be missed by
// one face, as always). The shares of the request itself differ from those of the first one
// with several components, so the count reached, asked for again, may stop once more. Within
// one regime of decimate only (with or without the pass over the cells, whose quotas are per
// component too); the caller names no request of the other.
std::size_t reachable_request(const TriMesh& T, const std::vector<std::size_t>& reached, std::size_t from) {
    if (reached.size() == 1) return from;  // one component: its share is the request
    const ComponentMeasures measures = measure_components(T);
    for (std::size_t faces = from; faces <= T.n_faces(); ++faces) {
        std::vector<std::size_t> shares;
        try {
            shares = shares_of(measures, faces).faces;
        } catch (const InvalidInput&) {
            continue;  // an odd count of closed surfaces
        }
        bool all = true;
        for (std::size_t c = 0; all && c < shares.size(); ++c) all = shares[c] >= reached[c];
        if (all) return faces;
    }
    return 0;
}

// The corners of T's boundary: vertices where it turns by more than `degrees`, in T's numbering.
std::vector<VertexId> boundary_corners(const TriMesh& T, double degrees) {
    const double cos_turn = std::cos(degrees * M_PI / 180.0);
    std::vector<VertexId> corners;
    for (HalfedgeId g : T.halfedges()) {
        if (!T.is_boundary(g)) continue;
        const HalfedgeId n = T.next(g);  // the loop goes on at to(g)
        const Vec3 in = T.position(T.to(g)) - T.position(T.from(g)), out = T.position(T.to(n)) - T.position(T.from(n));
        if (in.dot(out) < cos_turn * in.norm() * out.norm()) corners.push_back(T.to(g));
    }
    return corners;
}

// The identity decimation of T̂ (no collapse yet).
Domain identity(const TriMesh& mesh) {
    Domain d{mesh, {}, {}};
    for (VertexId v : mesh.vertices()) d.t_vertex.push_back(v);
    return d;
}

// options with T's boundary corners added to the vertices kept.
DecimateOptions with_corners(const TriMesh& T, const DecimateOptions& options) {
    DecimateOptions o = options;
    for (VertexId v : boundary_corners(T, options.corner_angle_deg)) o.keep.push_back(v);
    return o;
}

// decimate, with or without the pass over the cells.
Domain decimate_from_t(const TriMesh& T, const DecimateOptions& options, bool by_cells) {
    // T's components, found once (three searches of T were 6 % of §2 at 10⁶ faces).
    const Components comps = connected_components(T);
    std::vector<std::size_t> targets = targets_of(T, comps, options.target_faces);
    if (T.is_closed())
        return Decimator(T, identity(T), comps, T, vertex_quadrics(T, T.n_faces()), options, T.n_vertices(),
                         std::move(targets))
            .run(by_cells);
    const Coned C = add_cones(T);
    const DecimateOptions o = with_corners(T, options);
    Domain closed = Decimator(T, identity(C.mesh), connected_components(C.mesh), C.mesh,
                              vertex_quadrics(C.mesh, C.real_faces), o, C.real_vertices, std::move(targets))
                        .run(by_cells);
    return open_domain(std::move(closed), C.real_vertices);
}

}  // namespace

Domain decimate(const TriMesh& T, const DecimateOptions& options) {
    return decimate_from_t(T, options, cells_first(T, options.target_faces, options));
}

Domain decimate_again(const TriMesh& T, const Domain& previous, const DecimateOptions& options) {
    // The pass over the cells reads no history: afresh, in previous's regime. Its collapses up to
    // the first that removes a vertex kept now are previous's (the same steps from the same state).
    if (previous.by_cells) return decimate_from_t(T, options, true);
    std::vector<std::size_t> targets = targets_of(T, connected_components(T), options.target_faces);
    const Coned C = add_cones(T);
    const DecimateOptions o = T.is_closed() ? options : with_corners(T, options);
    const Domain prev = close_domain(previous, T);
    // The collapses of `previous` before its first that removes a vertex kept now, and leaving at
    // least the target's faces, are the ones a new decimation makes first.
    std::vector<std::uint8_t> kept(C.mesh.n_vertices(), 0);
    for (VertexId v : o.keep) kept[v.idx()] = 1;
    std::size_t reuse = 0;
    for (std::size_t faces = T.n_faces(); reuse < prev.history.size(); ++reuse) {
        const Collapse& c = prev.history[reuse];
        const std::size_t removed = c.left.idx() >= C.real_vertices || c.right.idx() >= C.real_vertices ? 1 : 2;
        if (kept[c.removed.idx()] || faces < options.target_faces + removed) break;
        faces -= removed;
    }
    const Domain start = undo_collapses(prev, C.mesh, prev.history.size() - reuse);
    std::vector<Quadric> merged = vertex_quadrics(C.mesh, C.real_faces);  // summed in the order decimate summed them
    for (std::size_t i = 0; i < reuse; ++i) merged[prev.history[i].kept.idx()] += merged[prev.history[i].removed.idx()];
    std::vector<Quadric> quadrics;
    for (VertexId x : start.t_vertex) quadrics.push_back(merged[x.idx()]);
    Domain d = Decimator(T, start, connected_components(start.mesh), C.mesh, std::move(quadrics), o, C.real_vertices,
                         std::move(targets))
                   .run(false);
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
    return T.is_closed() ? d : open_domain(std::move(d), C.real_vertices);
}

}  // namespace fhr::domain
