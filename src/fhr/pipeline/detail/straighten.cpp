// Beyond the paper (§3 → §4) — the curves moved between neighbouring patches (see straighten.hpp).
#include <fhr/pipeline/detail/straighten.hpp>

#include <algorithm>
#include <iterator>
#include <limits>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include <fhr/core/errors.hpp>
#include <fhr/core/surface_point.hpp>
#include <fhr/geodesic/exact.hpp>
#include <fhr/param/detail/mips_newton.hpp>
#include <fhr/partition/detail/region.hpp>
#include <fhr/partition/embed.hpp>
#include <fhr/partition/patches.hpp>

namespace fhr::pipeline {
namespace {

using Point2 = std::array<double, 2>;

// Where a vertex of T′ lies on T, as a SurfacePoint of T.
SurfacePoint surface_point(const TriMesh& T, const partition::Origin& o) {
    if (o.vertex.valid()) return SurfacePoint::at_vertex(VertexId(o.vertex));
    return canonical(T, SurfacePoint::on_edge(TriMesh::halfedge(EdgeId(o.edge), 0), o.t));
}

// The curve of domain edge e as it lies in T′ now: its nodes, exactly where they were embedded.
geodesic::GeodesicPath current_path(const TriMesh& T, const partition::Network& N, DEdgeId e) {
    geodesic::GeodesicPath path;
    for (VertexId v : N.path[e]) {
        path.points.push_back(surface_point(T, N.origin[v]));
        if (path.points.size() > 1)
            path.length += (N.mesh.position(v) - N.mesh.position(N.path[e][path.points.size() - 2])).norm();
    }
    return path;
}

// The edge of T that a segment of T′ from a to b lies on, with a's and b's parameters along
// T's halfedge (edge, 0); nothing when the segment is a chord inside a face of T.
struct OnEdge {
    EdgeId edge;
    double ta = 0, tb = 0;
};

std::optional<double> parameter_of_vertex(const TriMesh& T, EdgeId edge, TVertexId v) {
    const HalfedgeId h = TriMesh::halfedge(edge, 0);
    if (T.from(h) == VertexId(v)) return 0.0;
    if (T.to(h) == VertexId(v)) return 1.0;
    return std::nullopt;
}

std::optional<OnEdge> on_t_edge(const TriMesh& T, const partition::Origin& a, const partition::Origin& b) {
    if (a.vertex.valid() && b.vertex.valid()) {
        const HalfedgeId h = T.find_halfedge(VertexId(a.vertex), VertexId(b.vertex));
        if (!h.valid()) return std::nullopt;
        const EdgeId edge = TriMesh::edge(h);
        return OnEdge{edge, *parameter_of_vertex(T, edge, a.vertex), *parameter_of_vertex(T, edge, b.vertex)};
    }
    if (!a.vertex.valid() && !b.vertex.valid()) {
        if (a.edge != b.edge) return std::nullopt;
        return OnEdge{EdgeId(a.edge), a.t, b.t};
    }
    const partition::Origin& point = a.vertex.valid() ? b : a;
    const partition::Origin& corner = a.vertex.valid() ? a : b;
    const std::optional<double> t = parameter_of_vertex(T, EdgeId(point.edge), corner.vertex);
    if (!t) return std::nullopt;
    return a.vertex.valid() ? OnEdge{EdgeId(point.edge), *t, point.t} : OnEdge{EdgeId(point.edge), point.t, *t};
}

// The two domain triangles laid flat along AC: A, C, B (above AC), E (below).
std::array<Point2, 4> lay_out_triangles(const std::array<Vec3, 4>& acbe) {
    const double L = (acbe[1] - acbe[0]).norm();
    auto apex = [&](const Vec3& p, double sign) -> Point2 {
        const double a2 = (p - acbe[0]).squaredNorm(), c2 = (p - acbe[1]).squaredNorm();
        const double x = (L * L + a2 - c2) / (2 * L);
        return {x, sign * std::sqrt(std::max(a2 - x * x, 0.0))};
    };
    return {Point2{0, 0}, Point2{L, 0}, apex(acbe[2], 1), apex(acbe[3], -1)};
}

// The quadrilateral Q of the pseudocode: the triangles laid flat where that is convex enough,
// else a kite.
std::array<Point2, 4> lay_out_quad(const std::array<Point2, 4>& flat, double max_angle) {
    const double L = flat[1][0];
    Point2 B = flat[2], E = flat[3];
    auto angle = [](Point2 u, Point2 v) {
        return std::atan2(std::abs(u[0] * v[1] - u[1] * v[0]), u[0] * v[0] + u[1] * v[1]);
    };
    const double limit = max_angle * std::numbers::pi / 180;
    const double at_A = angle(B, {L, 0}) + angle({L, 0}, E);
    const double at_C = angle({B[0] - L, B[1]}, {-L, 0}) + angle({-L, 0}, {E[0] - L, E[1]});
    const double tiny = 1e-3 * L;  // a flat domain triangle still leaves Q a width
    if (!(at_A <= limit && at_C <= limit && B[1] > tiny && E[1] < -tiny)) {
        B = {L / 2, std::max(B[1], L / 4)};
        E = {L / 2, std::min(E[1], -L / 4)};
    }
    return {Point2{0, 0}, Point2{L, 0}, B, E};
}

// The faces of T′_S in a mask as a mesh of their own.
struct Piece {
    std::vector<std::int32_t> local;                      // vertex of T′_S -> of the piece, −1: outside
    std::vector<VertexId> global;                         // vertex of the piece -> of T′_S
    std::vector<std::array<std::uint32_t, 3>> triangles;  // into the piece's vertices
    std::vector<Vec3> positions;
};

Piece piece_of(const partition::Network& N, const FaceData<std::uint8_t>& inside) {
    Piece piece;
    piece.local.assign(N.mesh.n_vertices(), -1);
    for (FaceId f : N.mesh.faces()) {
        if (!inside[f]) continue;
        std::array<std::uint32_t, 3> t{};
        const auto corners = N.mesh.face_vertices(f);
        for (int k = 0; k < 3; ++k) {
            std::int32_t& l = piece.local[corners[k].idx()];
            if (l < 0) {
                l = static_cast<std::int32_t>(piece.global.size());
                piece.global.push_back(corners[k]);
                piece.positions.push_back(N.mesh.position(corners[k]));
            }
            t[k] = static_cast<std::uint32_t>(l);
        }
        piece.triangles.push_back(t);
    }
    return piece;
}

// Region curve k onto the segment p → q by chord length, its images fixed: the piece's numbers of
// its vertices in order, or nothing when one is not in the piece.
std::optional<std::vector<std::uint32_t>> place_on_segment(const partition::Network& N, std::size_t k,
                                                           const Piece& piece, Point2 p, Point2 q,
                                                           std::vector<std::uint8_t>& fixed,
                                                           std::vector<Point2>& images) {
    const std::vector<VertexId>& curve = N.path.at(DEdgeId(static_cast<DEdgeId::Index>(k)));
    std::vector<double> L(1, 0.0);
    for (std::size_t i = 1; i < curve.size(); ++i)
        L.push_back(L.back() + (N.mesh.position(curve[i]) - N.mesh.position(curve[i - 1])).norm());
    std::vector<std::uint32_t> out;
    for (std::size_t i = 0; i < curve.size(); ++i) {
        if (piece.local[curve[i].idx()] < 0) return std::nullopt;  // not around the piece after all
        const double lambda = L.back() > 0 ? L[i] / L.back() : 0.0;
        const auto u = static_cast<std::uint32_t>(piece.local[curve[i].idx()]);
        fixed[u] = 1;
        images[u] = {(1 - lambda) * p[0] + lambda * q[0], (1 - lambda) * p[1] + lambda * q[1]};
        out.push_back(u);
    }
    return out;
}

// The MIPS problem of a piece's map (param/detail/mips_newton.hpp), its energy's exponent `power`:
// an image not `fixed` moves in the plane, a fixed one with a direction `along` (not zero) slides
// along it, the rest stay.
param::detail::MipsProblem mips_problem(const Piece& piece, const std::vector<Point2>& images,
                                        const std::vector<std::uint8_t>& fixed,
                                        const std::vector<param::detail::Vec2>& along, double power) {
    param::detail::MipsProblem p;
    p.power = power;
    param::detail::set_faces(p, piece.positions, piece.triangles);
    p.lifts.resize(images.size());
    for (std::size_t v = 0; v < images.size(); ++v) {
        p.uv.emplace_back(images[v][0], images[v][1]);
        if (!fixed[v]) {
            p.lifts[v] = {param::detail::Lift{p.variables, {1, 0}}, param::detail::Lift{p.variables + 1, {0, 1}}};
            p.variables += 2;
        } else if (along[v] != param::detail::Vec2::Zero()) {
            p.lifts[v][0] = param::detail::Lift{p.variables++, along[v]};
        }
    }
    return p;
}

// The points of T whose images lie on the x-axis between 0 and `length` (the segment AC),
// ordered along it, from x_a to x_c (vertices of T′_S: of TS, which keeps their numbers).
std::optional<geodesic::GeodesicPath> preimage_of_segment(const TriMesh& T, const partition::Region& region,
                                                          const Piece& piece, const std::vector<Point2>& images,
                                                          VertexId xa, VertexId xc, double length) {
    const std::vector<VertexId>& global = piece.global;
    auto inside = [&](double x) { return x > 0 && x < length; };
    const partition::Network& N = region.cut();
    const TriMesh& S = region.sub();
    auto on_t = [&](const SurfacePoint& p) { return canonical(T, region.in_t(p)); };
    std::vector<std::pair<double, SurfacePoint>> nodes;
    for (std::size_t i = 0; i < global.size(); ++i)
        if (images[i][1] == 0 && global[i] != xa && global[i] != xc && inside(images[i][0]))
            nodes.emplace_back(images[i][0], on_t(surface_point(S, N.origin[global[i]])));
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
    for (const auto& t : piece.triangles)
        for (int k = 0; k < 3; ++k) edges.emplace_back(std::minmax(t[k], t[(k + 1) % 3]));
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    for (const auto& [u, w] : edges) {
        const double yu = images[u][1], yw = images[w][1];
        if (!((yu < 0 && yw > 0) || (yu > 0 && yw < 0))) continue;
        const std::optional<OnEdge> on = on_t_edge(S, N.origin[global[u]], N.origin[global[w]]);
        if (!on) continue;  // a chord inside a face of T: the curve runs straight there
        const double lambda = yu / (yu - yw);
        const double t = on->ta + lambda * (on->tb - on->ta), x = images[u][0] + lambda * (images[w][0] - images[u][0]);
        if (inside(x)) nodes.emplace_back(x, on_t(SurfacePoint::on_edge(TriMesh::halfedge(on->edge, 0), t)));
    }
    std::sort(nodes.begin(), nodes.end(), [](const auto& p, const auto& q) { return p.first < q.first; });
    geodesic::GeodesicPath path;
    path.points.push_back(SurfacePoint::at_vertex(region.in_t(xa)));
    for (const auto& node : nodes)
        if (!same_location(T, node.second, path.points.back())) path.points.push_back(node.second);
    path.points.push_back(SurfacePoint::at_vertex(region.in_t(xc)));
    for (std::size_t k = 1; k < path.points.size(); ++k) {
        if (same_location(T, path.points[k - 1], path.points[k]) || !share_face(T, path.points[k - 1], path.points[k]))
            return std::nullopt;  // rounding put two nodes out of order: the curve stays
        path.length += (position(T, path.points[k]) - position(T, path.points[k - 1])).norm();
    }
    return path;
}

// Where a curve lies on T, and whether embed() snaps it (a moved curve, placed as a geodesic) or
// places it exactly (a curve as §3 left it: its nodes are T′'s vertices already).
struct Placed {
    geodesic::GeodesicPath path;
    bool snapped = false;
};

// What a trial reads: T, the partition, where each curve lies now and the faces of T each patch
// touches now, the caller's §4, the options.
struct Context {
    const TriMesh& T;
    const partition::Partition& P;
    const TriMesh& D;
    const std::vector<Placed>& curves;
    const std::vector<std::vector<FaceId>>& touched;
    const Evaluate& evaluate;
    const StraightenOptions& options;
};

// A moved curve of domain edge e tried in the union of its two patches, cut out on its own: the
// curve on T, and per side (the patch on the left of D's halfedge (e, 0), then the right) the
// score of the new patch's map and the faces of T it touches.
struct Trial {
    geodesic::GeodesicPath path;
    std::array<PatchScore, 2> scores;
    std::array<std::vector<FaceId>, 2> touched;
};

// The new curve of domain edge e (D halfedge (e, 0) from A to C) and its two new patches, or
// nothing when its union of patches does not allow one (see straighten.hpp).
class UnionCurve {
public:
    explicit UnionCurve(const Context& c) : c_(c) {}

