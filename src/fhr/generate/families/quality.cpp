// FHR generate — the quality family (beyond the paper): meshes with a chosen share of
// needles, caps and slivers, the thinnest one's smallest corner at a chosen angle (10⁻⁴° by
// default, down to 10⁻⁹°). Real meshes (scans, CAD tessellations) have such triangles; the paper's
// pipeline must survive them. The argument in full is paper_notes/generator.md, "The quality
// family"; in short:
//
//   1. Plan. B = ⌈bad_fraction · F⌉ bad faces are made by n = ⌈3B/5⌉ insertions, each adding two
//      faces: 2n − B caps (one bad face each) and B − n two-bad-face insertions, needles and
//      slivers in turn, in a random order. So the mesh starts as the block of F − 2n faces.
//   2. Insert. Each insertion puts one vertex into a face (needle: close to a corner; cap: close to
//      the middle of an edge) or onto an interior edge (sliver: close to one end), at a distance
//      solved from the tangent of the angle it aims at. The first aims its bad faces' smaller tiny
//      corner at the chosen smallest angle θ; the others draw an angle between θ and 1°
//      (log-uniform by octaves). Every insertion is checked after rounding: its bad faces' smallest
//      corners lie in [7θ/8, 1°), its other new faces' corners above 1°, and the first one's
//      smaller tiny corner is below θ; then EmbeddingGuard must accept it. Insertions go only into
//      faces that are not bad and have all corners ≥ 10° (the pool), so no bad face is ever split
//      again: exactly B faces end with a corner below 1°.
//   3. Renumber by component (new vertices and faces go to their component) and rebuild, as the
//      block does, so the mesh is exactly what reading its written file gives.
//
// Exactness: the block's facets are axis-aligned, and a point p0 + t·d with d a combination of
// the facet's edge vectors keeps the facet's constant coordinate exactly (d has a zero there), so
// every insertion lies exactly in its facet (a sliver's point on a crease keeps both constant
// coordinates). Reproducibility: only +, −, ×, ÷, √ in a fixed order; the tangent of a small angle
// is our own Taylor polynomial, never the C library's tan.
#include <fhr/generate/detail/family.hpp>

#include <algorithm>
#include <array>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <vector>

#include <fhr/core/errors.hpp>
#include <fhr/core/topology.hpp>
#include <fhr/generate/embedding.hpp>

namespace fhr::generate::detail {
namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();
constexpr double radians_per_degree = 3.14159265358979323846 / 180;

/// tan x for x in degrees, 0 <= x <= 1.01: the Taylor polynomial x + x³/3 + 2x⁵/15 + 17x⁷/315 in
/// radians, whose remainder is below 3e−16 relative there.
double tan_degrees(double degrees) {
    const double x = degrees * radians_per_degree, x2 = x * x;
    return x * (1 + x2 * (1.0 / 3 + x2 * (2.0 / 15 + x2 * (17.0 / 315))));
}

/// tan 10°, correctly rounded: a face of the pool has no corner below 10°.
constexpr double tan_pool = 0.17632698070846498;

/// tan of the smallest corner of (a, b, c): |u × v| / (u · v) at each corner with u · v > 0 (the
/// smallest corner is below 60°, so at least one has). For a corner of size α the rounding of the
/// edge vectors costs a relative error of about 3·2⁻⁵³/α: 2e−5 at 10⁻⁹°.
double smallest_corner_tan(const Vec3& a, const Vec3& b, const Vec3& c) {
    double best = infinity;
    const auto corner = [&](const Vec3& u, const Vec3& v) {
        const double cosine = dot(u, v);
        if (cosine > 0) best = std::min(best, length(cross(u, v)) / cosine);
    };
    corner(b - a, c - a);
    corner(c - b, a - b);
    corner(a - c, b - c);
    return best;
}

enum class Kind { needle, cap, sliver };

/// Step 1: how many insertions of each kind, for F faces.
struct Plan {
    std::uint64_t bad = 0, insertions = 0, caps = 0, needles = 0, slivers = 0;
};

Plan plan(const RandomMeshOptions& o) {
    Plan p;
    p.bad = static_cast<std::uint64_t>(std::ceil(o.knobs.bad_fraction * static_cast<double>(o.faces)));
    p.insertions = (3 * p.bad + 4) / 5;  // ⌈3B/5⌉: B/2 <= n <= B, so both counts below are >= 0
    p.caps = 2 * p.insertions - p.bad;   // caps + 2 (needles + slivers) = B
    const std::uint64_t twos = p.bad - p.insertions;
    p.slivers = twos / 2;
    p.needles = twos - p.slivers;
    return p;
}

std::string shortest(double x) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%g", x);
    return buffer;
}

