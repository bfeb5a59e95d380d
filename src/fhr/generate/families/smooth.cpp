// FHR generate — the smooth family (beyond the paper: meshes as hard as real ones):
// curved surfaces of any genus, with the recipe's holes and components, and no flat facet or
// crease left. The block mesh of the recipe (embedded, proven: paper_notes/generator.md) keeps
// its connectivity; each vertex gets a target on a smooth surface, and the vertices move there
// only through edits an exact check accepts, so the result is embedded. The argument
// (paper_notes/generator.md, "The smooth family"):
//
//   1. Rounding. The block's solid, a union of unit cells, blurred by the separable kernel
//      K(x)K(y)K(z) of radius r = roundness whose CDF is the quintic smoothstep: in each
//      coordinate a cell's indicator becomes B(t) = CDF(t) − CDF(t − 1), and the blurred solid is
//      f = Σ_cells B(x − i) B(y − j) B(z − k), a polynomial on each piece. Its level set f = 1/2
//      is the block with every crease and corner rounded at a radius of about 0.8 r (farther than
//      r from every crease f = 1/2 exactly on the block's facets). Each vertex is projected onto
//      it along ∇f (a bracketed, safeguarded Newton iteration on that line).
//   2. Deformation. x ↦ x + d(x), d a sum of three random plane waves a e sin(2π(ω·x + φ)) with
//      Σ a = amplitude and wavelengths 1/|ω| in [λ, 2λ), λ = max(2, 2π·amplitude/0.75): |d| <=
//      amplitude and d's Lipschitz constant is <= amplitude·2π/λ <= 0.75 < 1, so the map is
//      injective (|x − y| − |d(x) − d(y)| > 0): it bends every facet of the rounded block without
//      making the surface meet itself.
//   3. Moving there, embedded by construction (move_embedded). The move of every vertex to its
//      target at once is one edit, kept if find_self_intersection (exact predicates) finds
//      nothing. Otherwise the vertices move in 8 fractional passes, base + (k/8)(target − base),
//      each vertex's move kept only if the EmbeddingGuard accepts it: the mesh stays embedded by
//      induction from the block.
//
// Reproducibility: only +, −, ×, ÷, √ and floor (exact) in a fixed order; sin is our own
// polynomial (an odd Taylor polynomial after an exact range reduction), never the C library's.
#include <fhr/generate/detail/smooth_map.hpp>

#include <algorithm>
#include <cmath>
#include <utility>

#include <fhr/core/topology.hpp>
#include <fhr/generate/embedding.hpp>

