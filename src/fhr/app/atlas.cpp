// Beyond the paper — textured.obj's atlas (see atlas.hpp for the pseudocode).
#include <fhr/app/atlas.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace fhr::app {
namespace {

using io::Vec2;
using Tri = std::array<Vec2, 3>;

// T_i laid flat: its longest side from (0, 0) along u, its apex above; corners in face order,
// `base` the corner where the longest side starts.
Tri laid_flat(const exchange::ParamFile& file, std::size_t d, int& base) {
    const auto& t = file.domain_faces[d];
    int k = 0;
    for (int e = 1; e < 3; ++e)
        if ((file.domain_vertices[t[(e + 1) % 3]] - file.domain_vertices[t[e]]).squaredNorm() >
            (file.domain_vertices[t[(k + 1) % 3]] - file.domain_vertices[t[k]]).squaredNorm())
            k = e;
    const Vec3 &a = file.domain_vertices[t[k]], &b = file.domain_vertices[t[(k + 1) % 3]],
               &c = file.domain_vertices[t[(k + 2) % 3]];
    const double ab = (b - a).norm();
    const double x = (c - a).dot(b - a) / ab, y = (b - a).cross(c - a).norm() / ab;
    Tri flat;
    flat[k] = Vec2(0, 0);
    flat[(k + 1) % 3] = Vec2(ab, 0);
    flat[(k + 2) % 3] = Vec2(std::clamp(x, 0.0, ab), y);  // over the base (x is there up to rounding)
    base = k;
    return flat;
}

// Each patch's area on the surface (its faces of T′ in 3D).
std::vector<double> surface_areas(const exchange::ParamFile& file) {
    std::vector<double> area(file.domain_faces.size(), 0.0);
    for (const exchange::ParamFace& f : file.surface_faces) {
        const Vec3 &a = file.surface_vertices[f.v[0]], &b = file.surface_vertices[f.v[1]],
                   &c = file.surface_vertices[f.v[2]];
        area[f.patch] += 0.5 * (b - a).cross(c - a).norm();
    }
    return area;
}

double area_of(const Tri& t) {
    return 0.5 * std::abs((t[1] - t[0]).x() * (t[2] - t[0]).y() - (t[1] - t[0]).y() * (t[2] - t[0]).x());
}

// The triangle grown about its incentre until each side has moved out by r (a similar triangle).
Tri grown(const Tri& t, double r) {
    const double a = (t[1] - t[2]).norm(), b = (t[2] - t[0]).norm(), c = (t[0] - t[1]).norm();
    const Vec2 incentre = (a * t[0] + b * t[1] + c * t[2]) / (a + b + c);
    const double inradius = 2 * area_of(t) / (a + b + c);
    const double k = (inradius + r) / inradius;
    Tri g;
    for (int i = 0; i < 3; ++i) g[i] = incentre + k * (t[i] - incentre);
    return g;
}

// The horizontal extent of triangle t at height y, y clamped into t's own heights.
std::pair<double, double> span_at(const Tri& t, double y) {
    const double lo_y = std::min({t[0].y(), t[1].y(), t[2].y()}), hi_y = std::max({t[0].y(), t[1].y(), t[2].y()});
    y = std::clamp(y, lo_y, hi_y);
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int i = 0; i < 3; ++i) {
        const Vec2 &a = t[i], &b = t[(i + 1) % 3];
        if (y < std::min(a.y(), b.y()) || y > std::max(a.y(), b.y())) continue;
        const double x = a.y() == b.y() ? a.x() : a.x() + (y - a.y()) / (b.y() - a.y()) * (b.x() - a.x());
        lo = std::min({lo, x, a.y() == b.y() ? b.x() : x});
        hi = std::max({hi, x, a.y() == b.y() ? b.x() : x});
    }
    return {lo, hi};
}

