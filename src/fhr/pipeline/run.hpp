// FHR §2–§5 — one call for the whole method, in memory: the domain D (§2), the partition and the
// certified parameterization (§3, §4), the independent oracle's verdict on it, and optionally the
// remesh, the prewavelet decomposition and its compression (§5). `fhr run` is this call between
// parsing its arguments and writing its files (src/cli/run.cpp, src/fhr/app/outputs.hpp).
//
// Pseudocode:
//   mesh_reduction:   D <- decimate(T) to `faces`, or the domain given (already attached to T);
//                     beside it (T below 2^18 faces) the oracle's side of T and §5's tree of T
//   geodesic_paths, parameterization: parameterize(T, D)                  (pipeline.hpp)
//   other_domains:    beyond the paper, the default map on §2's own D: where it misses a
//                     percentile goal, D decimated again under graded normal rules and
//                     parameterized, the better map kept               (pipeline.hpp, another_domain)
//   verification:     the oracle (src/fhr/exchange) on exactly what param.fhrp would hold
//   with J = levels > 0: refinement, decomposition, reconstruction: D^J sampled through φ, its
//                     prewavelet coefficients, the kept percentages reconstructed (src/fhr/wavelet),
//                     beside the oracle (two tasks: they read different parts of the result, and
//                     each stage's seconds are its own, so the stages' sum may exceed the wall time)
// Thread safety: run() keeps no state between calls; concurrent calls (on the same T too) are safe.
// Its progress lines and stage times are reported on the calling thread; its independent tasks run
// on options.method.executor (core/executor.hpp), with the same result on any executor.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include <fhr/domain/decimate.hpp>
#include <fhr/exchange/verify.hpp>
#include <fhr/pipeline/pipeline.hpp>
#include <fhr/wavelet/analyse.hpp>

namespace fhr::pipeline {

struct RunOptions {
    std::size_t faces = 0;                 ///< §2: decimate T to exactly this many faces, or 0 with `domain`
    double corner_angle_deg = 60.0;        ///< §2 with boundary: boundary corners D keeps (DecimateOptions)
    std::optional<domain::Domain> domain;  ///< §2: a domain given by the user, attached to T (domain::attach_domain)
    Options method;                        ///< §3–§4: weights, solver, keeping D, progress, stage observer
    int levels = 0;                        ///< §5: J ≥ 1 to remesh and decompose; 0 for none
    std::vector<double> keep;              ///< §5: the percentages of coefficients to keep, each in (0, 100]
};

struct RunResult {
    Parameterization parameterization;               ///< D (final), T′, ψ, certificates
    exchange::VerifyReport oracle;                   ///< fhr verify's judgement of it against T
    std::optional<wavelet::WaveletResult> wavelets;  ///< with levels > 0
    std::size_t domain_faces_asked = 0;              ///< RunOptions::faces (0 with a given domain)
    std::size_t domain_faces_requested = 0;          ///< D's faces before §3 (equal to the final ones when D is kept)
    bool certified() const { return parameterization.certified() && oracle.valid(); }
};

/// The parameterization as the exchange format holds it (spec/param.md): what `fhr run` writes as
/// param.fhrp and the oracle judges.
exchange::ParamFile to_param_file(const Parameterization& p);

/// The method end to end. A result that is not certified is returned, not thrown: its files can
/// still be written and inspected.
/// \pre T is valid (build_trimesh; boundary loops and several components allowed); exactly one of
///      faces > 0 and domain. With boundary or several components §2 may give D more faces than
///      asked (domain::decimate; the progress line says why).
/// \throws InvalidInput (a face count §2 cannot reach, levels or keep out of range),
///         PartitionFailure, NumericalFailure, InternalError (see parameterize).
RunResult run(const TriMesh& T, RunOptions options);

}  // namespace fhr::pipeline
