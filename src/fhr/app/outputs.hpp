// FHR §6 — what `fhr run` writes (spec/cli.md, spec/formats.md): the domain, the geodesic network,
// T′ with its patches, the `fhr-param 1` exchange file, a textured T′ for any mesh viewer, the
// report and the timings. Every file is written atomically; everything but timings.json is
// byte-identical across runs.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <fhr/core/trimesh.hpp>
#include <fhr/exchange/distortion.hpp>
#include <fhr/exchange/verify.hpp>
#include <fhr/pipeline/pipeline.hpp>
#include <fhr/wavelet/analyse.hpp>

namespace fhr::app {

using pipeline::Options;
using pipeline::Parameterization;
using pipeline::StageObserver;

/// Wall-clock seconds per stage, in the order run (names: paper §6's timing table): the observer
/// of a run whose timings.json is written.
struct Timings final : StageObserver {
    std::vector<std::pair<std::string, double>> stages;  ///< summed into "total"
    std::vector<std::pair<std::string, double>>
        after_total;  ///< written after "total", not summed: measurements of the result
    void stage(std::string_view name, double seconds, bool in_total) override {
        (in_total ? stages : after_total).emplace_back(std::string(name), seconds);
    }
};

/// What the report says about the input (and the domain asked for).
struct InputInfo {
    std::string path;
    std::size_t vertices = 0, faces = 0;
    long genus = 0;
    std::size_t boundary_loops = 0, components = 1;
    std::size_t domain_faces_asked = 0;      ///< `--faces` (0 for a domain given by the user)
    std::size_t domain_faces_requested = 0;  ///< the domain's faces before §3's recovery
};

/// Writes the files of the parameterization alone into DIR (created if needed): domain.off,
/// geodesics.obj, refined.ply, param.fhrp and textured.obj, each in parts on `executor`'s threads, from
/// `file`, which is pipeline::to_param_file(p) or the file p lends (pipeline::lend_param_file: then T′'s vertices and
/// β are in the file only). `fhr run` writes them beside the oracle (pipeline::RunBeside::beside_oracle).
void write_parameterization(const std::string& dir, const Parameterization& p, const exchange::ParamFile& file,
                            Executor* executor);

/// Writes §5's meshes into DIR (created if needed): remesh_L{J}.off (f^J on D^J) and
/// wavelet_keep{p}.off for each kept percentage, each in parts on `executor`'s threads. `fhr run` writes them
/// as soon as §5 is done, beside the oracle (pipeline::RunBeside::after_wavelets).
void write_wavelets(const std::string& dir, const wavelet::WaveletResult& wavelets, Executor* executor);

/// Files the caller has written already into DIR, with the seconds each group took: they are not
/// written again by write_outputs.
struct WrittenBeside {
    std::optional<double> parameterization;  ///< write_parameterization's five files
    std::optional<double> wavelets;          ///< write_wavelets' meshes
};

/// report.json's text: the input, D, the partition, the parameterization with the oracle's verdict
/// and distortion figures, and with §5's result its `remesh` and `wavelet` sections (spec/cli.md).
std::string report_json(const InputInfo& input, const Parameterization& p, const exchange::VerifyReport& oracle,
                        const Options& options, const wavelet::WaveletResult* wavelets);

/// timings.json's text: each stage's seconds, their "total", then the measurements after it.
std::string timings_json(const Timings& timings);

/// The texts of report.json and timings.json as write_outputs wrote them.
struct RunTexts {
    std::string report, timings;
};

/// Writes DIR/{domain.off, geodesics.obj, refined.ply, param.fhrp, textured.obj, report.json,
/// timings.json}; `oracle` is fhr verify's judgement of param.fhrp against T. With §5's result
/// (`wavelets` not null) also remesh_L{J}.off, wavelet_keep{p}.off and the report's `remesh`
/// and `wavelet` sections. Each file is written in parts on `options.executor`'s threads; timings.json
/// gets one more measurement after the total, "writing": the seconds spent on all the others.
/// `written`: the groups the caller has written already (beside the oracle); they are not written
/// again, "writing" adds their seconds, and "writing_beside_oracle" follows with them alone.
RunTexts write_outputs(const std::string& dir, const InputInfo& input, const Parameterization& p,
                       const exchange::VerifyReport& oracle, const Timings& timings, const Options& options,
                       const wavelet::WaveletResult* wavelets, const WrittenBeside& written = {});

/// DIST-1 of every face of the final T′: its image in its patch's domain triangle (D's own 3D
/// shape) onto the face, by the oracle's code (spec/distortion.md).
std::vector<exchange::FaceStretch> face_stretches(const Parameterization& p);

/// One point of §6's rate–distortion curve: f^J reconstructed from its largest `count` wavelet
/// coefficients (p percent of them), its L2 error (RMS over the vertices of D^J) and the lower end
/// of its Hausdorff bracket to T.
struct RateStep {
    double percent = 0;
    std::size_t count = 0;
    double l2 = 0, hausdorff = 0;
    std::vector<Vec3> positions;  ///< #V(D^J), on the faces of D^J
};

/// REN-14: the curve at 1, 2, 5, 10, 20, 50, 100 % and at the kept percentages (each once, by
/// increasing percentage). The kept points are §5's own; the others are made the same way
/// (keep_largest, reconstruct, rms_distance, hausdorff at analyse's default resolution).
std::vector<RateStep> rate_steps(const TriMesh& T, const TriMesh& D, const wavelet::WaveletResult& wavelets);

/// The paper's Figures 6 and 7 (fig6.png: T and D; fig7.png: the geodesic network on T, and T′
/// with a checkerboard over every patch through ψ) and one SVG per chosen patch (ψ_i(S_i) in its
/// triangle: the first patch and the one with the most faces) into DIR/figures/, all from one camera
/// with `up_axis` (0, 1, 2) up; with §5's result also fig8.png (D^J and f^J(Ω_D)) and, with two
/// or more kept percentages, fig9.png (the first two reconstructions), and rate_distortion.svg
/// (§6's compression: L2 and Hausdorff errors at 1, 2, 5, 10, 20, 50, 100 % and the kept
/// percentages; REN-14: `rate`, or rate_steps when it is empty). On a surface with boundary every
/// figure draws it, and fig7.png's left panel draws D's boundary curves (REN-15). Deterministic bytes.
void write_figures(const std::string& dir, const TriMesh& T, const Parameterization& p, int up_axis,
                   const wavelet::WaveletResult* wavelets, const std::vector<RateStep>& rate = {});

}  // namespace fhr::app
