// FHR exchange — `fhr verify` for UV atlases: ATLAS-1..8 of spec/atlas.md, in order.
//   ATLAS-1  every face a triangle, every corner with texture coordinates    (the reader)
//   ATLAS-2  the welded surface S an orientable manifold, consistently wound  (spec/mesh.md)
//   ATLAS-3  every UV triangle non-degenerate                                 (exact orient2d)
//   ATLAS-4  no fold: each face has its chart's sign; mirrored charts counted
//   ATLAS-5  no crack: no T-vertex on ∂S, no edge torn by rounding in UV
//   ATLAS-6  no two UV triangles of one texture with intersecting interiors  (exact)
//   ATLAS-7  contacts beyond shared corners reported (invalid with --strict) (exact)
//   ATLAS-8  with the input mesh T: S has T's topology and lies on T, T's vertices on S
// Decisions: welding by exactly equal 3D positions where the file's own indices leave a boundary
// (PLY writers duplicate vertices at seams; coincident vertices inside the surface stay apart);
// charts by exactly equal UV points across an edge; signs, overlaps and contacts decided by exact
// orient2d on the numbers read, so no fold or overlap can pass by rounding; the candidate pairs of
// ATLAS-6/7 from a uniform grid per texture, each pair tested once.
#include <fhr/exchange/atlas.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>

#include <gmpxx.h>

#include <fhr/core/build.hpp>
#include <fhr/core/errors.hpp>
#include <fhr/core/detail/predicates.hpp>
#include <fhr/exchange/detail/checks.hpp>
#include <fhr/io/read.hpp>

namespace fhr::exchange {

using namespace detail;  // the checks' shared parts (detail/checks.hpp)

// ---- ATLAS-1: reading ------------------------------------------------------------------------

Atlas atlas_from_soup(PolygonSoup soup) {
    const SoupTexture& tex = soup.texture;
    Atlas a;
    a.source = soup.source;
    const auto fail = [&](std::size_t p, const std::string& problem) {
        throw InvalidInput(soup.source, p < soup.polygon_line.size() ? soup.polygon_line[p] : 0,
                           "face " + std::to_string(p) + ": " + problem);
    };
    a.faces.reserve(soup.polygon_count());
    a.face_uv.reserve(soup.polygon_count());
    for (std::size_t p = 0; p < soup.polygon_count(); ++p) {
        if (soup.polygon_size(p) != 3)
            fail(p, "has " + std::to_string(soup.polygon_size(p)) + " corners (an atlas is judged on triangles)");
        Triangle t, uv;
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t i = soup.offsets[p] + static_cast<std::uint32_t>(k);
            t[k] = soup.indices[i];
            uv[k] = i < tex.corner_uv.size() ? tex.corner_uv[i] : SoupTexture::none;
            if (uv[k] == SoupTexture::none) fail(p, "corner " + std::to_string(k) + " has no texture coordinates");
        }
        a.faces.push_back(t);
        a.face_uv.push_back(uv);
    }
    a.points = std::move(soup.points);
    a.uv = tex.uv;
    a.face_texture = tex.polygon_texture;
    a.face_texture.resize(a.faces.size(), 0);
    a.texture_names = tex.texture_names;
    a.rounding = tex.rounding;
    return a;
}

Atlas parse_atlas(std::string_view bytes, const std::string& name) {
    const bool ply = bytes.substr(0, 4) == "ply\n" || bytes.substr(0, 5) == "ply\r\n";
    return atlas_from_soup(ply ? io::parse_ply(bytes, name, true) : io::parse_obj(bytes, name, true));
}

Atlas read_atlas(const std::string& path) { return parse_atlas(io::read_bytes(path), path); }

bool AtlasReport::valid() const { return first_failure() == nullptr; }

const CheckResult* AtlasReport::first_failure() const { return first_judged_failure(checks); }

namespace {

using Vec2 = Eigen::Vector2d;

constexpr const char* title_1 = "every face a triangle, every corner with texture coordinates";
constexpr const char* title_2 = "the welded surface is an orientable manifold, consistently wound";
constexpr const char* title_3 = "every UV triangle is non-degenerate";
constexpr const char* title_4 = "no fold: every face has its chart's orientation";
constexpr const char* title_5 = "no crack: no T-vertex, no edge torn in UV";
constexpr const char* title_6 = "no two UV triangles overlap";
constexpr const char* title_7 = "contacts beyond shared corners";
constexpr const char* title_8 = "the atlas's surface is the input mesh's";

std::string str(const UV& p) { return "(" + num(p[0]) + ", " + num(p[1]) + ")"; }

/// Union–find over faces: the charts, and the groups of overlapping faces.
class UnionFind {
public:
    explicit UnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), std::uint32_t{0}); }
    std::uint32_t find(std::uint32_t x) {
        while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
        return x;
    }
    void join(std::uint32_t a, std::uint32_t b) {
        a = find(a);
        b = find(b);
        if (a != b) parent_[std::max(a, b)] = std::min(a, b);
    }

private:
    std::vector<std::uint32_t> parent_;
};

/// An interior edge of S: its two faces, and in each the corner the edge starts from.
struct Edge {
    std::uint32_t f, g;
    std::uint8_t cf, cg;
};

class AtlasVerifier {
public:
    AtlasVerifier(const Atlas& atlas, const TriMesh* input, const AtlasOptions& options, Executor& executor)
        : a_(atlas), input_(input), options_(options), executor_(executor) {}

    AtlasReport run();

private:
    const Atlas& a_;
    const TriMesh* input_;
    const AtlasOptions& options_;
    Executor& executor_;
    AtlasReport report_;
    std::vector<std::uint32_t> weld_;          // point → welded vertex
    std::vector<Vec3> welded_;                 // welded vertex positions
    std::vector<Triangle> w_faces_;            // faces over welded vertices
    std::optional<TriMesh> surface_;           // S, when ATLAS-2 holds
    std::vector<Edge> edges_;                  // interior edges of S
    std::vector<std::uint32_t> chart_;         // per face: its chart (numbered by lowest face)
    std::vector<std::uint32_t> chart_number_;  // chart root → 0, 1, … in order of lowest face
    std::vector<int> sign_;                    // per face: exact orient2d of its UV triangle

