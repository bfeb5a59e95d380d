// FHR exchange — what the oracle's checks share, whatever kind of map they judge (a `fhr-param 1`
// file, spec/param.md; a UV atlas, spec/atlas.md): a check's result recorder, compensated sums,
// a surface's topology component by component, and the grids that measure how far points lie
// from an input mesh T. Internal to src/fhr/exchange, which shares no code with what it judges.
#pragma once

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numeric>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <fhr/core/build.hpp>
#include <fhr/core/errors.hpp>
#include <fhr/core/geometry.hpp>
#include <fhr/core/polygon_soup.hpp>
#include <fhr/core/topology.hpp>
#include <fhr/core/trimesh.hpp>
#include <fhr/exchange/verify.hpp>

namespace fhr::exchange::detail {

/// Unit roundoff u = 2^-53 of IEEE double arithmetic.
constexpr double unit_roundoff = std::numeric_limits<double>::epsilon() / 2;
constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();

inline std::string num(double x) {
    char buffer[32];
    const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x);
    return std::string(buffer, end);
}

inline std::string str(const Vec3& p) { return "(" + num(p.x()) + ", " + num(p.y()) + ", " + num(p.z()) + ")"; }

/// Neumaier's compensated summation: the error is at most 2u|S| + O(n u²) Σ|x_i|, independent of
/// the order and of n to first order (Higham 2002, §4.3).
class CompensatedSum {
public:
    void add(double x) {
        const double t = sum_ + x;
        compensation_ += std::fabs(sum_) >= std::fabs(x) ? (sum_ - t) + x : (x - t) + sum_;
        sum_ = t;
    }
    double value() const { return sum_ + compensation_; }

private:
    double sum_ = 0, compensation_ = 0;
};

/// Builds one CheckResult: counts failures, keeps the first one's description and location.
class Recorder {
public:
    Recorder(const char* id, const char* title) {
        result_.id = id;
        result_.title = title;
    }
    void examined(std::uint64_t n) { result_.checked += n; }
    /// Records one failure; `describe()` is called for the first one only. True for the first.
    template <class Describe>
    bool fail(Describe&& describe, std::int64_t face = -1, std::int64_t vertex = -1, std::int64_t patch = -1) {
        if (result_.failures++ != 0) return false;
        result_.first_failure = describe();
        result_.face = face;
        result_.vertex = vertex;
        result_.patch = patch;
        return true;
    }
    /// The first failure's chart and UV point (atlas checks).
    void locate(std::int64_t chart, const std::array<double, 2>& uv) {
        result_.chart = chart;
        result_.uv = uv;
    }
    std::uint64_t failures() const { return result_.failures; }
    CheckResult done() {
        result_.status = result_.failures == 0 ? CheckStatus::pass : CheckStatus::fail;
        return std::move(result_);
    }

private:
    CheckResult result_;
};

inline CheckResult skipped(const char* id, const char* title, const std::string& reason) {
    CheckResult r;
    r.id = id;
    r.title = title;
    r.status = CheckStatus::skipped;
    r.first_failure = "not checked: " + reason;
    return r;
}

/// The components of a mesh, each with its Euler characteristic and number of boundary loops. A
/// compact connected orientable surface is determined up to homeomorphism by these two numbers
/// (χ = 2 − 2g − b: the classification of surfaces), so they are what PARAM-4 and PARAM-11 compare.
struct Topology {
    Components components;                    ///< vertex → component, numbered by lowest vertex
    std::vector<long> chi;                    ///< per component
    std::vector<std::uint32_t> loops;         ///< boundary loops per component
    std::vector<std::uint32_t> vertices;      ///< number of vertices per component
    std::vector<std::uint32_t> first_vertex;  ///< the lowest vertex of each component (its name)

    std::size_t count() const { return chi.size(); }
    std::uint32_t of(std::uint32_t vertex) const { return components.vertex_component[VertexId(vertex)]; }
    long total_chi() const { return std::accumulate(chi.begin(), chi.end(), 0L); }
    std::uint64_t total_loops() const { return std::accumulate(loops.begin(), loops.end(), std::uint64_t{0}); }
};