void check_knobs(const FamilyKnobs& k) {
    if (!(k.bad_fraction > 0 && k.bad_fraction <= 0.5))
        invalid("--bad-fraction must be in (0, 0.5] (got " + shortest(k.bad_fraction) + ")");
    if (!(k.smallest_angle_deg >= 1e-9 && k.smallest_angle_deg <= 1))
        invalid("--smallest-angle must be in [1e-09, 1] (got " + shortest(k.smallest_angle_deg) + ")");
}

/// A tiny corner at o between the rays to q and to p(t) = p0 + t·d, where p0 lies on the ray from
/// o to q, so the corner is 0 at t = 0: with u = q − o, tan(corner) = t·|u × d| / (u·(p0 − o) + t·u·d).
struct TinyCorner {
    Vec3 o, q, p0;
};

/// The t at which the corner's tangent is T (infinite if it never gets there).
double t_for(const TinyCorner& k, const Vec3& d, double T) {
    const Vec3 u = k.q - k.o;
    const double A = dot(u, k.p0 - k.o), C = length(cross(u, d)), D = dot(u, d);
    const double denominator = C - T * D;
    return denominator > 0 ? T * A / denominator : infinity;
}

/// One proposed insertion: the new vertex at p0 + t·d, its two tiny corners, and the triangles
/// the edit makes (the new vertex has id `fresh`), bad or not.
struct Candidate {
    Vec3 p0, d;
    std::array<TinyCorner, 2> tiny;
    std::vector<FaceId> removed;
    std::vector<std::array<VertexId, 3>> triangles;
    std::vector<bool> bad;
    EdgeId edge;  // the edge a sliver splits (invalid for a face split)
};

/// Step 2: the insertions, each kept only if its shape checks pass and the guard accepts it.
class Inserter {
public:
    Inserter(TriMesh& m, const FamilyKnobs& knobs, Random& rng)
        : m_(m), rng_(rng), guard_(m, 0), theta_(knobs.smallest_angle_deg), slot_(m.n_faces(), npos) {
        T_lo_ = tan_degrees(theta_ * (1 - 0x1p-3));
        T_first_ = tan_degrees(theta_ * (1 - 0x1p-11));
        T_bad_ = tan_degrees(1 - 0x1p-11);
        T_good_ = tan_degrees(1 + 0x1p-11);
        for (FaceId f : m.faces()) {
            admit(f);
            bool near = true;  // all coordinates within 2 of the origin: component 0's middle
            for (VertexId v : m.face_vertices(f))
                for (int k = 0; k < 3; ++k) near = near && std::abs(m.position(v)[k]) <= 2;
            if (near) near_origin_.push_back(f);
        }
        // The octaves [θ·2^j, θ·2^(j+1)) below 1°, for the drawn angles.
        for (double a = theta_; a < 1; a *= 2) ++octaves_;
    }

    /// An angle between θ and 1°: a uniformly chosen octave, uniformly within it.
    double draw_angle() {
        if (octaves_ == 0) return theta_;
        double a = theta_;
        for (std::uint64_t j = rng_.below(octaves_); j > 0; --j) a *= 2;
        const double w = rng_.unit();
        return std::min(1.0, a * (1 + w));
    }

