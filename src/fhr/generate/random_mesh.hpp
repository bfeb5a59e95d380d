// FHR generate — random orientable manifold triangulations of any genus, with a chosen number of
// boundary loops (holes) and connected components. With no holes and one component they are
// exactly the meshes the paper (§1) takes as input T; surfaces with boundary and several
// components are beyond the paper (issue 19: fhr's extension to them). Made on demand for the
// property tests, the fuzzers, and users fuzzing their own code (`fhr generate`). The
// construction and its guarantees are described in paper_notes/generator.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include <fhr/core/trimesh.hpp>

namespace fhr::generate {

/// A recipe. genus and holes are totals over the components, spread as evenly as possible:
/// component c (0-based, of C) gets ⌊g/C⌋ handles, plus one if c < g mod C, and likewise
/// ⌊b/C⌋ (+1 if c < b mod C) holes. Existing recipes (holes = 0, components = 1) give the
/// same meshes as before these two options existed.
struct RandomMeshOptions {
    int genus = 0;            ///< g >= 0: number of handles, in total
    std::size_t faces = 1000; ///< exact face count F >= min_faces(genus, holes, components); even when holes = 0
    std::uint64_t seed = 1;   ///< the same options give a bit-identical mesh, on any compiler
    double noise = 0.0;       ///< in [0, 0.5): vertex jitter, as a fraction of the mean length of its edges
    int holes = 0;            ///< b in [0, max_holes]: number of boundary loops, in total
    int components = 1;       ///< C in [1, max_components]: number of connected components
};

/// Smallest face count the generator can produce for these totals: the sum over the components
/// (spread as in RandomMeshOptions) of 2·Q, Q = the unit squares on the surface of the
/// component's block (paper_notes/generator.md). One closed component: 12 for g = 0 (a unit
/// cube) and 36g + 28 for g >= 1. Always even; with holes > 0 every F >= min_faces is possible,
/// without holes every even one.
/// \throws InvalidInput("", 0, ...) when genus < 0, holes is not in [0, max_holes] or components
///         is not in [1, max_components].
std::size_t min_faces(int genus, int holes = 0, int components = 1);

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
/// \throws InvalidInput("", 0, ...) when an option is out of range: see min_faces, faces odd
///         while holes = 0, faces < min_faces(genus, holes, components), faces > max_faces, or
///         noise is not in [0, 0.5).
TriMesh random_mesh(const RandomMeshOptions& options);

/// random_mesh for a closed surface (the paper's input class, §1, when components = 1).
/// \throws InvalidInput("", 0, ...) when options.holes != 0, or as random_mesh.
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