/// \pre mesh has no garbage. \post one entry per connected component; Σ chi = χ(mesh).
/// Cost: the component search, then each vertex, each face and each boundary halfedge once — a
/// component with F faces and B boundary halfedges has E = (3F + B) / 2 edges.
inline Topology topology_of(const TriMesh& mesh) {
    Topology t;
    t.components = connected_components(mesh);
    const std::size_t n = t.components.count;
    t.chi.assign(n, 0);
    t.loops.assign(n, 0);
    t.vertices.assign(n, 0);
    t.first_vertex.assign(n, none);
    for (VertexId v : mesh.vertices()) {
        const std::uint32_t c = t.of(v.idx());
        if (t.vertices[c]++ == 0) t.first_vertex[c] = v.idx();
    }
    std::vector<long> faces(n, 0), boundary_halfedges(n, 0);
    for (FaceId f : mesh.faces()) ++faces[t.of(mesh.to(mesh.halfedge(f)).idx())];
    for (HalfedgeId h : boundary_loops(mesh)) {
        const std::uint32_t c = t.of(mesh.to(h).idx());
        ++t.loops[c];
        HalfedgeId g = h;
        do {
            ++boundary_halfedges[c];
            g = mesh.next(g);
        } while (g != h);
    }
    for (std::size_t c = 0; c < n; ++c)
        t.chi[c] = static_cast<long>(t.vertices[c]) - (3 * faces[c] + boundary_halfedges[c]) / 2 + faces[c];
    return t;
}

/// A mesh that passed PARAM-3 (VMAP-3), with its topology.
struct Surface {
    TriMesh mesh;
    Topology topology;
};

/// build_trimesh with every rule of spec/mesh.md (boundary loops and several components are
/// allowed; every vertex, boundary ones included, must be manifold, which makes every boundary
/// loop a simple closed curve; no closed component is flat, INV-IN-13). A file must need no
/// repair: no isolated vertex (a vertex in no face has no image) and no face turned — each
/// component consistently oriented, a closed one with positive volume (the orientation is part of
/// the contract: PARAM-8 and VMAP-7 read it; a component with boundary has no outside, so either of
/// its two orientations is accepted). Then the mesh's vertices and faces are the soup's, in order.
/// A failure is recorded in `rec`, naming the surface `what`.
inline std::optional<Surface> build_surface(const PolygonSoup& soup, const char* what, Recorder& rec) {
    BuildLog log;
    try {
        TriMesh mesh = build_trimesh(soup, BuildOptions{.require_closed = false, .require_connected = false}, log);
        if (log.dropped_vertices == 0 && log.reoriented_faces == 0) {
            Topology topology = topology_of(mesh);
            return Surface{std::move(mesh), std::move(topology)};
        }
        rec.fail([&] {
            std::string warning = log.warnings.front();  // ": dropped …" or ": re-oriented …" (no file name)
            if (warning.rfind(": ", 0) == 0) warning.erase(0, 2);
            return std::string(what) +
                   (log.dropped_vertices ? " has vertices in no face: "
                                         : " is not oriented counter-clockwise seen from outside "
                                           "(each component consistently, a closed one with "
                                           "positive volume): ") +
                   warning;
        });
    } catch (const InvalidInput& e) {
        rec.fail([&] { return std::string(what) + ": " + e.problem(); });
    }
    return std::nullopt;
}

/// "1 boundary loop", "2 boundary loops".
inline std::string loops_text(std::uint64_t n) {
    return std::to_string(n) + (n == 1 ? " boundary loop" : " boundary loops");
}

/// The key of grid cell (x, y, z), each coordinate in [0, 2²¹): the sparse grids below and in
/// atlas.cpp list their simplices or points as sorted (key, index) pairs.
inline std::uint64_t cell_key(std::uint64_t x, std::uint64_t y, std::uint64_t z) { return x << 42 | y << 21 | z; }

using Bits = std::array<std::uint64_t, 3>;

inline Bits bits(const Vec3& p) {
    Bits b;
    for (int c = 0; c < 3; ++c) std::memcpy(&b[c], &p[c], sizeof(double));
    return b;
}