    /// One insertion of this kind aiming at angle `aim` (the first one: at θ). A face is drawn
    /// from the pool up to 64 times, then from the pool's faces near the origin (where the
    /// coordinates are smallest, so the finest offsets are representable) up to 64 times; a
    /// sliver that finds no edge becomes a needle (both add two faces, two of them bad).
    void insert(Kind kind, double aim, bool first) {
        for (;;) {
            for (int attempt = 0; attempt < 128; ++attempt) {
                const bool near = first || attempt >= 64 || pool_.empty();
                if (near && near_origin_.empty()) break;
                const FaceId f = near ? near_origin_[rng_.below(near_origin_.size())] : pool_[rng_.below(pool_.size())];
                if (slot_[f.idx()] == npos) continue;
                if (try_insert(kind, f, aim, first)) return;
            }
            if (kind != Kind::sliver)
                throw InternalError("quality family: no face takes a " +
                                    std::string(kind == Kind::cap ? "cap" : "needle") + " of " + shortest(aim) +
                                    "° (a bug: see paper_notes/generator.md)");
            kind = Kind::needle;
        }
    }

private:
    static constexpr std::uint32_t npos = UINT32_MAX;
    TriMesh& m_;
    Random& rng_;
    EmbeddingGuard guard_;
    double theta_;
    double T_lo_, T_first_, T_bad_, T_good_;
    std::vector<FaceId> pool_, near_origin_;
    std::vector<std::uint32_t> slot_;  // a face's place in pool_, or npos
    std::uint64_t octaves_ = 0;

    const Vec3& pos(VertexId v) const { return m_.position(v); }

    // The pool: faces that are not bad and have every corner >= 10°, in O(1) per change.
    void admit(FaceId f) {
        if (f.idx() >= slot_.size()) slot_.resize(f.idx() + 1, npos);
        const auto v = m_.face_vertices(f);
        if (smallest_corner_tan(pos(v[0]), pos(v[1]), pos(v[2])) < tan_pool) return;
        slot_[f.idx()] = static_cast<std::uint32_t>(pool_.size());
        pool_.push_back(f);
    }
    void dismiss(FaceId f) {
        const std::uint32_t s = slot_[f.idx()];
        if (s == npos) return;
        pool_[s] = pool_.back();
        slot_[pool_[s].idx()] = s;
        pool_.pop_back();
        slot_[f.idx()] = npos;
    }

