// FHR cli — `fhr run`: the paper's method end to end (§2 domain, §3 partition, §4
// parameterization), its outputs and report (spec/cli.md CLI-RUN-*), progress on stderr.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <optional>

#include "cli/common.hpp"
#include "core/errors.hpp"
#include "core/topology.hpp"
#include "domain/user_domain.hpp"
#include "io/correspondence.hpp"
#include "io/read.hpp"
#include "pipeline/outputs.hpp"

namespace fhr::cli {
namespace {

double since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int run_run(const std::vector<std::string>& argv) {
    const Args args(argv, {"figures"}, {"faces", "domain", "correspondence", "out", "weights", "solver", "up", "levels", "keep", "paths"});
    const std::string& mesh_path = args.single_positional("MESH");
    const std::string out = args.require("out");
    const bool by_faces = args.get("faces").has_value(), by_domain = args.get("domain").has_value();
    if (by_faces == by_domain) usage_error("give exactly one of --faces N and --domain D.off --correspondence FILE");
    pipeline::Options options;
    if (const auto w = args.get("weights")) options.map.weights = param::parse_weights(*w);
    if (const auto s = args.get("solver")) options.map.solver = param::parse_solver(*s);
    if (const auto paths = args.get("paths")) {
        if (*paths != "keep" && *paths != "geodesic") usage_error("--paths must be keep or geodesic, not '" + *paths + "'");
        options.keep_domain = *paths == "keep";
    }
    options.progress = [](const std::string& line) { std::fprintf(stderr, "fhr run: %s\n", line.c_str()); };

    pipeline::Timings timings;
    auto start = std::chrono::steady_clock::now();
    TriMesh T = load_mesh(mesh_path, BuildOptions{});
    timings.stages.emplace_back("reading", since(start));
    pipeline::InputInfo input{mesh_path, T.n_vertices(), T.n_faces(), genus(T), 0};
    options.progress("read " + mesh_path + ": " + std::to_string(T.n_vertices()) + " vertices, " +
                     std::to_string(T.n_faces()) + " faces, genus " + std::to_string(input.genus));

    // §2: the domain, by decimation or from the user (points inside faces/edges inserted first).
    start = std::chrono::steady_clock::now();
    domain::Domain D;
    if (by_faces) {
        D = domain::decimate(T, {.target_faces = static_cast<std::size_t>(args.integer("faces", 0, 0, INT32_MAX))});
    } else {
        const domain::DomainSources sources{args.require("domain"), args.require("correspondence")};
        TriMesh user = load_mesh(sources.domain_file, BuildOptions{});
        const auto x = io::parse_correspondence(io::read_bytes(sources.correspondence_file), sources.correspondence_file,
                                                T.n_vertices(), T.n_faces());
        D = domain::attach_domain(T, std::move(user), x, sources);
    }
    timings.stages.emplace_back("mesh_reduction", since(start));
    input.domain_faces_requested = D.mesh.n_faces();
    options.progress("domain: " + std::to_string(D.mesh.n_vertices()) + " vertices, " + std::to_string(D.mesh.n_faces()) + " faces");

    const pipeline::Parameterization p = pipeline::parameterize(T, std::move(D), options, timings);

    // The independent oracle (src/exchange) judges exactly what param.fhrp will hold.
    start = std::chrono::steady_clock::now();
    const exchange::VerifyReport oracle = exchange::verify(pipeline::to_param_file(p), &T);
    timings.stages.emplace_back("verification", since(start));
    // §5: D^J sampled through φ, prewavelet decomposition, compression.
    const int levels = static_cast<int>(args.integer("levels", 0, 0, 8));
    std::vector<double> keep;
    if (const auto k = args.get("keep")) {
        if (levels == 0) usage_error("--keep needs --levels J (J >= 1)");
        for (std::size_t at = 0; at <= k->size();) {
            const std::size_t comma = std::min(k->find(',', at), k->size());
            const std::string item = k->substr(at, comma - at);
            char* end = nullptr;
            const double percent = std::strtod(item.c_str(), &end);
            if (item.empty() || *end != '\0' || !(percent > 0 && percent <= 100))
                usage_error("--keep takes percentages in (0, 100] separated by commas, not '" + *k + "'");
            keep.push_back(percent);
            at = comma + 1;
        }
    }
    std::optional<wavelet::WaveletResult> wavelets;
    if (levels > 0) {
        const auto located = std::chrono::steady_clock::now();
        const pipeline::GlobalMap phi(p);  // the point locators: part of evaluating φ, so of "refinement"
        const double locating = std::chrono::duration<double>(std::chrono::steady_clock::now() - located).count();
        wavelets = wavelet::analyse(p.partition.domain.mesh, [&](FaceId d, const std::array<double, 3>& beta) { return phi.phi(d, beta); },
                                    levels, keep, T);
        timings.stages.emplace_back("refinement", locating + wavelets->refinement_seconds);
        timings.stages.emplace_back("decomposition", wavelets->decomposition_seconds);
        timings.stages.emplace_back("reconstruction", wavelets->reconstruction_seconds);
        timings.after_total.emplace_back("hausdorff", wavelets->hausdorff_seconds);
        options.progress("wavelets: D^" + std::to_string(levels) + " " + std::to_string(wavelets->remesh_faces.size()) + " faces, " +
                         std::to_string(wavelets->coefficients) + " coefficients");
    }
    pipeline::write_outputs(out, input, p, oracle, timings, options, wavelets ? &*wavelets : nullptr);
    if (args.flag("figures")) {
        const std::string up = args.get("up").value_or("y");
        if (up != "x" && up != "y" && up != "z") usage_error("--up must be x, y or z, not '" + up + "'");
        pipeline::write_figures(out, T, p, up[0] - 'x', wavelets ? &*wavelets : nullptr);
        options.progress("figures: " + out + "/figures/");
    }
    const bool certified = p.certified() && oracle.valid();
    std::printf("%s: %zu faces -> domain %zu faces (%zu retries) -> %zu patches, T' %zu faces; %s\n", mesh_path.c_str(),
                T.n_faces(), p.partition.domain.mesh.n_faces(), p.partition.retries, p.disks.size(), p.refined_faces.size(),
                certified ? "certified one-to-one" : "NOT certified");
    if (!certified) {
        const exchange::CheckResult* bad = oracle.first_failure();
        throw NumericalFailure("the parameterization is not certified: " +
                               (bad ? bad->id + ": " + bad->first_failure : std::string("a patch certificate failed (see report.json)")));
    }
    return 0;
}

}  // namespace fhr::cli
