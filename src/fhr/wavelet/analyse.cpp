// FHR §5–§6 — the wavelet stage end to end (see analyse.hpp).
#include <fhr/wavelet/analyse.hpp>

#include <algorithm>
#include <cmath>

#include <fhr/core/detail/stopwatch.hpp>
#include <fhr/core/geometry.hpp>
#include <fhr/wavelet/compress.hpp>
#include <fhr/wavelet/filter_bank.hpp>

namespace fhr::wavelet {

WaveletResult analyse(const TriMesh& D, const DomainMap& phi, int levels, std::span<const double> keep_percent,
                      const TriMesh& T, const HausdorffOptions& hausdorff_options, Executor* executor) {
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
    // T's tree is built once for all of them (issue 18). hausdorff() takes the distance from T
    // first and searches the one to T only down to its lower bound (HausdorffOptions::known):
    // f^J's vertices lie on T, and resolving its distance to T to δ along the creases of a CAD
    // model was most of the brackets' time (the fandisk's f^J: 67 ms of 170). f^J's brackets need
    // no wavelets: they run beside the decomposition and reconstructions; the reconstructions'
    // run after them, from f^J's per-triangle bounds (kept_bracket).
    const auto bracketing = detail::Clock::now();
    const std::vector<Triangle> t_faces = T.triangles();
    out.bbox_diagonal = bounding_box(T).diagonal();
    HausdorffOptions ho = hausdorff_options;
    if (ho.resolution <= 0) ho.resolution = 1e-4 * out.bbox_diagonal;
    const TriangleTree t_tree(T.positions(), t_faces);
    const auto bracket = [&](const std::vector<Vec3>& positions, Hausdorff& h, const HausdorffOptions& o) {
        h = hausdorff(T.positions(), t_faces, t_tree, positions, out.remesh_faces, TriangleTree(positions, out.remesh_faces), o, executor);
    };
    // A reconstruction's brackets from f^J's (HausdorffOptions::prior): on a triangle of D^J its
    // distance to T is at most f^J's bound there plus the triangle's largest corner displacement,
    // and from a point of T at most f^J's distance plus the largest displacement of all (the
    // closest point of f^J moves by at most that). Raised by 10⁻¹² relative against rounding.
    // Where the bound is settled no point is sampled (issue 18: with the D of session 15, f^J
    // nearer to T, the fandisk's reconstructions' brackets took 42,000 samples each).
    const auto kept_bracket = [&](KeptResult& k) {
        const Hausdorff& f = out.remesh_hausdorff;
        std::vector<double> moved(k.positions.size());
        double most = 0;
        for (std::size_t v = 0; v < moved.size(); ++v) most = std::max(most, moved[v] = (k.positions[v] - out.remesh_positions[v]).norm());
        constexpr double up = 1 + 1e-12;
        std::vector<double> from_t(t_faces.size()), to_t(out.remesh_faces.size());
        for (std::size_t i = 0; i < from_t.size(); ++i) from_t[i] = (f.a_to_b.triangle_upper[i] + most) * up;
        for (std::size_t i = 0; i < to_t.size(); ++i) {
            const Triangle& t = out.remesh_faces[i];
            to_t[i] = (f.b_to_a.triangle_upper[i] + std::max({moved[t[0]], moved[t[1]], moved[t[2]]})) * up;
        }
        HausdorffOptions o = ho;
        o.prior = from_t;
        o.prior_back = to_t;
        bracket(k.positions, k.hausdorff, o);
    };
    executor_or_default(executor).for_each(2, 1, [&](std::size_t task) {
        if (task == 0) return bracket(out.remesh_positions, out.remesh_hausdorff, ho);
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
    });
    executor_or_default(executor).for_each(out.kept.size(), 1, [&](std::size_t i) { kept_bracket(out.kept[i]); });
    // Wall time from T's tree to the last bracket, which overlaps the decomposition and reconstructions.
    out.hausdorff_seconds = detail::seconds_since(bracketing);
    out.hausdorff_relative = out.remesh_hausdorff.lower() / out.bbox_diagonal;
    return out;
}

}  // namespace fhr::wavelet