// The least shift along u that puts p right of q at every height they share (touching allowed):
// both sides are linear between the corners' heights, so the corners' heights decide it.
double shift_past(const Tri& q, const Tri& p) {
    const double lo = std::max(std::min({q[0].y(), q[1].y(), q[2].y()}), std::min({p[0].y(), p[1].y(), p[2].y()}));
    const double hi = std::min(std::max({q[0].y(), q[1].y(), q[2].y()}), std::max({p[0].y(), p[1].y(), p[2].y()}));
    if (lo > hi) return -std::numeric_limits<double>::infinity();
    double shift = -std::numeric_limits<double>::infinity();
    auto at = [&](double y) { shift = std::max(shift, span_at(q, y).second - span_at(p, y).first); };
    at(lo);
    at(hi);
    for (const Tri* t : {&q, &p})
        for (const Vec2& v : *t)
            if (v.y() > lo && v.y() < hi) at(v.y());
    return shift;
}

// A rigid motion of the plane that keeps orientation: x -> R(angle)·x + shift, or that followed by
// a turn by 180° within a shelf (never a mirror: textured.obj's charts keep the faces' orientation).
struct Motion {
    double c = 1, s = 0;  // cos and sin of the rotation
    Vec2 shift = Vec2::Zero();
    Vec2 operator()(const Vec2& p) const { return Vec2(c * p.x() - s * p.y(), s * p.x() + c * p.y()) + shift; }
};

// Chart t turned so that its side from corner k to k + 1 lies along u with the chart above it,
// moved so that its leftmost point is at u = 0: the motion, and the turned chart's width and height.
struct Standing {
    Motion motion;
    double width = 0, height = 0;
};

Standing standing(const Tri& t, int k) {
    const Vec2 side = t[(k + 1) % 3] - t[k];
    const double length = side.norm();
    Standing out;
    out.motion.c = side.x() / length;
    out.motion.s = -side.y() / length;
    out.motion.shift = -Motion{out.motion.c, out.motion.s}(t[k]);
    double lo = 0, hi = 0;
    for (const Vec2& v : t) {
        const Vec2 w = out.motion(v);
        lo = std::min(lo, w.x());
        hi = std::max(hi, w.x());
        out.height = std::max(out.height, w.y());
    }
    out.motion.shift.x() -= lo;
    out.width = hi - lo;
    return out;
}

// Where one chart goes: stood on one of its sides, turned by 180° within its shelf or not, moved.
struct Placement {
    Standing stand;
    bool turned = false;
    double shelf_height = 0;
    Vec2 offset = Vec2::Zero();
    Vec2 place(const Vec2& p) const {
        const Vec2 q = stand.motion(p);
        return offset + (turned ? Vec2(stand.width - q.x(), shelf_height - q.y()) : q);
    }
};

struct Layout {
    std::vector<Placement> at;
    double extent = 0;  // the side of the square [0, extent]² that holds it
};