    /// `conformal`: the union's map made nearer conformal before the diagonal's preimage is taken.
    std::optional<Trial> operator()(DEdgeId e, bool conformal) const {
        const HalfedgeId h = TriMesh::halfedge(EdgeId(e), 0), twin = TriMesh::twin(h);
        const FaceId left = c_.D.face(h), right = c_.D.face(twin);
        if (!left.valid() || !right.valid()) return std::nullopt;
        const VertexId a = c_.D.from(h), c = c_.D.to(h);
        const VertexId b = c_.D.to(c_.D.next(h)), other = c_.D.to(c_.D.next(twin));
        if (b == other) return std::nullopt;  // the union is not a disk
        const std::array<VertexId, 4> quad{a, c, b, other};
        std::array<Vec3, 4> corners;
        for (int k = 0; k < 4; ++k) corners[k] = c_.T.position(c_.P.domain.t_vertex[quad[k]]);
        const std::array<Point2, 4> flat = lay_out_triangles(corners);
        const std::array<Point2, 4> layout = lay_out_quad(flat, c_.options.max_quad_angle);

        // The union U, cut out of T with the four other curves around it (curves 0..3 of the region).
        const std::array<HalfedgeId, 4> outer{c_.D.next(h), c_.D.next(c_.D.next(h)), c_.D.next(twin),
                                              c_.D.next(c_.D.next(twin))};
        std::vector<partition::RegionCurve> around;
        for (HalfedgeId g : outer) {
            const Placed& placed = c_.curves[TriMesh::edge(g).idx()];
            around.push_back({&placed.path, placed.snapped});
        }
        std::vector<FaceId> touched;
        std::set_union(c_.touched[left.idx()].begin(), c_.touched[left.idx()].end(), c_.touched[right.idx()].begin(),
                       c_.touched[right.idx()].end(), std::back_inserter(touched));
        Outcome<partition::Region> region = partition::Region::cut_out(c_.T, touched, around);
        if (!region) return std::nullopt;
        // U lies on the left of D's halfedge next(h), so on the left of curve 0 when it runs along it.
        Outcome<FaceData<std::uint8_t>> inside = region->side(0, outer[0].idx() % 2 == 0);
        if (!inside) return std::nullopt;
        const partition::Network& N = region->cut();
        const Piece piece = piece_of(N, *inside);
        const std::size_t n = piece.global.size();
        // U's boundary, the four other curves, onto Q's sides by chord length.
        std::vector<std::uint8_t> fixed(n, 0);
        std::vector<Point2> images(n, Point2{0, 0});
        std::vector<std::array<int, 2>> ends(n, {-1, -1});  // a boundary vertex's side: its corners' slots
        for (std::size_t k = 0; k < 4; ++k) {
            const HalfedgeId along = TriMesh::halfedge(TriMesh::edge(outer[k]), 0);
            const std::array<int, 2> end{slot(quad, c_.D.from(along)), slot(quad, c_.D.to(along))};
            const std::optional<std::vector<std::uint32_t>> placed =
                place_on_segment(N, k, piece, layout[end[0]], layout[end[1]], fixed, images);
            if (!placed) return std::nullopt;
            for (std::size_t i = 1; i + 1 < placed->size(); ++i) ends[(*placed)[i]] = end;
        }
        // U's interior (where the old curve ran) on T's boundary cannot be crossed.
        for (std::size_t i = 0; i < n; ++i)
            if (!fixed[i] && N.mesh.is_boundary(piece.global[i])) return std::nullopt;
        try {
            param::convex_combination(piece.positions, piece.triangles, fixed, 0, images, c_.options.weights);
        } catch (const NumericalFailure&) {
            return std::nullopt;  // a degenerate ring in U: the curve stays
        }
        if (conformal) {
            // Towards the triangles' own shape where Q had to be a kite (and they are not flat).
            const bool open = flat[2][1] > 1e-3 * flat[1][0] && flat[3][1] < -1e-3 * flat[1][0];
            make_conformal(piece, ends, fixed, layout, open ? flat : layout, images);
        }
        Trial trial;
        const VertexId xa = region->in_sub(VertexId(c_.P.domain.t_vertex[a]));
        const VertexId xc = region->in_sub(VertexId(c_.P.domain.t_vertex[c]));
        std::optional<geodesic::GeodesicPath> path =
            preimage_of_segment(c_.T, *region, piece, images, xa, xc, layout[1][0]);
        if (!path) return std::nullopt;
        trial.path = std::move(*path);
        // The two new patches: cut again along the new curve (curve 4 of the region).
        if (!region->add({&trial.path, true}) || !cut_pair(*region, e, outer, trial)) return std::nullopt;
        return trial;
    }

private:
    // The patches on the left and the right of the new curve (region curve 4, the others those of
    // `outer`) mapped and scored into `trial`; false when one is not a patch of its three curves.
    bool cut_pair(const partition::Region& region, DEdgeId e, const std::array<HalfedgeId, 4>& outer,
                  Trial& trial) const {
        const HalfedgeId h = TriMesh::halfedge(EdgeId(e), 0);
        for (int s = 0; s < 2; ++s) {
            Outcome<FaceData<std::uint8_t>> mask = region.side(4, s == 0);
            if (!mask) return false;
            const FaceId d = c_.D.face(s == 0 ? h : TriMesh::twin(h));
            std::array<std::pair<std::size_t, bool>, 3> sides;
            HalfedgeId dh = c_.D.halfedge(d);
            for (std::size_t k = 0; k < 3; ++k, dh = c_.D.next(dh)) {
                const EdgeId edge = TriMesh::edge(dh);
                const auto at =
                    std::find_if(outer.begin(), outer.end(), [&](HalfedgeId g) { return TriMesh::edge(g) == edge; });
                sides[k] = {edge == EdgeId(e) ? 4 : static_cast<std::size_t>(at - outer.begin()), (dh.idx() & 1u) != 0};
            }
            Outcome<partition::Patch> patch = region.patch(*mask, sides);
            if (!patch) return false;
            trial.scores[s] = c_.evaluate(d, std::move(patch->disk));
            trial.touched[s] = region.t_faces(*mask);
        }
        return true;
    }

