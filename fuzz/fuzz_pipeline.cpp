// FHR §2–§4 — libFuzzer target for the whole pipeline: the bytes choose a small random mesh T
// with the generator's recipe (an embedded family, genus 0–2, 0–5 boundary loops, 1–3 components,
// at most min_faces + 300 faces, seed, and noise for block; src/fhr/generate), a domain size, the weights and the
// solver; §2 decimates T to D and pipeline::parameterize runs §3 and §4. Every run must end
// certified (Proposition 1, the per-patch certificate) and accepted by the independent oracle
// (spec/param.md PARAM-2..11 against T), except uniform weights on the density family's graded
// meshes, which may end not certified and must then be refused by the oracle too. The one
// expected refusal is InvalidInput from the decimation (the size cannot be reached under its
// validity rules, spec/domain.md DOM-9); a
// PartitionFailure is a finding too, since §3's recovery ends at the latest at D = T. A finding
// prints the `fhr` commands that reproduce it and traps. Every input is a valid recipe; the seeds
// (fuzz/corpus/pipeline/) are 24 bytes long so that libFuzzer's length limit starts where a whole
// recipe fits (about 18 bytes).
#include <fuzzer/FuzzedDataProvider.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include <fhr/core/errors.hpp>
#include <fhr/domain/decimate.hpp>
#include <fhr/exchange/verify.hpp>
#include <fhr/generate/random_mesh.hpp>
#include <fhr/pipeline/run.hpp>
#include <fhr/pipeline/pipeline.hpp>

namespace {

using namespace fhr;

[[noreturn]] void finding(const generate::RandomMeshOptions& o, std::size_t target, const pipeline::Options& options,
                          const std::string& what) {
    std::fprintf(
        stderr,
        "fuzz_pipeline finding: %s\nreproduce: %s && fhr run mesh.off --faces %zu --weights %s --solver %s --out run\n",
        what.c_str(), generate::generate_command(o).c_str(), target,
        std::string(param::name(options.map.weights)).c_str(), std::string(param::name(options.map.solver)).c_str());
    __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    FuzzedDataProvider bytes(data, size);
    generate::RandomMeshOptions o;
    o.family = bytes.PickValueInArray(generate::embedded_families);
    o.genus = bytes.ConsumeIntegralInRange(0, 2);
    o.holes = bytes.ConsumeIntegralInRange(0, 5);
    o.components = bytes.ConsumeIntegralInRange(1, 3);
    const std::size_t step = o.holes == 0 ? 2 : 1;  // F is even without holes
    o.faces = generate::min_faces(o) + step * bytes.ConsumeIntegralInRange<std::size_t>(0, 300 / step);
    o.seed = bytes.ConsumeIntegral<std::uint64_t>() >> 1;   // `fhr generate --seed` takes < 2^63
    const int noise = bytes.ConsumeIntegralInRange(0, 45);  // the generator accepts [0, 0.5), for block only
    if (o.family == generate::Family::block) o.noise = noise / 100.0;
    // The domain size: even and from Heawood's bound for a closed connected T (DOM-9); otherwise
    // any count §2 accepts (component_targets raises each component's share to its least).
    const std::size_t lowest = o.holes == 0 && o.components == 1 ? domain::min_closed_faces(o.genus) : step;
    const std::size_t target = lowest + step * bytes.ConsumeIntegralInRange<std::size_t>(0, (o.faces - lowest) / step);
    pipeline::Options options;
    options.map.weights =
        bytes.PickValueInArray({param::Weights::shape_preserving, param::Weights::mean_value, param::Weights::uniform});
    options.map.solver = bytes.PickValueInArray({param::Solver::sparse_lu, param::Solver::bicgstab});

    const TriMesh T = generate::random_mesh(o);
    domain::Domain D;
    try {
        D = domain::decimate(T, {.target_faces = target});
    } catch (const InvalidInput&) {
        return 0;  // the expected refusal: this size cannot be reached under the decimation's rules
    }
    try {
        const pipeline::Parameterization p = pipeline::parameterize(T, std::move(D), options);
        const exchange::VerifyReport oracle = exchange::verify(pipeline::to_param_file(p), &T);
        const exchange::CheckResult* bad = oracle.first_failure();
        // Tutte's uniform weights crush graded refinement (the density family) below what doubles
        // resolve: not certified is then the right answer, if the oracle agrees (never a wrong
        // certificate; paper_notes/generator.md).
        if (!p.certified() && options.map.weights == param::Weights::uniform && o.family == generate::Family::density) {
            if (!bad) finding(o, target, options, "not certified, but the oracle accepts the output");
            return 0;
        }
        if (!p.certified()) finding(o, target, options, "a patch certificate failed");
        if (bad) finding(o, target, options, "fhr verify: " + bad->id + ": " + bad->first_failure);
    } catch (const Error& e) {  // PartitionFailure, NumericalFailure, or InvalidInput after §2
        finding(o, target, options, std::string("exception: ") + e.what());
    }
    return 0;
}
