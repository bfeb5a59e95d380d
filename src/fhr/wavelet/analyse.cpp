// FHR §5–§6 — the wavelet stage end to end (see analyse.hpp).
#include <fhr/wavelet/analyse.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include <fhr/core/detail/stopwatch.hpp>
#include <fhr/core/geometry.hpp>
#include <fhr/wavelet/detail/compress.hpp>
#include <fhr/wavelet/detail/filter_bank.hpp>

namespace fhr::wavelet {
namespace {

// Calls visit(g, l) for every face g of D^J under face g0 of D^{J − levels} that holds the point
// with coordinates l in g0 (within 1e−12: a point on a side shared by two faces goes to both), l
// its coordinates in g, down the one-to-four split of refine.hpp: children 4g … 4g + 3 =
// (a, m_ab, m_ca), (m_ab, b, m_bc), (m_ca, m_bc, c), (m_ab, m_bc, m_ca).
template <class Visit>
void locate(std::uint32_t g, const std::array<double, 3>& l, int levels, Visit& visit) {
    if (levels == 0) return visit(g, l);
    constexpr double margin = -1e-12;
    const double a = 2 * l[0], b = 2 * l[1], c = 2 * l[2];
    if (a - 1 >= margin && b >= margin && c >= margin) locate(4 * g, {a - 1, b, c}, levels - 1, visit);
    if (a >= margin && b - 1 >= margin && c >= margin) locate(4 * g + 1, {a, b - 1, c}, levels - 1, visit);
    if (a >= margin && b >= margin && c - 1 >= margin) locate(4 * g + 2, {a, b, c - 1}, levels - 1, visit);
    if (1 - c >= margin && 1 - a >= margin && 1 - b >= margin)
        locate(4 * g + 3, {1 - c, 1 - a, 1 - b}, levels - 1, visit);
}

constexpr std::size_t affine_blocks = 8;

}  // namespace

// The corners: the vertices of T′ (located once per patch in a row: a vertex has one β in a patch,
// and a face of T′ in another face of T of the same patch only takes the largest gap found there)
// and the crossings of T′'s sides with the lines β_c = m/2^J (each side is met from both its
// faces: its crossings are found twice). Blocks of T′'s faces with their own maxima, merged. The
// maxima are of squared gaps, square-rooted at the end: √ rounds monotonically, so the largest
// root is the root of the largest square, bit for bit (2·10⁶ square roots on the horse).
AffineBounds affine_bounds(const Refinement& r, std::span<const Vec3> f_j, const AffinePieces& pieces,
                           std::size_t t_faces, double on_t, Executor* executor) {
    const int J = r.depth();
    const double n = std::ldexp(1.0, J);
    const std::vector<Triangle> faces = r.finest().triangles();
    std::vector<AffineBounds> block(affine_blocks);
    executor_or_default(executor).for_each(affine_blocks, 1, [&](std::size_t b) {
        AffineBounds& m = block[b];
        m.remesh.assign(faces.size(), 0);
        m.t.assign(t_faces, 0);
        constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
        struct Seen {
            std::uint32_t patch;
            double gap2;  // the largest squared gap found at the vertex in that patch
        };
        std::vector<Seen> seen_in(pieces.points.size(), {none, 0});
        Triangle v;
        std::uint32_t d = 0, t = 0;
        std::array<std::array<double, 3>, 3> beta;
        Vec3 phi;
        double found = 0;  // the largest squared gap of the point being located
        auto visit = [&](std::uint32_t g, const std::array<double, 3>& l) {
            const Triangle& c = faces[g];
            const double gap2 = (l[0] * f_j[c[0]] + l[1] * f_j[c[1]] + l[2] * f_j[c[2]] - phi).squaredNorm();
            m.remesh[g] = std::max(m.remesh[g], gap2);
            found = std::max(found, gap2);
        };
        for (std::size_t i = pieces.faces * b / affine_blocks; i < pieces.faces * (b + 1) / affine_blocks; ++i) {
            pieces.face(i, v, d, beta, t);
            double& on_t_face = m.t[t];
            for (int k = 0; k < 3; ++k) {
                const int e = (k + 1) % 3;
                const Vec3 &x = pieces.points[v[k]], &y = pieces.points[v[e]];
                if (Seen& seen = seen_in[v[k]]; seen.patch != d) {
                    phi = x;
                    found = 0;
                    locate(d, beta[k], J, visit);
                    seen = {d, found};
                }
                on_t_face = std::max(on_t_face, seen_in[v[k]].gap2);
                for (int c = 0; c < 3; ++c) {
                    const double from = beta[k][c] * n, to = beta[e][c] * n;
                    for (double q = std::floor(std::min(from, to)) + 1; q < std::max(from, to); ++q) {
                        const double s = (q - from) / (to - from);
                        std::array<double, 3> at;
                        for (int w = 0; w < 3; ++w) at[w] = beta[k][w] + s * (beta[e][w] - beta[k][w]);
                        phi = x + s * (y - x);
                        found = 0;
                        locate(d, at, J, visit);
                        on_t_face = std::max(on_t_face, found);
                    }
                }
            }
        }
    });
    AffineBounds out{std::vector<double>(faces.size(), 0), std::vector<double>(t_faces, 0)};
    for (const AffineBounds& m : block) {
        for (std::size_t g = 0; g < faces.size(); ++g) out.remesh[g] = std::max(out.remesh[g], m.remesh[g]);
        for (std::size_t g = 0; g < t_faces; ++g) out.t[g] = std::max(out.t[g], m.t[g]);
    }
    for (std::vector<double>* bound : {&out.remesh, &out.t})
        for (double& x : *bound) x = std::sqrt(x) * (1 + 1e-12) + on_t;
    return out;
}

namespace {

// Task 1 of analyse: the filter bank, the decomposition, the round trip and each kept percentage's
// reconstruction, with their seconds.
void decompose_and_compress(WaveletResult& out, const Refinement& r, std::span<const double> keep_percent,
                            Executor* executor) {
    auto begin = detail::Clock::now();
    const FilterBank bank(r, executor);
    const Decomposition d = bank.decompose(out.remesh_positions, executor);
    out.decomposition_seconds = detail::seconds_since(begin);

    begin = detail::Clock::now();
    const std::vector<Vec3> round_trip = bank.reconstruct(d, executor);
    out.reconstruction_seconds = detail::seconds_since(begin);

    for (std::size_t v = 0; v < round_trip.size(); ++v) {
        out.reconstruction_max_error =
            std::max(out.reconstruction_max_error, (round_trip[v] - out.remesh_positions[v]).cwiseAbs().maxCoeff());
        out.max_abs_coordinate = std::max(out.max_abs_coordinate, out.remesh_positions[v].cwiseAbs().maxCoeff());
    }
    for (const LevelSolve& s : d.solves) out.cg_iterations.push_back(s.iterations);
    out.coefficients = d.coefficient_count();

    for (double p : keep_percent) {
        KeptResult k;
        k.percent = p;
        k.count = kept_count(out.coefficients, p);
        begin = detail::Clock::now();
        k.positions = bank.reconstruct(keep_largest(bank, d, k.count), executor);
        out.reconstruction_seconds += detail::seconds_since(begin);
        k.l2_error = rms_distance(out.remesh_positions, k.positions);
        out.kept.push_back(std::move(k));
    }
}

// A reconstruction's priors from f^J's brackets (HausdorffOptions::prior): on a triangle of D^J
// its distance to T is at most f^J's bound there plus the triangle's largest corner displacement,
// and from a point of T at most f^J's distance plus the largest displacement of all (the closest
// point of f^J moves by at most that). Raised by 10⁻¹² relative against rounding. Where the bound
// is settled no point is sampled (sampling it, the fandisk's reconstructions, whose f^J lies near
// T, took 42,000 samples per bracket).
struct KeptPriors {
    std::vector<double> from_t, to_t;  // per face of T, per face of D^J (HausdorffOptions::prior, prior_back)
};

KeptPriors kept_priors(const WaveletResult& out, const KeptResult& k, std::size_t t_faces) {
    const Hausdorff& f = out.remesh_hausdorff;
    std::vector<double> moved(k.positions.size());
    double most = 0;
    for (std::size_t v = 0; v < moved.size(); ++v)
        most = std::max(most, moved[v] = (k.positions[v] - out.remesh_positions[v]).norm());
    constexpr double up = 1 + 1e-12;
    std::vector<double> from_t(t_faces), to_t(out.remesh_faces.size());
    for (std::size_t i = 0; i < from_t.size(); ++i) from_t[i] = (f.a_to_b.triangle_upper[i] + most) * up;
    for (std::size_t i = 0; i < to_t.size(); ++i) {
        const Triangle& t = out.remesh_faces[i];
        to_t[i] = (f.b_to_a.triangle_upper[i] + std::max({moved[t[0]], moved[t[1]], moved[t[2]]})) * up;
    }
    return {std::move(from_t), std::move(to_t)};
}

// WAV-15: with φ's faces, per face of D^J a bound of its distance to T from |f^J − φ|, and per
// face of T one of its distance to f^J: f^J's priors both ways; through f^J's per-triangle bounds
// (DirectedHausdorff::triangle_upper) they sharpen the reconstructions' priors too. T′ lies on T
// within PARAM-11's tolerance (1e−9 of the diagonal plus 64u·|x|max), the points' rounding within
// as much again. Without φ's faces, none.
AffineBounds f_priors(const Refinement& r, const WaveletResult& out, const TriMesh& T, const AffinePieces* pieces,
                      Executor* executor) {
    if (!pieces) return {};
    double max_abs = 0;
    for (const Vec3& x : T.positions()) max_abs = std::max(max_abs, x.cwiseAbs().maxCoeff());
    const double on_t = 1e-9 * out.bbox_diagonal + 128 * std::numeric_limits<double>::epsilon() / 2 * max_abs;
    return affine_bounds(r, out.remesh_positions, *pieces, T.n_faces(), on_t, executor);
}

}  // namespace

WaveletResult analyse(const TriMesh& D, const DomainMap& phi, int levels, std::span<const double> keep_percent,
                      const TriMesh& T, const HausdorffOptions& hausdorff_options, Executor* executor,
                      const AffinePieces* pieces, const TriangleTree* t_tree_given) {
    WaveletResult out;
    out.levels = levels;
    for (double p : keep_percent) kept_count(0, p);  // refuse a bad percentage before any work

    auto start = detail::Clock::now();
    const Refinement r = refine(D, levels);
    out.remesh_positions = sample(r, phi, executor);
    for (const TriMesh& level : r.levels) out.remesh_level_faces.push_back(level.triangles());
    out.remesh_faces = out.remesh_level_faces.back();
    out.refinement_seconds = detail::seconds_since(start);

    // The Hausdorff brackets of D^J's f^J and of each reconstruction; each directed search runs in
    // fixed blocks on the executor (core/executor.hpp; the same result on any number of threads).
    // T's tree is built once for all of them, here or by the caller. hausdorff() takes
    // the distance from T first and searches the one to T only down to its lower bound (HausdorffOptions::known):
    // f^J's vertices lie on T, and resolving its distance to T to δ along the creases of a CAD
    // model was most of the brackets' time (the fandisk's f^J: 67 ms of 170). f^J's brackets need
    // no wavelets: they run beside the decomposition and reconstructions; the reconstructions'
    // run after them, from f^J's per-triangle bounds (kept_priors).
    const auto bracketing = detail::Clock::now();
    const std::vector<Triangle> t_faces = T.triangles();
    out.bbox_diagonal = bounding_box(T).diagonal();
    HausdorffOptions ho = hausdorff_options;
    if (ho.resolution <= 0) ho.resolution = 1e-4 * out.bbox_diagonal;
    std::optional<TriangleTree> t_tree_own;
    const TriangleTree& t_tree = t_tree_given ? *t_tree_given : t_tree_own.emplace(T.positions(), t_faces);
    const AffineBounds affine = f_priors(r, out, T, pieces, executor);
    // f^J's tree, built in its bracket's task; each reconstruction's is it refitted to its positions.
    std::optional<TriangleTree> f_tree;
    const auto bracket = [&](const std::vector<Vec3>& positions, const TriangleTree& tree, Hausdorff& h,
                             const HausdorffOptions& o) {
        h = hausdorff(T.positions(), t_faces, t_tree, positions, out.remesh_faces, tree, o, executor);
    };
    executor_or_default(executor).for_each(2, 1, [&](std::size_t task) {
        if (task == 1) return decompose_and_compress(out, r, keep_percent, executor);
        HausdorffOptions o = ho;
        o.prior = affine.t;
        o.prior_back = affine.remesh;
        bracket(out.remesh_positions, f_tree.emplace(out.remesh_positions, out.remesh_faces), out.remesh_hausdorff, o);
    });
    // Their trees first, the last one f^J's own (no more trees alive than when each was built).
    std::vector<TriangleTree> kept_trees;
    kept_trees.reserve(out.kept.size());
    for (std::size_t i = 0; i < out.kept.size(); ++i)
        kept_trees.emplace_back(i + 1 < out.kept.size() ? *f_tree : std::move(*f_tree), out.kept[i].positions);
    f_tree.reset();
    executor_or_default(executor).for_each(out.kept.size(), 1, [&](std::size_t i) {
        const KeptPriors priors = kept_priors(out, out.kept[i], t_faces.size());
        HausdorffOptions o = ho;
        o.prior = priors.from_t;
        o.prior_back = priors.to_t;
        bracket(out.kept[i].positions, kept_trees[i], out.kept[i].hausdorff, o);
    });
    // Wall time from T's tree to the last bracket, which overlaps the decomposition and reconstructions.
    out.hausdorff_seconds = detail::seconds_since(bracketing);
    out.hausdorff_relative = out.remesh_hausdorff.lower() / out.bbox_diagonal;
    return out;
}

}  // namespace fhr::wavelet
