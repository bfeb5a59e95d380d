// FHR tests — `fhr verify` end to end (spec/cli.md CLI-VERIFY-1..4): exit 0 for a valid file
// (also against its input mesh), 1 for an invalid one with the broken invariant named in the
// verdict and the JSON, 2 with one error line for an unreadable file or mesh.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include <fhr/exchange/fhr_param.hpp>
#include <fhr/generate/random_mesh.hpp>
#include <fhr/io/write.hpp>
#include "support/test_support.hpp"
#include "synthetic.hpp"

using fhr::test::run_fhr;
using fhr::test::temp_path;
using fhr::test::write_temp;

namespace {

int count_lines(const std::string& s) {
    int n = 0;
    for (char c : s) n += c == '\n';
    return n;
}

struct Files {
    std::string param, mesh;
    fhr::exchange::ParamFile file;
};

/// A valid file (the 3-to-9 subdivision of a random genus-2 mesh) and its domain as an OFF mesh.
const Files& files() {
    static const Files f = [] {
        fhr::generate::RandomMeshOptions o;
        o.genus = 2;
        o.faces = 240;
        o.seed = 21;
        o.noise = 0.2;
        const fhr::TriMesh domain = fhr::generate::random_closed_mesh(o);
        Files r;
        r.file = fhr::test::subdivided_param(domain, 3);
        r.param = temp_path("cli-valid.fhrp");
        fhr::exchange::write_param(r.param, r.file);
        r.mesh = temp_path("cli-domain.off");
        const auto triangles = domain.triangles();
        fhr::io::write_off(r.mesh, domain.positions(), triangles);
        return r;
    }();
    return f;
}

}  // namespace

TEST_CASE("CLI-VERIFY-1, CLI-VERIFY-4: a valid file gives exit code 0 and a pass for every check", "[cli][exchange]") {
    const auto r = run_fhr({"verify", files().param});
    INFO(r.out << r.err);
    CHECK(r.exit_code == 0);
    CHECK(r.err.empty());
    CHECK(r.out.rfind(files().param + ": valid\n", 0) == 0);
    CHECK(count_lines(r.out) == 2 + 10);  // verdict, sizes, PARAM-1..10

    const auto j = run_fhr({"verify", files().param, "--mesh", files().mesh, "--json"});
    INFO(j.out << j.err);
    CHECK(j.exit_code == 0);
    CHECK_THAT(j.out, Catch::Contains("\"valid\": true") && Catch::Contains("\"first_failure\": null") &&
                          Catch::Contains("\"id\": \"PARAM-11\"") && Catch::Contains("\"readable\": true") &&
                          Catch::Contains("\"faces\": 2160"));
    CHECK_THAT(j.out, !Catch::Contains("\"result\": \"fail\"") && !Catch::Contains("\"result\": \"skipped\""));
}

TEST_CASE("CLI-VERIFY-2, CLI-VERIFY-4: an invalid file gives exit code 1 and names the broken invariant",
          "[cli][exchange]") {
    auto file = files().file;
    std::swap(file.surface_faces[10].beta[1], file.surface_faces[10].beta[2]);  // a flipped image triangle
    const std::string path = temp_path("cli-flipped.fhrp");
    fhr::exchange::write_param(path, file);
    const auto r = run_fhr({"verify", path});
    INFO(r.out << r.err);
    CHECK(r.exit_code == 1);
    CHECK(r.out.rfind(path + ": INVALID: PARAM-7: surface vertex ", 0) == 0);
    CHECK_THAT(r.out, Catch::Contains("PARAM-8   fail") && Catch::Contains("first: surface face 10 (patch"));

    const auto j = run_fhr({"verify", path, "--json"});
    CHECK(j.exit_code == 1);
    CHECK_THAT(j.out, Catch::Contains("\"valid\": false") && Catch::Contains("\"first_failure\": \"PARAM-7\"") &&
                          Catch::Contains("\"face\": 10"));

    // T′ = the domain moved: every T vertex is missing with --mesh (PARAM-11 only).
    auto moved = files().file;
    for (auto& p : moved.surface_vertices) p.x() += 0.5;
    for (auto& p : moved.domain_vertices) p.x() += 0.5;
    const std::string moved_path = temp_path("cli-moved.fhrp");
    fhr::exchange::write_param(moved_path, moved);
    CHECK(run_fhr({"verify", moved_path}).exit_code == 0);
    const auto m = run_fhr({"verify", moved_path, "--mesh", files().mesh, "--json"});
    CHECK(m.exit_code == 1);
    CHECK_THAT(m.out, Catch::Contains("\"first_failure\": \"PARAM-11\""));
}

