// FHR cli — `fhr generate` (random manifolds, closed or with holes, in one or several components,
// in families from easy to hard: for tests and for users fuzzing their own code), `fhr convert` (validate and rewrite a mesh) and
// `fhr decimate` (§2: the domain D).
#include <cstdio>
#include <filesystem>

#include <fhr/core/topology.hpp>
#include <fhr/domain/decimate.hpp>
#include <fhr/domain/user_domain.hpp>
#include <fhr/generate/random_mesh.hpp>
#include <fhr/io/detail/atomic_file.hpp>
#include <fhr/io/correspondence.hpp>
#include <fhr/io/read.hpp>
#include "cli/common.hpp"

namespace fhr::cli {

int run_generate(const std::vector<std::string>& argv) {
    std::vector<std::string> options_taken{"family", "genus", "holes", "components", "faces", "seed", "noise", "out"};
    for (const generate::KnobName& k : generate::knob_names()) options_taken.push_back(k.name);
    const Args args(argv, {"min-faces"}, options_taken);
    if (!args.positional().empty()) usage_error("fhr generate takes no positional arguments");
    generate::RandomMeshOptions options;
    options.family = generate::parse_family(args.get("family").value_or("block"));
    options.genus = static_cast<int>(args.integer("genus", 0, 0, 1000));
    options.holes = static_cast<int>(args.integer("holes", 0, 0, generate::max_holes));
    options.components = static_cast<int>(args.integer("components", 1, 1, generate::max_components));
    options.faces = static_cast<std::size_t>(args.integer("faces", 1000, 4, 100'000'000));
    options.seed = static_cast<std::uint64_t>(args.integer("seed", 1, 0, INT64_MAX));
    options.noise = args.real("noise", 0.0, 0.0, 0.5);  // the generator refuses 0.5 itself
    // The family's own knobs, each accepted only with its family (generate::set_knob); their ranges
    // are checked by the generator (spec/generator.md).
    for (const generate::KnobName& k : generate::knob_names())
        if (args.get(k.name))
            generate::set_knob(options.knobs, options.family, k.name, args.real(k.name, 0, -1e300, 1e300));
    if (args.flag("min-faces")) {  // what a caller drawing face counts needs (bench/run_families.py)
        std::printf("%zu\n", generate::min_faces(options));
        return 0;
    }
    const std::string out = args.require("out");
    save_mesh(out, generate::random_mesh(options));
    return 0;
}

int run_convert(const std::vector<std::string>& argv) {
    const Args args(argv, {"triangulate"}, {"out"});
    BuildOptions options;
    options.triangulate = args.flag("triangulate");
    const TriMesh mesh = load_mesh(args.single_positional("MESH"), options);
    save_mesh(args.require("out"), mesh);
    return 0;
}

namespace {

// FMT-CORR-1: one vertex index of T per vertex of D, beside the file `mesh_path` names.
void write_correspondence(const std::string& mesh_path, const domain::Domain& d) {
    std::string corr = "# fhr correspondence: one line per domain vertex, its vertex in the mesh\n";
    for (VertexId v : d.t_vertex) corr += std::to_string(v.idx()) + "\n";
    io::write_file_atomically(std::filesystem::path(mesh_path).replace_extension(".correspondence").string(), corr);
}

}  // namespace

int run_decimate(const std::vector<std::string>& argv) {
    const Args args(argv, {}, {"faces", "vertices", "out", "min-angle", "max-normal-deviation", "corner-angle"});
    const TriMesh T = load_mesh(args.single_positional("MESH"), BuildOptions{});
    domain::DecimateOptions options;
    const bool by_faces = args.get("faces").has_value(), by_vertices = args.get("vertices").has_value();
    if (by_faces == by_vertices) usage_error("give exactly one of --faces N and --vertices N");
    if (by_faces) {
        options.target_faces = static_cast<std::size_t>(args.integer("faces", 0, 0, INT32_MAX));
    } else {
        // A closed triangulation has F = 2(V − χ) faces; with B boundary edges F = 2(V − χ) − B,
        // and B is not known before the decimation.
        if (!T.is_closed()) usage_error("--vertices needs a closed surface: with boundary give --faces N");
        const long v = static_cast<long>(args.integer("vertices", 0, 0, INT32_MAX));
        options.target_faces = static_cast<std::size_t>(std::max(0L, 2 * (v - euler_characteristic(T))));
    }
    options.min_angle_deg = args.real("min-angle", options.min_angle_deg, 0.0, 60.0);
    options.max_normal_deviation_deg = args.real("max-normal-deviation", options.max_normal_deviation_deg, 0.0, 180.0);
    options.corner_angle_deg = args.real("corner-angle", options.corner_angle_deg, 0.0, 180.0);
    const std::string out = args.require("out");
    const domain::Domain d = domain::decimate(T, options);
    write_correspondence(out, d);
    save_mesh(out, d.mesh);
    return 0;
}

int run_attach(const std::vector<std::string>& argv) {
    const Args args(argv, {}, {"domain", "correspondence", "out"});
    const std::string& mesh_path = args.single_positional("MESH");
    TriMesh T = load_mesh(mesh_path, BuildOptions{});
    const domain::DomainSources sources{args.require("domain"), args.require("correspondence")};
    TriMesh D = load_mesh(sources.domain_file, BuildOptions{});
    const auto x = io::parse_correspondence(io::read_bytes(sources.correspondence_file), sources.correspondence_file,
                                            T.n_vertices(), T.n_faces());
    const std::size_t before = T.n_vertices();
    const domain::Domain d = domain::attach_domain(T, std::move(D), x, sources);
    std::printf("domain %s: %zu vertices, %zu faces; %zu points inserted into %s (paper Fig. 4)\n",
                sources.domain_file.c_str(), d.mesh.n_vertices(), d.mesh.n_faces(), T.n_vertices() - before,
                mesh_path.c_str());
    if (const auto out = args.get("out")) {
        // The refined T, and the correspondence in its numbering: every x_j is now a vertex.
        write_correspondence(*out, d);
        save_mesh(*out, T);
    }
    return 0;
}

}  // namespace fhr::cli
