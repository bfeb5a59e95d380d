// FHR generate — what the generator's families share (beyond the paper): the
// deterministic random stream, geometry written out in a fixed evaluation order (bit-identical
// results on every compiler: only correctly rounded +, −, ×, ÷, √), and one entry point per
// family. Internal to libfhr_generate; the public API is random_mesh.hpp.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <string>

#include <fhr/core/errors.hpp>
#include <fhr/core/trimesh.hpp>
#include <fhr/generate/random_mesh.hpp>

namespace fhr::generate::detail {

[[noreturn]] inline void invalid(const std::string& what) { throw InvalidInput(what); }

/// std::mt19937_64 (fully specified by the standard) with our own uniform mappings (the
/// std::uniform_*_distribution outputs differ between standard libraries).
class Random {
public:
    explicit Random(std::uint64_t seed) : engine_(seed) {}
    /// Uniform in [0, n), n > 0: draws below 2^64 mod n are rejected, leaving a multiple of n values.
    std::uint64_t below(std::uint64_t n) {
        const std::uint64_t threshold = (0 - n) % n;
        for (;;) {
            const std::uint64_t x = engine_();
            if (x >= threshold) return x % n;
        }
    }
    /// Uniform in [−1, 1) on a grid of 2^−52.
    double symmetric() { return static_cast<double>(engine_() >> 11) * 0x1.0p-52 - 1.0; }
    /// Uniform in [0, 1) on a grid of 2^−53.
    double unit() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
    bool coin() { return (engine_() >> 63) != 0; }

private:
    std::mt19937_64 engine_;
};

/// The seed of a family's own stream: the recipe's seed mixed with the family (splitmix64's
/// finalizer), so a family's draws never repeat the block's.
inline std::uint64_t family_seed(std::uint64_t seed, Family family) {
    std::uint64_t z = seed + 0x9E3779B97F4A7C15ull * (static_cast<std::uint64_t>(family) + 1);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

// Geometry in a fixed evaluation order (Eigen's vectorized reductions may sum in another order).
inline double dot(const Vec3& a, const Vec3& b) { return a.x() * b.x() + a.y() * b.y() + a.z() * b.z(); }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
    return Vec3(a.y() * b.z() - a.z() * b.y(), a.z() * b.x() - a.x() * b.z(), a.x() * b.y() - a.y() * b.x());
}
inline double length(const Vec3& a) { return std::sqrt(dot(a, a)); }
inline Vec3 normal(const Vec3& a, const Vec3& b, const Vec3& c) { return cross(b - a, c - a); }

/// The block mesh of the recipe's genus, holes, components and seed with `faces` faces and no
/// noise: every family's starting point (embedded, proven: paper_notes/generator.md).
TriMesh base_block(const RandomMeshOptions& options, std::size_t faces);

/// The block family itself (block.cpp): its least face count and its mesh.
std::size_t block_min_faces(const RandomMeshOptions& options);
TriMesh block_mesh(const RandomMeshOptions& options);

/// A recipe's checks before any family makes it: the noise (the block's knob only), the face
/// count against `least_faces(options)` (the family's, its knobs checked there), its parity
/// without holes, and max_faces. \throws InvalidInput naming the first that fails.
void check_recipe(const RandomMeshOptions& options, std::size_t (*least_faces)(const RandomMeshOptions&));

// One entry point per family: `<family>_min_faces(options)` is the family's least face count (its
// knobs checked: InvalidInput naming the knob and its range), `<family>_mesh(options)` the mesh,
// exactly options.faces faces, options already checked against that least count.
std::size_t smooth_min_faces(const RandomMeshOptions& options);
TriMesh smooth_mesh(const RandomMeshOptions& options);
std::size_t quality_min_faces(const RandomMeshOptions& options);
TriMesh quality_mesh(const RandomMeshOptions& options);
std::size_t valence_min_faces(const RandomMeshOptions& options);
/// random_draws: the random faces tried for each valence-3 vertex before the scan that finds one
/// for certain. The recipes' meshes use 32, and no recipe tried reaches the scan then; the tests
/// pass 0 to exercise it (GEN-11 "the scan alone").
TriMesh valence_mesh(const RandomMeshOptions& options, int random_draws = 32);
std::size_t density_min_faces(const RandomMeshOptions& options);
TriMesh density_mesh(const RandomMeshOptions& options);
std::size_t degenerate_min_faces(const RandomMeshOptions& options);
TriMesh degenerate_mesh(const RandomMeshOptions& options);
std::size_t immersed_min_faces(const RandomMeshOptions& options);
TriMesh immersed_mesh(const RandomMeshOptions& options);

}  // namespace fhr::generate::detail
