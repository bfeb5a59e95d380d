// FHR exchange — `fhr verify --vertex-map`: VMAP-2..9 of spec/vertex_map.md on a per-vertex map of
// a mesh T onto a mesh D. Beyond the paper (whose map is written on a refinement T′, spec/param.md):
// a producer that gives only the images of T's vertices leaves the images of edges and faces to a
// rule, and the oracle judges the map that rule makes.
//
//   VMAP-2  every vertex has an image: a point of D, exactly w/Σw in a face of D
//   VMAP-3  T and D orientable manifolds as written (PARAM-3's builder, detail/checks.hpp)
//   VMAP-4  the same topology, component by component
//   VMAP-5  every edge of T has an image under the rule `adjacent`: straight in one face of D, or
//           in the isometric unfolding of a fan of faces around a vertex of D
//   VMAP-6  the images of vertices and edges form a graph embedded in D (no two pieces meet
//           beyond a common end) — exact, pieces listed in a grid per face of D
//   VMAP-7  every face's corners turn counter-clockwise by less than π (no fold)
//   VMAP-8  the tangents around every vertex wind once (T's rotation kept)
//   VMAP-9  ∂T onto ∂D
//
// Theorem (paper_notes/vertex_map.md): VMAP-2..9 ⇒ a homeomorphism T → D preserving orientation.
//
// Exactness: a point of D is a vertex set with weights, doubles as read or rationals (GMP) for the
// crossings of an edge's image with D's edges. Every decision — membership, orientation, crossing,
// order of tangents — is a sign computed exactly from those numbers (orient3d on three barycentric
// rows of doubles, rationals otherwise). The unfoldings of fans are computed in double by the
// formula spec/vertex_map.md fixes, and then used as exact numbers: the rule's charts are what
// that formula gives, so that every implementation decides the same map.
#include <fhr/exchange/vertex_map.hpp>

#include <gmpxx.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include <fhr/core/detail/predicates.hpp>
#include <fhr/exchange/detail/checks.hpp>

namespace fhr::exchange {

bool VertexMapReport::valid() const { return first_failure() == nullptr; }
const CheckResult* VertexMapReport::first_failure() const { return first_judged_failure(checks); }

namespace {

using namespace detail;
using Q = mpq_class;

constexpr const char* title_2 = "every vertex of T has an image in D";
constexpr const char* title_3 = "T and D are orientable manifolds, consistently oriented";
constexpr const char* title_4 = "T and D have the same topology, component by component";
constexpr const char* title_5 = "every edge of T has an image under the rule";
constexpr const char* title_6 = "the images of vertices and edges meet only in common ends";
constexpr const char* title_7 = "no fold: every corner turns counter-clockwise by less than pi";
constexpr const char* title_8 = "the images around every vertex wind once";
constexpr const char* title_9 = "the boundary of T maps onto the boundary of D";

/// VMAP-2's tolerance on the weights, as PARAM-5's on β (spec/param.md).
constexpr double weight_tolerance = 1e-12;

/// A point of D: the vertices of D with positive weight (ascending; `none` unused) and their
/// weights, as doubles or, for a crossing, as rationals in `exact`.
struct Point {
    std::array<std::uint32_t, 3> v{none, none, none};
    std::array<double, 3> w{};
    std::int32_t exact = -1;       // index into Checker::exact_
    std::uint32_t tvertex = none;  // the vertex of T it is the image of; none for a crossing
    std::uint32_t face = none;     // a face of D holding it (the record's, for a vertex of T)

    int size() const { return v[2] != none ? 3 : v[1] != none ? 2 : 1; }
};

/// A point's weights on the corners of a face of D, in the face's order: doubles (for a crossing
/// the rationals rounded to nearest), and for a crossing pointers to its rationals, null for a
/// corner of weight 0.
struct Bary {
    bool exact = false;
    std::array<double, 3> d{};
    std::array<const mpq_class*, 3> q{};
};

/// The corners of a face in its own weights.
const Bary corners[3] = {{false, {1, 0, 0}, {}}, {false, {0, 1, 0}, {}}, {false, {0, 0, 1}, {}}};

struct Q2 {
    Q x, y;
};

int sign(const Q& x) { return sgn(x); }
Q cross(const Q2& a, const Q2& b) { return a.x * b.y - a.y * b.x; }
Q2 sub(const Q2& a, const Q2& b) { return {a.x - b.x, a.y - b.y}; }

/// The counter-clockwise ring of faces around a vertex s of D: faces[i] = (s, spokes[i],
/// spokes[i+1]) (indices mod k on a closed ring; an open ring, at a boundary vertex, has k + 1
/// spokes from one boundary edge to the other). A closed ring starts at its lowest face.
struct Ring {
    std::vector<std::uint32_t> spokes, faces;
    bool closed = true;
    std::size_t k() const { return faces.size(); }
    std::uint32_t spoke(std::size_t i) const { return spokes[closed ? i % faces.size() : i]; }
    std::uint32_t face(std::size_t i) const { return faces[i % faces.size()]; }
};

/// The direction in which an edge's image leaves the image of one of its ends: the first piece of
/// the image, as a face of D holding it and its other end. Checker::sector gives its cyclic
/// position around the point (VMAP-8), Checker::convex the turn between two of them (VMAP-7).
struct Tangent {
    std::uint32_t face = none;  // a face of D holding the first piece
    Point q;                    // the first piece's other end
};

struct Piece {
    std::uint32_t face;
    Point a, b;
    std::uint32_t edge;  // of T
};

class Checker {
public:
    Checker(const VertexMapFile& map, const PolygonSoup& T, const PolygonSoup& D) : map_(map), ts_(T), ds_(D) {}

    VertexMapReport run() {
        VertexMapReport report;
        Recorder r3("VMAP-3", title_3);
        d_ = build_surface(ds_, "D", r3);
        t_ = build_surface(ts_, "T", r3);
        r3.examined(2);
        CheckResult c3 = r3.done();
        if (!d_) {
            report.checks.push_back(skipped("VMAP-2", title_2, "VMAP-3 failed (the images are points of D)"));
            report.checks.push_back(std::move(c3));
            for (auto [id, title] : later(4)) report.checks.push_back(skipped(id, title, "VMAP-3 failed"));
            return report;
        }
        make_rings();
        report.checks.push_back(check_images());
        const bool images = report.checks.back().status == CheckStatus::pass;
        report.checks.push_back(std::move(c3));
        if (!images || !t_) {
            for (auto [id, title] : later(4))
                report.checks.push_back(skipped(id, title, images ? "VMAP-3 failed" : "VMAP-2 failed"));
            return report;
        }
        report.checks.push_back(check_topology());
        report.checks.push_back(map_edges(report));
        // VMAP-6..9 judge what has an image: an edge without one (VMAP-5's failure) takes no part,
        // nor do the corners and vertices it is an edge of.
        report.checks.push_back(check_embedding(report));
        report.checks.push_back(check_corners(report));
        report.checks.push_back(check_winding());
        report.checks.push_back(check_boundary());
        if (report.edges_without_image.empty()) report.distortion = distortion();
        return report;
    }

private:
    const VertexMapFile& map_;
    const PolygonSoup &ts_, &ds_;
    std::optional<Surface> d_, t_;
    std::vector<Ring> rings_;              // per vertex of D
    std::vector<Point> image_;             // per vertex of T
    std::vector<std::array<Q, 3>> exact_;  // rational weights of crossings
    std::vector<Tangent> tangent_;         // per halfedge of T: the first piece from its tail
    std::vector<double> length_;           // per edge of T: its image's length
    std::vector<Piece> pieces_;