    bool try_insert(Kind kind, FaceId f, double aim, bool first) {
        Candidate c;
        const auto v = m_.face_vertices(f);
        const std::uint64_t r = rng_.below(3);
        const VertexId a = v[r], b = v[(r + 1) % 3], cc = v[(r + 2) % 3];
        const VertexId fresh(static_cast<VertexId::Index>(m_.n_vertices()));
        if (kind != Kind::sliver) {
            c.removed = {f};
            // split_face(f) makes (v0, v1, m), (v1, v2, m), (v2, v0, m).
            c.triangles = {{v[0], v[1], fresh}, {v[1], v[2], fresh}, {v[2], v[0], fresh}};
        }
        const Vec3 &A = pos(a), &Bp = pos(b), &Cp = pos(cc);
        if (kind == Kind::needle) {
            // Close to a, in the direction that makes the tiny corners at b and c equal to first
            // order: their tangents are t·|ab × d|/|ab|² and t·|ac × d|/|ac|².
            c.p0 = A;
            c.d = dot(Cp - A, Cp - A) * (Bp - A) + dot(Bp - A, Bp - A) * (Cp - A);
            c.tiny = {TinyCorner{Bp, A, A}, TinyCorner{Cp, A, A}};
            for (const auto& t : c.triangles) c.bad.push_back(std::find(t.begin(), t.end(), a) != t.end());
        } else if (kind == Kind::cap) {
            // Close to the midpoint of bc, perpendicular to bc towards a: equal tiny corners at b
            // and c, a corner near 180° at the new vertex.
            const Vec3 e = Cp - Bp;
            c.p0 = Bp + 0.5 * e;
            const Vec3 up = A - c.p0;
            c.d = up - (dot(up, e) / dot(e, e)) * e;
            c.tiny = {TinyCorner{Bp, Cp, c.p0}, TinyCorner{Cp, Bp, c.p0}};
            for (const auto& t : c.triangles) c.bad.push_back(std::find(t.begin(), t.end(), a) == t.end());
        } else {
            // Split the edge ab close to a: its two faces become four, the two at a thin with tiny
            // corners at the opposite vertices cc and y.
            const HalfedgeId h = m_.find_halfedge(a, b);
            if (m_.is_boundary(TriMesh::edge(h))) return false;
            const HalfedgeId o = TriMesh::twin(h);
            if (slot_[m_.face(o).idx()] == npos) return false;
            const VertexId y = m_.to(m_.next(o));
            c.edge = TriMesh::edge(h);
            c.removed = {f, m_.face(o)};
            // split_edge(e) with halfedge(e, 0) = (s → t), faces (s, t, x) and (t, s, z), makes
            // (s, m, x), (m, t, x), (t, m, z), (m, s, z).
            const HalfedgeId h0 = TriMesh::halfedge(c.edge, 0);
            const VertexId s = m_.from(h0), t = m_.to(h0), x = m_.to(m_.next(h0)),
                           z = m_.to(m_.next(TriMesh::twin(h0)));
            c.triangles = {{s, fresh, x}, {fresh, t, x}, {t, fresh, z}, {fresh, s, z}};
            c.p0 = A;
            c.d = Bp - A;
            c.tiny = {TinyCorner{Cp, A, A}, TinyCorner{pos(y), A, A}};
            for (const auto& tr : c.triangles) c.bad.push_back(std::find(tr.begin(), tr.end(), a) != tr.end());
        }
        // The larger tiny corner at the drawn angle, unless that puts the smaller one below θ.
        const double T_aim = tan_degrees(aim * (1 - 0x1p-10)), T_theta = tan_degrees(theta_ * (1 - 0x1p-10));
        double t = std::max(std::min(t_for(c.tiny[0], c.d, T_aim), t_for(c.tiny[1], c.d, T_aim)),
                            std::max(t_for(c.tiny[0], c.d, T_theta), t_for(c.tiny[1], c.d, T_theta)));
        if (!(t < infinity)) return false;
        // After rounding the corners may be a little off: shrink t while a bad corner is too large.
        for (int retry = 0; retry < 16; ++retry, t *= 1 - 0x1p-8) {
            Vec3 p;
            for (int k = 0; k < 3; ++k) p[k] = c.p0[k] + t * c.d[k];
            std::vector<TriangleAt> added;
            bool too_large = false, fails = false;
            double smallest_bad = infinity;
            for (std::size_t i = 0; i < c.triangles.size(); ++i) {
                TriangleAt tri{c.triangles[i], {}};
                for (int k = 0; k < 3; ++k) tri.p[k] = tri.v[k] == fresh ? p : pos(tri.v[k]);
                const double s = smallest_corner_tan(tri.p[0], tri.p[1], tri.p[2]);
                if (c.bad[i]) {
                    smallest_bad = std::min(smallest_bad, s);
                    too_large = too_large || s >= T_bad_;
                    fails = fails || !(s >= T_lo_);
                } else {
                    fails = fails || !(s > T_good_);
                }
                added.push_back(tri);
            }
            too_large = too_large || (first && smallest_bad >= T_first_);
            if (fails) return false;
            if (too_large) continue;
            if (!guard_.accepts(m_, c.removed, added)) return false;
            apply(c, p);
            return true;
        }
        return false;
    }

