// FHR §5 — Hausdorff distance between triangle meshes, bracketed (see hausdorff.hpp).
#include <fhr/core/detail/contract.hpp>
#include <fhr/wavelet/hausdorff.hpp>

#include <algorithm>
#include <cmath>
#include <array>
#include <bit>
#include <limits>
#include <unordered_map>

namespace fhr::wavelet {
namespace {

constexpr std::uint32_t leaf_size = 4;

}  // namespace

TriangleTree::TriangleTree(std::span<const Vec3> positions, std::span<const Triangle> triangles)
    : positions_(positions.begin(), positions.end()), triangles_(triangles.begin(), triangles.end()) {
    order_.resize(triangles_.size());
    std::vector<Extent> extent(triangles_.size());
    for (std::uint32_t t = 0; t < triangles_.size(); ++t) {
        order_[t] = t;
        const Vec3 &a = positions_[triangles_[t][0]], &b = positions_[triangles_[t][1]],
                   &c = positions_[triangles_[t][2]];
        extent[t] = {a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c), (a + b + c) / 3.0};
    }
    nodes_.reserve(2 * triangles_.size() / leaf_size + 2);
    std::vector<std::pair<double, std::uint32_t>> keys;
    keys.reserve(triangles_.size());
    if (!triangles_.empty()) build(0, static_cast<std::uint32_t>(triangles_.size()), extent, keys);
    fit_leaves();
    fan_start_.assign(positions_.size() + 1, 0);
    for (const Triangle& f : triangles_)
        for (std::uint32_t v : f) ++fan_start_[v + 1];
    for (std::size_t v = 0; v < positions_.size(); ++v) fan_start_[v + 1] += fan_start_[v];
    fan_.resize(fan_start_.back());
    std::vector<std::uint32_t> next(fan_start_.begin(), fan_start_.end() - 1);
    for (std::uint32_t t = 0; t < triangles_.size(); ++t)
        for (std::uint32_t v : triangles_[t]) fan_[next[v]++] = t;
}

TriangleTree::TriangleTree(TriangleTree other, std::span<const Vec3> positions) : TriangleTree(std::move(other)) {
    FHR_DCHECK(positions.size() == positions_.size());
    std::copy(positions.begin(), positions.end(), positions_.begin());
    fit_leaves();
    // Children come after their parent (build numbers nodes in preorder): from the last node to
    // the first, every box is refitted after its children's.
    for (std::size_t id = nodes_.size(); id-- > 0;) {
        Node& n = nodes_[id];
        if (n.count > 0) {
            n.lo = leaf_[n.first].lo, n.hi = leaf_[n.first].hi;
            for (std::uint32_t i = n.first + 1; i < n.first + n.count; ++i) {
                n.lo = n.lo.cwiseMin(leaf_[i].lo);
                n.hi = n.hi.cwiseMax(leaf_[i].hi);
            }
        } else {
            n.lo = nodes_[n.left].lo.cwiseMin(nodes_[n.right].lo);
            n.hi = nodes_[n.left].hi.cwiseMax(nodes_[n.right].hi);
        }
    }
}

// The leaves' triangles in leaf order, corners and box, where a query reads them in turn.
void TriangleTree::fit_leaves() {
    leaf_.resize(triangles_.size());
    for (std::size_t i = 0; i < order_.size(); ++i) {
        LeafTriangle& t = leaf_[i];
        for (int k = 0; k < 3; ++k) t.corner[k] = positions_[triangles_[order_[i]][k]];
        t.lo = t.corner[0].cwiseMin(t.corner[1]).cwiseMin(t.corner[2]);
        t.hi = t.corner[0].cwiseMax(t.corner[1]).cwiseMax(t.corner[2]);
    }
}

