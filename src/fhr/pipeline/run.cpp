// FHR §2–§5 — the method end to end (see run.hpp for the pseudocode).
#include <fhr/pipeline/run.hpp>

#include <stdexcept>
#include <string>

#include <fhr/core/detail/stopwatch.hpp>
#include <fhr/core/errors.hpp>
#include <fhr/core/executor.hpp>
#include <fhr/pipeline/outputs.hpp>

namespace fhr::pipeline {
namespace {

constexpr std::size_t prepare_beside_below = std::size_t{1} << 18;

}  // namespace

RunResult run(const TriMesh& T, RunOptions options) {
    if ((options.faces > 0) == options.domain.has_value()) throw ContractViolation("run: give exactly one of faces and domain");
    if (options.levels < 0 || options.levels > 8) throw InvalidInput("levels must be in 0..8, not " + std::to_string(options.levels));
    for (double k : options.keep)
        if (!(k > 0 && k <= 100)) throw InvalidInput("kept percentages must be in (0, 100], not " + std::to_string(k));
    if (!options.keep.empty() && options.levels == 0) throw InvalidInput("kept percentages need levels >= 1");
    const Options& method = options.method;
    auto say = [&](const std::string& line) {
        if (method.progress) method.progress(line);
    };
    auto observe = [&](const char* stage, double seconds, bool in_total) {
        if (method.observer) method.observer->stage(stage, seconds, in_total);
    };
    RunResult out;
    // §2: the domain. Its decimation runs on one thread; beside it, what the oracle and §5 need of
    // T alone (on the horse 45 and 42 ms of CPU off the busiest part of the run, where
    // the oracle, §5 and the writing share the cores). From prepare_beside_below faces of T on each
    // is left to its stage, as before: there the memory they would hold through §3 and §4 (the
    // oracle's grid of T, and §5's tree of T about 200 bytes per face) weighs more than the time
    // (the goal: 1 KB per triangle).
    Executor& executor = executor_or_default(method.executor);
    domain::Domain D;
    std::optional<exchange::PreparedInput> oracle_t;  // the oracle's side of T (PARAM-11)
    std::optional<wavelet::TriangleTree> t_tree;      // §5's brackets' tree of T
    double decimating = -1, oracle_t_seconds = 0, t_tree_seconds = 0;  // each counted in its stage's seconds
    executor.for_each(2, 1, [&](std::size_t task) {
        auto start = detail::Clock::now();
        if (task == 1) {
            if (T.n_faces() >= prepare_beside_below) return;
            oracle_t.emplace(T);
            oracle_t_seconds = detail::seconds_since(start);
            if (options.levels == 0) return;
            start = detail::Clock::now();
            t_tree.emplace(T.positions(), T.triangles());
            t_tree_seconds = detail::seconds_since(start);
        } else if (options.domain) {
            D = std::move(*options.domain);
        } else {
            D = domain::decimate(T, {.target_faces = options.faces, .corner_angle_deg = options.corner_angle_deg});
            decimating = detail::seconds_since(start);
        }
    });
    if (decimating >= 0) observe("mesh_reduction", decimating, true);
    out.domain_faces_asked = options.faces;
    out.domain_faces_requested = D.mesh.n_faces();
    std::string more;  // why §2 gave more faces than asked (surfaces with boundary, several components)
    if (options.faces > 0 && D.mesh.n_faces() > options.faces) {
        const std::size_t raised = domain::component_targets(T, options.faces).raised;
        more = " (" + std::to_string(options.faces) + " asked";
        if (raised) more += "; " + std::to_string(raised) + " more for the components' least sizes";
        if (D.mesh.n_faces() > options.faces + raised)
            more += "; no valid collapse left: the boundary's loops and corners (--corner-angle) or the angle and normal rules need more";
        more += ")";
    }
    say("domain: " + std::to_string(D.mesh.n_vertices()) + " vertices, " + std::to_string(D.mesh.n_faces()) + " faces" + more);
    // §3, §4.
    out.parameterization = parameterize(T, std::move(D), method);
    // The independent oracle (src/fhr/exchange) judges exactly what param.fhrp will hold; §5 reads
    // the patches' maps, which the oracle does not touch; the caller's task (fhr run: writing the
    // files) reads both: the three run side by side on the executor (most of the oracle runs on
    // one thread, §5 and the writing fill the other).
    exchange::ParamFile lent = lend_param_file(out.parameterization);
    double verifying = 0, locating = 0;
    executor.for_each(3, 1, [&](std::size_t task) {
        if (task == 2) {
            if (options.beside_oracle) options.beside_oracle(out.parameterization, lent);
            return;
        }
        const auto start = detail::Clock::now();
        if (task == 0) {
            // fhr's map is the paper's: chord length (PARAM-10) is judged.
            out.oracle = oracle_t ? exchange::verify(lent, *oracle_t, method.executor, true)
                                  : exchange::verify(lent, &T, method.executor, true);
            verifying = detail::seconds_since(start);
        } else if (options.levels > 0) {
            // §5: D^J sampled through φ, prewavelet decomposition, compression.
            const GlobalMap phi(out.parameterization);  // the point locators: part of evaluating φ, so of "refinement"
            locating = detail::seconds_since(start);
            // φ's faces, from the file the oracle reads (read-only on both sides).
            const wavelet::AffinePieces pieces{
                lent.surface_vertices, lent.surface_faces.size(),
                [&](std::size_t f, Triangle& corners, std::uint32_t& patch, std::array<std::array<double, 3>, 3>& beta,
                    std::uint32_t& t_face) {
                    const exchange::ParamFace& face = lent.surface_faces[f];
                    corners = face.v, patch = face.patch, beta = face.beta, t_face = out.parameterization.face_t[f];
                }};
            out.wavelets = wavelet::analyse(out.parameterization.partition.domain.mesh,
                                            [&](FaceId d, const std::array<double, 3>& beta) { return phi.phi(d, beta); },
                                            options.levels, options.keep, T, {}, options.method.executor, &pieces,
                                            t_tree ? &*t_tree : nullptr);
            if (options.after_wavelets) options.after_wavelets(*out.wavelets);
        }
    });
    take_back_param_file(out.parameterization, std::move(lent));
    observe("verification", oracle_t_seconds + verifying, true);
    if (out.wavelets) {
        observe("refinement", locating + out.wavelets->refinement_seconds, true);
        observe("decomposition", out.wavelets->decomposition_seconds, true);
        observe("reconstruction", out.wavelets->reconstruction_seconds, true);
        observe("hausdorff", t_tree_seconds + out.wavelets->hausdorff_seconds, false);
        say("wavelets: D^" + std::to_string(options.levels) + " " + std::to_string(out.wavelets->remesh_faces.size()) + " faces, " +
            std::to_string(out.wavelets->coefficients) + " coefficients");
    }
    return out;
}

}  // namespace fhr::pipeline
