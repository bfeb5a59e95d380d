// FHR §5–§6 — the wavelet stage end to end, for the pipeline (`fhr run --levels J --keep …`):
//
//   refinement:      D^J <- refine(D, J); f^J(v) <- φ(v) at every vertex of D^J        (§5, Fig. 8)
//   decomposition:   the filter bank's operators; f^J -> f^0 + g^0 + … + g^{J−1}      (§5, eq. 3)
//   reconstruction:  f^J again from all coefficients (the round trip)
//   then, untimed:   the Hausdorff distance between Ω_T and f^J(Ω_D); for each kept percentage p:
//                    keep the largest ⌊p·N/100⌋ coefficients, reconstruct, L2 and Hausdorff
//                    errors                                                          (§6, Fig. 9)
// The three timed stages are the rows `refinement`, `decomposition`, `reconstruction` of the
// paper's timing table (§6).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include <fhr/core/executor.hpp>
#include <fhr/wavelet/hausdorff.hpp>
#include <fhr/wavelet/refine.hpp>

namespace fhr::wavelet {

/// One compressed reconstruction.
struct KeptResult {
    double percent = 0;           ///< p as requested
    std::size_t count = 0;        ///< ⌊p·N/100⌋ coefficients kept (N = coefficients)
    std::vector<Vec3> positions;  ///< #V(D^J): the reconstruction (triangles: WaveletResult::remesh_faces)
    double l2_error = 0;          ///< RMS over the vertices of D^J of |f^J(v) − reconstruction(v)|
    Hausdorff hausdorff;          ///< between Ω_T and the reconstruction
};

struct WaveletResult {
    int levels = 0;                      ///< J
    std::vector<Vec3> remesh_positions;  ///< f^J at the vertices of D^J (#V(D^J))
    std::vector<Triangle> remesh_faces;  ///< the faces of D^J (#F(D^J) = 4^J #F(D))
    /// The first #V(D^j) positions with these faces are f^j(Ω_D) on D^j: remesh_level_faces[j], j = 0..J.
    std::vector<std::vector<Triangle>> remesh_level_faces;
    Hausdorff remesh_hausdorff;           ///< between Ω_T and f^J(Ω_D)
    double bbox_diagonal = 0;             ///< of T
    double hausdorff_relative = 0;        ///< remesh_hausdorff.lower() / bbox_diagonal
    std::size_t coefficients = 0;         ///< #V(D^J) − #V(D)
    double reconstruction_max_error = 0;  ///< max_v |f^J(v) − reconstruct(decompose(f^J))(v)|_∞ (absolute)
    double max_abs_coordinate = 0;        ///< ‖f^J‖_∞, to read the error relatively
    std::vector<int> cg_iterations;       ///< per level j = 1..J: CG steps of the decomposition's solve
    std::vector<KeptResult> kept;         ///< one per requested percentage, in the order given
    double refinement_seconds = 0;        ///< refine + sample φ (steady_clock)
    double decomposition_seconds = 0;     ///< build the filter bank + decompose
    double reconstruction_seconds =
        0;  ///< the round trip's reconstruction and, per kept percentage, choosing the coefficients and reconstructing
    double hausdorff_seconds =
        0;  ///< all Hausdorff brackets, from T's tree to the last (an error measure, not a stage of the paper; f^J's runs beside the decomposition and reconstructions, so this includes them)
};

/// φ where it is affine: on each face of T′ (T refined by the partition, paper §3) φ maps the
/// β of the face's corners in the face `patch` of D to the corners' points of T; the face lies in
/// the face `t_face` of T. With it, the brackets start from per-face bounds (affine_bounds, WAV-15).
struct AffinePieces {
    std::span<const Vec3> points;  ///< the vertices of T′
    std::size_t faces = 0;         ///< #F(T′)
    /// Face f of T′: its corners (into points), the face of D of its patch, the corners' β there,
    /// the face of T that holds it.
    std::function<void(std::size_t f, Triangle& corners, std::uint32_t& patch,
                       std::array<std::array<double, 3>, 3>& beta, std::uint32_t& t_face)>
        face;
};

/// WAV-15: on a face of D^J, d(f^J(p), T) ≤ |f^J(p) − φ(p)| + (how far T′ lies from T), f^J
/// affine on the faces of D^J and φ on the images of T′'s faces, both in the β of a face of D. So
/// f^J − φ is affine on each piece where they overlap, and its norm, convex there, is largest at
/// the pieces' corners: the vertices of T′, the crossings of T′'s sides with the sides of D^J's
/// faces (lines β_c = m/2^J), and the vertices of D^J, where it is 0. Likewise on a face t of T,
/// d(x, f^J) ≤ |x − f^J(ψ(x))| + (how far T′ lies from T), largest at the same corners in the
/// faces of T′ in t.
struct AffineBounds {
    std::vector<double> remesh;  ///< per face of D^J: max over it of |f^J − φ|
    std::vector<double> t;       ///< per face of T: max over it of |x − f^J(ψ(x))|
};
/// Both, each raised by 10⁻¹² relative and by `on_t`, in one pass over T′'s faces (a corner on a
/// side shared by two faces of D^J, within 10⁻¹² in β, counts for both), in fixed blocks of them on
/// `executor` (maxima: the same bits on any number of threads). f_j: f^J at the vertices of
/// D^J = r.finest(); t_faces: #F(T). \pre pieces certified (AffinePieces, analyse).
AffineBounds affine_bounds(const Refinement& r, std::span<const Vec3> f_j, const AffinePieces& pieces,
                           std::size_t t_faces, double on_t, Executor* executor = nullptr);

/// The §5 wavelet stage for a domain D (closed or with boundary, one component or several),
/// φ: Ω_D → Ω_T and the input surface T. Hausdorff distances use `hausdorff_options`; a
/// resolution of 0 there means 1e−4 of T's bounding-box diagonal (the bracket [lower, upper] of
/// each distance is then that narrow). The samples of φ (sample()) and the brackets, independent
/// tasks, run on `executor` (default_executor() when null). `pieces`, when given, is φ's faces
/// (AffinePieces; T′ certified: its faces' images tile D, PARAM-6..8, and its points lie on T
/// within PARAM-11's tolerance, which the bounds add).
/// `t_tree`, when given, is T's tree for the brackets, built by the caller (fhr run: beside §2's
/// decimation, which runs on one thread); else it is built here.
/// \pre D passes validate(); phi defined on all of Ω_D (DomainMap); 0 ≤ levels with
///      4^levels·#F(D) ≤ max_refined_faces; each keep_percent in [0, 100]; T has a face; t_tree,
///      when given, is TriangleTree(T.positions(), T.triangles()).
/// \throws InvalidInput for a bad level or percentage, NumericalFailure when the decomposition's
///         solve fails (filter_bank.hpp), and whatever phi throws.
WaveletResult analyse(const TriMesh& D, const DomainMap& phi, int levels, std::span<const double> keep_percent,
                      const TriMesh& T, const HausdorffOptions& hausdorff_options = {}, Executor* executor = nullptr,
                      const AffinePieces* pieces = nullptr, const TriangleTree* t_tree = nullptr);

}  // namespace fhr::wavelet
