// FHR generate — the exact embedding check and guard (beyond the paper); the argument is
// in embedding.hpp. Every sign comes from core/detail/predicates.hpp (exact for all finite doubles), or is an
// exact zero decided without arithmetic (points sharing a coordinate; below).
#include <fhr/generate/embedding.hpp>

#include <algorithm>
#include <cmath>

#include <fhr/core/detail/predicates.hpp>

namespace fhr::generate {
namespace {

using Vec2 = Eigen::Vector2d;

Vec2 drop_axis(const Vec3& p, int axis) { return Vec2(p[(axis + 1) % 3], p[(axis + 2) % 3]); }

// The signs below first look for an exact zero that needs no arithmetic: points with one
// coordinate in common lie in an axis-aligned plane (or line). The generator's meshes start from
// blocks made of such planes, where the floating-point filter of orient3d/orient2d can never
// decide a zero and the exact (GMP) fallback would run for nearly every pair of faces of a facet.

/// orient3d(a, b, c, d); 0 at once when the four points share a coordinate.
int orient(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    for (int k = 0; k < 3; ++k)
        if (a[k] == b[k] && a[k] == c[k] && a[k] == d[k]) return 0;
    return orient3d(a, b, c, d);
}

/// orient2d(a, b, c); 0 at once when the three points share a coordinate.
int orient(const Vec2& a, const Vec2& b, const Vec2& c) {
    for (int k = 0; k < 2; ++k)
        if (a[k] == b[k] && a[k] == c[k]) return 0;
    return orient2d(a, b, c);
}

/// The axis of the largest component of the normal of (p, q, r): dropping it maps the triangle's
/// plane one-to-one onto a coordinate plane. Only used where (p, q, r) is non-degenerate, and any
/// axis whose normal component is non-zero works, so rounding in n cannot give a wrong answer
/// unless every component rounds to zero, which a non-degenerate triangle's largest cannot.
int projection_axis(const Vec3& p, const Vec3& q, const Vec3& r) {
    const Vec3 n = (q - p).cross(r - p);
    int axis = 0;
    for (int k = 1; k < 3; ++k)
        if (std::abs(n[k]) > std::abs(n[axis])) axis = k;
    return axis;
}

/// Closed segments ab and cd of a plane meet.
bool segments_meet(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
    for (int k = 0; k < 2; ++k)  // disjoint extents: apart (exact comparisons, no arithmetic)
        if (std::max(a[k], b[k]) < std::min(c[k], d[k]) || std::max(c[k], d[k]) < std::min(a[k], b[k])) return false;
    const int o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
    // Not on one side of each other's line: they cross, or they are collinear with overlapping
    // extents (checked above).
    return !(o1 * o2 > 0 || o3 * o4 > 0);
}

/// The closed segment ab meets the closed non-degenerate triangle pqr.
bool segment_meets_triangle(const Vec3& a, const Vec3& b, const Vec3& p, const Vec3& q, const Vec3& r) {
    for (int k = 0; k < 3; ++k)  // disjoint bounding boxes: apart (exact comparisons, no arithmetic)
        if (std::max(a[k], b[k]) < std::min({p[k], q[k], r[k]}) || std::min(a[k], b[k]) > std::max({p[k], q[k], r[k]}))
            return false;
    const int oa = orient(p, q, r, a), ob = orient(p, q, r, b);
    if (oa * ob > 0) return false;
    if (oa != 0 || ob != 0) {
        // ab crosses the plane within the segment; the crossing is in the triangle iff the line
        // ab passes on no two strictly different sides of the three edge lines.
        const int s[3] = {orient(a, b, p, q), orient(a, b, q, r), orient(a, b, r, p)};
        const bool positive = s[0] > 0 || s[1] > 0 || s[2] > 0, negative = s[0] < 0 || s[1] < 0 || s[2] < 0;
        return !(positive && negative);
    }
    // Coplanar: in a projection the plane maps one-to-one, an end inside or an edge crossed.
    const int axis = projection_axis(p, q, r);
    const Vec2 a2 = drop_axis(a, axis), b2 = drop_axis(b, axis), p2 = drop_axis(p, axis), q2 = drop_axis(q, axis),
               r2 = drop_axis(r, axis);
    const int o = orient(p2, q2, r2);
    const auto inside = [&](const Vec2& x) {
        return o * orient(p2, q2, x) >= 0 && o * orient(q2, r2, x) >= 0 && o * orient(r2, p2, x) >= 0;
    };
    return inside(a2) || inside(b2) || segments_meet(a2, b2, p2, q2) || segments_meet(a2, b2, q2, r2) ||
           segments_meet(a2, b2, r2, p2);
}

/// The vertex ids a and b have in common: how many, and where each is in a and in b.
int shared_vertices(const TriangleAt& a, const TriangleAt& b, std::array<int, 3>& in_a, std::array<int, 3>& in_b) {
    int n = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (a.v[i] == b.v[j]) {
                in_a[n] = i;
                in_b[n] = j;
                ++n;
            }
    return n;
}

/// A face's cells cover its bounding box; a face with more than this many goes to a list of
/// faces tested against every other (a few long needles must not flood the grid).
constexpr std::int64_t max_cells_per_face = 4096;

struct CellRange {
    std::array<std::int64_t, 3> lo, hi;
    std::int64_t count() const { return (hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1); }
};

CellRange cell_range(const std::array<Vec3, 3>& p, double cell) {
    CellRange r;
    for (int k = 0; k < 3; ++k) {
        const double lo = std::min({p[0][k], p[1][k], p[2][k]}), hi = std::max({p[0][k], p[1][k], p[2][k]});
        r.lo[k] = static_cast<std::int64_t>(std::floor(lo / cell));
        r.hi[k] = static_cast<std::int64_t>(std::floor(hi / cell));
    }
    return r;
}

/// A hash of a cell's coordinates; two cells with one key share a bucket, which costs only time.
std::uint64_t cell_key(std::int64_t i, std::int64_t j, std::int64_t k) {
    std::uint64_t h = static_cast<std::uint64_t>(i) * 0x9E3779B97F4A7C15ull;
    h ^= static_cast<std::uint64_t>(j) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
    h ^= static_cast<std::uint64_t>(k) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
    return h;
}

/// Twice the mean edge length of m (1 for a mesh without faces): the grid's default cell.
double default_cell(const TriMesh& m) {
    double sum = 0;
    std::size_t count = 0;
    for (EdgeId e : m.edges()) {
        if (m.is_deleted(e)) continue;
        const HalfedgeId h = TriMesh::halfedge(e, 0);
        sum += (m.position(m.to(h)) - m.position(m.from(h))).norm();
        ++count;
    }
    return count == 0 || !(sum > 0) ? 1.0 : 2 * sum / static_cast<double>(count);
}

/// The closed bounding boxes of a and b overlap: two triangles whose boxes are disjoint cannot
/// meet (nor share a vertex), so meet_improperly is false for them. Exact comparisons.
bool boxes_overlap(const TriangleAt& a, const TriangleAt& b) {
    for (int k = 0; k < 3; ++k) {
        const double a_lo = std::min({a.p[0][k], a.p[1][k], a.p[2][k]}),
                     a_hi = std::max({a.p[0][k], a.p[1][k], a.p[2][k]});
        const double b_lo = std::min({b.p[0][k], b.p[1][k], b.p[2][k]}),
                     b_hi = std::max({b.p[0][k], b.p[1][k], b.p[2][k]});
        if (a_hi < b_lo || b_hi < a_lo) return false;
    }
    return true;
}

}  // namespace

TriangleAt triangle_at(const TriMesh& m, FaceId f) {
    const auto v = m.face_vertices(f);
    return {v, {m.position(v[0]), m.position(v[1]), m.position(v[2])}};
}

bool is_degenerate(const TriangleAt& t) { return collinear(t.p[0], t.p[1], t.p[2]); }

bool meet_improperly(const TriangleAt& a, const TriangleAt& b) {
    std::array<int, 3> ia{}, ib{};
    const int n = shared_vertices(a, b, ia, ib);
    if (n == 0) {
        for (int k = 0; k < 3; ++k)
            if (segment_meets_triangle(a.p[k], a.p[(k + 1) % 3], b.p[0], b.p[1], b.p[2]) ||
                segment_meets_triangle(b.p[k], b.p[(k + 1) % 3], a.p[0], a.p[1], a.p[2]))
                return true;
        return false;
    }
    if (n == 1) {  // the edges opposite the common vertex
        const int i = ia[0], j = ib[0];
        return segment_meets_triangle(a.p[(i + 1) % 3], a.p[(i + 2) % 3], b.p[0], b.p[1], b.p[2]) ||
               segment_meets_triangle(b.p[(j + 1) % 3], b.p[(j + 2) % 3], a.p[0], a.p[1], a.p[2]);
    }
    if (n == 2) {  // common edge uv: improper iff coplanar with the third corners on one side
        const Vec3 &u = a.p[ia[0]], &v = a.p[ia[1]], &x = a.p[3 - ia[0] - ia[1]], &y = b.p[3 - ib[0] - ib[1]];
        if (orient(u, v, x, y) != 0) return false;
        const int axis = projection_axis(u, v, x);
        const Vec2 u2 = drop_axis(u, axis), v2 = drop_axis(v, axis);
        return orient(u2, v2, drop_axis(x, axis)) * orient(u2, v2, drop_axis(y, axis)) > 0;
    }
    return true;  // the same three vertices twice
}

std::optional<std::array<FaceId, 2>> find_self_intersection(const TriMesh& m) {
    const double cell = default_cell(m);
    std::vector<TriangleAt> tri;
    tri.reserve(m.n_faces());
    for (FaceId f : m.faces()) tri.push_back(triangle_at(m, f));
    for (FaceId f : m.faces())
        if (is_degenerate(tri[f.idx()])) return std::array<FaceId, 2>{f, f};
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> buckets;
    std::vector<std::uint32_t> oversize;
    std::vector<CellRange> range(tri.size());
    for (std::uint32_t f = 0; f < tri.size(); ++f) {
        range[f] = cell_range(tri[f].p, cell);
        if (range[f].count() > max_cells_per_face) {
            oversize.push_back(f);
            continue;
        }
        for (auto i = range[f].lo[0]; i <= range[f].hi[0]; ++i)
            for (auto j = range[f].lo[1]; j <= range[f].hi[1]; ++j)
                for (auto k = range[f].lo[2]; k <= range[f].hi[2]; ++k) buckets[cell_key(i, j, k)].push_back(f);
    }
    // Face f against every g > f that may meet it, g in increasing order: the first pair found is
    // the lexicographically smallest, whatever the grid.
    std::vector<std::uint32_t> seen(tri.size(), UINT32_MAX), candidates;
    for (std::uint32_t f = 0; f < tri.size(); ++f) {
        candidates.clear();
        const auto take = [&](std::uint32_t g) {
            if (g > f && seen[g] != f) {
                seen[g] = f;
                candidates.push_back(g);
            }
        };
        if (range[f].count() > max_cells_per_face) {
            for (std::uint32_t g = f + 1; g < tri.size(); ++g) take(g);
        } else {
            for (auto i = range[f].lo[0]; i <= range[f].hi[0]; ++i)
                for (auto j = range[f].lo[1]; j <= range[f].hi[1]; ++j)
                    for (auto k = range[f].lo[2]; k <= range[f].hi[2]; ++k)
                        for (std::uint32_t g : buckets[cell_key(i, j, k)]) take(g);
            for (std::uint32_t g : oversize) take(g);
        }
        std::sort(candidates.begin(), candidates.end());
        for (std::uint32_t g : candidates)
            if (boxes_overlap(tri[f], tri[g]) && meet_improperly(tri[f], tri[g]))
                return std::array<FaceId, 2>{FaceId(f), FaceId(g)};
    }
    return std::nullopt;
}

// --- the guard --------------------------------------------------------------------------------

EmbeddingGuard::EmbeddingGuard(const TriMesh& m, double cell) : cell_(cell > 0 ? cell : default_cell(m)) {
    for (FaceId f : m.faces())
        if (!m.is_deleted(f)) insert(m, f);
}

template <typename F>
void EmbeddingGuard::for_each_cell(const std::array<Vec3, 3>& p, F&& f) const {
    const CellRange r = cell_range(p, cell_);
    if (r.count() > max_cells_per_face) {
        f(Key(0));  // oversize faces all live in one bucket that every query visits
        return;
    }
    for (auto i = r.lo[0]; i <= r.hi[0]; ++i)
        for (auto j = r.lo[1]; j <= r.hi[1]; ++j)
            for (auto k = r.lo[2]; k <= r.hi[2]; ++k) f(cell_key(i, j, k) | 1u);  // never key 0
}

void EmbeddingGuard::insert(const TriMesh& m, FaceId f) {
    for_each_cell(triangle_at(m, f).p, [&](Key key) { buckets_[key].push_back(f.idx()); });
}

void EmbeddingGuard::remove(const TriMesh& m, FaceId f) {
    for_each_cell(triangle_at(m, f).p, [&](Key key) {
        auto it = buckets_.find(key);
        if (it == buckets_.end()) return;
        auto& faces = it->second;
        faces.erase(std::remove(faces.begin(), faces.end(), f.idx()), faces.end());
        if (faces.empty()) buckets_.erase(it);
    });
}

bool EmbeddingGuard::accepts(const TriMesh& m, std::span<const FaceId> removed,
                             std::span<const TriangleAt> added) const {
    for (const TriangleAt& t : added)
        if (is_degenerate(t)) return false;
    for (std::size_t i = 0; i < added.size(); ++i)
        for (std::size_t j = i + 1; j < added.size(); ++j)
            if (meet_improperly(added[i], added[j])) return false;
    const auto is_removed = [&](std::uint32_t g) {
        return std::find(removed.begin(), removed.end(), FaceId(g)) != removed.end();
    };
    // Faces whose boxes miss t's cannot meet it. A face in several of t's (few) cells is tested
    // once; against an oversize t, which visits every bucket, faces are not tracked.
    std::vector<std::uint32_t> tested;
    bool track = true;
    const auto clashes = [&](const TriangleAt& t, Key key) {
        const auto it = buckets_.find(key);
        if (it == buckets_.end()) return false;
        for (std::uint32_t g : it->second) {
            if (is_removed(g)) continue;
            if (track) {
                if (std::find(tested.begin(), tested.end(), g) != tested.end()) continue;
                tested.push_back(g);
            }
            const TriangleAt u = triangle_at(m, FaceId(g));
            if (boxes_overlap(t, u) && meet_improperly(t, u)) return true;
        }
        return false;
    };
    for (const TriangleAt& t : added) {
        tested.clear();
        track = cell_range(t.p, cell_).count() <= max_cells_per_face;
        bool clash = clashes(t, Key(0));
        if (!track) {  // an oversize triangle: every face
            for (const auto& [key, faces] : buckets_) clash = clash || clashes(t, key);
        } else {
            for_each_cell(t.p, [&](Key key) { clash = clash || clashes(t, key); });
        }
        if (clash) return false;
    }
    return true;
}

}  // namespace fhr::generate