    // The union's map made nearer conformal (param/detail/mips_newton.hpp): the interior moved, the
    // boundary slid along Q's sides, the corners kept. Then, where Q is not `target` (a kite in
    // place of the triangles laid flat), B and E moved towards target's in steps, every image
    // carried along by the affine maps of the triangles ACB and ACE, each step followed by Newton
    // steps, halved where it would turn a face over. Where the convex combination's floating
    // images turned a face over, left as it is.
    void make_conformal(const Piece& piece, const std::vector<std::array<int, 2>>& ends,
                        const std::vector<std::uint8_t>& fixed, const std::array<Point2, 4>& layout,
                        const std::array<Point2, 4>& target, std::vector<Point2>& images) const {
        using param::detail::Vec2;
        auto at = [](const Point2& q) { return Vec2(q[0], q[1]); };
        std::vector<Vec2> along(images.size(), Vec2::Zero());
        for (std::size_t v = 0; v < images.size(); ++v)
            if (fixed[v] && ends[v][0] >= 0) along[v] = at(layout[ends[v][1]]) - at(layout[ends[v][0]]);
        param::detail::MipsProblem p = mips_problem(piece, images, fixed, along, c_.options.power);
        auto set_sides = [&](const std::array<Point2, 4>& quad) {
            for (std::size_t v = 0; v < images.size(); ++v)
                if (fixed[v] && ends[v][0] >= 0) p.lifts[v][0].direction = at(quad[ends[v][1]]) - at(quad[ends[v][0]]);
        };
        if (!std::isfinite(param::detail::mips_total(p)[0])) return;
        const double unbounded = std::numeric_limits<double>::infinity();
        param::detail::mips_newton(p, c_.options.newton_steps, 1e-6, unbounded);
        std::array<Point2, 4> now = layout;
        for (double t = 0, step = 0.25; t < 1 && step >= 1.0 / 64 && target != layout;) {
            const double next = std::min(1.0, t + step);
            std::array<Point2, 4> to = now;
            for (int k : {2, 3})
                to[k] = {layout[k][0] + next * (target[k][0] - layout[k][0]),
                         layout[k][1] + next * (target[k][1] - layout[k][1])};
            const std::vector<Vec2> before = p.uv;
            for (Vec2& q : p.uv) {  // q = c C + x X in the triangle A C X (X = B above AC, E below)
                const int k = q.y() >= 0 ? 2 : 3;
                const double x = q.y() / now[k][1], c = (q.x() - x * now[k][0]) / now[1][0];
                q = c * at(now[1]) + x * at(to[k]);
            }
            if (!std::isfinite(param::detail::mips_total(p)[0])) {
                p.uv = before;
                step /= 2;
                continue;
            }
            now = to;
            t = next;
            set_sides(now);
            param::detail::mips_newton(p, c_.options.newton_steps, 1e-6, unbounded);
        }
        for (std::size_t v = 0; v < images.size(); ++v) images[v] = {p.uv[v].x(), p.uv[v].y()};
    }