// A node's box is the union of its triangles' boxes (the same bounds as over their corners: min
// and max are exact); its triangles are split at the median centroid along the box's longest
// axis, ties by index. The split runs on packed (coordinate, index) keys (reading each
// comparison's centroids through order_ was most of the build's time).
std::uint32_t TriangleTree::build(std::uint32_t first, std::uint32_t count, const std::vector<Extent>& extent,
                                  std::vector<std::pair<double, std::uint32_t>>& keys) {
    const auto id = static_cast<std::uint32_t>(nodes_.size());
    nodes_.push_back(Node{});
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (std::uint32_t i = first; i < first + count; ++i) {
        lo = lo.cwiseMin(extent[order_[i]].lo);
        hi = hi.cwiseMax(extent[order_[i]].hi);
    }
    nodes_[id].lo = lo;
    nodes_[id].hi = hi;
    if (count <= leaf_size) {
        nodes_[id].first = first;
        nodes_[id].count = count;
        return id;
    }
    int axis = 0;
    (hi - lo).maxCoeff(&axis);
    const std::uint32_t half = count / 2;
    keys.clear();
    for (std::uint32_t i = first; i < first + count; ++i)
        keys.emplace_back(extent[order_[i]].centroid[axis], order_[i]);
    std::nth_element(keys.begin(), keys.begin() + half, keys.end());
    for (std::uint32_t i = 0; i < count; ++i) order_[first + i] = keys[i].second;
    const std::uint32_t left = build(first, half, extent, keys);
    const std::uint32_t right = build(first + half, count - half, extent, keys);
    nodes_[id].first = first;
    nodes_[id].count = 0;
    nodes_[id].left = left;
    nodes_[id].right = right;
    return id;
}

TriangleTree::Hit TriangleTree::closest(const Vec3& p, std::uint32_t hint) const {
    FHR_DCHECK(!triangles_.empty());
    auto at = [&](std::uint32_t t) {
        const Triangle& f = triangles_[t];
        return closest_point_on_triangle(p, positions_[f[0]], positions_[f[1]], positions_[f[2]]);
    };
    Hit best{0, hint < triangles_.size() ? hint : 0, Vec3::Zero()};
    best.point = at(best.triangle);
    double best2 = (best.point - p).squaredNorm();
    // Best-first descent with an explicit stack of (node, its box's squared distance): the nearer
    // child is visited first, a box no nearer than the best so far is skipped.
    struct Entry {
        std::uint32_t node;
        double box2;
    };
    Entry stack[128];
    int top = 0;
    stack[top++] = {0, box_distance2(p, nodes_[0].lo, nodes_[0].hi)};
    while (top > 0) {
        const Entry e = stack[--top];
        if (e.box2 >= best2) continue;
        const Node& n = nodes_[e.node];
        if (n.count > 0) {
            for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
                const LeafTriangle& t = leaf_[i];
                if (box_distance2(p, t.lo, t.hi) >= best2) continue;
                const Vec3 q = closest_point_on_triangle(p, t.corner[0], t.corner[1], t.corner[2]);
                const double d2 = (q - p).squaredNorm();
                if (d2 < best2) best2 = d2, best.point = q, best.triangle = order_[i];
            }
            continue;
        }
        const Entry l{n.left, box_distance2(p, nodes_[n.left].lo, nodes_[n.left].hi)};
        const Entry r{n.right, box_distance2(p, nodes_[n.right].lo, nodes_[n.right].hi)};
        // Push the farther child first so that the nearer one is popped next.
        const bool left_first = l.box2 <= r.box2;
        const Entry& far = left_first ? r : l;
        const Entry& near = left_first ? l : r;
        if (far.box2 < best2) stack[top++] = far;
        if (near.box2 < best2) stack[top++] = near;
    }
    best.distance = std::sqrt(best2);
    return best;
}

double TriangleTree::distance_to(const Vec3& p, std::uint32_t t) const {
    const Triangle& f = triangles_[t];
    return (closest_point_on_triangle(p, positions_[f[0]], positions_[f[1]], positions_[f[2]]) - p).norm();
}