    std::size_t n() const { return a_.faces.size(); }
    const UV& uv(std::uint32_t f, int k) const { return a_.uv[a_.face_uv[f][k]]; }
    Vec2 uv2(std::uint32_t f, int k) const { return {uv(f, k)[0], uv(f, k)[1]}; }
    std::int64_t chart_of(std::uint32_t f) const { return chart_number_[chart_[f]]; }
    double signed_area(std::uint32_t f) const {  // rounded: for the figures
        const UV &p = uv(f, 0), &q = uv(f, 1), &r = uv(f, 2);
        return 0.5 * ((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]));
    }

    void weld();
    CheckResult check_surface();
    CheckResult check_degenerate();
    void find_edges_and_charts();
    CheckResult check_folds();
    CheckResult check_cracks();
    void find_pairs(Recorder& overlaps, Recorder& contacts);
    using Pairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;
    void find_pairs_in(const std::vector<std::uint32_t>& faces, Pairs& found_overlap, Pairs& found_contact);
    std::array<Vec2, 3> ccw(std::uint32_t f) const;  // face f's UV triangle, counter-clockwise
    void judge_pair(std::uint32_t f, std::uint32_t g, Pairs& found_overlap, Pairs& found_contact) const;
    CheckResult check_input();
    void figures();
};

void AtlasVerifier::weld() {
    std::vector<std::uint8_t> used(a_.points.size(), 0);
    for (const Triangle& t : a_.faces)
        for (std::uint32_t v : t)
            if (v < used.size()) used[v] = 1;
    std::vector<std::uint32_t> order;
    for (std::uint32_t p = 0; p < used.size(); ++p)
        if (used[p]) order.push_back(p);
    const auto less = [&](std::uint32_t x, std::uint32_t y) {
        const Vec3 &p = a_.points[x], &q = a_.points[y];
        return std::tie(p[0], p[1], p[2], x) < std::tie(q[0], q[1], q[2], y);
    };
    std::sort(order.begin(), order.end(), less);
    // Points at one position are welded when they lie on the boundary of the surface the file's
    // own indices make (a seam of a writer that duplicates vertices there); points at one position
    // inside that surface are distinct vertices that happen to coincide, and stay apart.
    std::vector<std::uint8_t> on_index_boundary;
    const bool coincide = std::adjacent_find(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) {
                              return a_.points[x] == a_.points[y];
                          }) != order.end();
    if (coincide) {
        std::vector<std::uint64_t> edges;
        edges.reserve(3 * n());
        for (const Triangle& t : a_.faces)
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t a = t[k], b = t[(k + 1) % 3];
                edges.push_back(std::uint64_t{std::min(a, b)} << 32 | std::max(a, b));
            }
        std::sort(edges.begin(), edges.end());
        on_index_boundary.assign(a_.points.size(), 0);
        for (std::size_t e = 0; e < edges.size();) {
            std::size_t f = e;
            while (f < edges.size() && edges[f] == edges[e]) ++f;
            if (f - e == 1) on_index_boundary[edges[e] >> 32] = on_index_boundary[edges[e] & 0xffffffffu] = 1;
            e = f;
        }
    }
    weld_.assign(a_.points.size(), SoupTexture::none);
    for (std::size_t i = 0; i < order.size();) {
        std::size_t end = i;
        while (end < order.size() && a_.points[order[end]] == a_.points[order[i]]) ++end;
        std::uint32_t seam = SoupTexture::none;  // the welded vertex of this position's boundary points
        for (std::size_t k = i; k < end; ++k) {
            const std::uint32_t p = order[k];
            const bool weld_here = end - i > 1 && on_index_boundary[p];
            if (!weld_here || seam == SoupTexture::none) welded_.push_back(a_.points[p]);
            weld_[p] = static_cast<std::uint32_t>(welded_.size() - 1);
            if (weld_here && seam == SoupTexture::none) seam = weld_[p];
            if (weld_here) weld_[p] = seam;
        }
        i = end;
    }
    // Welded vertices numbered in order of their lowest point, so that messages follow the file.
    std::vector<std::uint32_t> first(welded_.size(), SoupTexture::none);
    for (std::uint32_t p : order) first[weld_[p]] = std::min(first[weld_[p]], p);
    std::vector<std::uint32_t> rank(welded_.size());
    std::iota(rank.begin(), rank.end(), std::uint32_t{0});
    std::sort(rank.begin(), rank.end(), [&](std::uint32_t x, std::uint32_t y) { return first[x] < first[y]; });
    std::vector<std::uint32_t> renumber(welded_.size());
    std::vector<Vec3> positions(welded_.size());
    for (std::uint32_t r = 0; r < rank.size(); ++r) {
        renumber[rank[r]] = r;
        positions[r] = welded_[rank[r]];
    }
    welded_ = std::move(positions);
    for (std::uint32_t& w : weld_)
        if (w != SoupTexture::none) w = renumber[w];
    w_faces_.reserve(n());
    for (const Triangle& t : a_.faces) w_faces_.push_back({weld_[t[0]], weld_[t[1]], weld_[t[2]]});
    report_.vertices = welded_.size();
}

// ---- ATLAS-2 ---------------------------------------------------------------------------------
CheckResult AtlasVerifier::check_surface() {
    Recorder rec("ATLAS-2", title_2);
    rec.examined(n());
    PolygonSoup soup;
    soup.source = a_.source;
    soup.points = welded_;
    for (const Triangle& t : w_faces_) soup.add_polygon(t.data(), 3);
    try {
        BuildLog log;
        TriMesh mesh = build_trimesh(soup, BuildOptions{}, log);
        // The file's own winding must be consistent: build_trimesh turns faces to agree with their
        // component (and a closed component outward, which the atlas's orientation does not depend
        // on), so in each component either every face was turned or none.
        const std::vector<Triangle> built = mesh.triangles();
        const Components components = connected_components(mesh);
        std::vector<std::int8_t> turned(components.count, -1);  // per component: unknown, no, yes
        for (std::uint32_t f = 0; f < n(); ++f) {
            const Triangle &t = w_faces_[f], &b = built[f];
            const bool same =
                (b[0] == t[0] && b[1] == t[1]) || (b[0] == t[1] && b[1] == t[2]) || (b[0] == t[2] && b[1] == t[0]);
            std::int8_t& c = turned[components.vertex_component[VertexId(t[0])]];
            if (c < 0)
                c = same ? 0 : 1;
            else if (c != (same ? 0 : 1))
                rec.fail(
                    [&] {
                        return "face " + std::to_string(f) +
                               " is wound against its neighbours: the surface is not "
                               "consistently oriented";
                    },
                    f);
        }
        if (rec.failures() == 0) surface_.emplace(std::move(mesh));
    } catch (const InvalidInput& e) {
        rec.fail([&] { return "the welded surface: " + e.problem(); });
    }
    return rec.done();
}

// ---- ATLAS-3 ---------------------------------------------------------------------------------
CheckResult AtlasVerifier::check_degenerate() {
    Recorder rec("ATLAS-3", title_3);
    sign_.resize(n());
    for (std::uint32_t f = 0; f < n(); ++f) {
        sign_[f] = orient2d(uv2(f, 0), uv2(f, 1), uv2(f, 2));
        if (sign_[f] == 0 && rec.fail(
                                 [&] {
                                     return "face " + std::to_string(f) + ": its UV triangle " + str(uv(f, 0)) + " " +
                                            str(uv(f, 1)) + " " + str(uv(f, 2)) + " is degenerate";
                                 },
                                 f))
            rec.locate(-1, uv(f, 0));
    }
    rec.examined(n());
    return rec.done();
}