namespace fhr::generate::detail {
namespace {

// --- step 1: rounding ---------------------------------------------------------------------------

/// S'(t), S the quintic smoothstep = 30 t²(1 − t)².
double smoothstep_slope(double t) {
    if (t <= 0 || t >= 1) return 0;
    const double s = t * (1 - t);
    return 30 * s * s;
}

/// A unit interval's indicator blurred by the kernel of radius r, B(t) = CDF(t) − CDF(t − 1) with
/// CDF(s) = S((s + r)/(2r)), and its derivative.
struct Blurred {
    double r;
    double value(double t) const { return cdf(t) - cdf(t - 1); }
    double slope(double t) const { return kernel(t) - kernel(t - 1); }
    double cdf(double s) const { return smoothstep((s + r) / (2 * r)); }
    double kernel(double s) const { return smoothstep_slope((s + r) / (2 * r)) / (2 * r); }
};

struct FieldValue {
    double f;
    Vec3 gradient;
};

/// f and ∇f of the blurred slab at p. Only the cells within r of p contribute: with r < 1/2 at
/// most two per axis, among the three from ⌊t − 1 − r⌋ on (the others add exact zeros), summed in
/// increasing order.
FieldValue field(const Slab& s, const Blurred& b, const Vec3& p) {
    const double u = p.x() - s.x0, v = p.y() + 0.5 * static_cast<double>(s.H), w = p.z() + 0.5;
    const auto first = [&](double t) { return static_cast<long>(std::floor(t - 1 - b.r)); };
    double sum = 0, dx = 0, dy = 0;
    for (long i = first(u); i <= first(u) + 2; ++i) {
        const double bx = b.value(u - static_cast<double>(i)), sx = b.slope(u - static_cast<double>(i));
        for (long j = first(v); j <= first(v) + 2; ++j) {
            if (!s.solid(i, j)) continue;
            const double by = b.value(v - static_cast<double>(j)), sy = b.slope(v - static_cast<double>(j));
            sum += bx * by;
            dx += sx * by;
            dy += bx * sy;
        }
    }
    const double bz = b.value(w), sz = b.slope(w);
    return {bz * sum, Vec3(bz * dx, bz * dy, sz * sum)};
}

// --- step 2: deformation ------------------------------------------------------------------------

/// sin(2πt) to about 1e−11: t reduced exactly to u in [−1/4, 1/4] (sin(2πu) is odd and symmetric
/// about u = ±1/4), then the Taylor polynomial of degree 15 of sin x, x = 2πu in [−π/2, π/2], in
/// Horner form (remainder below (π/2)^17/17! < 1e−11).
double sin_2pi(double t) {
    double u = t - std::floor(t + 0.5);  // in [−1/2, 1/2]
    if (u > 0.25) u = 0.5 - u;
    if (u < -0.25) u = -0.5 - u;
    const double x = 6.283185307179586 * u, x2 = x * x;
    double series = 1;
    for (int n = 15; n >= 3; n -= 2) series = 1 - x2 / static_cast<double>(n * (n - 1)) * series;
    return x * series;
}

/// A direction uniform on the unit sphere (rejection from the cube; draws in sequenced statements).
Vec3 random_direction(Random& rng) {
    for (;;) {
        Vec3 d;
        for (int k = 0; k < 3; ++k) d[k] = rng.symmetric();
        const double squared = dot(d, d);
        if (squared <= 1 && squared > 1e-4) return (1 / std::sqrt(squared)) * d;
    }
}

constexpr int n_waves = 3;
constexpr double two_pi = 6.283185307179586;
/// The bound on d's Lipschitz constant (step 2).
constexpr double lipschitz_bound = 0.75;
/// The shortest wavelength at small amplitudes: shorter waves would be noise on coarse meshes.
constexpr double min_wavelength = 2;

// --- step 3: moving the vertices ----------------------------------------------------------------

/// The faces around v with v at q, as the guard wants them (removed: the faces as they are).
void star_at(const TriMesh& m, VertexId v, const Vec3& q, std::vector<FaceId>& removed,
             std::vector<TriangleAt>& added) {
    removed.clear();
    added.clear();
    m.for_each_outgoing(v, [&](HalfedgeId h) {
        if (m.is_boundary(h)) return;
        const FaceId f = m.face(h);
        removed.push_back(f);
        TriangleAt t = triangle_at(m, f);
        for (int k = 0; k < 3; ++k)
            if (t.v[k] == v) t.p[k] = q;
        added.push_back(t);
    });
}

}  // namespace

std::vector<Slab> block_slabs(const TriMesh& block, const RandomMeshOptions& o,
                              const VertexData<std::uint32_t>& component) {
    const std::size_t count = static_cast<std::size_t>(o.components);
    std::vector<double> lo(count, INFINITY), hi(count, -INFINITY), ylo(count, INFINITY), yhi(count, -INFINITY);
    for (VertexId v : block.vertices()) {
        const std::uint32_t c = component[v];
        const Vec3& p = block.position(v);
        lo[c] = std::min(lo[c], p.x());
        hi[c] = std::max(hi[c], p.x());
        ylo[c] = std::min(ylo[c], p.y());
        yhi[c] = std::max(yhi[c], p.y());
    }
    std::vector<Slab> slabs(count);
    for (std::size_t c = 0; c < count; ++c) {
        slabs[c].x0 = lo[c];
        slabs[c].W = std::lround(hi[c] - lo[c]);
        slabs[c].H = std::lround(yhi[c] - ylo[c]);
        slabs[c].genus = share(o.genus, o.components, static_cast<int>(c));
    }
    return slabs;
}

Vec3 rounded(const Slab& slab, double roundness, const Vec3& p) {
    const Blurred b{roundness};
    const FieldValue start = field(slab, b, p);
    const double g0 = start.f - 0.5, norm = length(start.gradient);
    if (g0 == 0 || !(norm > 0)) return p;
    const Vec3 dir = (g0 < 0 ? 1 / norm : -1 / norm) * start.gradient;  // f goes toward 1/2 along dir
    const auto g = [&](double t) {
        const FieldValue at = field(slab, b, p + t * dir);
        return std::pair{at.f - 0.5, dot(at.gradient, dir)};
    };
    // The level set is within about 0.55 r of the block's surface (the most, at a corner along the
    // diagonal; 0.59 r along ∇f in a scan of 500 recipes), so [0, 2r] brackets the root: g has
    // g0's sign at 0 and must not at 2r (if it had, p would stay: never seen).
    double lo = 0, hi = 2 * b.r;
    const double g_hi = g(hi).first;
    if (g_hi == 0) return p + hi * dir;
    if ((g_hi < 0) == (g0 < 0)) return p;
    // Newton from 0, a step that leaves the bracket replaced by bisection; done when g(t) = 0,
    // when the step no longer changes t, or when the bracket is below 1e−15.
    double t = std::min(std::abs(g0) / norm, hi / 2);
    for (int iteration = 0; iteration < 100; ++iteration) {
        const auto [value, slope] = g(t);
        if (value == 0) break;
        if ((value < 0) == (g0 < 0))
            lo = t;
        else
            hi = t;
        double next = slope != 0 ? t - value / slope : lo;
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        if (next == t || !(hi - lo > 1e-15)) break;
        t = next;
    }
    return p + t * dir;
}

Deformation::Deformation(Random& rng, double amplitude) : waves_(n_waves) {
    const double shortest = std::max(min_wavelength, amplitude * two_pi / lipschitz_bound);
    for (Wave& w : waves_) {
        const double wavelength = shortest * (1 + rng.unit());
        w.frequency = (1 / wavelength) * random_direction(rng);
        w.phase = rng.unit();
        w.displacement = (amplitude / n_waves) * random_direction(rng);
    }
}

Vec3 Deformation::operator()(const Vec3& x) const {
    Vec3 y = x;
    for (const Wave& w : waves_) y = y + sin_2pi(dot(w.frequency, x) + w.phase) * w.displacement;
    return y;
}

std::size_t move_embedded(TriMesh& m, std::span<const Vec3> target, int passes) {
    const std::vector<Vec3> base = m.positions();
    for (VertexId v : m.vertices()) m.position(v) = target[v.idx()];
    if (!find_self_intersection(m)) return m.n_vertices();

    for (VertexId v : m.vertices()) m.position(v) = base[v.idx()];
    EmbeddingGuard guard(m, 0);
    std::vector<FaceId> removed;
    std::vector<TriangleAt> added;
    std::size_t arrived = 0;
    for (int k = 1; k <= passes; ++k) {
        const double t = static_cast<double>(k) / passes;
        for (VertexId v : m.vertices()) {
            const Vec3 q = k == passes ? target[v.idx()] : base[v.idx()] + t * (target[v.idx()] - base[v.idx()]);
            star_at(m, v, q, removed, added);
            if (!guard.accepts(m, removed, added)) continue;
            for (FaceId f : removed) guard.remove(m, f);
            m.position(v) = q;
            for (FaceId f : removed) guard.insert(m, f);
            if (k == passes) ++arrived;
        }
    }
    return arrived;
}

std::size_t smooth_min_faces(const RandomMeshOptions& o) {
    const FamilyKnobs& k = o.knobs;
    if (!(k.roundness > 0 && k.roundness <= 0.45))
        invalid("--roundness must be in (0, 0.45] (got " + std::to_string(k.roundness) + ")");
    if (!(k.amplitude >= 0 && k.amplitude <= 0.5))
        invalid("--amplitude must be in [0, 0.5] (got " + std::to_string(k.amplitude) + ")");
    return min_faces(o.genus, o.holes, o.components);
}

TriMesh smooth_mesh(const RandomMeshOptions& o) {
    TriMesh m = base_block(o, o.faces);
    const Components comps = connected_components(m);
    const std::vector<Slab> slabs = block_slabs(m, o, comps.vertex_component);
    Random rng(family_seed(o.seed, Family::smooth));
    const Deformation deform(rng, o.knobs.amplitude);
    std::vector<Vec3> target(m.n_vertices());
    for (VertexId v : m.vertices())
        target[v.idx()] = deform(rounded(slabs[comps.vertex_component[v]], o.knobs.roundness, m.position(v)));
    move_embedded(m, target);
    return m;
}

}  // namespace fhr::generate::detail