    void apply(const Candidate& c, const Vec3& p) {
        const std::size_t first_new = m_.n_faces();
        for (FaceId f : c.removed) {
            guard_.remove(m_, f);
            dismiss(f);
        }
        if (c.edge.valid())
            m_.split_edge(c.edge, p);
        else
            m_.split_face(c.removed[0], p);
        std::vector<FaceId> changed = c.removed;
        for (std::size_t f = first_new; f < m_.n_faces(); ++f) changed.push_back(FaceId(static_cast<FaceId::Index>(f)));
        for (FaceId f : changed) {
            guard_.insert(m_, f);
            admit(f);  // a bad face never passes the pool's 10° test
        }
    }
};

/// Step 3: vertices and faces in the order of their components (a new vertex or face goes to the
/// component it was inserted in), rebuilt from the triangles as a reader of the file would.
TriMesh renumbered_by_component(const TriMesh& m) {
    const Components comps = connected_components(m);
    std::vector<std::uint32_t> order(m.n_vertices());
    for (std::uint32_t v = 0; v < order.size(); ++v) order[v] = v;
    const auto component = [&](std::uint32_t v) { return comps.vertex_component[VertexId(v)]; };
    std::stable_sort(order.begin(), order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return component(a) < component(b); });
    std::vector<std::uint32_t> index(m.n_vertices());
    std::vector<Vec3> positions(m.n_vertices());
    for (std::uint32_t i = 0; i < order.size(); ++i) {
        index[order[i]] = i;
        positions[i] = m.position(VertexId(order[i]));
    }
    std::vector<Triangle> triangles = m.triangles();
    std::stable_sort(triangles.begin(), triangles.end(),
                     [&](const Triangle& s, const Triangle& t) { return component(s[0]) < component(t[0]); });
    for (Triangle& t : triangles)
        for (std::uint32_t& v : t) v = index[v];
    return TriMesh::from_triangles(std::move(positions), triangles);
}

}  // namespace

std::size_t quality_min_faces(const RandomMeshOptions& options) {
    check_knobs(options.knobs);
    // The block gets F − 2n faces with n = ⌈3B/5⌉ <= (3(bf·F + 1) + 4)/5, so F − 2n >=
    // F(1 − 1.2 bf) − 2.8: at least the block's minimum m0 once F >= (m0 + 3)/(1 − 1.2 bf), for
    // every larger F too (the slack 0.2 covers the rounding of bf·F and of this quotient).
    const std::size_t least = min_faces(options.genus, options.holes, options.components);
    const double bound = std::ceil((static_cast<double>(least) + 3) / (1 - 1.2 * options.knobs.bad_fraction));
    const auto faces = static_cast<std::size_t>(bound);
    return faces + faces % 2;
}

TriMesh quality_mesh(const RandomMeshOptions& options) {
    const Plan p = plan(options);
    Random rng(family_seed(options.seed, Family::quality));
    std::vector<Kind> kinds;
    kinds.insert(kinds.end(), p.caps, Kind::cap);
    for (std::uint64_t i = 0; i < p.needles + p.slivers; ++i) kinds.push_back(i % 2 == 0 ? Kind::needle : Kind::sliver);
    for (std::size_t i = kinds.size(); i > 1; --i) std::swap(kinds[i - 1], kinds[rng.below(i)]);  // Fisher–Yates
    TriMesh m = base_block(options, options.faces - 2 * p.insertions);
    Inserter inserter(m, options.knobs, rng);
    for (std::size_t i = 0; i < kinds.size(); ++i) {
        const double aim = i == 0 ? options.knobs.smallest_angle_deg : inserter.draw_angle();
        inserter.insert(kinds[i], aim, i == 0);
    }
    return renumbered_by_component(m);
}

}  // namespace fhr::generate::detail