double TriangleTree::pair_bound(const Vec3 (&x)[3], std::uint32_t t1, std::uint32_t t2) const {
    constexpr double none = std::numeric_limits<double>::infinity();
    const Triangle& f = triangles_[t1];
    const Triangle& g = triangles_[t2];
    // τ₁ = (a, b, c) with ab the edge shared with τ₂; d is τ₂'s other corner.
    int shared = 0, c_at = -1, d_at = -1;
    for (int i = 0; i < 3; ++i) {
        const bool in_g = f[i] == g[0] || f[i] == g[1] || f[i] == g[2];
        const bool in_f = g[i] == f[0] || g[i] == f[1] || g[i] == f[2];
        shared += in_g;
        if (!in_g) c_at = i;
        if (!in_f) d_at = i;
    }
    if (shared != 2 || c_at < 0 || d_at < 0) return none;
    const Vec3& a = positions_[f[(c_at + 1) % 3]];
    const Vec3& b = positions_[f[(c_at + 2) % 3]];
    const Vec3& c = positions_[f[c_at]];
    const Vec3& d = positions_[g[d_at]];
    const Vec3 normal = (b - a).cross(c - a);
    const double twice_area = normal.norm();
    if (!(twice_area > 0)) return none;
    const Vec3 n = normal / twice_area;
    const double lift = n.dot(d - a);
    const Vec3 d_flat = d - lift * n;
    // Q = a d' b c is convex when its diagonals cross: d' and c on opposite sides of ab, and a and
    // b on opposite sides of cd'. With orient(u, v, w) = n·((v − u) × (w − u)) in τ₁'s plane, where
    // orient(a, b, c) > 0, the first is side_d < 0, and then the second can only be
    // side_a < 0 < side_b: if the diagonals meet at
    // p = a + t(b − a) = c + s(d' − c), t, s ∈ (0, 1), then s·side_a = orient(c, p, a) =
    // −t·orient(a, b, c) < 0 and s·side_b = orient(c, p, b) = (1 − t)·orient(a, b, c) > 0. Each
    // signed area must clear a margin far above its rounding error.
    const double margin = 1e-9 * (b - a).squaredNorm() + 1e-9 * (d - c).squaredNorm();
    const double side_d = n.dot((b - a).cross(d_flat - a));
    const double side_a = n.dot((d_flat - c).cross(a - c)), side_b = n.dot((d_flat - c).cross(b - c));
    if (!(side_d < -margin) || !(side_a < -margin && side_b > margin)) return none;
    // The rounding in d' moves it by a few ulps of |d|: h covers it with the same relative margin.
    const double h = std::abs(lift) + 1e-12 * (d - a).norm();
    double sup = 0;
    for (const Vec3& p : x) {
        const double to_first = (closest_point_on_triangle(p, a, b, c) - p).norm();
        const double to_second = (closest_point_on_triangle(p, b, a, d_flat) - p).norm();
        sup = std::max(sup, std::min(to_first, to_second));
    }
    return sup + h;
}

