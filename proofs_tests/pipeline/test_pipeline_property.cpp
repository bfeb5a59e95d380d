// §2–§4 end to end on random inputs: for random closed meshes of genus 0–3 (the paper's input
// class, §1), random domain sizes and every weight choice, pipeline::parameterize must finish —
// §3's recovery ends at the latest at D = T, so PartitionFailure is a bug here too — with every
// patch certified (Proposition 1) and the independent oracle accepting the exchange file
// (spec/param.md PARAM-2..11 against T).
#include <catch2/catch.hpp>
#include <rapidcheck/catch.h>

#include <algorithm>
#include <string>

#include "core/errors.hpp"
#include "domain/decimate.hpp"
#include "exchange/verify.hpp"
#include "pipeline/outputs.hpp"
#include "pipeline/pipeline.hpp"
#include "support/gen_mesh.hpp"

using namespace fhr;

TEST_CASE("pipeline: every run on a random mesh of genus 0–3 is certified and verify-valid", "[pipeline][property]") {
    rc::prop("parameterize(random T, decimated D) is certified and valid", [] {
        const test::GeneratedMesh g = *test::gen_closed_mesh(0, 3, 1200);
        const TriMesh& T = g;
        const std::size_t lo = domain::min_closed_faces(g.options.genus) + 2 * 4;
        const std::size_t hi = std::max(lo, T.n_faces() / 3);
        const std::size_t target = 2 * *rc::gen::inRange(lo / 2, hi / 2 + 1);
        RC_PRE(target <= T.n_faces());
        domain::Domain D;
        try {
            D = domain::decimate(T, {.target_faces = target});
        } catch (const InvalidInput&) {
            RC_DISCARD("the decimation cannot reach this size under its rules");
        }
        pipeline::Options options;
        options.map.weights = *rc::gen::element(param::Weights::shape_preserving, param::Weights::mean_value,
                                                param::Weights::uniform);
        RC_LOG() << "domain faces " << target << ", weights " << param::name(options.map.weights) << "\n";
        pipeline::Timings timings;
        const pipeline::Parameterization p = pipeline::parameterize(T, std::move(D), options, timings);
        RC_TAG(p.partition.retries > 0 ? "recovered" : "first try");
        RC_ASSERT(p.certified());
        const exchange::VerifyReport oracle = exchange::verify(pipeline::to_param_file(p), &T);
        const exchange::CheckResult* bad = oracle.first_failure();
        RC_ASSERT((bad ? bad->id + ": " + bad->first_failure : std::string()) == "");
    });
}