    static int slot(const std::array<VertexId, 4>& quad, VertexId v) {
        return static_cast<int>(std::find(quad.begin(), quad.end(), v) - quad.begin());
    }

    const Context& c_;
};

// The moved curves around a corner x_v (D's vertex v inside D): the patches of v's star, mapped
// together, and the curves from v the preimages of straight spokes (see straighten.hpp).
struct StarTrial {
    std::vector<HalfedgeId> spokes;  // D's halfedges v -> w_i, counterclockwise
    std::vector<geodesic::GeodesicPath> paths;
    std::vector<PatchScore> scores;  // per face on the left of spoke i
    std::vector<std::vector<FaceId>> touched;
};

// v's star laid out flat: the angles at v of D's faces scaled to a full turn, the rim's vertices on
// a circle (a convex polygon); nothing when a scaled angle is above max_quad_angle.
std::optional<std::vector<Point2>> star_layout(const std::vector<Vec3>& w, const Vec3& v, double max_angle) {
    const std::size_t k = w.size();
    std::vector<double> theta(k);
    double sum = 0, radius = 0;
    for (std::size_t i = 0; i < k; ++i) {
        const Vec3 a = w[i] - v, b = w[(i + 1) % k] - v;
        theta[i] = std::atan2(a.cross(b).norm(), a.dot(b));
        sum += theta[i];
        radius += a.norm() / static_cast<double>(k);
    }
    std::vector<Point2> layout;
    double phi = 0;
    for (std::size_t i = 0; i < k; ++i) {
        if (!(theta[i] * 2 * std::numbers::pi / sum < max_angle * std::numbers::pi / 180)) return std::nullopt;
        layout.push_back({radius * std::cos(phi), radius * std::sin(phi)});
        phi += theta[i] * 2 * std::numbers::pi / sum;
    }
    return layout;
}

class StarCurves {
public:
    explicit StarCurves(const Context& c) : c_(c) {}