// The shelves at width `width`, the grown charts in `order` (tallest first). A shelf's first chart
// stands on its longest side and sets the shelf's height; every other is stood on any side that
// keeps it within that height, upright or turned, slid left until it touches the charts already
// there, and placed the way that ends leftmost.
Layout shelves(const std::vector<Tri>& grown_charts, const std::vector<std::size_t>& order, double width) {
    Layout out;
    out.at.resize(grown_charts.size());
    std::vector<Tri> shelf;
    std::vector<double> reach;  // per chart of the shelf: its rightmost u
    double floor = 0, height = 0, used = 0;
    for (std::size_t i : order) {
        const Tri& g = grown_charts[i];
        const std::array<Standing, 3> ways{standing(g, 0), standing(g, 1), standing(g, 2)};
        const Standing& lowest = *std::min_element(
            ways.begin(), ways.end(), [](const Standing& a, const Standing& b) { return a.height < b.height; });
        auto best_in_shelf = [&](Placement& best, Tri& best_moved) {
            double best_end = std::numeric_limits<double>::infinity();
            for (const Standing& st : ways) {
                if (st.height > height && &st != &lowest) continue;
                for (bool turned : {false, true}) {
                    Placement p{st, turned, height, Vec2(0, floor)};
                    Tri moved;
                    for (int k = 0; k < 3; ++k) moved[k] = p.place(g[k]);
                    double shift = 0;
                    for (std::size_t j = shelf.size(); j-- > 0;)  // a chart left of the shift cannot push
                        if (reach[j] > shift) shift = std::max(shift, shift_past(shelf[j], moved));
                    if (shift + st.width < best_end) {
                        best_end = shift + st.width;
                        p.offset.x() += shift;
                        for (Vec2& v : moved) v.x() += shift;
                        best = p;
                        best_moved = moved;
                    }
                }
            }
            return best_end;
        };
        Placement p;
        Tri moved{Vec2::Zero(), Vec2::Zero(), Vec2::Zero()};
        if (shelf.empty() || best_in_shelf(p, moved) > width) {  // a new shelf, this chart its tallest
            if (!shelf.empty()) floor += height;
            shelf.clear();
            reach.clear();
            height = lowest.height;
            p = Placement{lowest, false, height, Vec2(0, floor)};
            for (int k = 0; k < 3; ++k) moved[k] = p.place(g[k]);
        }
        shelf.push_back(moved);
        reach.push_back(p.offset.x() + p.stand.width);
        out.at[i] = p;
        used = std::max(used, p.offset.x() + p.stand.width);
    }
    out.extent = std::max(used, floor + height);
    return out;
}

}  // namespace

ChartAtlas::ChartAtlas(const exchange::ParamFile& file, const AtlasOptions& options) : file_(file) {
    const std::size_t m = file.domain_faces.size();
    // Each chart T_i at its patch's own scale: equal texel density.
    const std::vector<double> surface = surface_areas(file);
    std::vector<Tri> flat(m);
    std::vector<double> lowest(m);  // the chart's height stood on its longest side
    for (std::size_t d = 0; d < m; ++d) {
        int base = 0;
        flat[d] = laid_flat(file, d, base);
        const double s = std::sqrt(surface[d] / area_of(flat[d]));
        for (Vec2& v : flat[d]) v *= s;
        lowest[d] = flat[d][(base + 2) % 3].y();
    }
    std::vector<std::size_t> order(m);
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return lowest[i] > lowest[j]; });
    const double wanted = options.gutter_texels / options.texture_size;  // the gutter in [0, 1]² units
    double r = 0;
    Layout best;
    std::vector<Tri> grown_charts(m);
    for (int round = 0;; ++round) {
        double area = 0, widest = 0;
        for (std::size_t d = 0; d < m; ++d) {
            grown_charts[d] = grown(flat[d], r);
            area += area_of(grown_charts[d]);
            for (int k = 0; k < 3; ++k)
                widest = std::max(widest, (grown_charts[d][(k + 1) % 3] - grown_charts[d][k]).norm());
        }
        best = Layout{};
        for (double fill = 0.5; fill <= 1.0001; fill += 0.02) {
            Layout l = shelves(grown_charts, order, std::max(widest, std::sqrt(area / fill)));
            if (best.at.empty() || l.extent < best.extent) best = std::move(l);
        }
        if (2 * r / best.extent >= wanted || round == 8) break;  // (the extent grows with r: a few rounds)
        r = 1.02 * wanted * best.extent / 2;
    }
    gutter_ = 2 * r / best.extent;
    chart_.resize(m);
    for (std::size_t d = 0; d < m; ++d)
        for (int k = 0; k < 3; ++k) chart_[d][k] = best.at[d].place(flat[d][k]) / best.extent;
}

io::Vec2 ChartAtlas::operator()(std::size_t c) const {
    const exchange::ParamFace& face = file_.surface_faces[c / 3];
    const auto& beta = face.beta[c % 3];
    const auto& t = chart_[face.patch];
    return beta[0] * t[0] + beta[1] * t[1] + beta[2] * t[2];
}

}  // namespace fhr::app