void AtlasVerifier::find_edges_and_charts() {
    // The interior edges of S, from its halfedges; each edge's corners in the file's two faces.
    const TriMesh& s = *surface_;
    const auto corner = [&](std::uint32_t f, std::uint32_t v) {
        const Triangle& t = w_faces_[f];
        return static_cast<std::uint8_t>(t[0] == v ? 0 : t[1] == v ? 1 : 2);
    };
    UnionFind charts(n());
    for (HalfedgeId h : s.halfedges()) {
        const HalfedgeId o = TriMesh::twin(h);
        if (o.idx() < h.idx() || s.is_boundary(h) || s.is_boundary(o)) continue;
        Edge e{s.face(h).idx(), s.face(o).idx(), 0, 0};
        // As the file winds them: a→b in f, b→a in g.
        const std::uint32_t a = s.from(h).idx(), b = s.to(h).idx();
        const std::uint8_t ca = corner(e.f, a);
        const bool forward = w_faces_[e.f][(ca + 1) % 3] == b;
        e.cf = forward ? ca : corner(e.f, b);
        e.cg = corner(e.g, w_faces_[e.f][(e.cf + 1) % 3]);  // b in g
        edges_.push_back(e);
        const bool joined = a_.face_texture[e.f] == a_.face_texture[e.g] && uv(e.f, e.cf) == uv(e.g, (e.cg + 1) % 3) &&
                            uv(e.f, (e.cf + 1) % 3) == uv(e.g, e.cg);
        if (joined) charts.join(e.f, e.g);
    }
    chart_.resize(n());
    chart_number_.assign(n(), SoupTexture::none);
    for (std::uint32_t f = 0; f < n(); ++f) {
        chart_[f] = charts.find(f);
        if (chart_number_[chart_[f]] == SoupTexture::none)
            chart_number_[chart_[f]] = static_cast<std::uint32_t>(report_.charts++);
    }
}

// ---- ATLAS-4 ---------------------------------------------------------------------------------
CheckResult AtlasVerifier::check_folds() {
    Recorder rec("ATLAS-4", title_4);
    // The chart's sign is the exact sign of the sum of its faces' doubled signed areas: a
    // compensated sum decides it when it is clear of the sum's rounding bound, exact rationals
    // otherwise (a closed surface projected to the plane sums to exactly 0, whatever the rounding).
    std::vector<CompensatedSum> area(report_.charts);
    std::vector<double> magnitude(report_.charts, 0);
    for (std::uint32_t f = 0; f < n(); ++f) {
        const UV &p = uv(f, 0), &q = uv(f, 1), &r = uv(f, 2);
        const double a = (q[0] - p[0]) * (r[1] - p[1]), b = (q[1] - p[1]) * (r[0] - p[0]);
        area[chart_of(f)].add(a - b);
        magnitude[chart_of(f)] += std::fabs(a) + std::fabs(b);
    }
    std::vector<int> chart_sign(report_.charts, 0);
    std::vector<mpq_class> exact;
    for (std::size_t c = 0; c < report_.charts; ++c) {
        // Each term is within 4u of its products' magnitude (three roundings of differences and
        // products, one of the subtraction), the sum within 2u|S| + n·u²·Σ|x| (Neumaier): 1e-12 of
        // the magnitude covers both for any chart below 10⁸ faces.
        const double sum = area[c].value();
        if (std::fabs(sum) > 1e-12 * magnitude[c]) chart_sign[c] = sum < 0 ? -1 : 1;
    }
    for (std::uint32_t f = 0; f < n(); ++f) {
        const std::int64_t c = chart_of(f);
        if (chart_sign[c] != 0) continue;
        if (exact.empty()) exact.resize(report_.charts);
        const auto x = [](double d) { return mpq_class(d); };
        const UV &p = uv(f, 0), &q = uv(f, 1), &r = uv(f, 2);
        exact[c] += (x(q[0]) - x(p[0])) * (x(r[1]) - x(p[1])) - (x(q[1]) - x(p[1])) * (x(r[0]) - x(p[0]));
    }
    for (std::size_t c = 0; c < report_.charts; ++c) {
        if (chart_sign[c] == 0) chart_sign[c] = sgn(exact[c]) < 0 ? -1 : 1;  // an exact zero counts as positive
        report_.mirrored_charts += chart_sign[c] < 0;
    }
    for (std::uint32_t f = 0; f < n(); ++f) {
        const std::int64_t c = chart_of(f);
        if (sign_[f] == chart_sign[c]) continue;
        report_.folded.push_back(f);
        if (rec.fail(
                [&] {
                    return "face " + std::to_string(f) + " of chart " + std::to_string(c) +
                           " is folded: its UV triangle " + str(uv(f, 0)) + " " + str(uv(f, 1)) + " " + str(uv(f, 2)) +
                           " is " + (sign_[f] > 0 ? "counter-clockwise" : "clockwise") + ", its chart " +
                           (chart_sign[c] > 0 ? "counter-clockwise" : "clockwise");
                },
                f))
            rec.locate(c, uv(f, 0));
    }
    if (options_.no_mirror) {
        std::vector<std::uint8_t> named(report_.charts, 0);
        for (std::uint32_t f = 0; f < n(); ++f) {
            const std::int64_t c = chart_of(f);
            if (chart_sign[c] > 0 || named[c]) continue;
            named[c] = 1;
            if (rec.fail(
                    [&] {
                        return "chart " + std::to_string(c) + " (face " + std::to_string(f) +
                               ") is mirrored: clockwise in UV (--no-mirror)";
                    },
                    f))
                rec.locate(c, uv(f, 0));
        }
    }
    rec.examined(n());
    return rec.done();
}

