// <fhr/testing/rapidcheck.hpp> — random closed meshes for RapidCheck properties (fhr/generate),
// for users fuzzing their own code and for fhr's own property tests, which draw their input
// surfaces T (paper §1: closed orientable manifold triangulations of any genus) from here.
// Header-only: it needs RapidCheck (<rapidcheck.h>, Debian's librapidcheck-dev) and libfhr; fhr
// itself never needs RapidCheck to build. A failing case shows the `fhr generate` command that
// writes the same mesh to a file, and reading the file gives exactly the same TriMesh back
// (spec/library.md LIB-7).
#pragma once

#include <rapidcheck.h>

#include <cstdint>
#include <limits>
#include <ostream>
#include <sstream>
#include <string>

#include <fhr/core/trimesh.hpp>
#include <fhr/generate/random_mesh.hpp>

namespace fhr::testing {

/// The command line that writes the mesh of these options.
inline std::string generate_command(const generate::RandomMeshOptions& o) {
    std::ostringstream s;
    s << "fhr generate --genus " << o.genus << " --faces " << o.faces << " --seed " << o.seed;
    if (o.noise != 0) s << " --noise " << o.noise;
    s << " --out mesh.off";
    return s.str();
}

/// Random options: genus in [min_genus, max_genus], an even face count in
/// [min_faces(genus), max_faces], a seed the CLI accepts (< 2^63) and a noise of 0, 0.05, 0.1
/// or 0.25 (exact in decimal, so the shown command reproduces it). Shrinks towards the
/// smallest genus, the fewest faces, seed 0 and no noise. Properties pick gen_closed_mesh,
/// whose values show their options in a counterexample.
/// \pre 0 <= min_genus <= max_genus and max_faces >= generate::min_faces(max_genus).
inline rc::Gen<generate::RandomMeshOptions> gen_mesh_options(int min_genus = 0, int max_genus = 4,
                                                             std::size_t max_faces = 2000) {
    return rc::gen::exec([=] {
        generate::RandomMeshOptions o;
        o.genus = *rc::gen::inRange(min_genus, max_genus + 1);
        const std::size_t least = generate::min_faces(o.genus);
        o.faces = least + 2 * *rc::gen::inRange<std::size_t>(0, (max_faces - least) / 2 + 1);
        o.seed = *rc::gen::inRange<std::uint64_t>(0, std::numeric_limits<std::int64_t>::max());
        // an index, not gen::element (which never shrinks): shrinks toward no noise
        constexpr double noises[] = {0.0, 0.05, 0.1, 0.25};
        o.noise = noises[*rc::gen::inRange(0, 4)];
        return o;
    });
}

/// A generated mesh that remembers its options. RapidCheck shows it in a counterexample as the
/// `fhr generate` command that writes it (showValue below). (Generators run in a fresh RapidCheck
/// scope where RC_LOG cannot reach the case's log, so the value itself carries the recipe.)
struct GeneratedMesh : TriMesh {
    generate::RandomMeshOptions options;
};

inline void showValue(const GeneratedMesh& m, std::ostream& os) {
    os << generate_command(m.options) << "  (" << m.n_vertices() << " vertices, " << m.n_faces() << " faces)";
}

/// A random closed mesh (see gen_mesh_options); use it as a TriMesh:
/// `const TriMesh& m = *gen_closed_mesh();`.
inline rc::Gen<GeneratedMesh> gen_closed_mesh(int min_genus = 0, int max_genus = 4, std::size_t max_faces = 2000) {
    return rc::gen::map(gen_mesh_options(min_genus, max_genus, max_faces), [](const generate::RandomMeshOptions& o) {
        return GeneratedMesh{generate::random_closed_mesh(o), o};
    });
}

}  // namespace fhr::testing
