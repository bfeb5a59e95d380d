// `fhr run` on self-intersecting input (the generator's immersed family, spec/generator.md
// GEN-14): fhr's pipeline works on the surface's combinatorics and per-patch geometry,
// so an immersion must give a certified result that the independent oracle `fhr verify --mesh`
// accepts, or a clear error with its documented exit code — never a crash or a wrong certificate.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include <fhr/generate/random_mesh.hpp>
#include "support/test_support.hpp"

using fhr::test::run_fhr;
using fhr::test::temp_path;

TEST_CASE("fhr run on immersed meshes: certified and verified, or a clear error; never a crash", "[cli][run]") {
    struct Case {
        const char* genus;
        const char* faces;
        const char* seed;
        const char* depth;
        const char* holes;
        const char* components;
        const char* domain_faces;
    };
    // Every genus 0–3, with holes and two components, from the smallest immersed mesh (20 faces)
    // to 5,000 faces, the finger from just through (1.1) to the deepest (4).
    const Case cases[] = {{"0", "20", "6", "4", "0", "1", "12"},      {"0", "3000", "2", "1.1", "2", "1", "60"},
                          {"1", "3001", "3", "4", "3", "2", "100"},   {"2", "5000", "4", "2.5", "0", "2", "120"},
                          {"3", "2500", "5", "3.9", "1", "1", "150"}, {"1", "72", "7", "4", "0", "1", "40"}};
    for (const Case& c : cases) {
        const std::string mesh = temp_path("immersed.off"), out = temp_path("immersed_run");
        const std::vector<std::string> generate{"generate", "--family",     "immersed",   "--genus", c.genus, "--faces",
                                                c.faces,    "--seed",       c.seed,       "--depth", c.depth, "--holes",
                                                c.holes,    "--components", c.components, "--out",   mesh};
        INFO("fhr generate --family immersed --genus " << c.genus << " --faces " << c.faces << " --seed " << c.seed
                                                       << " --depth " << c.depth << " --holes " << c.holes
                                                       << " --components " << c.components);
        REQUIRE(run_fhr(generate).exit_code == 0);
        const auto run = run_fhr({"run", mesh, "--faces", c.domain_faces, "--out", out});
        INFO(run.err);
        // 0 certified, 2 refused input, 3 no partition, 4 not certified: all clear answers.
        CHECK((run.exit_code == 0 || run.exit_code == 2 || run.exit_code == 3 || run.exit_code == 4));
        if (run.exit_code != 0) {
            CHECK_FALSE(run.err.empty());
            continue;
        }
        const auto verify = run_fhr({"verify", out + "/param.fhrp", "--mesh", mesh});
        INFO(verify.out);
        CHECK(verify.exit_code == 0);
    }
}