// ---- ATLAS-5 ---------------------------------------------------------------------------------
CheckResult AtlasVerifier::check_cracks() {
    Recorder rec("ATLAS-5", title_5);
    const TriMesh& s = *surface_;
    // (a) T-vertices: a vertex of ∂S inside an edge of ∂S, exactly. Boundary edges listed in a
    // grid of cells about one mean edge long; a vertex tests the edges of its cell.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> boundary;
    double length = 0;
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (HalfedgeId h : s.halfedges())
        if (s.is_boundary(h)) {
            const std::uint32_t a = s.from(h).idx(), b = s.to(h).idx();
            boundary.emplace_back(a, b);
            length += (welded_[a] - welded_[b]).norm();
            lo = lo.cwiseMin(welded_[a]);
            hi = hi.cwiseMax(welded_[a]);
        }
    if (!boundary.empty()) {
        const double cell = std::max({length / static_cast<double>(boundary.size()), (hi - lo).maxCoeff() / (1 << 20),
                                      std::numeric_limits<double>::min()});
        const auto cell_of = [&](const Vec3& p) {
            std::array<std::uint64_t, 3> c;
            for (int k = 0; k < 3; ++k)
                c[k] = static_cast<std::uint64_t>(std::clamp((p[k] - lo[k]) / cell, 0.0, 1048575.0));
            return c;
        };
        std::vector<std::pair<std::uint64_t, std::uint32_t>> grid;  // (cell, boundary edge)
        for (std::uint32_t e = 0; e < boundary.size(); ++e) {
            const Vec3 &p = welded_[boundary[e].first], &q = welded_[boundary[e].second];
            const auto c0 = cell_of(p.cwiseMin(q)), c1 = cell_of(p.cwiseMax(q));
            for (std::uint64_t x = c0[0]; x <= c1[0]; ++x)
                for (std::uint64_t y = c0[1]; y <= c1[1]; ++y)
                    for (std::uint64_t z = c0[2]; z <= c1[2]; ++z) grid.emplace_back(cell_key(x, y, z), e);
        }
        std::sort(grid.begin(), grid.end());
        std::vector<std::uint32_t> vertices;  // ascending: the lowest T-vertex is named first
        for (const auto& [a, b] : boundary) vertices.push_back(a);
        std::sort(vertices.begin(), vertices.end());
        for (std::uint32_t v : vertices) {
            const Vec3& p = welded_[v];
            const auto c = cell_of(p);
            const std::uint64_t key = cell_key(c[0], c[1], c[2]);
            auto it = std::lower_bound(grid.begin(), grid.end(), std::pair<std::uint64_t, std::uint32_t>(key, 0));
            for (; it != grid.end() && it->first == key; ++it) {
                const std::uint32_t a = boundary[it->second].first, b = boundary[it->second].second;
                if (a == v || b == v) continue;
                const Vec3 &x = welded_[a], &y = welded_[b];
                const bool inside =
                    (p.array() >= x.cwiseMin(y).array()).all() && (p.array() <= x.cwiseMax(y).array()).all();
                if (inside && p != x && p != y && collinear(x, p, y))
                    rec.fail(
                        [&] {
                            return "vertex " + std::to_string(v) + " " + detail::str(p) +
                                   " lies inside the boundary edge (" + std::to_string(a) + ", " + std::to_string(b) +
                                   ") without being its vertex: a T-vertex";
                        },
                        -1, v);
            }
        }
    }
    // (b) torn edges: one end's UV points equal, the other's at most ε_UV of the texture apart.
    std::vector<double> eps(a_.texture_names.size() + 1, 0);
    {
        std::vector<Vec2> lo2, hi2;
        for (std::uint32_t f = 0; f < n(); ++f) {
            const std::uint32_t t = a_.face_texture[f];
            if (t >= lo2.size()) {
                lo2.resize(t + 1, Vec2::Constant(std::numeric_limits<double>::infinity()));
                hi2.resize(t + 1, Vec2::Constant(-std::numeric_limits<double>::infinity()));
            }
            for (int k = 0; k < 3; ++k) {
                lo2[t] = lo2[t].cwiseMin(uv2(f, k));
                hi2[t] = hi2[t].cwiseMax(uv2(f, k));
            }
        }
        eps.assign(lo2.size(), 0);
        for (std::size_t t = 0; t < lo2.size(); ++t)
            if (lo2[t].allFinite()) eps[t] = 1e-6 * (hi2[t] - lo2[t]).norm();
    }
    for (const Edge& e : edges_) {
        if (a_.face_texture[e.f] != a_.face_texture[e.g]) continue;
        const int fa = e.cf, fb = (e.cf + 1) % 3, ga = (e.cg + 1) % 3, gb = e.cg;  // a→b in f, b→a in g
        const bool same_a = uv(e.f, fa) == uv(e.g, ga), same_b = uv(e.f, fb) == uv(e.g, gb);
        if (same_a == same_b) continue;
        const int f_end = same_a ? fb : fa, g_end = same_a ? gb : ga;
        const double gap = (uv2(e.f, f_end) - uv2(e.g, g_end)).norm();
        if (gap <= eps[a_.face_texture[e.f]] &&
            rec.fail(
                [&] {
                    return "the edge (" + std::to_string(w_faces_[e.f][fa]) + ", " + std::to_string(w_faces_[e.f][fb]) +
                           ") of faces " + std::to_string(e.f) + " and " + std::to_string(e.g) +
                           " is torn in UV: its images meet at one end and miss at the other by " + num(gap);
                },
                e.f, w_faces_[e.f][f_end]))
            rec.locate(chart_of(e.f), uv(e.f, f_end));
    }
    rec.examined(edges_.size() + boundary.size());
    return rec.done();
}

// ---- ATLAS-6, ATLAS-7 ------------------------------------------------------------------------

/// The exact relation of two non-degenerate UV triangles (each given counter-clockwise).
enum class Meeting { apart, touch, overlap };

/// Whether triangle b lies in the closed (strict: open) outer half-plane of some edge of a.
bool separated_by_edge_of(const std::array<Vec2, 3>& a, const std::array<Vec2, 3>& b, bool strict) {
    for (int k = 0; k < 3; ++k) {
        bool outside = true;
        for (int j = 0; j < 3 && outside; ++j) {
            // A corner the two triangles share is on the line: 0 without the exact evaluation that
            // orient2d's filter leaves every zero to (neighbouring faces share corners by the million).
            const bool on_end = b[j] == a[k] || b[j] == a[(k + 1) % 3];
            const int o = on_end ? 0 : orient2d(a[k], a[(k + 1) % 3], b[j]);
            outside = strict ? o < 0 : o <= 0;
        }
        if (outside) return true;
    }
    return false;
}

Meeting meeting(const std::array<Vec2, 3>& a, const std::array<Vec2, 3>& b) {
    // Two convex polygons: their interiors are disjoint iff an edge line of one leaves the other
    // in its closed outer half-plane; the closed sets are disjoint iff one does so strictly.
    if (!separated_by_edge_of(a, b, false) && !separated_by_edge_of(b, a, false)) return Meeting::overlap;
    if (separated_by_edge_of(a, b, true) || separated_by_edge_of(b, a, true)) return Meeting::apart;
    return Meeting::touch;
}

/// Whether ray p→c lies in the closed cone at p spanned counter-clockwise from p→x to p→y (< π).
bool in_cone(const Vec2& p, const Vec2& x, const Vec2& y, const Vec2& c) {
    return orient2d(p, x, c) >= 0 && orient2d(p, c, y) >= 0;
}