    static std::vector<std::pair<const char*, const char*>> later(int first) {
        const std::vector<std::pair<const char*, const char*>> all{{"VMAP-4", title_4}, {"VMAP-5", title_5},
                                                                   {"VMAP-6", title_6}, {"VMAP-7", title_7},
                                                                   {"VMAP-8", title_8}, {"VMAP-9", title_9}};
        return {all.begin() + (first - 4), all.end()};
    }

    const TriMesh& dm() const { return d_->mesh; }
    const TriMesh& tm() const { return t_->mesh; }
    std::array<std::uint32_t, 3> dtri(std::uint32_t g) const {
        const std::uint32_t* p = ds_.polygon(g);
        return {p[0], p[1], p[2]};
    }
    std::array<std::uint32_t, 3> ttri(std::uint32_t f) const {
        const std::uint32_t* p = ts_.polygon(f);
        return {p[0], p[1], p[2]};
    }
    const Vec3& dpos(std::uint32_t v) const { return ds_.points[v]; }

    // ---- points of D ------------------------------------------------------------------------
    Q weight_q(const Point& p, int k) const { return p.exact >= 0 ? exact_[p.exact][k] : Q(p.w[k]); }

    bool contains(std::uint32_t g, const Point& p) const {
        const auto t = dtri(g);
        for (std::uint32_t v : p.v)
            if (v != none && v != t[0] && v != t[1] && v != t[2]) return false;
        return true;
    }

    Bary coords(const Point& p, std::uint32_t g) const {
        const auto t = dtri(g);
        Bary b;
        b.exact = p.exact >= 0;
        for (int c = 0; c < 3; ++c)
            for (int k = 0; k < 3; ++k)
                if (p.v[k] == t[c]) {
                    b.d[c] = p.w[k];
                    if (b.exact) b.q[c] = &exact_[static_cast<std::size_t>(p.exact)][k];
                }
        return b;
    }

    static Q as_q(const Bary& b, int c) { return b.exact ? (b.q[c] ? *b.q[c] : Q(0)) : Q(b.d[c]); }

    /// Sign of det[a; b; c]: +1 when the three points turn counter-clockwise in the face (the
    /// weights are non-negative with positive sums, so this is the orientation of w/Σw).
    static int orient(const Bary& a, const Bary& b, const Bary& c) {
        auto zero = [](const Bary& x, int k) { return x.exact ? !x.q[k] || sgn(*x.q[k]) == 0 : x.d[k] == 0; };
        for (int k = 0; k < 3; ++k)  // three points of one edge of the face: a zero column
            if (zero(a, k) && zero(b, k) && zero(c, k)) return 0;
        if (!a.exact && !b.exact && !c.exact)
            return fhr::orient3d(Vec3(a.d[0], a.d[1], a.d[2]), Vec3(b.d[0], b.d[1], b.d[2]),
                                 Vec3(c.d[0], c.d[1], c.d[2]), Vec3::Zero());
        // A filter on the rounded weights: each is within u of its rational (relative), and the
        // determinant's six products of three and their sum add at most 8u of the permanent; 1e-14
        // of it (about 90u) decides, else the rationals do.
        const auto& x = a.d;
        const auto& y = b.d;
        const auto& z = c.d;
        const double det = x[0] * (y[1] * z[2] - y[2] * z[1]) - x[1] * (y[0] * z[2] - y[2] * z[0]) +
                           x[2] * (y[0] * z[1] - y[1] * z[0]);
        const double permanent = std::fabs(x[0]) * (std::fabs(y[1] * z[2]) + std::fabs(y[2] * z[1])) +
                                 std::fabs(x[1]) * (std::fabs(y[0] * z[2]) + std::fabs(y[2] * z[0])) +
                                 std::fabs(x[2]) * (std::fabs(y[0] * z[1]) + std::fabs(y[1] * z[0]));
        if (std::fabs(det) > 1e-14 * permanent + 1e-300) return det > 0 ? 1 : -1;
        const Q a0 = as_q(a, 0), a1 = as_q(a, 1), a2 = as_q(a, 2), b0 = as_q(b, 0), b1 = as_q(b, 1), b2 = as_q(b, 2),
                c0 = as_q(c, 0), c1 = as_q(c, 1), c2 = as_q(c, 2);
        return sign(a0 * (b1 * c2 - b2 * c1) - a1 * (b0 * c2 - b2 * c0) + a2 * (b0 * c1 - b1 * c0));
    }

    /// w/Σw's coordinates 1 and 2: an affine chart of the face, exactly.
    static Q2 affine(const Bary& b) {
        const Q s = as_q(b, 0) + as_q(b, 1) + as_q(b, 2);
        return {as_q(b, 1) / s, as_q(b, 2) / s};
    }

    /// Whether weights w and x are proportional (one point), exactly: every w_a·x_b = w_b·x_a, each
    /// product held as fl(ab) plus its exact rounding error (fma) — rationals below 2⁻⁴⁰⁰, where
    /// that error could underflow.
    static bool proportional(const std::array<double, 3>& w, const std::array<double, 3>& x) {
        for (int a = 0; a < 3; ++a)
            for (int b = a + 1; b < 3; ++b) {
                const double p = w[a] * x[b], q = w[b] * x[a];
                if ((p != 0 && std::fabs(p) < 0x1p-400) || (q != 0 && std::fabs(q) < 0x1p-400)) {
                    if (Q(w[a]) * Q(x[b]) != Q(w[b]) * Q(x[a])) return false;
                } else if (p != q || std::fma(w[a], x[b], -p) != std::fma(w[b], x[a], -q)) {
                    return false;
                }
            }
        return true;
    }

    static std::array<double, 2> approx(const Bary& b) {
        const double s = b.d[0] + b.d[1] + b.d[2];
        return {b.d[1] / s, b.d[2] / s};
    }

    Vec3 position(const Point& p) const {
        Vec3 x = Vec3::Zero();
        double s = 0;
        for (int k = 0; k < p.size(); ++k) {
            const double w = p.w[k];
            x += w * dpos(p.v[k]);
            s += w;
        }
        return x / s;
    }