double TriangleTree::fan_bound(const Vec3 (&x)[3], std::uint32_t v) const {
    constexpr double none = std::numeric_limits<double>::infinity();
    const std::uint32_t first = fan_start_[v], count = fan_start_[v + 1] - first;
    // The link: triangle (v, p, q) in its own orientation gives the link edge p -> q. Around an
    // inner vertex the edges make one closed cycle; around a boundary vertex one open
    // path, walked from the neighbour that no link edge enters.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> link;
    link.reserve(count);
    for (std::uint32_t i = first; i < first + count; ++i) {
        const Triangle& f = triangles_[fan_[i]];
        const int at = f[0] == v ? 0 : f[1] == v ? 1 : 2;
        link.emplace_back(f[(at + 1) % 3], f[(at + 2) % 3]);
    }
    if (link.empty()) return none;
    std::uint32_t start = link[0].first;
    for (const auto& e : link)
        if (std::none_of(link.begin(), link.end(), [&](const auto& g) { return g.second == e.first; })) start = e.first;
    std::vector<std::uint32_t> cycle{start};
    for (std::uint32_t step = 0; step < count; ++step) {
        const std::uint32_t from = cycle.back();
        auto it = std::find_if(link.begin(), link.end(), [&](const auto& e) { return e.first == from; });
        if (it == link.end()) return none;
        cycle.push_back(it->second);
    }
    const bool closed = cycle.back() == cycle.front();
    if (closed) {
        if (count < 3) return none;
        cycle.pop_back();
    }
    for (std::size_t i = 0; i < cycle.size(); ++i)
        for (std::size_t j = i + 1; j < cycle.size(); ++j)
            if (cycle[i] == cycle[j]) return none;                   // not a simple cycle or path: not a disk
    const std::size_t k = cycle.size(), edges = closed ? k : k - 1;  // link edges (i, i + 1 mod k)
    // Flatten into the plane through v normal to the fan's area-weighted normal.
    const Vec3& o = positions_[v];
    Vec3 normal = Vec3::Zero();
    for (std::size_t i = 0; i < edges; ++i) {
        const Vec3 &p = positions_[cycle[i]], &q = positions_[cycle[(i + 1) % k]];
        normal += (p - o).cross(q - o);
    }
    if (!(normal.norm() > 0)) return none;
    const Vec3 n = normal.normalized();
    std::vector<Vec3> w(k);
    double lift = 0, scale = 0;
    for (std::size_t i = 0; i < k; ++i) {
        const Vec3& p = positions_[cycle[i]];
        const double l = n.dot(p - o);
        lift = std::max(lift, std::abs(l));
        scale = std::max(scale, (p - o).norm());
        w[i] = p - l * n;
    }
    const double slack = 1e-12 * scale;  // rounding in the flattening and the measures below
    auto turn = [&](const Vec3& a, const Vec3& b, const Vec3& c) { return n.dot((b - a).cross(c - b)); };
    for (std::size_t i = 0; i < edges; ++i)  // the flat fan's triangles keep their orientation
        if (!(n.dot((w[i] - o).cross(w[(i + 1) % k] - o)) > 1e-9 * (w[i] - o).norm() * (w[(i + 1) % k] - o).norm()))
            return none;
    // The flat fan's outline P: the link cycle around v, or v followed by the link path. When P is
    // convex the fan's positively oriented triangles tile it.
    if (!closed) w.insert(w.begin(), o);
    const std::size_t K = w.size();
    // Corners: the outline points that turn left by more than 1e−9 (sine); a right turn beyond it is reflex.
    std::vector<std::size_t> corners;
    for (std::size_t i = 0; i < K; ++i) {
        const Vec3 &a = w[(i + K - 1) % K], &b = w[i], &c = w[(i + 1) % K];
        const double t = turn(a, b, c), tol = 1e-9 * (b - a).norm() * (c - b).norm();
        if (t < -tol) return none;
        if (t > tol) corners.push_back(i);
    }
    if (corners.size() < 3) return none;
    // Straight points onto their corners' chord (ε), and the corners' polygon convex.
    double eps = 0;
    const std::size_t m = corners.size();
    for (std::size_t j = 0; j < m; ++j) {
        const Vec3 &a = w[corners[j]], &b = w[corners[(j + 1) % m]], &c = w[corners[(j + 2) % m]];
        if (!(turn(a, b, c) > 1e-9 * (b - a).norm() * (c - b).norm())) return none;
        for (std::size_t i = (corners[j] + 1) % K; i != corners[(j + 1) % m]; i = (i + 1) % K)
            eps = std::max(eps, (b - a).cross(w[i] - a).norm() / (b - a).norm());
    }
    // d(·, P) over a fan of P's corners: from v inside a closed fan, from the first corner otherwise.
    const Vec3& apex = closed ? o : w[corners[0]];
    double sup = 0;
    for (const Vec3& p : x) {
        double d = std::numeric_limits<double>::infinity();
        for (std::size_t j = closed ? 0 : 1; j < (closed ? m : m - 1); ++j)
            d = std::min(d, (closest_point_on_triangle(p, apex, w[corners[j]], w[corners[(j + 1) % m]]) - p).norm());
        sup = std::max(sup, d);
    }
    return sup + lift + eps + slack;
}

namespace {

// The search of the file header over a block of A's triangles, with its own lower bound, samples
// and midpoints: blocks are searched independently (in parallel on the executor) and merged, so
// that the result is the same on any number of threads.
class BlockSearch {
public:
    BlockSearch(std::span<const Vec3> a_positions, std::span<const Triangle> a_triangles, const TriangleTree& B,
                const HausdorffOptions& options, std::span<const TriangleTree::Hit> at_vertex)
        : a_positions_(a_positions), a_triangles_(a_triangles), B_(B), options_(options), at_vertex_(at_vertex) {}

    DirectedHausdorff h;  // lower, samples, farthest of this block (upper once finished)

    TriangleTree::Hit query(const Vec3& p) {
        const TriangleTree::Hit hit = B_.closest(p, hint_);
        hint_ = hit.triangle;
        ++h.samples;
        if (hit.distance > h.lower) h.lower = hit.distance, h.farthest = p;
        return hit;
    }

