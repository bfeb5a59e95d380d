// FHR §2–§4 — the method end to end, in memory: the domain D (§2), the partition of T into
// patches by geodesics (§3), and one convex-combination map per patch (§4), certified.
//
// Pseudocode (paper §6 runs exactly these stages; their names are the timing table's):
//   mesh_reduction:   D <- decimate(T) (or the user's D, attached to T)
//   geodesic_paths:   paths, T′, patches <- partition(T, D)       (D may be refined: §3 recovery)
//   parameterization: for each patch S_i: split its dividing edges (Floater 2003, Thm 6.1);
//                     ψ_i <- chord-length boundary + convex combinations inside (eq. 2);
//                     beyond the paper (unless the paper's map is asked for): ψ_i relaxed, kept
//                     when its certificate passes (param/relax.hpp);
//                     certify ψ_i (exact orientation, boundary monotone, areas);
//                     beyond the paper: the curves beside poorly mapped patches moved
//                     (detail/straighten.hpp) and the patches cut anew mapped again; the curves'
//                     vertices slid along D's edges (detail/slide.hpp), kept when every changed
//                     patch's certificate passes
//   the final T′ (with the dividing-edge midpoints) and, per face, its patch and the β of ψ
//   at its corners: the `fhr-param 1` content (spec/param.md)
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include <fhr/core/executor.hpp>
#include <fhr/core/trimesh.hpp>
#include <fhr/domain/decimate.hpp>
#include <fhr/domain/domain.hpp>
#include <fhr/param/certificate.hpp>
#include <fhr/param/locate.hpp>
#include <fhr/param/patch_map.hpp>
#include <fhr/partition/partition.hpp>