/// The closest point to p on the segment [a, b], in its box. \pre a ≠ b (an edge of a valid mesh).
inline Vec3 closest_point_on_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
    const Vec3 ab = b - a;
    const Vec3 q = a + std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) * ab;
    return q.cwiseMax(a.cwiseMin(b)).cwiseMin(a.cwiseMax(b));  // in the segment's box despite rounding
}

/// A uniform grid over simplices of T — its faces, or its boundary edges — stored sparsely as
/// sorted (cell, simplex) pairs: each simplex is listed in every cell its bounding box, grown by
/// `tolerance`, meets. Then a point within `tolerance` of a simplex finds it in its own cell. A
/// segment (a, b) is stored as the triple (a, b, b).
class SimplexGrid {
public:
    /// \pre simplices is not empty; `size` > 0 is their typical diameter.
    SimplexGrid(const TriMesh& mesh, std::vector<Triangle> simplices, double size, double tolerance)
        : mesh_(mesh), tolerance_(tolerance), simplices_(std::move(simplices)) {
        min_ = max_ = mesh.position(VertexId(0));
        for (const Vec3& p : mesh.positions()) {
            min_ = min_.cwiseMin(p);
            max_ = max_.cwiseMax(p);
        }
        min_.array() -= tolerance;
        max_.array() += tolerance;
        // Cells about twice the typical size, at most 2^20 per axis (keys of 21 bits), and
        // coarsened until the simplices are listed at most 16 times each on average.
        const double extent = (max_ - min_).maxCoeff();
        cell_ = std::max({2 * size, extent / (1 << 20), 4 * tolerance, std::numeric_limits<double>::min()});
        double listed = listings();
        while (listed > 16.0 * static_cast<double>(simplices_.size()) + 1024) {
            cell_ *= 2;
            listed = listings();
        }
        std::vector<std::pair<std::uint64_t, std::uint32_t>> entries;
        entries.reserve(static_cast<std::size_t>(listed));
        for (std::uint32_t f = 0; f < simplices_.size(); ++f) {
            const auto [lo, hi] = cell_range(f);
            for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
                for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
                    for (std::int64_t z = lo[2]; z <= hi[2]; ++z) entries.emplace_back(key(x, y, z), f);
        }
        std::sort(entries.begin(), entries.end());
        listing_ = std::move(entries);
    }

    /// The distance from p to the nearest simplex listed in p's cell, or +inf when there is none
    /// (then p is farther than the tolerance from every simplex).
    double distance(const Vec3& p) const {
        if ((p.array() < min_.array()).any() || (p.array() > max_.array()).any())
            return std::numeric_limits<double>::infinity();
        const auto c = cell(p);
        const std::uint64_t k = key(c[0], c[1], c[2]);
        auto it = std::lower_bound(listing_.begin(), listing_.end(), std::pair<std::uint64_t, std::uint32_t>(k, 0));
        // Squared distances; a simplex whose box is no nearer than the best so far is skipped (its
        // closest point lies in its box — closest_point_on_triangle clamps to it — so its rounded
        // distance is never below the box's: the same minimum).
        double best = std::numeric_limits<double>::infinity();
        for (; it != listing_.end() && it->first == k; ++it) {
            const Triangle& t = simplices_[it->second];
            const Vec3 &a = pos(t[0]), &b = pos(t[1]), &c = pos(t[2]);
            if (!(box_distance2(p, a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c)) < best)) continue;
            const Vec3 q = t[1] == t[2] ? closest_point_on_segment(p, a, b) : closest_point_on_triangle(p, a, b, c);
            best = std::min(best, (q - p).squaredNorm());
        }
        return std::sqrt(best);
    }