    /// The faces of D holding p: a vertex's ring, or one or two faces kept inline.
    struct FaceList {
        const std::uint32_t* first = nullptr;
        std::size_t n = 0;
        std::array<std::uint32_t, 2> own{};
        const std::uint32_t* begin() const { return first ? first : own.data(); }
        const std::uint32_t* end() const { return begin() + n; }
        std::size_t size() const { return n; }
    };

    FaceList faces_of(const Point& p) const {
        FaceList list;
        if (p.size() == 3) {
            list.own[list.n++] = p.face;
        } else if (p.size() == 1) {
            const std::vector<std::uint32_t>& ring = rings_[p.v[0]].faces;
            list.first = ring.data();
            list.n = ring.size();
        } else {
            for (HalfedgeId h : {dm().find_halfedge(VertexId(p.v[0]), VertexId(p.v[1])),
                                 dm().find_halfedge(VertexId(p.v[1]), VertexId(p.v[0]))})
                if (h.valid() && !dm().is_boundary(h)) list.own[list.n++] = dm().face(h).idx();
        }
        return list;
    }

    bool on_boundary(const Point& p) const {
        if (p.size() == 1) return dm().is_boundary(VertexId(p.v[0]));
        if (p.size() == 2) return faces_of(p).size() == 1;
        return false;
    }

    void make_rings() {
        const TriMesh& m = dm();
        rings_.resize(m.n_vertices());
        for (VertexId s : m.vertices()) {
            std::vector<HalfedgeId> cw;
            m.for_each_outgoing(s, [&](HalfedgeId h) { cw.push_back(h); });
            Ring& r = rings_[s.idx()];
            if (m.is_boundary(cw.front())) {
                // cw = [boundary, g1, …, g_{n−1}]: counter-clockwise the faces run from g_{n−1} to g1.
                r.closed = false;
                for (std::size_t i = cw.size() - 1; i >= 1; --i) {
                    r.spokes.push_back(m.to(cw[i]).idx());
                    r.faces.push_back(m.face(cw[i]).idx());
                }
                r.spokes.push_back(m.to(cw.front()).idx());
            } else {
                std::reverse(cw.begin(), cw.end());
                const auto lowest = std::min_element(cw.begin(), cw.end(), [&](HalfedgeId a, HalfedgeId b) {
                    return m.face(a).idx() < m.face(b).idx();
                });
                std::rotate(cw.begin(), lowest, cw.end());
                for (HalfedgeId h : cw) {
                    r.spokes.push_back(m.to(h).idx());
                    r.faces.push_back(m.face(h).idx());
                }
            }
        }
    }

    // ---- VMAP-2 -----------------------------------------------------------------------------
    CheckResult check_images() {
        Recorder rec("VMAP-2", title_2);
        const std::size_t n = ts_.points.size(), nd = ds_.points.size(), md = ds_.polygon_count();
        image_.assign(n, Point{});
        if (map_.records.size() != n)
            rec.fail([&] {
                return "the map has " + std::to_string(map_.records.size()) + " records but T has " +
                       std::to_string(n) + " vertices";
            });
        for (std::uint32_t u = 0; u < std::min(n, map_.records.size()); ++u) {
            const VertexImageRecord& r = map_.records[u];
            auto fail = [&](const std::string& what) {
                rec.fail(
                    [&] {
                        return "vertex " + std::to_string(u) + " of T (" + map_.source + " line " +
                               std::to_string(r.line) + "): " + what;
                    },
                    -1, u);
            };
            auto vertex_ok = [&](std::int64_t v) { return v >= 0 && static_cast<std::uint64_t>(v) < nd; };
            std::uint32_t face = none;
            std::array<double, 3> w{};  // in the face's corner order
            switch (r.ref) {
                case VertexImageRecord::Ref::none: fail("no image"); continue;
                case VertexImageRecord::Ref::face:
                    if (r.a < 0 || static_cast<std::uint64_t>(r.a) >= md) {
                        fail("face " + std::to_string(r.a) + " of D out of range (" + std::to_string(md) + " faces)");
                        continue;
                    }
                    face = static_cast<std::uint32_t>(r.a);
                    w = r.weights;
                    break;
                case VertexImageRecord::Ref::halfedge: {
                    if (!vertex_ok(r.a) || !vertex_ok(r.b)) {
                        fail("halfedge " + std::to_string(r.a) + " -> " + std::to_string(r.b) +
                             ": vertex of D out of range (" + std::to_string(nd) + " vertices)");
                        continue;
                    }
                    const HalfedgeId h = dm().find_halfedge(VertexId(static_cast<std::uint32_t>(r.a)),
                                                            VertexId(static_cast<std::uint32_t>(r.b)));
                    if (!h.valid() || dm().is_boundary(h)) {
                        fail("no face of D has the halfedge " + std::to_string(r.a) + " -> " + std::to_string(r.b));
                        continue;
                    }
                    face = dm().face(h).idx();
                    const auto t = dtri(face);
                    const int k = t[0] == r.a ? 0 : t[1] == r.a ? 1 : 2;
                    for (int c = 0; c < 3; ++c) w[(k + c) % 3] = r.weights[c];
                    break;
                }
                case VertexImageRecord::Ref::vertices: {
                    std::vector<std::uint32_t> vs;
                    bool ok = true;
                    for (std::int64_t c : r.corners)
                        if (c >= 0) {
                            ok = ok && vertex_ok(c);
                            if (ok) vs.push_back(static_cast<std::uint32_t>(c));
                        }
                    if (!ok) {
                        fail("a vertex of D out of range (" + std::to_string(nd) + " vertices)");
                        continue;
                    }
                    Point probe;
                    for (std::size_t k = 0; k < vs.size(); ++k) probe.v[k] = vs[k];
                    std::sort(probe.v.begin(), probe.v.begin() + static_cast<long>(vs.size()));
                    face = find_face(probe, vs.size());
                    if (face == none) {
                        fail("the vertices of D named are not a vertex, an edge or a face of D");
                        continue;
                    }
                    const auto t = dtri(face);
                    for (std::size_t k = 0; k < vs.size(); ++k)
                        w[t[0] == vs[k] ? 0 : t[1] == vs[k] ? 1 : 2] = r.weights[k];
                    break;
                }
            }
            if (!std::isfinite(w[0]) || !std::isfinite(w[1]) || !std::isfinite(w[2])) {
                fail("weights " + str(Vec3(w[0], w[1], w[2])) + " are not finite");
                continue;
            }
            if (std::min({w[0], w[1], w[2]}) < -weight_tolerance ||
                std::abs(w[0] + w[1] + w[2] - 1) > weight_tolerance) {
                fail("weights " + str(Vec3(w[0], w[1], w[2])) + " on face " + std::to_string(face) +
                     " are not barycentric (each >= -1e-12, sum 1 within 1e-12)");
                continue;
            }
            image_[u] = make_point(face, w, u);
        }
        rec.examined(n);
        return rec.done();
    }