    // Triangles [first, last) of A: the 64 with the farthest corner first, which raise lower
    // soonest; then the others in A's order, where neighbours follow one another and find the
    // tree's nodes in cache (in farthest-first order throughout, the horse's brackets took half as
    // long again, with the same bounds). Writes triangle_upper[i] for each.
    void run(std::uint32_t first, std::uint32_t last, std::span<double> triangle_upper) {
        std::vector<std::pair<double, std::uint32_t>> order;  // (−farthest corner, triangle)
        order.reserve(last - first);
        for (std::uint32_t i = first; i < last; ++i) {
            const Triangle& t = a_triangles_[i];
            order.emplace_back(
                -std::max({at_vertex_[t[0]].distance, at_vertex_[t[1]].distance, at_vertex_[t[2]].distance}), i);
        }
        const std::size_t farthest = std::min<std::size_t>(order.size(), 64);
        std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(farthest), order.end());
        std::sort(order.begin() + static_cast<std::ptrdiff_t>(farthest), order.end(),
                  [](const auto& x, const auto& y) { return x.second < y.second; });
        for (const auto& [_, i] : order) triangle_upper[i] = root(i);
        h.upper = std::max({h.upper, h.lower, dropped_});
    }

private:
    struct Piece {
        Vec3 x[3];
        double d[3];            // d(x_k, B)
        std::uint32_t near[3];  // the triangle of B closest to x_k
        unsigned depth;
    };
    std::span<const Vec3> a_positions_;
    std::span<const Triangle> a_triangles_;
    const TriangleTree& B_;
    const HausdorffOptions& options_;
    std::span<const TriangleTree::Hit> at_vertex_;
    std::uint32_t hint_ = 0;
    double dropped_ = 0;  // the largest bound of a piece done for being ≤ known but above lower then
    // A side's midpoint is shared by the pieces on both sides of it (and a side of A's triangle by
    // two triangles): its distance is evaluated once (0.5·(u + v) is the same double either way).
    using Point = std::array<double, 3>;
    struct PointHash {
        std::size_t operator()(const Point& p) const {
            std::uint64_t h = 0;
            for (double x : p) h = (h ^ std::bit_cast<std::uint64_t>(x)) * 0x9E3779B97F4A7C15ull;
            return h ^ (h >> 29);
        }
    };
    std::unordered_map<Point, std::pair<double, std::uint32_t>, PointHash> midpoints_;
    std::vector<Piece> stack_;

    // A piece whose bound is at most this is done whatever its exact value: either no more than
    // a sample already found, or no more than what the caller knows it will report.
    double settled() const { return std::max(h.lower, options_.known); }

    // The piece's bound is the least of the four below. Each is tried, cheapest first, only while
    // the least so far is not settled (on the horse, the Lipschitz bound alone settles 99.8 % of
    // T's triangles).
    double bound(const Piece& q) const {
        double b = std::max({q.d[0], q.d[1], q.d[2]}) + corner_cover_radius(q.x[0], q.x[1], q.x[2]);  // Lipschitz
        if (b <= settled()) return b;
        for (int j = 0; j < 3; ++j) {  // convexity
            const std::uint32_t t = q.near[j];
            if ((j > 0 && t == q.near[0]) || (j > 1 && t == q.near[1])) continue;  // tried already
            double sup = 0;  // d(x_k, near_k) is d_k: the same computation
            for (int k = 0; k < 3; ++k) sup = std::max(sup, q.near[k] == t ? q.d[k] : B_.distance_to(q.x[k], t));
            b = std::min(b, sup);
        }
        if (b <= settled()) return b;
        for (int i = 0; i < 3; ++i)  // two triangles
            if (const std::uint32_t s = q.near[i], t = q.near[(i + 1) % 3]; s != t)
                b = std::min(b, B_.pair_bound(q.x, s, t));
        if (b <= settled()) return b;
        if (q.near[0] != q.near[1] || q.near[1] != q.near[2])  // a vertex fan: at a vertex common to them all
            for (std::uint32_t v : B_.triangle(q.near[0]))
                if (std::count(B_.triangle(q.near[1]).begin(), B_.triangle(q.near[1]).end(), v) &&
                    std::count(B_.triangle(q.near[2]).begin(), B_.triangle(q.near[2]).end(), v))
                    b = std::min(b, B_.fan_bound(q.x, v));
        return b;
    }
    // Triangle i of A searched; the largest bound of its pieces where the search ended.
    double root(std::uint32_t i) {
        if (!options_.prior.empty() && options_.prior[i] <= settled()) {
            if (options_.prior[i] > h.lower) dropped_ = std::max(dropped_, options_.prior[i]);
            return options_.prior[i];
        }
        double upper = 0;
        const Triangle& t = a_triangles_[i];
        Piece first{};
        for (int k = 0; k < 3; ++k) {
            first.x[k] = a_positions_[t[k]];
            first.d[k] = at_vertex_[t[k]].distance;
            first.near[k] = at_vertex_[t[k]].triangle;
        }
        stack_.push_back(first);
        while (!stack_.empty()) {
            const Piece q = stack_.back();
            stack_.pop_back();
            const double dmax = std::max({q.d[0], q.d[1], q.d[2]});
            double b = bound(q);
            if (q.depth == 0 && !options_.prior.empty()) b = std::min(b, options_.prior[i]);
            if (b <= settled()) {
                if (b > h.lower) dropped_ = std::max(dropped_, b);
                upper = std::max(upper, b);
                continue;
            }
            if (b - dmax <= options_.resolution || q.depth >= options_.max_depth) {
                h.upper = std::max(h.upper, b);
                upper = std::max(upper, b);
                continue;
            }
            // 1-to-4 split; m_k is the midpoint of the side opposite corner k.
            Piece mid{};
            for (int k = 0; k < 3; ++k) {
                mid.x[k] = 0.5 * (q.x[(k + 1) % 3] + q.x[(k + 2) % 3]);
                const auto [at, fresh] = midpoints_.try_emplace(Point{mid.x[k][0], mid.x[k][1], mid.x[k][2]});
                if (fresh) {
                    const TriangleTree::Hit hit = query(mid.x[k]);
                    at->second = {hit.distance, hit.triangle};
                }
                mid.d[k] = at->second.first;
                mid.near[k] = at->second.second;
            }
            mid.depth = q.depth + 1;
            for (int k = 0; k < 3; ++k) {  // the corner piece at x_k: x_k, m_{k+2}, m_{k+1}
                Piece c = mid;
                const int a = (k + 2) % 3, e = (k + 1) % 3;
                c.x[0] = q.x[k], c.d[0] = q.d[k], c.near[0] = q.near[k];
                c.x[1] = mid.x[a], c.d[1] = mid.d[a], c.near[1] = mid.near[a];
                c.x[2] = mid.x[e], c.d[2] = mid.d[e], c.near[2] = mid.near[e];
                stack_.push_back(c);
            }
            stack_.push_back(mid);
        }
        return upper;
    }
};