// The faces of one texture on a grid of cells as wide as the faces' boxes are on average (so a
// face is listed in a few cells and a cell lists a few faces, however much of the texture is
// empty), at most 2^20 per axis and about as many cells as faces; the faces of each cell by a
// counting sort on the cell (row-major, nx columns).
class UvGrid {
public:
    UvGrid(const std::vector<std::uint32_t>& faces, const std::function<Vec2(std::uint32_t, int)>& uv2)
        : box(faces.size()) {
        Vec2 lo_ = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo_;
        for (std::size_t i = 0; i < faces.size(); ++i) {
            box[i] = {uv2(faces[i], 0).cwiseMin(uv2(faces[i], 1)).cwiseMin(uv2(faces[i], 2)),
                      uv2(faces[i], 0).cwiseMax(uv2(faces[i], 1)).cwiseMax(uv2(faces[i], 2))};
            lo_ = lo_.cwiseMin(box[i][0]);
            hi = hi.cwiseMax(box[i][1]);
        }
        lo = lo_;
        const Vec2 extent = (hi - lo).cwiseMax(Vec2::Constant(std::numeric_limits<double>::min()));
        double mean_box = 0;
        for (const auto& b : box) mean_box += (b[1] - b[0]).maxCoeff();
        mean_box /= static_cast<double>(faces.size());
        side = std::max({mean_box, std::sqrt(extent[0] * extent[1] / static_cast<double>(faces.size())) / 4,
                         extent.maxCoeff() / (1 << 20), std::numeric_limits<double>::min()});
        nx = cell(hi)[0] + 1;
        start.assign(nx * (cell(hi)[1] + 1) + 1, 0);
        for (std::uint32_t i = 0; i < faces.size(); ++i) for_cells(i, [&](std::uint64_t c) { ++start[c + 1]; });
        std::partial_sum(start.begin(), start.end(), start.begin());
        listed.resize(start.back());
        std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
        for (std::uint32_t i = 0; i < faces.size(); ++i) for_cells(i, [&](std::uint64_t c) { listed[next[c]++] = i; });
    }
    std::array<std::uint64_t, 2> cell(const Vec2& p) const {
        return {static_cast<std::uint64_t>(std::clamp((p[0] - lo[0]) / side, 0.0, 1048575.0)),
                static_cast<std::uint64_t>(std::clamp((p[1] - lo[1]) / side, 0.0, 1048575.0))};
    }
    template <class Visit>
    void for_cells(std::uint32_t i, const Visit& visit) const {
        const auto c0 = cell(box[i][0]), c1 = cell(box[i][1]);
        for (std::uint64_t y = c0[1]; y <= c1[1]; ++y)
            for (std::uint64_t x = c0[0]; x <= c1[0]; ++x) visit(y * nx + x);
    }
    std::vector<std::array<Vec2, 2>> box;  // per face (its index in `faces`): lower left, upper right
    Vec2 lo;
    double side = 0;
    std::uint64_t nx = 0;
    std::vector<std::uint32_t> start, listed;  // cell c lists listed[start[c] .. start[c + 1])
};

std::array<Vec2, 3> AtlasVerifier::ccw(std::uint32_t f) const {
    std::array<Vec2, 3> t{uv2(f, 0), uv2(f, 1), uv2(f, 2)};
    if (sign_[f] < 0) std::swap(t[1], t[2]);
    return t;
}

// Faces f < g whose boxes meet: an overlap, or a contact beyond their shared corners, or neither.
void AtlasVerifier::judge_pair(std::uint32_t f, std::uint32_t g, Pairs& found_overlap, Pairs& found_contact) const {
    const std::array<Vec2, 3> tf = ccw(f), tg = ccw(g);
    const Meeting m = meeting(tf, tg);
    if (m == Meeting::apart) return;
    if (m == Meeting::overlap) {
        found_overlap.emplace_back(f, g);
        return;
    }
    // Touching: legitimate only in shared corners (same vertex, same UV point).
    int shared = 0, sf = -1;
    for (int p = 0; p < 3; ++p)
        for (int q = 0; q < 3; ++q)
            if (w_faces_[f][p] == w_faces_[g][q] && uv(f, p) == uv(g, q)) {
                ++shared;
                sf = p;
            }
    bool contact = shared == 0;
    if (shared == 1) {
        // The two faces meet beyond their shared corner iff one's cone there holds a side of the
        // other's (both cones are below π).
        const Vec2 pf = uv2(f, sf);
        const auto others = [&](const std::array<Vec2, 3>& t) {
            int k = 0;
            while (t[k] != pf) ++k;
            return std::pair<Vec2, Vec2>(t[(k + 1) % 3], t[(k + 2) % 3]);
        };
        const auto [fx, fy] = others(tf);
        const auto [gx, gy] = others(tg);
        contact =
            in_cone(pf, fx, fy, gx) || in_cone(pf, fx, fy, gy) || in_cone(pf, gx, gy, fx) || in_cone(pf, gx, gy, fy);
    }
    if (contact) found_contact.emplace_back(f, g);
}

// The pairs among one texture's faces: each pair of faces listed in a cell is tested once, in the
// cell of their boxes' common lower-left corner; the cells in blocks on the executor, each
// block's pairs apart (sorted by the caller: the same result on any number of threads).
void AtlasVerifier::find_pairs_in(const std::vector<std::uint32_t>& faces, Pairs& found_overlap, Pairs& found_contact) {
    const UvGrid grid(faces, [&](std::uint32_t f, int k) { return uv2(f, k); });
    const std::size_t cells = grid.start.size() - 1, block = 4096;
    std::vector<Pairs> block_overlap((cells + block - 1) / block), block_contact((cells + block - 1) / block);
    for_each_block(executor_, cells, block, 1, [&](std::size_t first_cell, std::size_t end_cell) {
        for (std::uint64_t c = first_cell; c < end_cell; ++c)
            for (std::size_t x = grid.start[c]; x < grid.start[c + 1]; ++x)
                for (std::size_t y = x + 1; y < grid.start[c + 1]; ++y) {
                    const std::uint32_t i = grid.listed[x], j = grid.listed[y];
                    const Vec2 blo = grid.box[i][0].cwiseMax(grid.box[j][0]),
                               bhi = grid.box[i][1].cwiseMin(grid.box[j][1]);
                    if ((blo.array() > bhi.array()).any()) continue;  // boxes apart
                    const auto corner_cell = grid.cell(blo);
                    if (corner_cell[1] * grid.nx + corner_cell[0] != c) continue;
                    judge_pair(std::min(faces[i], faces[j]), std::max(faces[i], faces[j]),
                               block_overlap[first_cell / block], block_contact[first_cell / block]);
                }
    });
    for (auto& v : block_overlap) found_overlap.insert(found_overlap.end(), v.begin(), v.end());
    for (auto& v : block_contact) found_contact.insert(found_contact.end(), v.begin(), v.end());
}

