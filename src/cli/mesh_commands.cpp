// FHR cli — `fhr generate` (random closed manifolds, for tests and for users fuzzing their own
// code) and `fhr convert` (validate and rewrite a mesh).
#include "cli/common.hpp"
#include "generate/random_mesh.hpp"

namespace fhr::cli {

int run_generate(const std::vector<std::string>& argv) {
    const Args args(argv, {}, {"genus", "faces", "seed", "noise", "out"});
    if (!args.positional().empty()) usage_error("fhr generate takes no positional arguments");
    generate::RandomMeshOptions options;
    options.genus = static_cast<int>(args.integer("genus", 0, 0, 1000));
    options.faces = static_cast<std::size_t>(args.integer("faces", 1000, 4, 100'000'000));
    options.seed = static_cast<std::uint64_t>(args.integer("seed", 1, 0, INT64_MAX));
    options.noise = args.real("noise", 0.0, 0.0, 0.5);  // the generator refuses 0.5 itself
    const std::string out = args.require("out");
    save_mesh(out, generate::random_closed_mesh(options));
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

}  // namespace fhr::cli