// The blocks of A's triangles searched apart: a fixed count, whatever the threads, so that the
// bracket is the same on any (the fandisk's f^J → T, 37 ms on one thread, was the
// long pole of §5 on two).
constexpr std::uint32_t search_blocks = 8;

}  // namespace

DirectedHausdorff directed_hausdorff(std::span<const Vec3> a_positions, std::span<const Triangle> a_triangles,
                                     const TriangleTree& B, const HausdorffOptions& options, Executor* executor) {
    // The vertices first: they give the search a good lower bound to prune with. With priors, a
    // vertex's distance is at most the least prior of its triangles: the vertices are queried one
    // by one in decreasing order of that bound until it falls below the largest distance found or
    // below `known` — the others cannot raise max(lower, known), so that is the same as from all
    // vertices, and so is lower (with its first farthest vertex) when it is above known — and
    // then, in blocks, those of the triangles their priors do not settle yet. Without
    // priors, all of them in blocks. Each vertex's distance is the same whatever the block (the
    // hint only speeds the query).
    std::vector<TriangleTree::Hit> at_vertex(a_positions.size(), TriangleTree::Hit{0, 0, Vec3::Zero()});
    enum : char { unused, wanted, queried };
    std::vector<char> state(a_positions.size(), unused);
    for (const Triangle& t : a_triangles)
        for (std::uint32_t v : t) state[v] = wanted;
    DirectedHausdorff h;
    if (!options.prior.empty()) {
        std::vector<double> bound(a_positions.size(), std::numeric_limits<double>::infinity());
        for (std::size_t i = 0; i < a_triangles.size(); ++i)
            for (std::uint32_t v : a_triangles[i]) bound[v] = std::min(bound[v], options.prior[i]);
        std::vector<std::uint32_t> order;
        for (std::uint32_t v = 0; v < state.size(); ++v)
            if (state[v] == wanted) order.push_back(v);
        std::sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) {
            return bound[x] > bound[y] || (bound[x] == bound[y] && x < y);
        });
        BlockSearch first(a_positions, a_triangles, B, options, at_vertex);
        for (std::uint32_t v : order) {
            if (bound[v] < std::max(first.h.lower, options.known)) break;
            at_vertex[v] = first.query(a_positions[v]);
            state[v] = queried;
        }
        h.lower = first.h.lower;
        h.samples = first.h.samples;
        std::uint32_t farthest = static_cast<std::uint32_t>(state.size());  // the lowest index at lower
        for (std::uint32_t v : order)
            if (state[v] == queried && at_vertex[v].distance == h.lower) farthest = std::min(farthest, v);
        if (farthest < state.size()) h.farthest = a_positions[farthest];
        std::replace(state.begin(), state.end(), char{wanted}, char{unused});
        const double settled = std::max(h.lower, options.known);
        for (std::size_t i = 0; i < a_triangles.size(); ++i)
            if (!(options.prior[i] <= settled))
                for (std::uint32_t v : a_triangles[i])
                    if (state[v] == unused) state[v] = wanted;
    }
    std::vector<DirectedHausdorff> parts(search_blocks);
    const auto nv = static_cast<std::uint64_t>(a_positions.size());
    executor_or_default(executor).for_each(search_blocks, 1, [&](std::size_t k) {
        BlockSearch block(a_positions, a_triangles, B, options, at_vertex);
        for (std::size_t v = nv * k / search_blocks; v < nv * (k + 1) / search_blocks; ++v)
            if (state[v] == wanted) at_vertex[v] = block.query(a_positions[v]);
        parts[k] = std::move(block.h);
    });
    for (const DirectedHausdorff& part : parts) {  // in block order: the first farthest vertex
        if (part.lower > h.lower) h.lower = part.lower, h.farthest = part.farthest;
        h.samples += part.samples;
    }
    h.triangle_upper.assign(a_triangles.size(), 0);
    const auto n = static_cast<std::uint64_t>(a_triangles.size());
    executor_or_default(executor).for_each(search_blocks, 1, [&](std::size_t k) {
        BlockSearch block(a_positions, a_triangles, B, options, at_vertex);
        block.h.lower = h.lower;
        block.h.farthest = h.farthest;
        block.run(static_cast<std::uint32_t>(n * k / search_blocks),
                  static_cast<std::uint32_t>(n * (k + 1) / search_blocks), h.triangle_upper);
        parts[k] = std::move(block.h);
    });
    for (const DirectedHausdorff& part : parts) {  // in block order: the first farthest point found
        if (part.lower > h.lower) h.lower = part.lower, h.farthest = part.farthest;
        h.upper = std::max(h.upper, part.upper);
        h.samples += part.samples;
    }
    h.upper = std::max(h.upper, h.lower);
    return h;
}

