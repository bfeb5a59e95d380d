// FHR §5 — Hausdorff distance between triangle meshes, bracketed (see hausdorff.hpp).
#include "wavelet/hausdorff.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fhr::wavelet {
namespace {

// Squared distance from p to the box [lo, hi] (0 inside).
double box_distance2(const Vec3& p, const Vec3& lo, const Vec3& hi) {
    double d2 = 0;
    for (int i = 0; i < 3; ++i) {
        const double d = p[i] < lo[i] ? lo[i] - p[i] : p[i] > hi[i] ? p[i] - hi[i] : 0.0;
        d2 += d * d;
    }
    return d2;
}

constexpr std::uint32_t leaf_size = 4;

}  // namespace

TriangleTree::TriangleTree(std::span<const Vec3> positions, std::span<const Triangle> triangles)
    : positions_(positions.begin(), positions.end()), triangles_(triangles.begin(), triangles.end()) {
    order_.resize(triangles_.size());
    std::vector<Vec3> centroid(triangles_.size());
    for (std::uint32_t t = 0; t < triangles_.size(); ++t) {
        order_[t] = t;
        const Triangle& f = triangles_[t];
        centroid[t] = (positions_[f[0]] + positions_[f[1]] + positions_[f[2]]) / 3.0;
    }
    nodes_.reserve(2 * triangles_.size() / leaf_size + 2);
    if (!triangles_.empty()) build(0, static_cast<std::uint32_t>(triangles_.size()), centroid);
}

std::uint32_t TriangleTree::build(std::uint32_t first, std::uint32_t count, std::vector<Vec3>& centroid) {
    const auto id = static_cast<std::uint32_t>(nodes_.size());
    nodes_.push_back(Node{});
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (std::uint32_t i = first; i < first + count; ++i)
        for (std::uint32_t v : triangles_[order_[i]]) {
            lo = lo.cwiseMin(positions_[v]);
            hi = hi.cwiseMax(positions_[v]);
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
    std::nth_element(order_.begin() + first, order_.begin() + first + half, order_.begin() + first + count,
                     [&](std::uint32_t x, std::uint32_t y) {
                         return centroid[x][axis] < centroid[y][axis] || (centroid[x][axis] == centroid[y][axis] && x < y);
                     });
    const std::uint32_t left = build(first, half, centroid);
    const std::uint32_t right = build(first + half, count - half, centroid);
    nodes_[id].first = first;
    nodes_[id].count = 0;
    nodes_[id].left = left;
    nodes_[id].right = right;
    return id;
}

TriangleTree::Hit TriangleTree::closest(const Vec3& p, std::uint32_t hint) const {
    auto at = [&](std::uint32_t t) {
        const Triangle& f = triangles_[t];
        return closest_point_on_triangle(p, positions_[f[0]], positions_[f[1]], positions_[f[2]]);
    };
    Hit best{0, hint < triangles_.size() ? hint : 0, Vec3::Zero()};
    best.point = at(best.triangle);
    double best2 = (best.point - p).squaredNorm();
    // Best-first descent with an explicit stack: the nearer child is visited first, a box no
    // nearer than the best so far is skipped.
    std::uint32_t stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& n = nodes_[stack[--top]];
        if (box_distance2(p, n.lo, n.hi) >= best2) continue;
        if (n.count > 0) {
            for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
                const Vec3 q = at(order_[i]);
                const double d2 = (q - p).squaredNorm();
                if (d2 < best2) best2 = d2, best.point = q, best.triangle = order_[i];
            }
            continue;
        }
        const double dl = box_distance2(p, nodes_[n.left].lo, nodes_[n.left].hi);
        const double dr = box_distance2(p, nodes_[n.right].lo, nodes_[n.right].hi);
        // Push the farther child first so that the nearer one is popped next.
        if (dl <= dr) {
            stack[top++] = n.right;
            stack[top++] = n.left;
        } else {
            stack[top++] = n.left;
            stack[top++] = n.right;
        }
    }
    best.distance = std::sqrt(best2);
    return best;
}

double TriangleTree::distance_to(const Vec3& p, std::uint32_t t) const {
    const Triangle& f = triangles_[t];
    return (closest_point_on_triangle(p, positions_[f[0]], positions_[f[1]], positions_[f[2]]) - p).norm();
}

