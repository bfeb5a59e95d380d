// FHR §2–§5 — the run with the application's own tasks beside it: the command and the Python
// module write a run's files while the oracle judges it and §5 runs (they need no verdict), so
// that writing costs no wall time of its own. Not part of the public API (run.hpp is).
#pragma once

#include <functional>

#include <fhr/exchange/fhr_param.hpp>
#include <fhr/pipeline/run.hpp>

namespace fhr::pipeline {

/// Tasks of the caller's run beside the oracle and §5; each optional.
struct RunBeside {
    /// Run once beside the oracle (and §5) once the parameterization is made, such as writing its
    /// files (`fhr run`: app::write_parameterization), which need no verdict. Meanwhile p lends T′'s
    /// vertices and β to `file` (lend_param_file: exactly what param.fhrp holds), so it reads them
    /// there; both are read-only for every task. Its exception is rethrown by run once the other
    /// tasks are done.
    std::function<void(const Parameterization& p, const exchange::ParamFile& file)> beside_oracle;
    /// With levels ≥ 1: run on §5's result as soon as it is made, on §5's task (so still beside the
    /// oracle and `beside_oracle`), such as writing its meshes (`fhr run`: app::write_wavelets).
    std::function<void(const wavelet::WaveletResult& wavelets)> after_wavelets;
};

/// run(T, options) with the caller's tasks beside it: the same result.
RunResult run(const TriMesh& T, RunOptions options, const RunBeside& beside);

/// to_param_file(p) made from p's own arrays, which p lends it: its vertices are moved and its β
/// freed (they are in the file's faces); take_back_param_file(p, file) returns both, bitwise. In
/// between, p has no refined_positions and no face_beta. So the final T′ is not held twice while
/// the oracle judges the file: at 10⁶ faces that phase sets the peak memory.
exchange::ParamFile lend_param_file(Parameterization& p);
void take_back_param_file(Parameterization& p, exchange::ParamFile file);

}  // namespace fhr::pipeline
