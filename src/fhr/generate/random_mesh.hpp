// FHR generate — random orientable manifold triangulations of any genus, with a chosen number of
// boundary loops (holes) and connected components. With no holes and one component they are
// exactly the meshes the paper (§1) takes as input T; surfaces with boundary and several
// components are beyond the paper (fhr's extension to them). Made on demand for the
// property tests, the fuzzers, and users fuzzing their own code (`fhr generate`). The
// construction and its guarantees are described in paper_notes/generator.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include <fhr/core/trimesh.hpp>

namespace fhr::generate {

/// The kinds of mesh the generator makes (meshes as hard as real ones). `block` is the
/// generator's first kind, the re-triangulated perforated slab (paper_notes/generator.md); the
/// others start from a block mesh of the same genus, holes and components and make it hard in one
/// way each, keeping the exact face count. All but `immersed` are embedded, which their
/// construction guarantees edit by edit with exact predicates (generate/embedding.hpp).
/// `immersed` is drawn only when asked for by name.
enum class Family {
    block,       ///< the perforated slab: corners >= 20°, valences 3–10, flat facets, creases
    smooth,      ///< curved: the slab rounded and smoothly deformed, no flat facet left
    quality,     ///< needles, caps and slivers down to a chosen smallest angle
    valence,     ///< vertices of valence 3 and a fan of very high valence, by flips and splits
    density,     ///< graded and anisotropic refinement: edge-length ratios of 10^4 and more
    degenerate,  ///< coordinates on a coarse grid: exact coplanarity and collinearity, no zero area
    immersed,    ///< combinatorially manifold and oriented, but self-intersecting (opt-in only)
};

/// The family's name as `fhr generate --family` spells it ("block", "smooth", ...).
const char* family_name(Family family);
/// The family of that name. \throws InvalidInput(...) naming the families for another.
Family parse_family(const std::string& name);
/// The embedded families (all but immersed), in the order of the enum: what fuzzers and
/// property tests draw from.
inline constexpr Family embedded_families[] = {Family::block,   Family::smooth,  Family::quality,
                                               Family::valence, Family::density, Family::degenerate};

/// Each family's own knobs; a family reads only its own. The defaults are the ones the family's
/// guarantees are stated for (spec/generator.md GEN-8..13).
struct FamilyKnobs {
    // smooth
    double roundness = 0.3;   ///< radius of the rounding of the slab's creases, in unit cells, in (0, 0.45]
    double amplitude = 0.25;  ///< size of the random smooth deformation, in unit cells, in [0, 0.5]
    // quality
    double bad_fraction = 0.1;         ///< share of the faces that are needles, caps or slivers, in (0, 0.5]
    double smallest_angle_deg = 1e-4;  ///< the thinnest triangle's smallest corner, degrees, in [1e-9, 1]
    // valence
    int high_valence = 64;       ///< one vertex per component reaches at least this valence, in [7, 1000]
    double low_fraction = 0.05;  ///< share of the vertices made valence 3, in [0, 0.2]
    // density
    double edge_ratio = 1e5;  ///< longest / shortest edge reached by graded refinement, in [10, 1e9]
    double anisotropy = 100;  ///< aspect ratio of the anisotropic band's triangles, in [1, 1e6]
    // degenerate
    int grid_cells =
        8;  ///< grid steps per mean edge length (coordinates on a power-of-two grid <= mean edge / grid_cells), in [2, 1024]
    // immersed
    double depth = 1.5;  ///< how far a bump is pushed through the slab, in slab thicknesses, in [1.1, 4]
    bool operator==(const FamilyKnobs&) const = default;
};

/// The knobs by the names `fhr generate` gives them (`--smallest-angle` is "smallest-angle"), each
/// with its family, in the order of FamilyKnobs: knob_names() lists them all.
struct KnobName {
    const char* name;
    Family family;
};
std::span<const KnobName> knob_names();

/// Sets the knob of that name (as in knob_names; '_' may stand for '-') to value: the one place
/// the CLI and the Python package turn a name into a knob. Integer knobs take an integral value.
/// \throws InvalidInput(...) for an unknown name, a knob of another family than `family`
///         (it would be silently ignored) or a non-integral value for an integer knob. Ranges are
///         checked by min_faces(options) and random_mesh.
void set_knob(FamilyKnobs& knobs, Family family, const std::string& name, double value);

/// A recipe. genus and holes are totals over the components, spread as evenly as possible:
/// component c (0-based, of C) gets ⌊g/C⌋ handles, plus one if c < g mod C, and likewise
/// ⌊b/C⌋ (+1 if c < b mod C) holes. Recipes with holes = 0 and components = 1 give the
/// closed generator's meshes, pinned by GEN-4.
struct RandomMeshOptions {
    int genus = 0;                  ///< g >= 0: number of handles, in total
    std::size_t faces = 1000;       ///< exact face count F >= min_faces(genus, holes, components); even when holes = 0
    std::uint64_t seed = 1;         ///< the same options give a bit-identical mesh, on any compiler
    double noise = 0.0;             ///< in [0, 0.5): vertex jitter, as a fraction of the mean length of its edges
    int holes = 0;                  ///< b in [0, max_holes]: number of boundary loops, in total
    int components = 1;             ///< C in [1, max_components]: number of connected components
    Family family = Family::block;  ///< what kind of mesh; block recipes give the meshes pinned by GEN-4
    FamilyKnobs knobs{};            ///< the family's own options (ignored by block)
};

/// Smallest face count the generator can produce for these totals: the sum over the components
/// (spread as in RandomMeshOptions) of 2·Q, Q = the unit squares on the surface of the
/// component's block (paper_notes/generator.md). One closed component: 12 for g = 0 (a unit
/// cube) and 36g + 28 for g >= 1. Always even; with holes > 0 every F >= min_faces is possible,
/// without holes every even one.
/// \throws InvalidInput(...) when genus < 0, holes is not in [0, max_holes] or components
///         is not in [1, max_components].
std::size_t min_faces(int genus, int holes = 0, int components = 1);

/// The smallest face count random_mesh accepts for this recipe (its faces ignored): min_faces of
/// its genus, holes and components for block, more for families that add features of a given
/// size (quality's insertions, valence's fan, density's refinement levels).
/// \throws InvalidInput as min_faces, or when a knob of the family is out of its range.
std::size_t min_faces(const RandomMeshOptions& options);

/// A random mesh with exactly `options.faces` faces, `options.components` connected components
/// and `options.holes` boundary loops in total, component c having Euler characteristic
/// 2 − 2g_c − b_c (its share of the totals).
/// \post the mesh passes TriMesh::validate() (no garbage) and build_trimesh with
///       require_closed = require_connected = false (no degenerate triangle, every vertex
///       manifold); every boundary loop is a simple closed curve and no two share a vertex;
///       every component is consistently oriented, outward: a closed one has positive signed
///       volume, one with holes has the orientation of the closed block surface it was cut from;
///       component c is numbered before component c + 1 (vertices, faces) and lies at x
///       coordinates at least 1 beyond the components before it; every corner angle is at least
///       20° (min_corner_angle_degrees); the output depends only on the options.
/// \throws InvalidInput(...) when an option is out of range: see min_faces, faces odd
///         while holes = 0, faces < min_faces(genus, holes, components), faces > max_faces, or
///         noise is not in [0, 0.5).
TriMesh random_mesh(const RandomMeshOptions& options);

/// random_mesh for a closed surface (the paper's input class, §1, when components = 1).
/// \throws InvalidInput(...) when options.holes != 0, or as random_mesh.
TriMesh random_closed_mesh(const RandomMeshOptions& options);

/// The `fhr generate` command line that writes the mesh of these options to `out`, options at
/// their defaults left out (no --holes 0, --components 1, --noise 0), the noise as %g prints it:
/// what a failing property test or a fuzzer's finding shows to reproduce its mesh.
std::string generate_command(const RandomMeshOptions& options, const std::string& out = "mesh.off");

/// The largest face count accepted (the connectivity of 5·10^7 faces takes about 3 GB).
inline constexpr std::size_t max_faces = 50'000'000;
/// The largest numbers of holes and components accepted.
inline constexpr int max_holes = 10'000;
inline constexpr int max_components = 10'000;

/// Every corner angle of a generated mesh is at least this many degrees.
inline constexpr double min_corner_angle_degrees = 20.0;

}  // namespace fhr::generate