    std::optional<StarTrial> operator()(VertexId v) const {
        if (c_.D.is_boundary(v)) return std::nullopt;
        StarTrial trial;
        const HalfedgeId first = c_.D.out(v);
        HalfedgeId h = first;
        do {
            trial.spokes.push_back(h);
            h = c_.D.ccw_rotated(h);
        } while (h != first);
        const std::size_t k = trial.spokes.size();
        std::vector<VertexId> rim_vertices;
        std::vector<Vec3> w;
        for (HalfedgeId s : trial.spokes) {
            rim_vertices.push_back(c_.D.to(s));
            w.push_back(c_.T.position(c_.P.domain.t_vertex[c_.D.to(s)]));
        }
        std::sort(rim_vertices.begin(), rim_vertices.end());
        if (k < 3 || std::adjacent_find(rim_vertices.begin(), rim_vertices.end()) != rim_vertices.end())
            return std::nullopt;  // the star is not a disk
        const std::optional<std::vector<Point2>> layout =
            star_layout(w, c_.T.position(c_.P.domain.t_vertex[v]), c_.options.max_quad_angle);
        if (!layout) return std::nullopt;
        std::vector<FaceId> touched;
        for (HalfedgeId s : trial.spokes) {
            const std::vector<FaceId>& t = c_.touched[c_.D.face(s).idx()];
            touched.insert(touched.end(), t.begin(), t.end());
        }
        std::sort(touched.begin(), touched.end());
        touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
        if (!star_map(trial, touched, *layout, v) || !cut_star(trial, touched)) return std::nullopt;
        return trial;
    }

private:
    // Region curves: the rim's (0..k−1, rim i from w_i to w_{i+1}), then with `spokes` the spokes'.
    std::vector<partition::RegionCurve> region_curves(const StarTrial& trial, bool spokes) const {
        std::vector<partition::RegionCurve> out;
        for (HalfedgeId s : trial.spokes) {
            const Placed& placed = c_.curves[TriMesh::edge(c_.D.next(s)).idx()];
            out.push_back({&placed.path, placed.snapped});
        }
        if (spokes)
            for (HalfedgeId s : trial.spokes) {
                const Placed& placed = c_.curves[TriMesh::edge(s).idx()];
                out.push_back({&placed.path, placed.snapped});
            }
        return out;
    }

    // The star's map onto `layout` (each patch onto its triangle by eq. 2, then Newton steps with
    // the spokes free and the rim sliding), the new spokes' paths into `trial`; false when none.
    bool star_map(StarTrial& trial, const std::vector<FaceId>& touched, const std::vector<Point2>& layout,
                  VertexId v) const {
        using param::detail::Vec2;
        const std::size_t k = trial.spokes.size();
        const std::vector<partition::RegionCurve> around = region_curves(trial, true);
        Outcome<partition::Region> region = partition::Region::cut_out(c_.T, touched, around);
        if (!region) return false;
        // The star: its patches, each on the left of its rim curve (the spokes are curves too).
        FaceData<std::uint8_t> inside(region->cut().mesh, 0);
        for (std::size_t i = 0; i < k; ++i) {
            const HalfedgeId rim = c_.D.next(trial.spokes[i]);
            Outcome<FaceData<std::uint8_t>> patch = region->side(i, TriMesh::edge(rim).idx() * 2 == rim.idx());
            if (!patch) return false;
            for (FaceId f : region->cut().mesh.faces()) inside[f] = inside[f] | (*patch)[f];
        }
        const partition::Network& N = region->cut();
        const Piece piece = piece_of(N, inside);
        const std::size_t n = piece.global.size();
        std::vector<std::uint8_t> fixed(n, 0), spoke(n, 0);
        std::vector<Point2> images(n, Point2{0, 0});
        std::vector<Vec2> along(n, Vec2::Zero());
        auto place = [&](std::size_t curve, HalfedgeId g, Point2 from, Point2 to) {
            const bool forward = TriMesh::edge(g).idx() * 2 == g.idx();
            return place_on_segment(N, curve, piece, forward ? from : to, forward ? to : from, fixed, images);
        };
        for (std::size_t i = 0; i < k; ++i) {
            const Point2 a = layout[i], b = layout[(i + 1) % k];
            const auto rim = place(i, c_.D.next(trial.spokes[i]), a, b);
            const auto ray = place(k + i, trial.spokes[i], Point2{0, 0}, a);
            if (!rim || !ray) return false;
            for (std::size_t j = 1; j + 1 < rim->size(); ++j) along[(*rim)[j]] = Vec2(b[0] - a[0], b[1] - a[1]);
            for (std::size_t j = 1; j + 1 < ray->size(); ++j) spoke[(*ray)[j]] = 1;
        }
        for (std::size_t i = 0; i < n; ++i)
            if ((!fixed[i] || spoke[i]) && N.mesh.is_boundary(piece.global[i])) return false;
        try {
            param::convex_combination(piece.positions, piece.triangles, fixed, 0, images, c_.options.weights);
        } catch (const NumericalFailure&) {
            return false;
        }
        for (std::size_t i = 0; i < n; ++i)
            if (spoke[i]) fixed[i] = 0;
        param::detail::MipsProblem p = mips_problem(piece, images, fixed, along, c_.options.power);
        if (!std::isfinite(param::detail::mips_total(p)[0])) return false;
        param::detail::mips_newton(p, c_.options.newton_steps, 1e-6, std::numeric_limits<double>::infinity());
        const VertexId xv = region->in_sub(VertexId(c_.P.domain.t_vertex[v]));
        for (std::size_t i = 0; i < k; ++i) {
            // The spoke to w_i along the x-axis: the images turned by −Φ_i.
            const double R = std::hypot(layout[i][0], layout[i][1]);
            const double c = layout[i][0] / R, s = layout[i][1] / R;
            std::vector<Point2> turned(n);
            for (std::size_t j = 0; j < n; ++j)
                turned[j] = {c * p.uv[j].x() + s * p.uv[j].y(), -s * p.uv[j].x() + c * p.uv[j].y()};
            const VertexId xw = region->in_sub(VertexId(c_.P.domain.t_vertex[c_.D.to(trial.spokes[i])]));
            turned[static_cast<std::size_t>(piece.local[xv.idx()])] = {0, 0};
            turned[static_cast<std::size_t>(piece.local[xw.idx()])] = {R, 0};
            std::optional<geodesic::GeodesicPath> path = preimage_of_segment(c_.T, *region, piece, turned, xv, xw, R);
            if (!path) return false;
            if (TriMesh::edge(trial.spokes[i]).idx() * 2 != trial.spokes[i].idx())
                std::reverse(path->points.begin(), path->points.end());
            trial.paths.push_back(std::move(*path));
        }
        return true;
    }

