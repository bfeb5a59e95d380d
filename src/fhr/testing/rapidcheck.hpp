// <fhr/testing/rapidcheck.hpp> — random meshes for RapidCheck properties (fhr/generate), for
// users fuzzing their own code and for fhr's own property tests, which draw their input surfaces
// T (paper §1: closed orientable manifold triangulations of any genus) from here; surfaces with
// boundary loops and several components (beyond the paper) on request.
// Header-only: it needs RapidCheck (<rapidcheck.h>, Debian's librapidcheck-dev) and libfhr; fhr
// itself never needs RapidCheck to build. A failing case shows the `fhr generate` command that
// writes the same mesh to a file, and reading the file gives exactly the same TriMesh back
// (spec/library.md LIB-7).
#pragma once

#include <rapidcheck.h>

#include <cstdint>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

#include <fhr/core/errors.hpp>
#include <fhr/core/trimesh.hpp>
#include <fhr/generate/random_mesh.hpp>

namespace fhr::testing {

/// The command line that writes the mesh of these options (generate/random_mesh.hpp).
using generate::generate_command;

/// The ranges recipes are drawn from (closed ranges; genus and holes are totals over the
/// components, generate::RandomMeshOptions). Holes and components are opt-in: the defaults give
/// closed connected meshes, the paper's input class (§1).
struct MeshRanges {
    int min_genus = 0, max_genus = 4;
    std::size_t max_faces = 2000;
    int min_holes = 0, max_holes = 0;
    int min_components = 1, max_components = 1;
    /// The families drawn from, knobs at their defaults (drawn only when there is more than one;
    /// e.g. `std::span(generate::embedded_families)` for every embedded family).
    std::vector<generate::Family> families{generate::Family::block};
};

/// Random options: a family of `families`, genus, holes and components in their ranges (family,
/// holes and components are drawn only when their range has more than one value, so the default
/// ranges spend no draw on them), a face count in [min_faces(options),
/// max_faces] (even when there are no holes), a seed the CLI accepts (< 2^63) and, for the block
/// family, a noise of 0, 0.05, 0.1 or 0.25 (exact in decimal, so the shown command reproduces
/// it). Shrinks towards the first family, the smallest genus, holes and components, the fewest
/// faces, seed 0 and no noise. Properties pick gen_mesh or
/// gen_closed_mesh, whose values show their options in a counterexample.
/// \pre 0 <= min_genus <= max_genus, 0 <= min_holes <= max_holes <= generate::max_holes,
///      1 <= min_components <= max_components <= generate::max_components.
/// \throws InvalidInput (when a value is drawn) if max_faces is below min_faces of the drawn
///         genus, holes and components.
inline rc::Gen<generate::RandomMeshOptions> gen_mesh_options(const MeshRanges& r) {
    return rc::gen::exec([=] {
        const auto draw_if_varies = [](int lo, int hi) { return lo == hi ? lo : *rc::gen::inRange(lo, hi + 1); };
        generate::RandomMeshOptions o;
        if (r.families.size() > 1)
            o.family = r.families[*rc::gen::inRange<std::size_t>(0, r.families.size())];
        else if (r.families.size() == 1)
            o.family = r.families[0];
        o.genus = *rc::gen::inRange(r.min_genus, r.max_genus + 1);
        o.holes = draw_if_varies(r.min_holes, r.max_holes);
        o.components = draw_if_varies(r.min_components, r.max_components);
        const std::size_t least = generate::min_faces(o);
        if (least > r.max_faces)
            throw InvalidInput("gen_mesh_options: " + generate_command(o) + " needs at least " + std::to_string(least) +
                               " faces, more than max_faces = " + std::to_string(r.max_faces));
        const std::size_t step = o.holes == 0 ? 2 : 1;  // F is even without holes
        o.faces = least + step * *rc::gen::inRange<std::size_t>(0, (r.max_faces - least) / step + 1);
        o.seed = *rc::gen::inRange<std::uint64_t>(0, std::numeric_limits<std::int64_t>::max());
        // an index, not gen::element (which never shrinks): shrinks toward no noise
        constexpr double noises[] = {0.0, 0.05, 0.1, 0.25};
        if (o.family == generate::Family::block) o.noise = noises[*rc::gen::inRange(0, 4)];  // a knob of block only
        return o;
    });
}

/// Closed connected recipes: genus in [min_genus, max_genus], faces up to max_faces.
/// \pre 0 <= min_genus <= max_genus and max_faces >= generate::min_faces(max_genus).
inline rc::Gen<generate::RandomMeshOptions> gen_mesh_options(int min_genus = 0, int max_genus = 4,
                                                             std::size_t max_faces = 2000) {
    return gen_mesh_options(MeshRanges{min_genus, max_genus, max_faces});
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

/// A random mesh of a recipe drawn from the ranges (see gen_mesh_options); use it as a TriMesh:
/// `const TriMesh& m = *gen_mesh({.max_holes = 5, .max_components = 3});`.
inline rc::Gen<GeneratedMesh> gen_mesh(const MeshRanges& ranges) {
    return rc::gen::map(gen_mesh_options(ranges), [](const generate::RandomMeshOptions& o) {
        return GeneratedMesh{generate::random_mesh(o), o};
    });
}

/// A random closed connected mesh (see gen_mesh_options); use it as a TriMesh:
/// `const TriMesh& m = *gen_closed_mesh();`.
inline rc::Gen<GeneratedMesh> gen_closed_mesh(int min_genus = 0, int max_genus = 4, std::size_t max_faces = 2000) {
    return gen_mesh(MeshRanges{min_genus, max_genus, max_faces});
}

}  // namespace fhr::testing