    /// The face of D with the `count` vertices of `probe` as corners, or none.
    std::uint32_t find_face(const Point& probe, std::size_t count) const {
        if (count == 1) return rings_[probe.v[0]].faces.front();
        for (HalfedgeId h : {dm().find_halfedge(VertexId(probe.v[0]), VertexId(probe.v[1])),
                             dm().find_halfedge(VertexId(probe.v[1]), VertexId(probe.v[0]))}) {
            if (!h.valid() || dm().is_boundary(h)) continue;
            const std::uint32_t g = dm().face(h).idx();
            if (count == 2 || contains(g, probe)) return g;
        }
        return none;
    }

    /// The point w⁺/Σw⁺ of face g (w⁺: negative weights read as 0).
    Point make_point(std::uint32_t g, const std::array<double, 3>& w, std::uint32_t tvertex) const {
        const auto t = dtri(g);
        std::array<std::pair<std::uint32_t, double>, 3> vw;
        int n = 0;
        for (int c = 0; c < 3; ++c)
            if (w[c] > 0) vw[n++] = {t[c], w[c]};
        std::sort(vw.begin(), vw.begin() + n);
        Point p;
        for (int k = 0; k < n; ++k) {
            p.v[k] = vw[k].first;
            p.w[k] = vw[k].second;
        }
        p.tvertex = tvertex;
        p.face = g;
        return p;
    }

    // ---- VMAP-4 -----------------------------------------------------------------------------
    CheckResult check_topology() const {
        Recorder rec("VMAP-4", title_4);
        const Topology &tt = t_->topology, &td = d_->topology;
        std::vector<std::uint32_t> image(tt.count(), none), preimage(td.count(), none);
        std::vector<std::uint8_t> spans(tt.count(), 0);
        for (std::uint32_t u = 0; u < image_.size(); ++u) {
            const std::uint32_t c = tt.of(u), e = td.of(image_[u].v[0]);
            if (image[c] == none)
                image[c] = e;
            else if (image[c] != e && !spans[c]) {
                spans[c] = 1;
                rec.fail(
                    [&] {
                        return "the component of T at vertex " + std::to_string(tt.first_vertex[c]) +
                               " has images in two components of D (vertex " + std::to_string(u) + ")";
                    },
                    -1, u);
            }
        }
        for (std::uint32_t c = 0; c < tt.count(); ++c) {
            if (spans[c]) continue;
            const std::uint32_t e = image[c];
            const std::string tc = "the component of T at vertex " + std::to_string(tt.first_vertex[c]),
                              dc = "the component of D at vertex " + std::to_string(td.first_vertex[e]);
            if (preimage[e] != none) {
                rec.fail([&] { return tc + " and another map into " + dc; }, -1, tt.first_vertex[c]);
                continue;
            }
            preimage[e] = c;
            if (tt.chi[c] != td.chi[e])
                rec.fail(
                    [&] {
                        return "chi = " + std::to_string(tt.chi[c]) + " for " + tc + " but " +
                               std::to_string(td.chi[e]) + " for " + dc;
                    },
                    -1, tt.first_vertex[c]);
            else if (tt.loops[c] != td.loops[e])
                rec.fail(
                    [&] {
                        return tc + " has " + loops_text(tt.loops[c]) + " but " + dc + " has " +
                               loops_text(td.loops[e]);
                    },
                    -1, tt.first_vertex[c]);
        }
        for (std::uint32_t e = 0; e < td.count(); ++e)
            if (preimage[e] == none && std::find(image.begin(), image.end(), e) == image.end())
                rec.fail([&] {
                    return "the component of D at vertex " + std::to_string(td.first_vertex[e]) + " holds no image";
                });
        rec.examined(tt.count() + td.count());
        return rec.done();
    }

    // ---- VMAP-5: the rule `adjacent` --------------------------------------------------------
    /// The fan of ring(s) from position i over m + 1 faces, unfolded by spec/vertex_map.md's
    /// formula: P[t] is spoke i + t in the plane, s at the origin.
    std::vector<std::array<double, 2>> unfold(const Ring& ring, std::uint32_t s, std::size_t i, std::size_t m) const {
        const Vec3& o = dpos(s);
        auto e = [&](std::size_t t) {
            const Vec3& a = dpos(ring.spoke(i + t));
            return std::array<double, 3>{a.x() - o.x(), a.y() - o.y(), a.z() - o.z()};
        };
        auto dot = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
            return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        };
        std::vector<std::array<double, 2>> P(m + 2);
        std::array<double, 3> ei = e(0);
        P[0] = {std::sqrt(dot(ei, ei)), 0.0};
        for (std::size_t t = 0; t <= m; ++t) {
            const std::array<double, 3> ej = e(t + 1);
            const double d = dot(ei, ej);
            const std::array<double, 3> c{ei[1] * ej[2] - ei[2] * ej[1], ei[2] * ej[0] - ei[0] * ej[2],
                                          ei[0] * ej[1] - ei[1] * ej[0]};
            const double k = std::sqrt(dot(c, c)), l = dot(ei, ei);
            const double x = P[t][0], y = P[t][1];
            P[t + 1] = {(d * x - k * y) / l, (d * y + k * x) / l};
            ei = ej;
        }
        return P;
    }

    /// Point p (in fan face t = (s, spoke t, spoke t+1)) in the fan's chart, exactly.
    Q2 chart(const Point& p, const Ring& ring, std::uint32_t s, std::size_t i, std::size_t t,
             const std::vector<std::array<double, 2>>& P) const {
        const std::uint32_t a = ring.spoke(i + t), b = ring.spoke(i + t + 1);
        Q ws = 0, wa = 0, wb = 0;
        for (int k = 0; k < p.size(); ++k) {
            const Q w = weight_q(p, k);
            if (p.v[k] == s)
                ws = w;
            else if (p.v[k] == a)
                wa = w;
            else if (p.v[k] == b)
                wb = w;
        }
        const Q sum = ws + wa + wb;
        return {(wa * Q(P[t][0]) + wb * Q(P[t + 1][0])) / sum, (wa * Q(P[t][1]) + wb * Q(P[t + 1][1])) / sum};
    }

    struct Candidate {
        std::uint32_t s = none;
        std::size_t i = 0, m = 0;
        bool u_first = true;
        double length = std::numeric_limits<double>::infinity();
    };

    /// The straight segment of a candidate fan, when it crosses every inner spoke properly.
    bool valid_segment(const Q2& U, const Q2& V, const std::vector<std::array<double, 2>>& P, std::size_t m) const {
        const Q2 origin{0, 0};
        const Q2 d = sub(V, U);
        const int so = sign(cross(d, sub(origin, U)));
        if (so == 0) return false;
        for (std::size_t j = 1; j <= m; ++j) {
            const Q2 Pj{P[j][0], P[j][1]};
            const int sp = sign(cross(d, sub(Pj, U)));
            if (sp == 0 || sp == so) return false;
            const int su = sign(cross(Pj, U)), sv = sign(cross(Pj, V));
            if (su == 0 || sv == 0 || su == sv) return false;
        }
        return true;
    }