    // The star cut again along the new spokes, its patches mapped and scored into `trial`.
    bool cut_star(StarTrial& trial, const std::vector<FaceId>& touched) const {
        const std::size_t k = trial.spokes.size();
        const std::vector<partition::RegionCurve> around = region_curves(trial, false);
        Outcome<partition::Region> region = partition::Region::cut_out(c_.T, touched, around);
        if (!region) return false;
        for (const geodesic::GeodesicPath& path : trial.paths)
            if (!region->add({&path, true})) return false;
        for (std::size_t i = 0; i < k; ++i) {
            const HalfedgeId s = trial.spokes[i];
            const FaceId d = c_.D.face(s);
            Outcome<FaceData<std::uint8_t>> mask = region->side(k + i, TriMesh::edge(s).idx() * 2 == s.idx());
            if (!mask) return false;
            std::array<std::pair<std::size_t, bool>, 3> sides;
            HalfedgeId dh = c_.D.halfedge(d);
            for (std::size_t j = 0; j < 3; ++j, dh = c_.D.next(dh)) {
                const EdgeId edge = TriMesh::edge(dh);
                std::size_t index = k;  // the rim's i
                if (edge == TriMesh::edge(s))
                    index = k + i;
                else if (edge == TriMesh::edge(trial.spokes[(i + 1) % k]))
                    index = k + (i + 1) % k;
                else
                    index = i;
                sides[j] = {index, (dh.idx() & 1u) != 0};
            }
            Outcome<partition::Patch> patch = region->patch(*mask, sides);
            if (!patch) return false;
            trial.scores.push_back(c_.evaluate(d, std::move(patch->disk)));
            trial.touched.push_back(region->t_faces(*mask));
        }
        return true;
    }

