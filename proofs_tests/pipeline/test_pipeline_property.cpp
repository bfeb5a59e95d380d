// §2–§4 end to end on random inputs: for random closed meshes of genus 0–3 (the paper's input
// class, §1), random domain sizes and every weight choice, pipeline::parameterize must finish —
// §3's recovery ends at the latest at D = T, so PartitionFailure is a bug here too — with every
// patch certified (Proposition 1) and the independent oracle accepting the exchange file
// (spec/param.md PARAM-2..11 against T).
#include <catch2/catch.hpp>
#include <rapidcheck/catch.h>

#include <algorithm>
#include <string>

#include <fhr/core/errors.hpp>
#include <fhr/domain/decimate.hpp>
#include <fhr/exchange/verify.hpp>
#include <fhr/pipeline/outputs.hpp>
#include <fhr/pipeline/pipeline.hpp>
#include <fhr/testing/rapidcheck.hpp>
#include "support/gen_domain.hpp"

using namespace fhr;

TEST_CASE("pipeline: every run on a random mesh of genus 0–3 is certified and verify-valid", "[pipeline][property]") {
    rc::prop("parameterize(random T, decimated D) is certified and valid", [] {
        const fhr::testing::GeneratedMesh g = *fhr::testing::gen_closed_mesh(0, 3, 1200);
        const TriMesh& T = g;
        domain::Domain D = test::random_domain(T, g.options.genus);
        const std::size_t target = D.mesh.n_faces();
        pipeline::Options options;
        options.map.weights = *rc::gen::element(param::Weights::shape_preserving, param::Weights::mean_value,
                                                param::Weights::uniform);
        RC_LOG() << "domain faces " << target << ", weights " << param::name(options.map.weights) << "\n";
        const pipeline::Parameterization p = pipeline::parameterize(T, std::move(D), options);
        RC_TAG(p.partition.retries > 0 ? "recovered" : "first try");
        RC_ASSERT(p.certified());
        const exchange::VerifyReport oracle = exchange::verify(pipeline::to_param_file(p), &T);
        const exchange::CheckResult* bad = oracle.first_failure();
        RC_ASSERT((bad ? bad->id + ": " + bad->first_failure : std::string()) == "");
    });
}