namespace fhr::pipeline {

/// Told the wall-clock seconds of each stage as it ends (names: paper §6's timing table, spec/cli.md
/// CLI-RUN-3); `in_total` is false for a measurement of the result rather than a stage of the
/// method. Called on the thread that called the pipeline. Timings stay out of the algorithms'
/// signatures: a caller that wants them passes an observer.
class StageObserver {
public:
    virtual ~StageObserver() = default;
    virtual void stage(std::string_view name, double seconds, bool in_total) = 0;
};

struct Options {
    param::PatchMapOptions map;
    /// Beyond the paper: each patch map relaxed (param/relax.hpp) where that lowers its distortion
    /// and keeps its certificate; false: the paper's §4 map exactly (`fhr run --map paper`).
    bool relax = true;
    /// Beyond the paper (Options::relax): the sliding's faces weighed by their image area's share
    /// (detail/slide.hpp, SlideOptions::image_weighted); another_domain's last try.
    bool image_weighted_sliding = false;
    bool keep_domain = true;  ///< §3: keep D (restricted paths where geodesics conflict), else change it
    std::function<void(const std::string&)> progress;  ///< optional: one line per step, on the calling thread
    StageObserver* observer = nullptr;                 ///< optional: the seconds of each stage
    Executor* executor =
        nullptr;  ///< optional: runs the independent tasks (paths, patches, §5's brackets); default_executor()
};

/// The parameterization φ: Ω_D → Ω_T as computed, with everything the outputs need.
struct Parameterization {
    /// D (final), paths, T′ before §4, patches (their faces and vertices; each patch's disk is moved
    /// to `disks`, not copied: at 10⁶ faces 57 MB)
    partition::Partition partition;
    IdVector<DFaceId, param::Disk> disks;     ///< #F(D): each patch's disk after its dividing edges were split
    IdVector<DFaceId, param::PatchMap> maps;  ///< #F(D): ψ_i at the disk's vertices
    IdVector<DFaceId, param::Certificate> certificates;  ///< #F(D)
    std::size_t dividing_edges_split = 0;
    std::size_t relaxed_patches = 0;  ///< patches whose map is the relaxed one (Options::relax)
    std::size_t slid_patches = 0;     ///< patches whose curves' vertices slid along D's edges (Options::relax)
    /// Options::relax: the relaxed map before any curve moved, the bounds every choice of the default
    /// map keeps to: Σ over its patches of Σ_f a_f (σ₁² + σ₂²) / 2 (a_f the image area: DIST-3's
    /// numerator, T's area its denominator whatever D), and its faces
    struct Unmoved {
        double l2_energy = 0;
        std::size_t faces = 0;
    } unmoved;
    /// another_domain: the graded rules' first angles (degrees) of the D it chose; 0: §2's D
    double graded_normal_rule = 0;
    double graded_min_angle = 0;
    std::size_t domains_tried = 1;  ///< the domains parameterized to choose this one (another_domain)
    /// another_domain: the vertices T was refined by at D's vertices for this map (detail/corners.hpp);
    /// 0: none. Otherwise `partition` is of that refinement, `corner_refined_t` (T's vertices keep
    /// their ids there, the cuts come after them; its faces are T's faces cut), and face_t still names
    /// faces of T.
    std::size_t corner_vertices = 0;
    TriMesh corner_refined_t;
    bool image_weighted_sliding = false;  ///< this map's sliding weighed its faces by image area (Options)
    // The final T′: T′ of §3 plus the dividing-edge midpoints, as plain arrays (for writers and numpy;
    // nothing reads its connectivity after §4, which a TriMesh would hold: paper_notes/library.md).
    std::vector<Vec3> refined_positions;
    std::vector<Triangle> refined_faces;
    // Per face of the final T′ (parallel to refined_faces, as in the `fhr-param 1` file):
    IdVector<RefinedFaceId, DFaceId> face_patch;                              ///< the D face of its patch
    IdVector<RefinedFaceId, std::array<std::array<double, 3>, 3>> face_beta;  ///< per corner: β of ψ
    IdVector<RefinedFaceId, TFaceId> face_t;                                  ///< the face of T that holds it
    bool certified() const;                                                   ///< every patch's certificate passed
};

/// The global maps of §4: φ = ψ⁻¹ from any point of Ω_D (a face of D and barycentric coordinates
/// in its corner order) to Ω_T, and ψ from any point of T′ (a face of the final T′ and barycentric
/// coordinates in its corner order) to Ω_D. A point on an edge of D gives the same point of T from
/// both faces, bit for bit (the patches' sides are parameterized from a canonical end, MAP-11).
class GlobalMap {
public:
    /// \pre p is certified (every patch one-to-one); p outlives this object.
    explicit GlobalMap(const Parameterization& p);
    /// φ(d, β): the point of Ω_T whose image under ψ is β in domain face d.
    /// \throws InvalidInput for β outside the triangle (beyond 1e−12), as PatchLocator.
    Vec3 phi(DFaceId d, const std::array<double, 3>& beta) const;
    /// ψ(f, w): the domain face and β of the point Σ w_k · (corner k of face f of T′).
    std::pair<DFaceId, std::array<double, 3>> psi(RefinedFaceId f, const std::array<double, 3>& w) const;

private:
    const Parameterization& p_;
    IdVector<DFaceId, param::PatchLocator> locators_;
};

/// §3 and §4 for T and a domain D whose vertices are vertices of T.
/// \throws PartitionFailure (§3 conditions unrecoverable), NumericalFailure (a weight or solve),
///         InternalError (a patch §3 made that §4 refuses).
Parameterization parameterize(const TriMesh& T, domain::Domain D, const Options& options);

/// Beyond the paper, for the default map (Options::relax) on fhr's own coarse D (at most
/// coarse_domain_faces faces), decimated from T with `decimated_with` (the plain normal rule):
/// where p's map misses a goal of spec/distortion.md, T is decimated again under the first
/// mapped_rules of domain_rules (the graded normal rule, domain::DecimateOptions::
/// first_normal_deviation_deg) in turn, and each D with p's faces and not yet tried is
/// parameterized, until one's map meets the goals. While none does, the D's of the other rules
/// (with the graded angle rule too, first_min_angle_deg) are screened by their first maps (§4's,
/// relaxed, before any curve moves), and the mapped_rules with the least image area above
/// σ₁/σ₂ = 3 there are parameterized in that order, until one meets the goals. While none does, last,
/// T is refined at the vertices of the best D so far (detail/corners.hpp) and that D parameterized
/// on it; then, the same, the best D so far (on T) mapped again with the sliding's faces weighed by
/// their image area (Options::image_weighted_sliding). Returned: the first that meets the goals,
/// else the best, or p itself. A map is a candidate only
/// when its L2 energy is at most p.unmoved's (so its L2 stretch is never above the paper map's on
/// §2's D), its faces at most 20 % more than p.unmoved's, and its D of p's faces (§3 kept it); it replaces the best so far when it meets all three goals, or when its σ₁/σ₂ 99th percentile
/// (image-area weighted, measured by the map's own scores) is lower, its 99.9th no higher than the
/// best's or 10, and its worst face no worse than the best's or 10³. Its seconds are the stage
/// `other_domains` (Options::observer), reported when another D was tried.
/// Each other domain mapped costs a whole §3–§4, each screened one §3 and §4's first maps; on the
/// corpus only domains of at most 184 faces gained (paper_notes/distortion_causes.md, "Another
/// domain"), and the cheese's 1,232 took over 30 min.
struct DomainRule {
    double normal, min_angle;
};
inline constexpr std::array<DomainRule, 20> domain_rules{{{45, 0},  {60, 0},  {30, 0},  {20, 0},  // mapped in turn
                                                          {75, 0},  {45, 10}, {60, 10}, {30, 10}, {20, 10}, {75, 10},
                                                          {45, 15}, {60, 15}, {30, 15}, {20, 15}, {75, 15}, {45, 20},
                                                          {60, 20}, {30, 20}, {20, 20}, {75, 20}}};
inline constexpr std::size_t mapped_rules = 4;
inline constexpr std::size_t coarse_domain_faces = 256;
Parameterization another_domain(const TriMesh& T, Parameterization p, const domain::DecimateOptions& decimated_with,
                                const Options& options);

}  // namespace fhr::pipeline