DirectedHausdorff directed_hausdorff(std::span<const Vec3> a_positions, std::span<const Triangle> a_triangles,
                                     const TriangleTree& B, const HausdorffOptions& options) {
    DirectedHausdorff h;
    std::uint32_t hint = 0;
    auto query = [&](const Vec3& p) {
        const TriangleTree::Hit hit = B.closest(p, hint);
        hint = hit.triangle;
        ++h.samples;
        if (hit.distance > h.lower) h.lower = hit.distance, h.farthest = p;
        return hit;
    };
    // The vertices first: they give the search a good lower bound to prune with.
    std::vector<TriangleTree::Hit> at_vertex(a_positions.size(), TriangleTree::Hit{0, 0, Vec3::Zero()});
    std::vector<char> used(a_positions.size(), 0);
    for (const Triangle& t : a_triangles)
        for (std::uint32_t v : t) used[v] = 1;
    for (std::size_t v = 0; v < a_positions.size(); ++v)
        if (used[v]) at_vertex[v] = query(a_positions[v]);

    struct Piece {
        Vec3 x[3];
        double d[3];            // d(x_k, B)
        std::uint32_t near[3];  // the triangle of B closest to x_k
        unsigned depth;
    };
    const double root3 = std::sqrt(3.0);
    auto bound = [&](const Piece& q, double ell) {
        double b = std::max({q.d[0], q.d[1], q.d[2]}) + ell / root3;  // Lipschitz
        for (std::uint32_t t : q.near)                                  // convexity
            b = std::min(b, std::max({B.distance_to(q.x[0], t), B.distance_to(q.x[1], t), B.distance_to(q.x[2], t)}));
        return b;
    };
    // The triangles with the farthest corner first: they raise lower soonest.
    std::vector<std::uint32_t> order(a_triangles.size());
    std::vector<double> corner_max(a_triangles.size());
    for (std::uint32_t i = 0; i < order.size(); ++i) {
        const Triangle& t = a_triangles[i];
        order[i] = i;
        corner_max[i] = std::max({at_vertex[t[0]].distance, at_vertex[t[1]].distance, at_vertex[t[2]].distance});
    }
    std::sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) {
        return corner_max[x] > corner_max[y] || (corner_max[x] == corner_max[y] && x < y);
    });
    std::vector<Piece> stack;
    for (std::uint32_t i : order) {
        const Triangle& t = a_triangles[i];
        Piece root{};
        for (int k = 0; k < 3; ++k) {
            root.x[k] = a_positions[t[k]];
            root.d[k] = at_vertex[t[k]].distance;
            root.near[k] = at_vertex[t[k]].triangle;
        }
        stack.push_back(root);
        while (!stack.empty()) {
            const Piece q = stack.back();
            stack.pop_back();
            const double ell = std::max({(q.x[1] - q.x[0]).norm(), (q.x[2] - q.x[1]).norm(), (q.x[0] - q.x[2]).norm()});
            const double b = bound(q, ell);
            if (b <= h.lower) continue;
            if (b - std::max({q.d[0], q.d[1], q.d[2]}) <= options.resolution || q.depth >= options.max_depth) {
                h.upper = std::max(h.upper, b);
                continue;
            }
            // 1-to-4 split; m_k is the midpoint of the side opposite corner k.
            Piece mid{};
            for (int k = 0; k < 3; ++k) {
                mid.x[k] = 0.5 * (q.x[(k + 1) % 3] + q.x[(k + 2) % 3]);
                const TriangleTree::Hit hit = query(mid.x[k]);
                mid.d[k] = hit.distance;
                mid.near[k] = hit.triangle;
            }
            mid.depth = q.depth + 1;
            for (int k = 0; k < 3; ++k) {  // the corner piece at x_k: x_k, m_{k+2}, m_{k+1}
                Piece c = mid;
                const int a = (k + 2) % 3, e = (k + 1) % 3;
                c.x[0] = q.x[k], c.d[0] = q.d[k], c.near[0] = q.near[k];
                c.x[1] = mid.x[a], c.d[1] = mid.d[a], c.near[1] = mid.near[a];
                c.x[2] = mid.x[e], c.d[2] = mid.d[e], c.near[2] = mid.near[e];
                stack.push_back(c);
            }
            stack.push_back(mid);
        }
    }
    h.upper = std::max(h.upper, h.lower);
    return h;
}

Hausdorff hausdorff(std::span<const Vec3> a_positions, std::span<const Triangle> a_triangles,
                    std::span<const Vec3> b_positions, std::span<const Triangle> b_triangles, const HausdorffOptions& options) {
    HausdorffOptions o = options;
    if (o.resolution <= 0) {
        Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
        for (const auto* set : {&a_positions, &b_positions})
            for (const Vec3& p : *set) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
        o.resolution = 1e-4 * (hi - lo).norm();
        // All points equal: any positive δ will do.
        if (!(o.resolution > 0)) o.resolution = 1;
    }
    Hausdorff h;
    h.resolution = o.resolution;
    const TriangleTree A(a_positions, a_triangles), B(b_positions, b_triangles);
    h.a_to_b = directed_hausdorff(a_positions, a_triangles, B, o);
    h.b_to_a = directed_hausdorff(b_positions, b_triangles, A, o);
    return h;
}

double rms_distance(std::span<const Vec3> a, std::span<const Vec3> b) {
    double sum = 0;
    for (std::size_t i = 0; i < a.size(); ++i) sum += (a[i] - b[i]).squaredNorm();
    return std::sqrt(sum / static_cast<double>(a.size()));
}

}  // namespace fhr::wavelet
