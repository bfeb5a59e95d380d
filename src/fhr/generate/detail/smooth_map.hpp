// FHR generate — the smooth family's maps (beyond the paper), shared by the smooth and
// the immersed family: where a vertex of a block mesh goes on the rounded, deformed surface, and
// how a mesh is moved to such targets without ever leaving the embedded meshes. The construction
// and the argument are in families/smooth.cpp and paper_notes/generator.md ("The smooth family").
// Internal to libfhr_generate.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <fhr/core/trimesh.hpp>
#include <fhr/generate/detail/family.hpp>

namespace fhr::generate::detail {

/// The quintic smoothstep S(t) = t³(10 − 15t + 6t²) on [0, 1], 0 below, 1 above: C², with
/// S(1/2) = 1/2 exactly.
inline double smoothstep(double t) {
    if (t <= 0) return 0;
    if (t >= 1) return 1;
    return t * t * t * (t * (t * 6 - 15) + 10);
}

/// One component's block as its mesh lies: W x H unit cells, one thick, the smallest corner at
/// (x0, −H/2, −1/2), the genus cells (1, 1), (3, 1), … removed (paper_notes/generator.md, step 1).
struct Slab {
    double x0 = 0;
    long W = 1, H = 1, genus = 0;
    bool solid(long i, long j) const {
        return i >= 0 && j >= 0 && i < W && j < H && !(j == 1 && i % 2 == 1 && i < 2 * genus);
    }
};

/// Component c's share of a total over C components (spec/generator.md).
inline int share(int total, int components, int c) { return total / components + (c < total % components ? 1 : 0); }

/// The slab of each component of a block mesh of the recipe `o` (its components numbered in
/// order, as random_mesh makes them), read from the mesh's bounding boxes and the genus shares.
std::vector<Slab> block_slabs(const TriMesh& block, const RandomMeshOptions& o,
                              const VertexData<std::uint32_t>& component);

/// Step 1, rounding: p on the surface of `slab` moved along the gradient of the slab blurred by
/// the kernel of radius `roundness` (in (0, 1/2)) onto its level set 1/2.
Vec3 rounded(const Slab& slab, double roundness, const Vec3& p);

/// Step 2, deformation: x ↦ x + d(x), d a sum of random plane waves with |d| <= amplitude and
/// Lipschitz constant <= 0.75 (injective for amplitude in [0, 1/2]). Draws its waves from rng.
class Deformation {
public:
    Deformation(Random& rng, double amplitude);
    Vec3 operator()(const Vec3& x) const;

private:
    struct Wave {
        Vec3 frequency;     // direction / wavelength
        double phase;       // in [0, 1)
        Vec3 displacement;  // direction × amplitude
    };
    std::vector<Wave> waves_;
};

/// Moves every vertex v of the embedded mesh m toward target[v], keeping m embedded: all at once
/// when the result is embedded (find_self_intersection, exact), otherwise in `passes` passes,
/// vertex by vertex, to base + (k/passes)(target − base), each move only if the EmbeddingGuard
/// accepts it. \return how many vertices reached their target.
std::size_t move_embedded(TriMesh& m, std::span<const Vec3> target, int passes = 8);

}  // namespace fhr::generate::detail
