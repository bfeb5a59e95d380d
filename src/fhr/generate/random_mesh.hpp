// FHR generate — random closed, connected, orientable manifold triangulations of any genus:
// exactly the meshes the paper (§1) takes as input T, made on demand for the property tests,
// the fuzzers, and users fuzzing their own code (`fhr generate`). The construction and its
// guarantees are described in paper_notes/generator.md.
#pragma once

#include <cstddef>
#include <cstdint>

#include <fhr/core/trimesh.hpp>

namespace fhr::generate {

struct RandomMeshOptions {
    int genus = 0;            ///< g >= 0: number of handles
    std::size_t faces = 1000; ///< exact face count F: even and >= min_faces(genus)
    std::uint64_t seed = 1;   ///< the same options give a bit-identical mesh, on any compiler
    double noise = 0.0;       ///< in [0, 0.5): vertex jitter, as a fraction of the mean length of its edges
};

/// Smallest face count the generator can produce for genus g: 12 for g = 0 (a unit cube), and
/// 36g + 28 for g >= 1 (the (2g+1) x 3 x 1 block of unit cells with g unit holes in a row: its
/// surface has 18g + 14 unit squares, two triangles each).
/// \throws InvalidInput("", 0, ...) when genus < 0.
std::size_t min_faces(int genus);

/// A random mesh with exactly `options.faces` faces and Euler characteristic 2 − 2·genus.
/// \post the mesh passes TriMesh::validate() (no garbage) and build_trimesh (no degenerate
///       triangle); it is oriented outward (positive signed volume); every corner angle is at
///       least 20° (min_corner_angle_degrees); the output depends only on the options.
/// \throws InvalidInput("", 0, ...) when genus < 0, faces is odd, faces < min_faces(genus),
///         faces > max_faces, or noise is not in [0, 0.5).
TriMesh random_closed_mesh(const RandomMeshOptions& options);

/// The largest face count accepted (the connectivity of 5·10^7 faces takes about 3 GB).
inline constexpr std::size_t max_faces = 50'000'000;

/// Every corner angle of a generated mesh is at least this many degrees.
inline constexpr double min_corner_angle_degrees = 20.0;

}  // namespace fhr::generate