void AtlasVerifier::find_pairs(Recorder& overlaps, Recorder& contacts) {
    // Faces by texture, non-degenerate only (ATLAS-3 passed, so all).
    std::uint32_t textures = 0;
    for (std::uint32_t t : a_.face_texture) textures = std::max(textures, t + 1);
    std::vector<std::vector<std::uint32_t>> by_texture(textures);
    for (std::uint32_t f = 0; f < n(); ++f) by_texture[a_.face_texture[f]].push_back(f);
    Pairs found_overlap, found_contact;
    for (const std::vector<std::uint32_t>& faces : by_texture) {
        if (faces.size() < 2) continue;
        ++report_.textures;
        find_pairs_in(faces, found_overlap, found_contact);
    }
    std::sort(found_overlap.begin(), found_overlap.end());
    std::sort(found_contact.begin(), found_contact.end());
    const auto pair_text = [&](std::uint32_t f, std::uint32_t g) {
        return "faces " + std::to_string(f) + " (chart " + std::to_string(chart_of(f)) + ") and " + std::to_string(g) +
               " (chart " + std::to_string(chart_of(g)) + ")";
    };
    for (const auto& [f, g] : found_overlap)
        if (overlaps.fail([&, f = f, g = g] { return pair_text(f, g) + " overlap in UV"; }, f))
            overlaps.locate(chart_of(f), uv(f, 0));
    for (const auto& [f, g] : found_contact)
        if (contacts.fail([&, f = f, g = g] { return pair_text(f, g) + " touch in UV beyond their shared corners"; },
                          f))
            contacts.locate(chart_of(f), uv(f, 0));
    overlaps.examined(n());
    contacts.examined(n());
    report_.overlapping = std::move(found_overlap);
    report_.contacts = std::move(found_contact);
}

// ---- ATLAS-8 ---------------------------------------------------------------------------------
// ATLAS-8: every vertex of T within δ of a vertex of the atlas (`welded`), found through a grid
// of the atlas's vertices in cells 2δ wide (or coarser).
void t_vertices_in_atlas(const TriMesh& t, const std::vector<Vec3>& welded, double delta, Recorder& rec) {
    Vec3 lo = welded.front(), hi = lo;
    for (const Vec3& p : welded) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    const double cell = std::max({2 * delta, (hi - lo).maxCoeff() / 1048575.0, std::numeric_limits<double>::min()});
    const auto coord = [&](double x, int k) {
        return static_cast<std::int64_t>(std::floor(std::clamp((x - lo[k]) / cell, -1.0, 1048576.0)));
    };
    const auto key = [](std::int64_t x, std::int64_t y, std::int64_t z) {  // cells from −1: shifted by one
        return cell_key(static_cast<std::uint64_t>(x + 1), static_cast<std::uint64_t>(y + 1),
                        static_cast<std::uint64_t>(z + 1));
    };
    std::vector<std::pair<std::uint64_t, std::uint32_t>> grid;
    grid.reserve(welded.size());
    for (std::uint32_t v = 0; v < welded.size(); ++v)
        grid.emplace_back(key(coord(welded[v][0], 0), coord(welded[v][1], 1), coord(welded[v][2], 2)), v);
    std::sort(grid.begin(), grid.end());
    for (VertexId v : t.vertices()) {
        const Vec3& p = t.position(v);
        bool found = false;
        const std::int64_t cx = coord(p[0], 0), cy = coord(p[1], 1), cz = coord(p[2], 2);
        for (std::int64_t dx = -1; dx <= 1 && !found; ++dx)
            for (std::int64_t dy = -1; dy <= 1 && !found; ++dy)
                for (std::int64_t dz = -1; dz <= 1 && !found; ++dz) {
                    const std::int64_t x = cx + dx, y = cy + dy, z = cz + dz;
                    if (std::min({x, y, z}) < -1 || std::max({x, y, z}) > 1048576) continue;
                    const std::uint64_t k = key(x, y, z);
                    for (auto it =
                             std::lower_bound(grid.begin(), grid.end(), std::pair<std::uint64_t, std::uint32_t>(k, 0));
                         it != grid.end() && it->first == k && !found; ++it)
                        found = (welded[it->second] - p).norm() <= delta;
                }
        if (!found)
            rec.fail(
                [&] {
                    return "vertex " + std::to_string(v.idx()) + " of T " + detail::str(p) +
                           " has no vertex of the atlas within " + num(delta);
                },
                -1, v.idx());
    }
}

CheckResult AtlasVerifier::check_input() {
    Recorder rec("ATLAS-8", title_8);
    const TriMesh& t = *input_;
    const TriMesh& s = *surface_;
    const Topology tt = topology_of(t), ts = topology_of(s);
    if (tt.total_chi() != ts.total_chi())
        rec.fail([&] {
            return "chi(atlas) = " + std::to_string(ts.total_chi()) + " but chi(T) = " + std::to_string(tt.total_chi());
        });
    if (tt.total_loops() != ts.total_loops())
        rec.fail([&] {
            return "the atlas has " + loops_text(ts.total_loops()) + " but T has " + loops_text(tt.total_loops());
        });
    if (tt.count() != ts.count())
        rec.fail([&] {
            return "the atlas has " + std::to_string(ts.count()) + " components but T has " +
                   std::to_string(tt.count());
        });
    const InputSide side(t, 2 * a_.rounding);
    const double delta = side.tolerance;
    // Every vertex of S on T, and on ∂T when it is on ∂S.
    std::vector<double> distance(s.n_vertices()), boundary_distance(s.n_vertices(), 0);
    for_each_block(executor_, distance.size(), 4096, 4, [&](std::size_t first, std::size_t end) {
        for (std::size_t v = first; v < end; ++v) {
            const Vec3& p = s.position(VertexId(static_cast<VertexId::Index>(v)));
            distance[v] = side.faces.distance(p);
            if (s.is_boundary(VertexId(static_cast<VertexId::Index>(v))))
                boundary_distance[v] =
                    side.boundary ? side.boundary->distance(p) : std::numeric_limits<double>::infinity();
        }
    });
    for (VertexId v : s.vertices()) {
        const double d = distance[v.idx()], b = boundary_distance[v.idx()];
        if (!(d <= delta))
            rec.fail(
                [&] {
                    return "vertex " + std::to_string(v.idx()) + " " + detail::str(s.position(v)) +
                           " of the atlas is not on T (distance " + (std::isinf(d) ? "> " + num(delta) : num(d)) +
                           ", tolerance " + num(delta) + ")";
                },
                -1, v.idx());
        else if (!(b <= delta))
            rec.fail(
                [&] {
                    return "vertex " + std::to_string(v.idx()) + " " + detail::str(s.position(v)) +
                           " is on the atlas's boundary but not on T's (distance " +
                           (std::isinf(b) ? "> " + num(delta) : num(b)) + ", tolerance " + num(delta) + ")";
                },
                -1, v.idx());
    }
    // Every vertex of T at a vertex of S.
    t_vertices_in_atlas(t, welded_, delta, rec);
    // The same area, up to the rounding of the atlas's points.
    double edge_length = 0;
    for (HalfedgeId h : s.halfedges()) edge_length += (s.position(s.to(h)) - s.position(s.from(h))).norm();
    const double area_s = total_area(s), allowed = geometry_tolerance * side.area + delta * edge_length;
    if (!(std::fabs(area_s - side.area) <= allowed))
        rec.fail([&] {
            return "the atlas's area is " + num(area_s) + " but T's is " + num(side.area) + " (difference " +
                   num(area_s - side.area) + ", allowed " + num(allowed) + ")";
        });
    rec.examined(3 + s.n_vertices() + t.n_vertices());
    return rec.done();
}

