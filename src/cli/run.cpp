// FHR cli — `fhr run`: parse the arguments, read T (and a given D), call pipeline::run (§2–§5),
// write its outputs and report (spec/cli.md CLI-RUN-*), print the summary; progress on stderr.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>

#include <fhr/core/detail/stopwatch.hpp>
#include <fhr/core/errors.hpp>
#include <fhr/core/executor.hpp>
#include <fhr/core/topology.hpp>
#include <fhr/domain/user_domain.hpp>
#include <fhr/io/correspondence.hpp>
#include <fhr/io/read.hpp>
#include <fhr/app/outputs.hpp>
#include <fhr/app/page.hpp>
#include <fhr/pipeline/detail/run_beside.hpp>
#include "cli/common.hpp"

namespace fhr::cli {

int run_run(const std::vector<std::string>& argv) {
    // Parse.
    const Args args(argv, {"figures", "html"},
                    {"faces", "domain", "correspondence", "out", "weights", "solver", "map", "up", "levels", "keep",
                     "paths", "corner-angle", "threads", "page-faces"});
    const std::string& mesh_path = args.single_positional("MESH");
    const std::string out = args.require("out");
    const bool by_faces = args.get("faces").has_value(), by_domain = args.get("domain").has_value();
    if (by_faces == by_domain) usage_error("give exactly one of --faces N and --domain D.off --correspondence FILE");
    pipeline::RunOptions options;
    pipeline::Options& method = options.method;
    if (const auto w = args.get("weights")) method.map.weights = param::parse_weights(*w);
    if (const auto s = args.get("solver")) method.map.solver = param::parse_solver(*s);
    if (const auto map = args.get("map")) {
        if (*map != "relaxed" && *map != "paper") usage_error("--map must be relaxed or paper, not '" + *map + "'");
        method.relax = *map == "relaxed";
    }
    if (const auto paths = args.get("paths")) {
        if (*paths != "keep" && *paths != "geodesic")
            usage_error("--paths must be keep or geodesic, not '" + *paths + "'");
        method.keep_domain = *paths == "keep";
    }
    options.corner_angle_deg = args.real("corner-angle", options.corner_angle_deg, 0.0, 180.0);
    options.levels = static_cast<int>(args.integer("levels", 0, 0, 8));
    if (const auto k = args.get("keep")) {
        if (options.levels == 0) usage_error("--keep needs --levels J (J >= 1)");
        for (std::size_t at = 0; at <= k->size();) {
            const std::size_t comma = std::min(k->find(',', at), k->size());
            const std::string item = k->substr(at, comma - at);
            char* end = nullptr;
            const double percent = std::strtod(item.c_str(), &end);
            if (item.empty() || *end != '\0' || !(percent > 0 && percent <= 100))
                usage_error("--keep takes percentages in (0, 100] separated by commas, not '" + *k + "'");
            options.keep.push_back(percent);
            at = comma + 1;
        }
    }
    if (args.get("page-faces") && !args.flag("html")) usage_error("--page-faces N needs --html");
    if (args.flag("html") && !app::page_available())
        usage_error(
            "--html: this fhr was built without its page; install web/'s npm packages (npm ci --prefix web, "
            "as ./run does) and reconfigure with -Dpage=enabled");
    const std::string up = args.get("up").value_or("y");
    if (up != "x" && up != "y" && up != "z") usage_error("--up must be x, y or z, not '" + up + "'");
    // --threads N: the pool that runs the independent tasks (0: as many as the hardware has); the
    // outputs are the same bytes on any count (CLI-RUN-4).
    std::optional<ThreadPool> pool;
    if (args.get("threads"))
        method.executor = &pool.emplace(static_cast<unsigned>(args.integer("threads", 0, 0, 1024)));
    method.progress = [](const std::string& line) { std::fprintf(stderr, "fhr run: %s\n", line.c_str()); };
    app::Timings timings;
    method.observer = &timings;

    // Read T and, for --domain, the user's D attached to it (§2, points inside faces/edges inserted).
    auto start = detail::Clock::now();
    TriMesh T = load_mesh(mesh_path, BuildOptions{});
    timings.stage("reading", detail::seconds_since(start), true);
    app::InputInfo input{.path = mesh_path,
                         .vertices = T.n_vertices(),
                         .faces = T.n_faces(),
                         .genus = genus(T),
                         .boundary_loops = boundary_loops(T).size(),
                         .components = connected_components(T).count};
    method.progress(
        "read " + mesh_path + ": " + std::to_string(T.n_vertices()) + " vertices, " + std::to_string(T.n_faces()) +
        " faces, genus " + std::to_string(input.genus) +
        (input.boundary_loops ? ", " + std::to_string(input.boundary_loops) + " boundary loops" : std::string()) +
        (input.components > 1 ? ", " + std::to_string(input.components) + " components" : std::string()));
    if (by_faces) {
        options.faces = static_cast<std::size_t>(args.integer("faces", 0, 0, INT32_MAX));
    } else {
        start = detail::Clock::now();
        const domain::DomainSources sources{args.require("domain"), args.require("correspondence")};
        TriMesh user = load_mesh(sources.domain_file, BuildOptions{});
        const auto x = io::parse_correspondence(io::read_bytes(sources.correspondence_file),
                                                sources.correspondence_file, T.n_vertices(), T.n_faces());
        options.domain = domain::attach_domain(T, std::move(user), x, sources);
        timings.stage("mesh_reduction", detail::seconds_since(start), true);
    }

    // Run; the files of the parameterization, and §5's meshes once §5 is done, are written beside
    // the oracle (they need no verdict).
    app::WrittenBeside written;
    pipeline::RunBeside tasks;
    tasks.beside_oracle = [&](const pipeline::Parameterization& p, const exchange::ParamFile& file) {
        const auto writing = detail::Clock::now();
        app::write_parameterization(out, p, file, method.executor);
        written.parameterization = detail::seconds_since(writing);
    };
    tasks.after_wavelets = [&](const wavelet::WaveletResult& w) {
        const auto writing = detail::Clock::now();
        app::write_wavelets(out, w, method.executor);
        written.wavelets = detail::seconds_since(writing);
    };
    const pipeline::RunResult result = pipeline::run(T, options, tasks);  // a copy: `method` is used below
    const pipeline::Parameterization& p = result.parameterization;
    const wavelet::WaveletResult* wavelets = result.wavelets ? &*result.wavelets : nullptr;
    input.domain_faces_asked = result.domain_faces_asked;
    input.domain_faces_requested = result.domain_faces_requested;

    // Write.
    const app::RunTexts texts = app::write_outputs(out, input, p, result.oracle, timings, method, wavelets, written);
    std::vector<app::RateStep> rate;  // §6's curve, for the figures and the page
    if (wavelets && (args.flag("figures") || args.flag("html")))
        rate = app::rate_steps(T, p.partition.domain.mesh, *wavelets);
    if (args.flag("figures")) {
        app::write_figures(out, T, p, up[0] - 'x', wavelets, rate);
        method.progress("figures: " + out + "/figures/");
    }
    if (args.flag("html")) {
        const std::string name = std::filesystem::path(mesh_path).stem().string();
        const auto display =
            static_cast<std::size_t>(args.integer("page-faces", app::page_display_faces, 1000, INT64_MAX));
        app::write_page(out + "/index.html", T, p,
                        {name, texts.report, texts.timings, up[0] - 'x', wavelets, std::move(rate), display});
        method.progress("page: " + out + "/index.html");
    }

    // Print.
    std::printf("%s: %zu faces -> domain %zu faces (%zu retries) -> %zu patches, T' %zu faces; %s\n", mesh_path.c_str(),
                T.n_faces(), p.partition.domain.mesh.n_faces(), p.partition.retries, p.disks.size(),
                p.refined_faces.size(), result.certified() ? "certified one-to-one" : "NOT certified");
    if (!result.certified()) {
        const exchange::CheckResult* bad = result.oracle.first_failure();
        throw NumericalFailure(
            "the parameterization is not certified: " +
            (bad ? bad->id + ": " + bad->first_failure : std::string("a patch certificate failed (see report.json)")));
    }
    return 0;
}

}  // namespace fhr::cli