    CheckResult map_edges(VertexMapReport& report) {
        Recorder rec("VMAP-5", title_5);
        const TriMesh& t = tm();
        tangent_.assign(t.n_halfedges(), Tangent{});
        length_.assign(t.n_edges(), 0);
        for (EdgeId e : t.edges()) {
            const HalfedgeId h = TriMesh::halfedge(e, 0);
            const std::uint32_t u = t.from(h).idx(), v = t.to(h).idx();
            if (!map_edge(e, h, image_[u], image_[v])) {
                report.edges_without_image.emplace_back(std::min(u, v), std::max(u, v));
                rec.fail(
                    [&] {
                        return "edge (" + std::to_string(u) + ", " + std::to_string(v) +
                               ") of T: its ends' images share no face of D and no fan around a vertex of D "
                               "in which the straight segment stays";
                    },
                    -1, u);
            }
        }
        std::sort(report.edges_without_image.begin(), report.edges_without_image.end());
        rec.examined(t.n_edges());
        return rec.done();
    }

    bool map_edge(EdgeId e, HalfedgeId h, const Point& P, const Point& R) {
        const HalfedgeId g = TriMesh::twin(h);
        std::vector<std::uint32_t> common;
        for (std::uint32_t f : faces_of(P))
            if (contains(f, R)) common.push_back(f);
        if (!common.empty()) {
            for (std::uint32_t f : common) pieces_.push_back({f, P, R, e.idx()});
            tangent_[h.idx()] = {common.front(), R};
            tangent_[g.idx()] = {common.front(), P};
            length_[e.idx()] = (position(P) - position(R)).norm();
            return true;
        }
        // The fans: candidate vertices s ascending, f₀'s position, then m.
        std::vector<std::uint32_t> around;
        for (std::uint32_t f : faces_of(P))
            for (std::uint32_t v : dtri(f)) around.push_back(v);
        std::sort(around.begin(), around.end());
        around.erase(std::unique(around.begin(), around.end()), around.end());
        Candidate best;
        for (std::uint32_t s : around) {
            const Ring& ring = rings_[s];
            const std::size_t k = ring.k();
            std::vector<std::uint8_t> in_p(k), in_r(k);
            bool any_r = false;
            for (std::size_t i = 0; i < k; ++i) {
                in_p[i] = contains(ring.faces[i], P);
                in_r[i] = contains(ring.faces[i], R);
                any_r = any_r || in_r[i];
            }
            if (!any_r) continue;
            for (std::size_t i = 0; i < k; ++i) {
                if (!in_p[i] && !in_r[i]) continue;
                const std::size_t longest = ring.closed ? k - 2 : k - 1 - i;
                for (std::size_t m = 1; m <= longest; ++m) {
                    const std::size_t j = (i + m) % k;
                    const bool u_first = in_p[i] && in_r[j], v_first = in_r[i] && in_p[j];
                    if (!u_first && !v_first) continue;
                    const std::vector<std::array<double, 2>> F = unfold(ring, s, i, m);
                    const Point &first = u_first ? P : R, &last = u_first ? R : P;
                    const Q2 U = chart(first, ring, s, i, 0, F), V = chart(last, ring, s, i, m, F);
                    if (!valid_segment(U, V, F, m)) continue;
                    const double dx = U.x.get_d() - V.x.get_d(), dy = U.y.get_d() - V.y.get_d();
                    const double length = std::sqrt(dx * dx + dy * dy);
                    if (length < best.length) best = Candidate{s, i, m, u_first, length};
                }
            }
        }
        if (best.s == none) return false;
        const Ring& ring = rings_[best.s];
        const std::vector<std::array<double, 2>> F = unfold(ring, best.s, best.i, best.m);
        const Point &first = best.u_first ? P : R, &last = best.u_first ? R : P;
        const Q2 U = chart(first, ring, best.s, best.i, 0, F), V = chart(last, ring, best.s, best.i, best.m, F);
        const Q2 d = sub(V, U);
        std::vector<Point> x{first};
        for (std::size_t j = 1; j <= best.m; ++j) {
            const Q2 Pj{F[j][0], F[j][1]};
            const Q lambda = cross(d, U) / cross(d, Pj);
            const std::uint32_t a = ring.spoke(best.i + j);
            Point c;
            const bool s_low = best.s < a;
            c.v = {s_low ? best.s : a, s_low ? a : best.s, none};
            c.exact = static_cast<std::int32_t>(exact_.size());
            c.face = ring.face(best.i + j);
            exact_.push_back(s_low ? std::array<Q, 3>{1 - lambda, lambda, 0} : std::array<Q, 3>{lambda, 1 - lambda, 0});
            for (int k = 0; k < 2; ++k) c.w[k] = exact_.back()[k].get_d();
            x.push_back(c);
        }
        x.push_back(last);
        for (std::size_t t = 0; t <= best.m; ++t) pieces_.push_back({ring.face(best.i + t), x[t], x[t + 1], e.idx()});
        const HalfedgeId from_first = best.u_first ? h : g, from_last = best.u_first ? g : h;
        tangent_[from_first.idx()] = {ring.face(best.i), x[1]};
        tangent_[from_last.idx()] = {ring.face(best.i + best.m), x[best.m]};
        length_[e.idx()] = best.length;
        return true;
    }

    // ---- VMAP-6 -----------------------------------------------------------------------------
    /// A corner of the face off the line through a and b (a ≠ b), so that orient(r, x, y) orders
    /// the points x, y of that line: its sign is the same for every pair in the same order.
    static const Bary& off_line(const Bary& a, const Bary& b) {
        for (const Bary& c : corners)
            if (orient(a, b, c) != 0) return c;
        return corners[0];  // a = b: every order is 0
    }

    /// Whether two collinear closed segments (a1, b1), (a2, b2) of one face share a point.
    static bool collinear_overlap(const Bary& a1, const Bary& b1, const Bary& a2, const Bary& b2) {
        const bool first = orient(a1, b1, corners[0]) != 0 || orient(a1, b1, corners[1]) != 0;
        const Bary& r = first ? off_line(a1, b1) : off_line(a2, b2);
        if (!first && orient(a2, b2, r) == 0) {  // both of length 0: one point each
            const Q2 p = affine(a1), q = affine(a2);
            return p.x == q.x && p.y == q.y;
        }
        auto before = [&](const Bary& x, const Bary& y) { return orient(r, x, y) > 0; };
        const Bary &lo1 = before(b1, a1) ? b1 : a1, &hi1 = &lo1 == &a1 ? b1 : a1;
        const Bary &lo2 = before(b2, a2) ? b2 : a2, &hi2 = &lo2 == &a2 ? b2 : a2;
        return !before(hi1, lo2) && !before(hi2, lo1);
    }