// ---- Figures ---------------------------------------------------------------------------------

/// The area of triangle t (counter-clockwise) inside [0, 1]² (Sutherland–Hodgman clipping).
double area_in_unit_square(const std::array<Vec2, 3>& t) {
    const Vec2 lo = t[0].cwiseMin(t[1]).cwiseMin(t[2]), hi = t[0].cwiseMax(t[1]).cwiseMax(t[2]);
    if ((lo.array() >= 0).all() && (hi.array() <= 1).all())  // inside: nothing to clip
        return std::fabs((t[1] - t[0]).x() * (t[2] - t[0]).y() - (t[1] - t[0]).y() * (t[2] - t[0]).x()) / 2;
    std::vector<Vec2> poly(t.begin(), t.end());
    for (int side = 0; side < 4 && !poly.empty(); ++side) {
        const int axis = side / 2;
        const double bound = side % 2 ? 1.0 : 0.0, dir = side % 2 ? -1.0 : 1.0;  // keep dir·(x − bound) ≥ 0
        std::vector<Vec2> out;
        for (std::size_t i = 0; i < poly.size(); ++i) {
            const Vec2 &p = poly[i], &q = poly[(i + 1) % poly.size()];
            const double dp = dir * (p[axis] - bound), dq = dir * (q[axis] - bound);
            if (dp >= 0) out.push_back(p);
            if ((dp >= 0) != (dq >= 0)) out.push_back(p + (q - p) * (dp / (dp - dq)));
        }
        poly = std::move(out);
    }
    double a = 0;
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const Vec2 &p = poly[i], &q = poly[(i + 1) % poly.size()];
        a += p[0] * q[1] - p[1] * q[0];
    }
    return std::fabs(a) / 2;
}

/// The area of the union of triangles (counter-clockwise) within x ∈ [x0, x1], y ∈ [y0, y1]. In a
/// vertical slab between two consecutive x of the events — every vertex, every crossing of an edge
/// with y0 or y1, and every crossing of two edges of an overlapping pair (`pairs`, indices into
/// ts: the union's height changes its slope only where two triangles' spans start or stop
/// overlapping, which needs their edges to cross) — the union's height is linear in x, so its
/// value at the slab's middle times the width is exact up to rounding. The triangles whose x-range
/// holds the slab are kept in an active list as the slabs advance.
double union_area(const std::vector<std::array<Vec2, 3>>& ts,
                  const std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs, double x0, double x1, double y0,
                  double y1) {
    std::vector<double> xs{x0, x1};
    for (const auto& t : ts)
        for (int e = 0; e < 3; ++e) {
            const Vec2 &p = t[e], &q = t[(e + 1) % 3];
            xs.push_back(std::clamp(p[0], x0, x1));
            for (const double y : {y0, y1})  // where the clipping at y0 or y1 starts or ends
                if (std::isfinite(y) && (p[1] < y) != (q[1] < y))
                    xs.push_back(std::clamp(p[0] + (q[0] - p[0]) * ((y - p[1]) / (q[1] - p[1])), x0, x1));
        }
    for (const auto& [i, j] : pairs)
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b) {
                const Vec2 &p = ts[i][a], &r = ts[i][(a + 1) % 3] - p, &q = ts[j][b], &s = ts[j][(b + 1) % 3] - q;
                const double d = r[0] * s[1] - r[1] * s[0];
                if (d == 0) continue;
                const Vec2 w = q - p;
                const double u = (w[0] * s[1] - w[1] * s[0]) / d, v = (w[0] * r[1] - w[1] * r[0]) / d;
                if (u >= 0 && u <= 1 && v >= 0 && v <= 1) xs.push_back(std::clamp(p[0] + u * r[0], x0, x1));
            }
    std::sort(xs.begin(), xs.end());
    xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
    // Triangles by their smallest x; the active list holds those that may reach the current slab.
    std::vector<std::uint32_t> by_start(ts.size());
    std::iota(by_start.begin(), by_start.end(), std::uint32_t{0});
    const auto min_x = [&](std::uint32_t i) { return std::min({ts[i][0][0], ts[i][1][0], ts[i][2][0]}); };
    const auto max_x = [&](std::uint32_t i) { return std::max({ts[i][0][0], ts[i][1][0], ts[i][2][0]}); };
    std::sort(by_start.begin(), by_start.end(), [&](std::uint32_t a, std::uint32_t b) { return min_x(a) < min_x(b); });
    std::vector<std::uint32_t> active;
    std::size_t next = 0;
    double area = 0;
    std::vector<std::pair<double, double>> spans;
    for (std::size_t k = 0; k + 1 < xs.size(); ++k) {
        const double x = (xs[k] + xs[k + 1]) / 2;
        while (next < by_start.size() && min_x(by_start[next]) <= x) active.push_back(by_start[next++]);
        std::erase_if(active, [&](std::uint32_t i) { return max_x(i) < x; });
        spans.clear();
        for (std::uint32_t i : active) {
            const auto& t = ts[i];
            double lo = std::numeric_limits<double>::infinity(), hi = -lo;
            for (int e = 0; e < 3; ++e) {
                const Vec2 &p = t[e], &q = t[(e + 1) % 3];
                if ((p[0] <= x) == (q[0] <= x)) continue;
                const double y = p[1] + (q[1] - p[1]) * ((x - p[0]) / (q[0] - p[0]));
                lo = std::min(lo, y);
                hi = std::max(hi, y);
            }
            lo = std::max(lo, y0);
            hi = std::min(hi, y1);
            if (lo < hi) spans.emplace_back(lo, hi);
        }
        std::sort(spans.begin(), spans.end());
        double covered = 0, top = -std::numeric_limits<double>::infinity();
        for (const auto& [lo, hi] : spans) {
            if (hi <= top) continue;
            covered += hi - std::max(lo, top);
            top = hi;
        }
        area += covered * (xs[k + 1] - xs[k]);
    }
    return area;
}