private:
    const TriMesh& mesh_;
    double tolerance_;
    std::vector<Triangle> simplices_;
    Vec3 min_, max_;
    double cell_ = 0;
    std::vector<std::pair<std::uint64_t, std::uint32_t>> listing_;  // (cell key, simplex), sorted

    const Vec3& pos(std::uint32_t v) const { return mesh_.position(VertexId(v)); }

    std::array<std::int64_t, 3> cell(const Vec3& p) const {
        std::array<std::int64_t, 3> c;
        for (int k = 0; k < 3; ++k) {
            const double x = std::floor((p[k] - min_[k]) / cell_);
            c[k] = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::min(x, 1048575.0)), 0, (1 << 20) - 1);
        }
        return c;
    }

    std::pair<std::array<std::int64_t, 3>, std::array<std::int64_t, 3>> cell_range(std::uint32_t f) const {
        const Triangle& t = simplices_[f];
        const Vec3 lo = pos(t[0]).cwiseMin(pos(t[1])).cwiseMin(pos(t[2])).array() - tolerance_;
        const Vec3 hi = pos(t[0]).cwiseMax(pos(t[1])).cwiseMax(pos(t[2])).array() + tolerance_;
        return {cell(lo), cell(hi)};
    }

    /// How many (cell, simplex) pairs the grid lists (a double: up to 2^60 cells per simplex).
    double listings() const {
        double n = 0;
        for (std::uint32_t f = 0; f < simplices_.size(); ++f) {
            const auto [lo, hi] = cell_range(f);
            n += static_cast<double>(hi[0] - lo[0] + 1) * static_cast<double>(hi[1] - lo[1] + 1) *
                 static_cast<double>(hi[2] - lo[2] + 1);
        }
        return n;
    }

    static std::uint64_t key(std::int64_t x, std::int64_t y, std::int64_t z) {
        return cell_key(static_cast<std::uint64_t>(x), static_cast<std::uint64_t>(y), static_cast<std::uint64_t>(z));
    }
};

inline double total_area(const TriMesh& mesh) {
    CompensatedSum sum;
    for (const Triangle& t : mesh.triangles()) {
        const Vec3 &a = mesh.position(VertexId(t[0])), &b = mesh.position(VertexId(t[1])),
                   &c = mesh.position(VertexId(t[2]));
        sum.add(0.5 * (b - a).cross(c - a).norm());
    }
    return sum.value();
}

/// PARAM-11's and ATLAS-8's side of T alone (prepared by the caller, PreparedInput, or beside PARAM-3 when they
/// run side by side): the tolerance (within 1e-9 of the bounding-box diagonal, plus 64u·|x|max for
/// the rounding of a point computed on an edge or face of T — a few u·|x| per coordinate, by the
/// producer and again by closest_point — when T lies far from the origin), its area, and grids
/// over its faces and over its boundary edges (none when T is closed: then no point is on its
/// boundary).
struct InputSide {
    const double tolerance, area;
    const SimplexGrid faces;
    std::optional<SimplexGrid> boundary;

    /// `extra` is added to the tolerance (an atlas's printed rounding, ATLAS-8).
    explicit InputSide(const TriMesh& t, double extra = 0)
        : tolerance(tolerance_of(t) + extra),
          area(total_area(t)),
          faces(t, t.triangles(), std::sqrt(area / static_cast<double>(t.n_faces())), tolerance) {
        std::vector<Triangle> edges;
        double length = 0;
        for (HalfedgeId h : t.halfedges())
            if (t.is_boundary(h)) {
                edges.push_back({t.from(h).idx(), t.to(h).idx(), t.to(h).idx()});
                length += (t.position(t.to(h)) - t.position(t.from(h))).norm();
            }
        const double mean_length = length / static_cast<double>(std::max<std::size_t>(edges.size(), 1));
        if (!edges.empty()) boundary.emplace(t, std::move(edges), mean_length, tolerance);
    }

private:
    static double tolerance_of(const TriMesh& t) {
        double max_abs = 0;
        Vec3 lo = t.position(VertexId(0)), hi = lo;
        for (const Vec3& p : t.positions()) {
            max_abs = std::max(max_abs, p.cwiseAbs().maxCoeff());
            lo = lo.cwiseMin(p);
            hi = hi.cwiseMax(p);
        }
        return geometry_tolerance * (hi - lo).norm() + 64 * unit_roundoff * max_abs;
    }
};

}  // namespace fhr::exchange::detail