    /// Whether two pieces of different edges of T meet beyond a common end (VMAP-6), exactly.
    bool meet(const Piece& A, const Piece& B) const {
        const std::uint32_t g = A.face;
        // Ends that are one vertex of T, the image of a common end of the two edges.
        const Point* shared_a = nullptr;
        const Point *other_a = nullptr, *other_b = nullptr;
        for (const Point* pa : {&A.a, &A.b})
            for (const Point* pb : {&B.a, &B.b})
                if (pa->tvertex != none && pa->tvertex == pb->tvertex) {
                    shared_a = pa;
                    other_a = pa == &A.a ? &A.b : &A.a;
                    other_b = pb == &B.a ? &B.b : &B.a;
                }
        if (shared_a) {
            const Bary o = coords(*shared_a, g), p = coords(*other_a, g), q = coords(*other_b, g);
            if (orient(o, p, q) != 0) return false;
            // Collinear from o: they overlap when p and q lie on one side of o.
            const Bary& r = off_line(o, p);
            const int sp = orient(r, o, p), sq = orient(r, o, q);
            return sp == 0 || sq == 0 || sp == sq;  // 0: a piece of length 0
        }
        const Bary a1 = coords(A.a, g), b1 = coords(A.b, g), a2 = coords(B.a, g), b2 = coords(B.b, g);
        const int o1 = orient(a1, b1, a2), o2 = orient(a1, b1, b2);
        if (o1 * o2 > 0) return false;
        const int o3 = orient(a2, b2, a1), o4 = orient(a2, b2, b1);
        if (o3 * o4 > 0) return false;
        if (o1 == 0 && o2 == 0) return collinear_overlap(a1, b1, a2, b2);
        return true;
    }