void AtlasVerifier::figures() {
    // Seam length: the interior edges of S between faces that are not joined.
    const auto joined = [&](const Edge& e) {
        return chart_[e.f] == chart_[e.g] && a_.face_texture[e.f] == a_.face_texture[e.g] &&
               uv(e.f, e.cf) == uv(e.g, (e.cg + 1) % 3) && uv(e.f, (e.cf + 1) % 3) == uv(e.g, e.cg);
    };
    double seams = 0, area = 0;
    for (const Edge& e : edges_)
        if (!joined(e)) seams += (welded_[w_faces_[e.f][e.cf]] - welded_[w_faces_[e.f][(e.cf + 1) % 3]]).norm();
    for (const Triangle& t : w_faces_)
        area += 0.5 * (welded_[t[1]] - welded_[t[0]]).cross(welded_[t[2]] - welded_[t[0]]).norm();
    if (area > 0) report_.seam_length = seams / std::sqrt(area);
    // Packing: per texture, the union of its UV triangles; faces that overlap others are grouped
    // (connected by ATLAS-6's pairs) and each group's union computed by slabs.
    std::uint32_t textures = 0;
    for (std::uint32_t t : a_.face_texture) textures = std::max(textures, t + 1);
    UnionFind groups(n());
    for (const auto& [f, g] : report_.overlapping) groups.join(f, g);
    std::vector<std::uint32_t> group_size(n(), 0);
    for (const auto& [f, g] : report_.overlapping) ++group_size[groups.find(f)], ++group_size[groups.find(g)];
    std::vector<std::vector<std::uint32_t>> members(n());
    std::vector<double> in_unit(textures, 0), total(textures, 0);
    std::vector<Vec2> lo(textures, Vec2::Constant(std::numeric_limits<double>::infinity())), hi(textures, -lo.front());
    for (std::uint32_t f = 0; f < n(); ++f) {
        std::array<Vec2, 3> t{uv2(f, 0), uv2(f, 1), uv2(f, 2)};
        if (sign_[f] < 0) std::swap(t[1], t[2]);
        const std::uint32_t x = a_.face_texture[f];
        for (const Vec2& p : t) {
            lo[x] = lo[x].cwiseMin(p);
            hi[x] = hi[x].cwiseMax(p);
        }
        if (group_size[groups.find(f)] > 0) {  // overlaps another face
            members[groups.find(f)].push_back(f);
            continue;
        }
        in_unit[x] += area_in_unit_square(t);
        total[x] += std::fabs(signed_area(f));
    }
    // Each group's overlapping pairs, as indices into the group's list of faces.
    std::vector<std::uint32_t> place(n(), 0);
    for (std::uint32_t root = 0; root < n(); ++root)
        for (std::uint32_t k = 0; k < members[root].size(); ++k) place[members[root][k]] = k;
    std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> group_pairs(n());
    for (const auto& [f, g] : report_.overlapping) group_pairs[groups.find(f)].emplace_back(place[f], place[g]);
    for (std::uint32_t root = 0; root < n(); ++root) {
        if (members[root].empty()) continue;
        const std::uint32_t x = a_.face_texture[root];
        std::vector<std::array<Vec2, 3>> ts;
        for (std::uint32_t f : members[root]) {
            std::array<Vec2, 3> t{uv2(f, 0), uv2(f, 1), uv2(f, 2)};
            if (sign_[f] < 0) std::swap(t[1], t[2]);
            ts.push_back(t);
        }
        constexpr double inf = std::numeric_limits<double>::infinity();
        in_unit[x] += union_area(ts, group_pairs[root], 0, 1, 0, 1);
        total[x] += union_area(ts, group_pairs[root], lo[x][0], hi[x][0], -inf, inf);
    }
    double unit = 0, covered = 0, squares = 0;
    std::uint32_t used = 0;
    for (std::uint32_t x = 0; x < textures; ++x) {
        if (!lo[x].allFinite()) continue;
        ++used;
        unit += in_unit[x];
        covered += total[x];
        const double side = (hi[x] - lo[x]).maxCoeff();
        squares += side * side;
    }
    if (used > 0) report_.packing_unit_square = unit / used;
    if (squares > 0) report_.packing_bounding_square = covered / squares;
}

AtlasReport AtlasVerifier::run() {
    CheckResult grammar;
    grammar.id = "ATLAS-1";
    grammar.title = title_1;
    grammar.status = CheckStatus::pass;
    grammar.checked = n();
    report_.checks.push_back(grammar);
    weld();
    report_.checks.push_back(check_surface());
    report_.checks.push_back(check_degenerate());
    const bool surface = surface_.has_value(), triangles = report_.checks.back().status == CheckStatus::pass;
    if (surface && triangles) {
        find_edges_and_charts();
        report_.checks.push_back(check_folds());
        report_.checks.push_back(check_cracks());
        Recorder overlaps("ATLAS-6", title_6), contacts("ATLAS-7", title_7);
        find_pairs(overlaps, contacts);
        report_.checks.push_back(overlaps.done());
        CheckResult c = contacts.done();
        if (!options_.strict && c.status == CheckStatus::fail) c.status = CheckStatus::info;  // reported, not judged
        report_.checks.push_back(std::move(c));
        figures();
    } else {
        const std::string reason = !surface ? "ATLAS-2 failed" : "ATLAS-3 failed";
        report_.checks.push_back(skipped("ATLAS-4", title_4, reason));
        report_.checks.push_back(skipped("ATLAS-5", title_5, reason));
        report_.checks.push_back(skipped("ATLAS-6", title_6, reason));
        report_.checks.push_back(skipped("ATLAS-7", title_7, reason));
    }
    if (input_) report_.checks.push_back(surface ? check_input() : skipped("ATLAS-8", title_8, "ATLAS-2 failed"));
    // Distortion: UV onto the surface triangle, face by face (DIST-1), whatever the verdict.
    report_.distortion = summarize(n(), [&](std::size_t f) {
        const auto i = static_cast<std::uint32_t>(f);
        const Vec3 q0(uv(i, 0)[0], uv(i, 0)[1], 0), q1(uv(i, 1)[0], uv(i, 1)[1], 0), q2(uv(i, 2)[0], uv(i, 2)[1], 0);
        return face_stretch(q0, q1, q2, a_.points[a_.faces[f][0]], a_.points[a_.faces[f][1]],
                            a_.points[a_.faces[f][2]]);
    });
    return std::move(report_);
}

}  // namespace

AtlasReport verify_atlas(const Atlas& atlas, const TriMesh* input_mesh, const AtlasOptions& options,
                         Executor* executor) {
    return AtlasVerifier(atlas, input_mesh, options, executor_or_default(executor)).run();
}

}  // namespace fhr::exchange
