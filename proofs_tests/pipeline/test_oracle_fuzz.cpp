// `fhr oracle-fuzz` (spec/cli.md CLI-ORACLE-*): fhr itself, posing as another implementation
// (peers/fhr-param), passes on every mesh — with boundary loops and
// several components too, which the defaults draw, and of every embedded family; the same wrapper
// made to flip one triangle's image fails on every mesh, and each failure is kept with its reason
// and a smaller mesh that fails the same way; a program failing only with boundary shrinks to the
// smallest mesh with one hole. The tests of exact shrinking results use block meshes (`--family
// block`), whose least sizes are known (12 faces closed, 10 with one hole); the families' tests
// (CLI-ORACLE-6) hold for any family. Sharding and merging are tested with GNU parallel in
// proofs_tests/campaign/test_campaigns.py.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "support/test_support.hpp"

using fhr::test::read_file;
using fhr::test::run_fhr;
using fhr::test::temp_path;
namespace fs = std::filesystem;

namespace {

/// fhr itself as another program (peers/fhr-param), with this build's fhr.
std::string wrapper_command(const std::string& extra) {
    return "FHR='" FHR_EXE "' '" + fhr::test::peer_path("fhr-param") + "' {mesh} {out}" + extra;
}

int count_of(const std::string& text, const std::string& what) {
    int n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

}  // namespace

TEST_CASE("CLI-ORACLE-1: fhr itself as the program, on block meshes: no failures", "[cli][oracle]") {
    const std::string keep = temp_path("oracle-keep-good");
    const auto r = run_fhr({"oracle-fuzz", "--cmd", wrapper_command(""), "--count", "12", "--genus-max", "3", "--seed",
                            "7", "--family", "block", "--keep", keep});
    INFO(r.out << r.err);
    CHECK(r.exit_code == 0);
    CHECK(count_of(r.out, ": valid\n") == 12);
    CHECK(r.out.find("12 meshes, 0 failures\n") != std::string::npos);
    CHECK(!fs::exists(keep));
    // The defaults draw surfaces with boundary loops and with several components (CLI-ORACLE-4).
    CHECK(count_of(r.out, " --holes ") >= 3);
    CHECK(count_of(r.out, " --components ") >= 3);
}

TEST_CASE("CLI-ORACLE-2: a program that flips a triangle fails on every mesh; each failure is kept and shrunk",
          "[cli][oracle]") {
    const std::string keep = temp_path("oracle-keep-broken");
    const int count = 5;
    const auto r = run_fhr({"oracle-fuzz", "--cmd", wrapper_command(" --flip"), "--count", std::to_string(count),
                            "--genus-max", "3", "--seed", "11", "--family", "block", "--keep", keep});
    INFO(r.out << r.err);
    CHECK(r.exit_code == 1);
    CHECK(count_of(r.out, " --holes ") >= 2);  // shrinking takes holes and components away too
    CHECK(r.out.find(std::to_string(count) + " meshes, " + std::to_string(count) + " failures\n") != std::string::npos);
    for (int i = 0; i < count; ++i) {
        const fs::path dir = fs::path(keep) / ("mesh-" + std::to_string(i));
        REQUIRE(fs::is_regular_file(dir / "mesh.off"));
        REQUIRE(fs::is_regular_file(dir / "smaller.off"));
        const std::string reason = read_file((dir / "reason.txt").string());
        INFO(reason);
        // Swapping two corners' β breaks continuity (PARAM-7) or orientation (PARAM-8) first.
        CHECK((reason.find("\nreason: PARAM-7: ") != std::string::npos ||
               reason.find("\nreason: PARAM-8: ") != std::string::npos));
        // The shrunk mesh fails the same way and is strictly smaller: the flip breaks any mesh, so
        // shrinking reaches the smallest closed connected mesh the generator makes, the 12-face cube.
        const std::string kind = reason.substr(reason.find("\nreason: ") + 9, 8);
        CHECK(reason.find("\nsmaller reason: " + kind) != std::string::npos);
        CHECK(reason.find("\nsmaller.off: fhr generate --genus 0 --faces 12 --seed ") != std::string::npos);
        CHECK(fhr::test::load_mesh((dir / "smaller.off").string()).n_faces() == 12);
        CHECK(fhr::test::load_mesh((dir / "mesh.off").string()).n_faces() > 12);
        // The kept mesh and output reproduce the failure with `fhr verify`.
        CHECK(run_fhr({"verify", (dir / "out.fhrp").string(), "--mesh", (dir / "mesh.off").string()}).exit_code == 1);
    }
}

TEST_CASE("CLI-ORACLE-3: the program's exit code and stderr are the reason when it fails", "[cli][oracle]") {
    const std::string keep = temp_path("oracle-keep-exit");
    const auto r = run_fhr({"oracle-fuzz", "--cmd", "echo broken {mesh} >&2; exit 3 # {out}", "--count", "2",
                            "--genus-max", "0", "--family", "block", "--keep", keep});
    INFO(r.out << r.err);
    CHECK(r.exit_code == 1);
    CHECK(r.out.find("2 meshes, 2 failures\n") != std::string::npos);
    const std::string reason = read_file(keep + "/mesh-0/reason.txt");
    CHECK(reason.find("reason: the program exited with code 3\nbroken ") != std::string::npos);
    CHECK(!fs::exists(keep + "/mesh-0/out.fhrp"));
}

TEST_CASE("CLI-ORACLE-4: a program that writes nothing, or not a fhr-param file, fails", "[cli][oracle]") {
    const std::string keep = temp_path("oracle-keep-nothing");
    auto r =
        run_fhr({"oracle-fuzz", "--cmd", "true {mesh} {out}", "--count", "1", "--family", "block", "--keep", keep});
    CHECK(r.exit_code == 1);
    CHECK(r.out.find("wrote no file at {out}") != std::string::npos);
    r = run_fhr({"oracle-fuzz", "--cmd", "cp {mesh} {out}", "--count", "1", "--family", "block", "--keep", keep});
    CHECK(r.exit_code == 1);
    CHECK(r.out.find("FAILED: PARAM-1: ") != std::string::npos);
}

TEST_CASE("CLI-ORACLE-4: recipes in the ranges asked; block without holes and components gives the pinned recipes",
          "[cli][oracle]") {
    // `true` writes nothing: every mesh fails at once ("no output"), so the lines come fast.
    const std::string keep = temp_path("oracle-keep-ranges");
    auto r = run_fhr({"oracle-fuzz", "--cmd", "true {mesh} {out}", "--count", "8", "--holes-max", "0",
                      "--components-max", "1", "--family", "block", "--keep", keep});
    INFO(r.out << r.err);
    CHECK(count_of(r.out, "FAILED") == 8);
    CHECK(count_of(r.out, " --holes ") == 0);
    CHECK(count_of(r.out, " --components ") == 0);
    // Mesh 0 of seed 1 with closed ranges: the recipe pinned for block meshes (no draw spent on holes or components).
    CHECK(r.out.find(
              "mesh 0: fhr generate --genus 2 --faces 256 --seed 417422127403058876 --noise 0.05 --out mesh.off: ") ==
          0);
    r = run_fhr({"oracle-fuzz", "--cmd", "true {mesh} {out}", "--count", "12", "--holes-max", "2", "--components-max",
                 "2", "--seed", "5", "--family", "block", "--keep", keep});
    INFO(r.out);
    CHECK(count_of(r.out, " --holes 1 ") + count_of(r.out, " --holes 2 ") == count_of(r.out, " --holes "));
    CHECK(count_of(r.out, " --components 2 ") == count_of(r.out, " --components "));
    CHECK(count_of(r.out, " --holes ") > 0);
    CHECK(count_of(r.out, " --components ") > 0);
}

TEST_CASE("CLI-ORACLE-5: a program failing only on surfaces with boundary shrinks to one hole and 10 faces",
          "[cli][oracle]") {
    // Exit code 3 on a mesh with boundary, a closed one gets exit code 0 and no output (another kind).
    const std::string keep = temp_path("oracle-keep-open");
    const std::string cmd =
        "'" FHR_EXE "' info --json {mesh} | grep -q '\"boundary_loops\": 0' && exit 0; exit 3 # {out}";
    const auto r =
        run_fhr({"oracle-fuzz", "--cmd", cmd, "--count", "4", "--seed", "3", "--family", "block", "--keep", keep});
    INFO(r.out << r.err);
    int open = 0;
    for (int i = 0; i < 4; ++i) {
        const std::string reason = read_file(keep + "/mesh-" + std::to_string(i) + "/reason.txt");
        if (reason.find("\nreason: the program exited with code 3") == std::string::npos) continue;
        ++open;
        INFO(reason);
        CHECK(reason.find("\nsmaller reason: the program exited with code 3") != std::string::npos);
        CHECK(reason.find("\nsmaller.off: fhr generate --genus 0 --holes 1 --faces 10 --seed ") != std::string::npos);
        CHECK(fhr::test::load_mesh(keep + "/mesh-" + std::to_string(i) + "/smaller.off").n_faces() == 10);
    }
    CHECK(open >= 2);
}

TEST_CASE("CLI-ORACLE-5: usage errors", "[cli][oracle]") {
    CHECK(run_fhr({"oracle-fuzz", "--count", "1"}).exit_code == 2);
    CHECK(run_fhr({"oracle-fuzz", "--cmd", "prog {mesh}", "--count", "1"}).exit_code == 2);
    CHECK(run_fhr({"oracle-fuzz", "--cmd", "prog {mesh} {out}"}).exit_code == 2);
    CHECK(run_fhr({"oracle-fuzz", "--cmd", "prog {mesh} {out}", "--count", "0"}).exit_code == 2);
    CHECK(run_fhr({"oracle-fuzz", "--cmd", "prog {mesh} {out}", "--count", "1", "--holes-max", "-1"}).exit_code == 2);
    CHECK(run_fhr({"oracle-fuzz", "--cmd", "prog {mesh} {out}", "--count", "1", "--components-max", "0"}).exit_code ==
          2);
    CHECK(run_fhr({"oracle-fuzz", "--cmd", "prog {mesh} {out}", "--count", "1", "--family", "blocks"}).exit_code == 2);
    for (const char* shard : {"0/2", "3/2", "1/0", "2", "a/b", "1/2/3", "-1/2", "01/2"})
        CHECK(run_fhr({"oracle-fuzz", "--cmd", "prog {mesh} {out}", "--count", "1", "--shard", shard}).exit_code == 2);
    CHECK(run_fhr({"oracle-fuzz", "--merge"}).exit_code == 2);
    CHECK(run_fhr({"oracle-fuzz", "--merge", "a.tsv", "--cmd", "prog {mesh} {out}"}).exit_code == 2);
    CHECK(run_fhr({"oracle-fuzz", "--cmd", "prog {mesh} {out}", "--count", "1", "stray.tsv"}).exit_code == 2);
}

// The tests below need every family of the generator.

TEST_CASE("CLI-ORACLE-6: fhr itself as the program, on meshes of every embedded family: no failures", "[cli][oracle]") {
    // Seed 116 draws each of the six embedded families once in its first 6 meshes (--family all, the default).
    const std::string keep = temp_path("oracle-keep-families");
    const auto r = run_fhr({"oracle-fuzz", "--cmd", wrapper_command(""), "--count", "6", "--genus-max", "3", "--seed",
                            "116", "--keep", keep});
    INFO(r.out << r.err);
    CHECK(r.exit_code == 0);
    CHECK(r.out.find("6 meshes, 0 failures\n") != std::string::npos);
    for (const char* family : {"smooth", "quality", "valence", "density", "degenerate"})
        CHECK(count_of(r.out, std::string(" --family ") + family + " ") == 1);
    CHECK(count_of(r.out, " --family ") == 5);  // and block, which generate_command does not name
}

TEST_CASE(
    "CLI-ORACLE-6: --family all draws the embedded families from (seed, i); a block draw is --family block's; "
    "shrinking keeps the family",
    "[cli][oracle]") {
    const std::string keep = temp_path("oracle-keep-all");
    const auto all =
        run_fhr({"oracle-fuzz", "--cmd", "true {mesh} {out}", "--count", "18", "--seed", "5", "--keep", keep});
    const auto block = run_fhr({"oracle-fuzz", "--cmd", "true {mesh} {out}", "--count", "18", "--seed", "5", "--family",
                                "block", "--keep", temp_path("oracle-keep-all-block")});
    INFO(all.out << all.err);
    CHECK(all.exit_code == 1);
    CHECK(all.out.find("18 meshes, 18 failures\n") != std::string::npos);
    CHECK(count_of(all.out, " --family immersed ") == 0);  // immersed only when named
    int blocks = 0;
    for (int i = 0; i < 18; ++i) {
        const std::string head = "mesh " + std::to_string(i) + ": ";
        const auto line_of = [&](const std::string& out) {  // "mesh i: <recipe>" (the keep folders differ)
            const std::size_t at = out.find(head);
            return at == std::string::npos ? std::string() : out.substr(at, out.find(": FAILED", at) - at);
        };
        const std::string line = line_of(all.out);
        REQUIRE(!line.empty());
        const std::string reason = read_file(keep + "/mesh-" + std::to_string(i) + "/reason.txt");
        INFO(line << "\n" << reason);
        const std::size_t named = line.find(" --family ");
        if (named == std::string::npos) {  // block: the very recipe of --family block
            ++blocks;
            CHECK(line == line_of(block.out));
            CHECK(reason.find("\nsmaller.off: fhr generate --genus ") != std::string::npos);
        } else {
            const std::string family = line.substr(named, line.find(' ', named + 10) - named);
            CHECK(reason.find("\nsmaller.off: fhr generate" + family + " ") != std::string::npos);
            CHECK(line.find(" --noise ") == std::string::npos);  // noise is block's alone
        }
    }
    CHECK(blocks >= 2);
    CHECK(blocks <= 12);
}

TEST_CASE("CLI-ORACLE-6: --family immersed when named", "[cli][oracle]") {
    const auto r = run_fhr({"oracle-fuzz", "--cmd", "true {mesh} {out}", "--count", "2", "--family", "immersed",
                            "--keep", temp_path("oracle-keep-immersed")});
    INFO(r.out << r.err);
    CHECK(r.out.find("2 meshes, 2 failures\n") != std::string::npos);
    CHECK(count_of(r.out, ": fhr generate --family immersed ") == 2);
}