    CheckResult check_embedding(VertexMapReport& report) const {
        Recorder rec("VMAP-6", title_6);
        const TriMesh& t = tm();
        // Two vertices of T with one image: sorted by their vertex sets and normalized weights,
        // each compared exactly with the groups of equal images whose keys lie within 1e-9 of its
        // own (equal images have keys a few ulps apart); a group of c vertices is c(c-1)/2 pairs.
        std::vector<std::uint32_t> order(image_.size());
        std::iota(order.begin(), order.end(), 0u);
        auto key = [&](std::uint32_t u) {
            const Point& p = image_[u];
            const double s = p.w[0] + p.w[1] + p.w[2];
            return std::make_tuple(p.v, p.w[0] / s, p.w[1] / s, u);
        };
        std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return key(a) < key(b); });
        auto equal = [&](const Point& p, const Point& q) { return proportional(p.w, q.w); };
        std::uint64_t coincident = 0;
        std::vector<std::pair<std::uint32_t, std::uint64_t>> groups;  // (first vertex, size) of the window's groups
        for (std::size_t i = 0; i < order.size(); ++i) {
            const std::uint32_t u = order[i];
            const Point& p = image_[u];
            std::erase_if(groups, [&](const auto& g) {
                return image_[g.first].v != p.v || std::get<1>(key(u)) - std::get<1>(key(g.first)) > 1e-9;
            });
            auto same =
                std::find_if(groups.begin(), groups.end(), [&](const auto& g) { return equal(image_[g.first], p); });
            if (same == groups.end()) {
                groups.emplace_back(u, 1);
                continue;
            }
            const std::uint32_t x = std::min(same->first, u), y = std::max(same->first, u);
            for (std::uint64_t k = 0; k < same->second; ++k)  // a pair with each vertex of the group
                rec.fail(
                    [&] {
                        return "vertices " + std::to_string(x) + " and " + std::to_string(y) + " of T have one image";
                    },
                    -1, x, p.face);
            coincident += same->second++;
        }
        // The pieces of each face of D in a grid over the face's affine chart [0,1]².
        const std::size_t md = ds_.polygon_count();
        std::vector<std::uint32_t> per_face(md, 0);
        for (const Piece& p : pieces_) ++per_face[p.face];
        std::vector<std::uint64_t> offset(md + 1, 0);
        std::vector<std::uint32_t> side(md);
        for (std::size_t g = 0; g < md; ++g) {
            side[g] =
                static_cast<std::uint32_t>(std::clamp(std::sqrt(static_cast<double>(per_face[g]) / 2), 1.0, 4096.0));
            offset[g + 1] = offset[g] + std::uint64_t{side[g]} * side[g];
        }
        std::vector<std::pair<std::uint64_t, std::uint32_t>> cells;
        for (std::uint32_t i = 0; i < pieces_.size(); ++i) {
            const Piece& p = pieces_[i];
            // A piece of length 0 joins two vertices of T with one image, counted above.
            if (p.a.tvertex != none && p.b.tvertex != none && p.a.v == p.b.v && equal(p.a, p.b)) continue;
            const auto a = approx(coords(p.a, p.face)), b = approx(coords(p.b, p.face));
            const double n = side[p.face];
            auto cell = [&](double x) { return static_cast<std::uint64_t>(std::clamp(std::floor(x * n), 0.0, n - 1)); };
            constexpr double grow = 1e-9;  // the rounding of `approx`, far below it
            const std::uint64_t x0 = cell(std::min(a[0], b[0]) - grow), x1 = cell(std::max(a[0], b[0]) + grow),
                                y0 = cell(std::min(a[1], b[1]) - grow), y1 = cell(std::max(a[1], b[1]) + grow);
            for (std::uint64_t x = x0; x <= x1; ++x)
                for (std::uint64_t y = y0; y <= y1; ++y) cells.emplace_back(offset[p.face] + x * side[p.face] + y, i);
        }
        std::sort(cells.begin(), cells.end());
        std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
        for (std::size_t a = 0; a < cells.size();) {
            std::size_t b = a;
            while (b < cells.size() && cells[b].first == cells[a].first) ++b;
            for (std::size_t i = a; i < b; ++i)
                for (std::size_t j = i + 1; j < b; ++j) {
                    const Piece &P = pieces_[cells[i].second], &R = pieces_[cells[j].second];
                    if (P.edge == R.edge || !meet(P, R)) continue;
                    pairs.emplace_back(std::min(P.edge, R.edge), std::max(P.edge, R.edge));
                }
            a = b;
        }
        std::sort(pairs.begin(), pairs.end());
        pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
        for (const auto& [e1, e2] : pairs) {
            const HalfedgeId h1 = TriMesh::halfedge(EdgeId(e1), 0), h2 = TriMesh::halfedge(EdgeId(e2), 0);
            rec.fail(
                [&] {
                    return "the images of edges (" + std::to_string(t.from(h1).idx()) + ", " +
                           std::to_string(t.to(h1).idx()) + ") and (" + std::to_string(t.from(h2).idx()) + ", " +
                           std::to_string(t.to(h2).idx()) + ") of T meet beyond a common end";
                },
                -1, t.from(h1).idx());
        }
        report.crossing_pairs = pairs.size() + coincident;
        rec.examined(image_.size() + t.n_edges());
        return rec.done();
    }

    // ---- tangents around a point of D (VMAP-7, VMAP-8) -------------------------------------
    /// The sector of tangent `x` around the image p of a vertex of T: around a vertex s of D,
    /// 2i for spoke i and 2i + 1 for the inside of face i of ring(s); around a point of an edge
    /// (a, b) of D with face L on the left of a → b: 0 toward b, 1 in L, 2 toward a, 3 in the other
    /// face; in a face: 0 or 1, the two sides of the line from p to the face's first corner.
    int sector(const Point& p, const Tangent& x) const {
        const Point& q = x.q;
        if (p.size() == 1) {
            const std::uint32_t s = p.v[0];
            const Ring& ring = rings_[s];
            // Along a spoke when q's vertices are s and one spoke.
            if (q.size() <= 2) {
                std::uint32_t other = none;
                bool edge = true;
                for (int k = 0; k < q.size(); ++k)
                    if (q.v[k] != s) {
                        if (other != none) edge = false;
                        other = q.v[k];
                    }
                if (edge && other != none)
                    for (std::size_t i = 0; i < ring.spokes.size(); ++i)
                        if (ring.spokes[i] == other) return static_cast<int>(2 * i);
            }
            for (std::size_t i = 0; i < ring.k(); ++i)
                if (ring.faces[i] == x.face) return static_cast<int>(2 * i + 1);
            return -1;  // unreachable for a first piece, which starts at s
        }
        if (p.size() == 2) {
            const auto [a, b, left, right] = edge_sides(p);
            if (q.size() <= 2 && (q.v[0] == a || q.v[0] == b) && (q.size() == 1 || q.v[1] == a || q.v[1] == b)) {
                // Along the edge: toward b when q and b lie on one side of p (ordered from the
                // third corner of face `left`).
                const auto t = dtri(left);
                const int ib = t[0] == b   ? 0
                               : t[1] == b ? 1
                                           : 2,
                          ir = t[0] != a && t[0] != b   ? 0
                               : t[1] != a && t[1] != b ? 1
                                                        : 2;
                const Bary o = coords(p, left), y = coords(q, left);
                return orient(corners[ir], o, y) == orient(corners[ir], o, corners[ib]) ? 0 : 2;
            }
            return x.face == left ? 1 : 3;
        }
        const Bary o = coords(p, p.face), y = coords(q, p.face);
        const int side = orient(o, corners[0], y);
        if (side > 0) return 0;
        if (side < 0) return 1;
        return orient(o, corners[1], y) == orient(o, corners[1], corners[0])
                   ? 0
                   : 1;  // on the line: toward the first corner or away
    }

    /// The edge (a, b) of D holding p, oriented so that face `left` has a → b; `right` the other face or none.
    std::tuple<std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t> edge_sides(const Point& p) const {
        HalfedgeId h = dm().find_halfedge(VertexId(p.v[0]), VertexId(p.v[1]));
        if (dm().is_boundary(h)) h = TriMesh::twin(h);
        const HalfedgeId o = TriMesh::twin(h);
        return {dm().from(h).idx(), dm().to(h).idx(), dm().face(h).idx(),
                dm().is_boundary(o) ? none : dm().face(o).idx()};
    }

    /// Whether tangent y comes strictly after tangent x counter-clockwise, within one turn
    /// starting at the sector order's origin (`sx`, `sy` their sectors).
    bool before(const Point& p, const Tangent& x, int sx, const Tangent& y, int sy) const {
        if (sx != sy) return sx < sy;
        if (p.size() == 1 && sx % 2 == 0) return false;  // one spoke: one direction
        if (p.size() == 2 && sx % 2 == 0) return false;  // along the edge
        const std::uint32_t g = p.size() == 3 ? p.face : x.face;
        return orient(coords(p, g), coords(x.q, g), coords(y.q, g)) > 0;
    }

    /// The faces of D holding the first piece of tangent x (one, or two along an edge of D).
    FaceList piece_faces(const Point& p, const Tangent& x) const {
        FaceList faces;
        for (std::uint32_t f : faces_of(x.q))
            if (contains(f, p) && faces.n < 2) faces.own[faces.n++] = f;
        return faces;
    }

    /// VMAP-7 at one corner: tangent y turns counter-clockwise from x by an angle in (0, π).
    bool convex(const Point& p, const Tangent& x, const Tangent& y) const {
        const FaceList fx = piece_faces(p, x), fy = piece_faces(p, y);
        for (std::uint32_t g : fx)
            if (std::find(fy.begin(), fy.end(), g) != fy.end())
                return orient(coords(p, g), coords(x.q, g), coords(y.q, g)) > 0;
        // Different faces: unfold the faces swept from x to y around p.
        const int sx = sector(p, x);
        if (p.size() == 1) {
            const int sy = sector(p, y);
            const std::uint32_t s = p.v[0];
            const Ring& ring = rings_[s];
            const auto k = static_cast<int>(ring.k());
            const int i = sx / 2;                             // the face after a spoke, or x's face
            const int j = sy % 2 == 1 ? sy / 2 : sy / 2 - 1;  // the face before a spoke, or y's face
            int m = j - i;
            if (ring.closed)
                m = ((m % k) + k) % k;
            else if (m < 0)
                return false;  // the sweep would leave D
            const auto P = unfold(ring, s, static_cast<std::size_t>(i), static_cast<std::size_t>(m));
            const Q2 X = chart(x.q, ring, s, static_cast<std::size_t>(i), 0, P),
                     Y = chart(y.q, ring, s, static_cast<std::size_t>(i), static_cast<std::size_t>(m), P);
            for (int t = 1; t <= m; ++t)
                if (sign(cross(X, Q2{P[static_cast<std::size_t>(t)][0], P[static_cast<std::size_t>(t)][1]})) <= 0)
                    return false;
            return sign(cross(X, Y)) > 0;
        }
        // On an edge (a, b): the two faces unfolded as the fan of ring(a) around the spoke b.
        const auto sides = edge_sides(p);
        const std::uint32_t a = std::get<0>(sides), b = std::get<1>(sides), right = std::get<3>(sides);
        const Ring& ring = rings_[a];
        std::size_t t = 0;
        while (ring.spokes[t] != b) ++t;
        const std::size_t i = ring.closed ? (t + ring.k() - 1) % ring.k() : t - 1;  // the face before spoke b: right
        const auto P = unfold(ring, a, i, 1);
        auto at = [&](const Point& q, std::uint32_t f) { return chart(q, ring, a, i, f == right ? 0 : 1, P); };
        const Q2 o = at(p, right), X = sub(at(x.q, x.face), o), Y = sub(at(y.q, y.face), o);
        // From L (sector 1) to the right face the sweep passes toward a; from the right face, toward b.
        const Q2 through = sx == 1 ? sub(Q2{0, 0}, o) : sub(Q2{P[1][0], P[1][1]}, o);
        return sign(cross(X, through)) > 0 && sign(cross(X, Y)) > 0;
    }

    /// T's outgoing halfedges of u counter-clockwise; for a boundary vertex from one boundary
    /// edge to the other through the faces.
    std::vector<HalfedgeId> rotation(VertexId u) const {
        std::vector<HalfedgeId> cw;
        tm().for_each_outgoing(u, [&](HalfedgeId h) { cw.push_back(h); });
        if (tm().is_boundary(cw.front())) {
            std::vector<HalfedgeId> ccw(cw.rbegin(), cw.rend() - 1);
            ccw.push_back(cw.front());
            return ccw;
        }
        return {cw.rbegin(), cw.rend()};
    }

    CheckResult check_corners(VertexMapReport& report) const {
        Recorder rec("VMAP-7", title_7);
        const TriMesh& t = tm();
        for (std::uint32_t f = 0; f < ts_.polygon_count(); ++f) {
            const auto c = ttri(f);
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t u = c[k], v = c[(k + 1) % 3], w = c[(k + 2) % 3];
                const HalfedgeId hv = t.find_halfedge(VertexId(u), VertexId(v)),
                                 hw = t.find_halfedge(VertexId(u), VertexId(w));
                const Tangent &x = tangent_[hv.idx()], &y = tangent_[hw.idx()];
                if (x.face == none || y.face == none || convex(image_[u], x, y)) continue;
                report.folded.push_back(f);
                rec.fail(
                    [&] {
                        return "face " + std::to_string(f) + " (" + std::to_string(c[0]) + ", " + std::to_string(c[1]) +
                               ", " + std::to_string(c[2]) + ") of T is folded: at vertex " + std::to_string(u) +
                               " its edges' images do not turn counter-clockwise by less than pi";
                    },
                    f, u, image_[u].face);
                break;
            }
        }
        rec.examined(ts_.polygon_count());
        return rec.done();
    }

    CheckResult check_winding() const {
        Recorder rec("VMAP-8", title_8);
        const TriMesh& t = tm();
        for (VertexId u : t.vertices()) {
            const Point& p = image_[u.idx()];
            const bool boundary = t.is_boundary(u);
            if (boundary != on_boundary(p)) continue;  // VMAP-9's failure
            const std::vector<HalfedgeId> hs = rotation(u);
            if (std::any_of(hs.begin(), hs.end(), [&](HalfedgeId h) { return tangent_[h.idx()].face == none; }))
                continue;
            std::vector<int> sectors;
            for (HalfedgeId h : hs) sectors.push_back(sector(p, tangent_[h.idx()]));
            std::size_t turns = 0;
            const std::size_t n = hs.size(), steps = boundary ? n - 1 : n;
            for (std::size_t i = 0; i < steps; ++i) {
                const std::size_t j = (i + 1) % n;
                if (!before(p, tangent_[hs[i].idx()], sectors[i], tangent_[hs[j].idx()], sectors[j])) ++turns;
            }
            if (turns == (boundary ? 0u : 1u)) continue;
            rec.fail(
                [&] {
                    return "around vertex " + std::to_string(u.idx()) + " of T the images of its " + std::to_string(n) +
                           " edges " +
                           (boundary ? "turn back " + std::to_string(turns) + " times"
                                     : "wind " + std::to_string(turns) + " times") +
                           " (" + (boundary ? "0" : "1") + " expected)";
                },
                -1, u.idx(), p.face);
        }
        rec.examined(t.n_vertices());
        return rec.done();
    }

    CheckResult check_boundary() const {
        Recorder rec("VMAP-9", title_9);
        const TriMesh& t = tm();
        for (VertexId u : t.vertices())
            if (!t.is_boundary(u) && on_boundary(image_[u.idx()]))
                rec.fail(
                    [&] {
                        return "interior vertex " + std::to_string(u.idx()) +
                               " of T has its image on the boundary of D";
                    },
                    -1, u.idx(), image_[u.idx()].face);
        for (EdgeId e : t.edges()) {
            if (!t.is_boundary(e)) continue;
            const HalfedgeId h = TriMesh::halfedge(e, 0);
            const Point &a = image_[t.from(h).idx()], &b = image_[t.to(h).idx()];
            std::vector<std::uint32_t> vs;
            for (const Point* p : {&a, &b})
                for (int k = 0; k < p->size(); ++k) vs.push_back(p->v[k]);
            std::sort(vs.begin(), vs.end());
            vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
            Point span;
            for (std::size_t k = 0; k < std::min<std::size_t>(vs.size(), 3); ++k) span.v[k] = vs[k];
            const bool inside =
                vs.size() == 1 ? dm().is_boundary(VertexId(vs[0])) : vs.size() == 2 && on_boundary(span);
            if (!inside)
                rec.fail(
                    [&] {
                        return "boundary edge (" + std::to_string(t.from(h).idx()) + ", " +
                               std::to_string(t.to(h).idx()) + ") of T has an image off the boundary of D";
                    },
                    -1, t.from(h).idx());
        }
        rec.examined(t.n_vertices() + t.n_edges());
        return rec.done();
    }

    // ---- figures ----------------------------------------------------------------------------
    Distortion distortion() const {
        const TriMesh& t = tm();
        return summarize(ts_.polygon_count(), [&](std::size_t f) {
            const auto c = ttri(static_cast<std::uint32_t>(f));
            auto len = [&](std::uint32_t a, std::uint32_t b) {
                return length_[TriMesh::edge(t.find_halfedge(VertexId(a), VertexId(b))).idx()];
            };
            const double l01 = len(c[0], c[1]), l02 = len(c[0], c[2]), l12 = len(c[1], c[2]);
            // The image laid flat from its side lengths; a broken triangle inequality makes it
            // collinear (y = 0), hence degenerate (DIST-2).
            const double x = (l01 * l01 + l02 * l02 - l12 * l12) / (2 * l01), y2 = l02 * l02 - x * x;
            const double y = y2 > 0 && std::isfinite(y2) ? std::sqrt(y2) : 0.0;
            return face_stretch(Vec3::Zero(), Vec3(l01, 0, 0), Vec3(std::isfinite(x) ? x : 0, y, 0), ts_.points[c[0]],
                                ts_.points[c[1]], ts_.points[c[2]]);
        });
    }
};

}  // namespace

VertexMapReport verify_vertex_map(const VertexMapFile& map, const PolygonSoup& T, const PolygonSoup& D, VertexMapRule) {
    return Checker(map, T, D).run();
}

}  // namespace fhr::exchange