    const Context& c_;
};

// Per vertex of D: the largest over the least ratio, over the patches at x_v, of the patch's
// angle at x_v on the surface to its domain triangle's there (1: the curves split x_v's angle in
// D's proportions).
std::vector<double> corner_spread(const partition::Partition& P) {
    const TriMesh& D = P.domain.mesh;
    const TriMesh& M = P.network.mesh;
    std::vector<double> surface(D.n_halfedges(), 0);  // per patch and corner: at D's halfedge out of it
    for (FaceId d : D.faces())
        for (FaceId f : P.patches.patch[d].faces) {
            const auto x = M.face_vertices(f);
            for (int j = 0; j < 3; ++j) {
                const DVertexId v = P.network.corner[x[j]];
                if (!v.valid()) continue;
                HalfedgeId g = D.halfedge(d);
                while (D.from(g) != VertexId(v)) g = D.next(g);
                const Vec3 a = M.position(x[(j + 1) % 3]) - M.position(x[j]),
                           b = M.position(x[(j + 2) % 3]) - M.position(x[j]);
                surface[g.idx()] += std::atan2(a.cross(b).norm(), a.dot(b));
            }
        }
    std::vector<double> least(D.n_vertices(), INFINITY), most(D.n_vertices(), 0);
    for (HalfedgeId g : D.halfedges()) {
        if (D.is_boundary(g)) continue;
        const VertexId v = D.from(g);
        const Vec3 a = D.position(D.to(g)) - D.position(v), b = D.position(D.from(D.prev(g))) - D.position(v);
        const double ratio = surface[g.idx()] / std::atan2(a.cross(b).norm(), a.dot(b));
        least[v.idx()] = std::min(least[v.idx()], ratio);
        most[v.idx()] = std::max(most[v.idx()], ratio);
    }
    std::vector<double> spread(D.n_vertices());
    for (std::size_t v = 0; v < spread.size(); ++v) spread[v] = most[v] / least[v];
    return spread;
}

// The vertices of D whose corner spread is above `spread`, in rounds of vertices no two of them
// neighbours (their stars share no patch and no moved curve), the largest spreads first.
std::vector<std::vector<VertexId>> star_rounds(const TriMesh& D, const std::vector<double>& spread, double least) {
    std::vector<VertexId> order;
    for (VertexId v : D.vertices())
        if (spread[v.idx()] > least) order.push_back(v);
    std::stable_sort(order.begin(), order.end(),
                     [&](VertexId a, VertexId b) { return spread[a.idx()] > spread[b.idx()]; });
    std::vector<std::vector<VertexId>> rounds;
    std::vector<std::int64_t> round_of(D.n_vertices(), -1);
    for (VertexId v : order) {
        auto taken = [&](std::size_t r) {
            bool neighbour = false;
            D.for_each_outgoing(v, [&](HalfedgeId h) {
                neighbour = neighbour || round_of[D.to(h).idx()] == static_cast<std::int64_t>(r);
            });
            return neighbour;
        };
        std::size_t r = 0;
        while (taken(r)) ++r;
        if (r == rounds.size()) rounds.emplace_back();
        rounds[r].push_back(v);
        round_of[v.idx()] = static_cast<std::int64_t>(r);
    }
    return rounds;
}

// The curves where a straighten() call has them so far, and T′'s faces then.
struct Moves {
    std::vector<Placed> curves;                // per domain edge
    std::vector<std::vector<FaceId>> touched;  // per patch: the faces of T it touches
    std::size_t faces = 0, budget = 0, moved = 0;
};

// The stars of the vertices of D whose corner spread is above `star_spread` moved once (see the
// pseudocode), each kept when its patches are all certified, their worst face no worse than before
// or than `poor`, and T′ within the budget.
void move_stars(const TriMesh& T, partition::Partition& P, Executor& executor, std::vector<PatchScore>& scores,
                const Evaluate& evaluate, const StraightenOptions& options, Moves& m) {
    const TriMesh& D = P.domain.mesh;
    for (const std::vector<VertexId>& round : star_rounds(D, corner_spread(P), options.star_spread)) {
        std::vector<std::optional<StarTrial>> trials(round.size());
        const Context context{T, P, D, m.curves, m.touched, evaluate, options};
        const StarCurves star(context);
        executor.for_each(round.size(), 1, [&](std::size_t i) { trials[i] = star(round[i]); });
        for (std::optional<StarTrial>& trial : trials) {
            if (!trial) continue;
            double worst = options.poor, worst_after = 0;
            std::array<double, 2> tail{0, 0}, poor{0, 0};  // image area above `tail`, `poor`: before, after
            std::size_t after = m.faces;
            bool certified = true;
            for (std::size_t i = 0; i < trial->spokes.size(); ++i) {
                const PatchScore& before = scores[D.face(trial->spokes[i]).idx()];
                const PatchScore& now = trial->scores[i];
                worst = std::max(worst, before.worst);
                worst_after = std::max(worst_after, now.worst);
                certified = certified && now.certified;
                after = after - before.faces + now.faces;
                tail = {tail[0] + before.above_tail, tail[1] + now.above_tail};
                poor = {poor[0] + before.above_poor, poor[1] + now.above_poor};
            }
            if (!certified || worst_after > worst || !(tail[1] < tail[0]) || poor[1] > poor[0] || after > m.budget)
                continue;
            m.faces = after;
            for (std::size_t i = 0; i < trial->spokes.size(); ++i) {
                const FaceId d = D.face(trial->spokes[i]);
                const EdgeId e = TriMesh::edge(trial->spokes[i]);
                scores[d.idx()] = trial->scores[i];
                m.touched[d.idx()] = std::move(trial->touched[i]);
                P.paths[e].path = trial->paths[i];
                P.curves[e].kind = partition::CurveKind::straightened;
                m.curves[e.idx()] = {std::move(trial->paths[i]), true};
                ++m.moved;
            }
        }
    }
}

// The interior edges of D beside a poor patch, in rounds whose edges share no face of D (greedy
// colouring).
std::vector<std::vector<DEdgeId>> rounds_of(const partition::Partition& P, const std::vector<std::uint8_t>& poor) {
    const TriMesh& D = P.domain.mesh;
    std::vector<std::vector<DEdgeId>> rounds;
    std::vector<std::vector<std::size_t>> used(D.n_faces());  // per face: the rounds of its edges so far
    for (EdgeId e : D.edges()) {
        const FaceId f = D.face(TriMesh::halfedge(e, 0)), g = D.face(TriMesh::halfedge(e, 1));
        if (!f.valid() || !g.valid() || P.curves[e].kind == partition::CurveKind::boundary) continue;
        if (!poor[f.idx()] && !poor[g.idx()]) continue;
        auto taken = [&](std::size_t k) {
            return std::find(used[f.idx()].begin(), used[f.idx()].end(), k) != used[f.idx()].end() ||
                   std::find(used[g.idx()].begin(), used[g.idx()].end(), k) != used[g.idx()].end();
        };
        std::size_t r = 0;
        while (taken(r)) ++r;
        if (r == rounds.size()) rounds.emplace_back();
        rounds[r].push_back(DEdgeId(e));
        used[f.idx()].push_back(r);
        used[g.idx()].push_back(r);
    }
    return rounds;
}

// Whether the pair of patches beside a moved curve got better (straighten.hpp's pseudocode).
bool better(const std::array<PatchScore, 2>& now, const std::array<PatchScore, 2>& before,
            const StraightenOptions& options) {
    if (!now[0].certified || !now[1].certified) return false;
    const double worst = std::max(now[0].worst, now[1].worst),
                 worst_before = std::max(before[0].worst, before[1].worst);
    const double l2 = now[0].l2_energy + now[1].l2_energy, l2_before = before[0].l2_energy + before[1].l2_energy;
    return (worst < worst_before && l2 <= (1 + options.l2_slack) * l2_before) ||
           (worst <= std::max(worst_before, options.poor) && l2 < l2_before);
}

// Whether a thorough sweep keeps the pair of a moved curve: both maps certified, its worst face no
// worse than before or than `poor` (its L2 part under chord length not asked: the sliding moves
// that boundary after).
bool acceptable(const std::array<PatchScore, 2>& now, const std::array<PatchScore, 2>& before,
                const StraightenOptions& options) {
    return now[0].certified && now[1].certified &&
           std::max(now[0].worst, now[1].worst) <= std::max({before[0].worst, before[1].worst, options.poor});
}

enum class Mode { plain, both, conformal };

// The trial of the union's convex-combination map (`plain`), of its nearer conformal map
// (`conformal`, the other where that gives none), or of both the better, as better() judges the
// second against the first (`both`).
std::optional<Trial> trial_of(const UnionCurve& union_curve, DEdgeId e, Mode mode, const StraightenOptions& options) {
    if (mode == Mode::plain) return union_curve(e, false);
    std::optional<Trial> bent = union_curve(e, true);
    if (mode == Mode::conformal && bent) return bent;
    std::optional<Trial> plain = union_curve(e, false);
    if (!bent || (plain && !better(bent->scores, plain->scores, options))) return plain;
    return bent;
}

}  // namespace

PatchScore score(const Disk& disk, const param::PatchMap& psi, const std::array<Vec3, 3>& triangle,
                 const StraightenOptions& options, std::vector<std::array<double, 2>>* faces) {
    PatchScore out;
    out.certified = true;
    out.faces = disk.triangles.size();
    for (const auto& t : disk.triangles) {
        // The face and its image, each in a frame of its own plane: J = S · I⁻¹.
        std::array<Vec3, 3> image;
        for (int k = 0; k < 3; ++k)
            image[k] =
                psi.beta[t[k]][0] * triangle[0] + psi.beta[t[k]][1] * triangle[1] + psi.beta[t[k]][2] * triangle[2];
        auto frame = [](const Vec3& a, const Vec3& b, const Vec3& c) {
            const Vec3 u = b - a, v = c - a;
            const double lu = u.norm();
            const Vec3 x = u / lu;
            Eigen::Matrix2d m;
            m << lu, x.dot(v), 0, (v - x.dot(v) * x).norm();
            return m;
        };
        const Eigen::Matrix2d S = frame(disk.positions[t[0]], disk.positions[t[1]], disk.positions[t[2]]);
        const Eigen::Matrix2d I = frame(image[0], image[1], image[2]);
        if (!(I.determinant() > 0)) {
            out.worst = INFINITY;
            out.l2_energy = INFINITY;
            if (faces) faces->push_back({INFINITY, 0});
            continue;
        }
        const Eigen::Matrix2d J = S * I.inverse();
        const param::detail::Vec2 sigma = param::detail::singular_values(J);
        const double s1 = sigma[0], s2 = sigma[1];
        const double ratio = s2 > 0 ? s1 / s2 : INFINITY, area = 0.5 * I(0, 0) * I(1, 1);
        out.worst = std::max(out.worst, ratio);
        out.l2_energy += area * (s1 * s1 + s2 * s2) / 2;
        out.image_area += area;
        if (ratio > options.tail) out.above_tail += area;
        if (ratio > options.poor) out.above_poor += area;
        if (faces) faces->push_back({ratio, area});
    }
    return out;
}

bool goals_missed(const std::vector<PatchScore>& scores, const StraightenOptions& options) {
    double area = 0, above_tail = 0, above_poor = 0;
    for (const PatchScore& s : scores) {
        area += s.image_area;
        above_tail += s.above_tail;
        above_poor += s.above_poor;
    }
    return above_tail > options.tail_share * area || above_poor > options.poor_share * area;
}

std::size_t straighten(const TriMesh& T, partition::Partition& P, Executor& executor, std::vector<PatchScore>& scores,
                       const Evaluate& evaluate, const StraightenOptions& options) {
    const TriMesh& D = P.domain.mesh;
    Moves m;
    for (EdgeId e : P.curves.ids()) m.curves.push_back({current_path(T, P.network, DEdgeId(e)), false});
    m.touched.resize(D.n_faces());
    for (FaceId d : D.faces()) {
        std::vector<FaceId>& touched = m.touched[d.idx()];
        for (FaceId f : P.patches.patch[d].faces) touched.push_back(FaceId(P.network.t_face[f]));
        std::sort(touched.begin(), touched.end());
        touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    }
    for (const PatchScore& s : scores) m.faces += s.faces;
    m.budget = static_cast<std::size_t>((1 + options.thorough_growth) *
                                        static_cast<double>(options.growth_from ? options.growth_from : m.faces));
    if (options.thorough && options.stars && goals_missed(scores, options))
        move_stars(T, P, executor, scores, evaluate, options, m);
    std::vector<Placed>& curves = m.curves;
    std::vector<std::vector<FaceId>>& touched = m.touched;
    for (int sweep = 0; sweep < (options.thorough ? options.thorough_sweeps : options.sweeps); ++sweep) {
        std::vector<std::uint8_t> poor(D.n_faces(), 0);
        const bool missed = goals_missed(scores, options), thorough = missed && options.thorough;
        const Mode mode = thorough ? Mode::conformal : missed ? Mode::both : Mode::plain;
        const double limit = thorough ? 0 : missed ? options.tail : options.poor;
        for (std::size_t f = 0; f < poor.size(); ++f) poor[f] = !(scores[f].worst <= limit);
        for (const std::vector<DEdgeId>& round : rounds_of(P, poor)) {
            // The edges of a round share no patch: each is tried in its own union, all at once.
            std::vector<std::optional<Trial>> trials(round.size());
            const Context context{T, P, D, curves, touched, evaluate, options};
            const UnionCurve union_curve(context);
            executor.for_each(round.size(), 1,
                              [&](std::size_t i) { trials[i] = trial_of(union_curve, round[i], mode, options); });
            for (std::size_t i = 0; i < round.size(); ++i) {
                if (!trials[i]) continue;
                const HalfedgeId h = TriMesh::halfedge(EdgeId(round[i]), 0);
                const std::array<FaceId, 2> pair{D.face(h), D.face(TriMesh::twin(h))};
                const std::array<PatchScore, 2> before{scores[pair[0].idx()], scores[pair[1].idx()]};
                const std::size_t after = m.faces - before[0].faces - before[1].faces + trials[i]->scores[0].faces +
                                          trials[i]->scores[1].faces;
                if (!(thorough ? acceptable(trials[i]->scores, before, options) && after <= m.budget
                               : better(trials[i]->scores, before, options)))
                    continue;
                m.faces = after;
                for (int s = 0; s < 2; ++s) {
                    scores[pair[s].idx()] = trials[i]->scores[s];
                    touched[pair[s].idx()] = std::move(trials[i]->touched[s]);
                }
                P.paths[EdgeId(round[i])].path = trials[i]->path;
                P.curves[EdgeId(round[i])].kind = partition::CurveKind::straightened;
                curves[round[i].idx()] = {std::move(trials[i]->path), true};
                ++m.moved;
            }
        }
    }
    if (m.moved == 0) return 0;
    // The whole network once more, each curve where its region put it: (1) and (2) held in every
    // region, so they hold here (checked all the same), and T′ around each patch is its region's.
    std::vector<geodesic::GeodesicPath> paths;
    std::vector<std::uint8_t> exact;
    for (Placed& c : curves) {
        paths.push_back(std::move(c.path));
        exact.push_back(c.snapped ? 0 : 1);
    }
    partition::Embedding embedding = partition::embed(T, P.domain, paths, exact, &executor);
    if (!embedding.conflicts.empty())
        throw InternalError("moving the curves: the network breaks (1)/(2) where no region did: " +
                            embedding.conflicts.front().describe());
    P.patches = partition::extract_patches(P.domain, embedding.network, &executor);
    P.network = std::move(embedding.network);
    return m.moved;
}

}  // namespace fhr::pipeline