Hausdorff hausdorff(std::span<const Vec3> a_positions, std::span<const Triangle> a_triangles,
                    std::span<const Vec3> b_positions, std::span<const Triangle> b_triangles,
                    const HausdorffOptions& options, Executor* executor) {
    HausdorffOptions o = options;
    if (o.resolution <= 0) {
        Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
        for (const auto* set : {&a_positions, &b_positions})
            for (const Vec3& p : *set) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
        o.resolution = 1e-4 * (hi - lo).norm();
        // All points equal: any positive δ will do.
        if (!(o.resolution > 0)) o.resolution = 1;
    }
    return hausdorff(a_positions, a_triangles, TriangleTree(a_positions, a_triangles), b_positions, b_triangles,
                     TriangleTree(b_positions, b_triangles), o, executor);
}

Hausdorff hausdorff(std::span<const Vec3> a_positions, std::span<const Triangle> a_triangles, const TriangleTree& A,
                    std::span<const Vec3> b_positions, std::span<const Triangle> b_triangles, const TriangleTree& B,
                    const HausdorffOptions& options, Executor* executor) {
    Hausdorff h;
    h.resolution = options.resolution;
    h.a_to_b = directed_hausdorff(a_positions, a_triangles, B, options, executor);
    HausdorffOptions second = options;
    second.known = std::max(options.known, h.a_to_b.lower);
    second.prior = options.prior_back;
    second.prior_back = {};
    h.b_to_a = directed_hausdorff(b_positions, b_triangles, A, second, executor);
    return h;
}

double rms_distance(std::span<const Vec3> a, std::span<const Vec3> b) {
    FHR_DCHECK(a.size() == b.size() && !a.empty());
    double sum = 0;
    for (std::size_t i = 0; i < a.size(); ++i) sum += (a[i] - b[i]).squaredNorm();
    return std::sqrt(sum / static_cast<double>(a.size()));
}

}  // namespace fhr::wavelet
