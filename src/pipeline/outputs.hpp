// FHR §6 — what `fhr run` writes (spec/cli.md, spec/formats.md): the domain, the geodesic network,
// T′ with its patches, the `fhr-param 1` exchange file, a textured T′ for any mesh viewer, the
// report and the timings. Every file is written atomically; everything but timings.json is
// byte-identical across runs.
#pragma once

#include <string>

#include "core/trimesh.hpp"
#include "exchange/verify.hpp"
#include "pipeline/pipeline.hpp"

namespace fhr::pipeline {

/// The parameterization as the exchange format holds it (spec/param.md).
exchange::ParamFile to_param_file(const Parameterization& p);

/// What the report says about the input.
struct InputInfo {
    std::string path;
    std::size_t vertices = 0, faces = 0;
    long genus = 0;
    std::size_t domain_faces_requested = 0;  ///< the domain's faces before §3's recovery
};

/// Writes DIR/{domain.off, geodesics.obj, refined.ply, param.fhrp, textured.obj, report.json,
/// timings.json}; `oracle` is fhr verify's judgement of param.fhrp against T.
void write_outputs(const std::string& dir, const InputInfo& input, const Parameterization& p,
                   const exchange::VerifyReport& oracle, const Timings& timings, const Options& options);

}  // namespace fhr::pipeline