TEST_CASE("CLI-VERIFY-3, CLI-VERIFY-4: an unreadable file or mesh gives one error line and exit code 2",
          "[cli][exchange]") {
    const std::string good = fhr::test::read_file(files().param);
    struct Bad {
        const char* name;
        std::string bytes;
        const char* expect;
    };
    const std::vector<Bad> cases{
        {"garbage",
         "\x7f"
         "ELF\x01\x02 binary junk",
         ":1: header: PARAM-1: not a fhr-param file"},
        {"wrong header", "fhr-param 7\n" + good.substr(good.find('\n') + 1), "unsupported version"},
        {"truncated", good.substr(0, good.size() / 2), "unexpected end of file"},
        {"huge counts", "fhr-param 1\ndomain_vertices 4294967295\n0 0 0\n", "truncated"},
        {"empty", "", "empty file"},
    };
    for (const Bad& c : cases) {
        DYNAMIC_SECTION(c.name) {
            const std::string path = write_temp(std::string("bad-") + c.name + ".fhrp", c.bytes);
            const auto r = run_fhr({"verify", path});
            INFO(r.err);
            CHECK(r.exit_code == 2);
            CHECK(r.out.empty());
            CHECK(count_lines(r.err) == 1);
            CHECK(r.err.rfind("fhr: error: " + path, 0) == 0);
            CHECK_THAT(r.err, Catch::Contains(c.expect));
            const auto j = run_fhr({"verify", path, "--json"});
            CHECK(j.exit_code == 2);
            CHECK_THAT(j.out, Catch::Contains("\"readable\": false") && Catch::Contains("\"error\": "));
        }
    }
    const auto missing = run_fhr({"verify", temp_path("none.fhrp")});
    CHECK(missing.exit_code == 2);
    CHECK_THAT(missing.err, Catch::Contains("cannot open"));
    const auto bad_mesh = run_fhr({"verify", files().param, "--mesh", write_temp("bad.off", "OFF\n3 1 0\n")});
    CHECK(bad_mesh.exit_code == 2);
    CHECK(count_lines(bad_mesh.err) == 1);
    const auto usage = run_fhr({"verify"});
    CHECK(usage.exit_code == 2);
    CHECK_THAT(usage.err, Catch::Contains("FILE"));
}

TEST_CASE("CLI-VERIFY-1..4: a surface with boundary and several components: exit codes 0, 1 and 2", "[cli][exchange]") {
    // D = a genus-1 mesh with two holes beside a hexagonal disk; T = D.
    fhr::generate::RandomMeshOptions o;
    o.genus = 1;
    o.faces = 120;
    o.seed = 8;
    o.noise = 0.1;
    const fhr::TriMesh domain = fhr::test::disjoint_union(
        fhr::test::with_holes(fhr::generate::random_closed_mesh(o), 2, 3), fhr::test::hexagon_disk());
    const fhr::exchange::ParamFile file = fhr::test::subdivided_param(domain, 4);
    const std::string param = temp_path("cli-boundary.fhrp"), mesh = temp_path("cli-boundary.off");
    fhr::exchange::write_param(param, file);
    fhr::io::write_off(mesh, domain.positions(), domain.triangles());

    const auto valid = run_fhr({"verify", param, "--mesh", mesh});
    INFO(valid.out << valid.err);
    CHECK(valid.exit_code == 0);
    CHECK(valid.err.empty());
    CHECK(valid.out.rfind(param + ": valid\n", 0) == 0);
    CHECK(count_lines(valid.out) == 2 + 11);

    // T′ with a hole inside patch 0: its face 9 at k = 4, the one whose corners are all inside it.
    auto holed = file;
    holed.surface_faces.erase(holed.surface_faces.begin() + 9);
    const std::string holed_path = temp_path("cli-boundary-holed.fhrp");
    fhr::exchange::write_param(holed_path, holed);
    const auto invalid = run_fhr({"verify", holed_path, "--json"});
    INFO(invalid.out << invalid.err);
    CHECK(invalid.exit_code == 1);
    CHECK_THAT(invalid.out, Catch::Contains("\"first_failure\": \"PARAM-4\"") &&
                                Catch::Contains("chi(the component of T' at surface vertex 0) = -3 but chi(the "
                                                "component of D at domain vertex 0) = -2"));

    // T with a non-manifold boundary vertex (two triangles meeting at one vertex): unreadable.
    const std::string bowtie =
        write_temp("bowtie.off", "OFF\n5 2 0\n0 0 0\n1 0 0\n0 1 0\n-1 0 0\n0 -1 0\n3 0 1 2\n3 0 3 4\n");
    const auto unreadable = run_fhr({"verify", param, "--mesh", bowtie});
    INFO(unreadable.err);
    CHECK(unreadable.exit_code == 2);
    CHECK(count_lines(unreadable.err) == 1);
    CHECK_THAT(unreadable.err, Catch::Contains("non-manifold vertex 0"));
}
