// `fhr oracle-fuzz` (spec/cli.md CLI-ORACLE-*): fhr itself, posing as another implementation
// (proofs_tests/data/fhr_as_other_program.py), passes on every mesh; the same wrapper made to
// flip one triangle's image fails on every mesh, and each failure is kept with its reason and a
// smaller mesh that fails the same way.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "support/test_support.hpp"

using fhr::test::data_path;
using fhr::test::read_file;
using fhr::test::run_fhr;
using fhr::test::temp_path;
namespace fs = std::filesystem;

namespace {

std::string wrapper_command(const std::string& extra) {
    return "python3 '" + data_path("fhr_as_other_program.py") + "' '" FHR_EXE "' {mesh} {out}" + extra;
}

int count_of(const std::string& text, const std::string& what) {
    int n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

}  // namespace

TEST_CASE("CLI-ORACLE-1: fhr itself as the program: no failures", "[cli][oracle]") {
    const std::string keep = temp_path("oracle-keep-good");
    const auto r = run_fhr({"oracle-fuzz", "--cmd", wrapper_command(""), "--count", "12", "--genus-max", "3", "--seed", "7",
                            "--keep", keep});
    INFO(r.out << r.err);
    CHECK(r.exit_code == 0);
    CHECK(count_of(r.out, ": valid\n") == 12);
    CHECK(r.out.find("12 meshes, 0 failures\n") != std::string::npos);
    CHECK(!fs::exists(keep));
}

TEST_CASE("CLI-ORACLE-2: a program that flips a triangle fails on every mesh; each failure is kept and shrunk",
          "[cli][oracle]") {
    const std::string keep = temp_path("oracle-keep-broken");
    const int count = 5;
    const auto r = run_fhr({"oracle-fuzz", "--cmd", wrapper_command(" --flip"), "--count", std::to_string(count),
                            "--genus-max", "3", "--seed", "11", "--keep", keep});
    INFO(r.out << r.err);
    CHECK(r.exit_code == 1);
    CHECK(r.out.find(std::to_string(count) + " meshes, " + std::to_string(count) + " failures\n") != std::string::npos);
    for (int i = 0; i < count; ++i) {
        const fs::path dir = fs::path(keep) / ("mesh-" + std::to_string(i));
        REQUIRE(fs::is_regular_file(dir / "mesh.off"));
        REQUIRE(fs::is_regular_file(dir / "smaller.off"));
        const std::string reason = read_file((dir / "reason.txt").string());
        INFO(reason);
        // Swapping two corners' β breaks continuity (PARAM-7) or orientation (PARAM-8) first.
        CHECK((reason.find("\nreason: PARAM-7: ") != std::string::npos || reason.find("\nreason: PARAM-8: ") != std::string::npos));
        // The shrunk mesh fails the same way and is strictly smaller: the flip breaks any mesh, so
        // shrinking reaches the smallest the generator makes, the 12-face cube.
        const std::string kind = reason.substr(reason.find("\nreason: ") + 9, 8);
        CHECK(reason.find("\nsmaller reason: " + kind) != std::string::npos);
        CHECK(fhr::test::load_mesh((dir / "smaller.off").string()).n_faces() == 12);
        CHECK(fhr::test::load_mesh((dir / "mesh.off").string()).n_faces() > 12);
        // The kept mesh and output reproduce the failure with `fhr verify`.
        CHECK(run_fhr({"verify", (dir / "out.fhrp").string(), "--mesh", (dir / "mesh.off").string()}).exit_code == 1);
    }
}

TEST_CASE("CLI-ORACLE-3: the program's exit code and stderr are the reason when it fails", "[cli][oracle]") {
    const std::string keep = temp_path("oracle-keep-exit");
    const auto r = run_fhr({"oracle-fuzz", "--cmd", "echo broken {mesh} >&2; exit 3 # {out}", "--count", "2", "--genus-max",
                            "0", "--keep", keep});
    INFO(r.out << r.err);
    CHECK(r.exit_code == 1);
    CHECK(r.out.find("2 meshes, 2 failures\n") != std::string::npos);
    const std::string reason = read_file(keep + "/mesh-0/reason.txt");
    CHECK(reason.find("reason: the program exited with code 3\nbroken ") != std::string::npos);
    CHECK(!fs::exists(keep + "/mesh-0/out.fhrp"));
}

TEST_CASE("CLI-ORACLE-4: a program that writes nothing, or not a fhr-param file, fails", "[cli][oracle]") {
    const std::string keep = temp_path("oracle-keep-nothing");
    auto r = run_fhr({"oracle-fuzz", "--cmd", "true {mesh} {out}", "--count", "1", "--keep", keep});
    CHECK(r.exit_code == 1);
    CHECK(r.out.find("wrote no file at {out}") != std::string::npos);
    r = run_fhr({"oracle-fuzz", "--cmd", "cp {mesh} {out}", "--count", "1", "--keep", keep});
    CHECK(r.exit_code == 1);
    CHECK(r.out.find("FAILED: PARAM-1: ") != std::string::npos);
}

TEST_CASE("CLI-ORACLE-5: usage errors", "[cli][oracle]") {
    CHECK(run_fhr({"oracle-fuzz", "--count", "1"}).exit_code == 2);
    CHECK(run_fhr({"oracle-fuzz", "--cmd", "prog {mesh}", "--count", "1"}).exit_code == 2);
    CHECK(run_fhr({"oracle-fuzz", "--cmd", "prog {mesh} {out}"}).exit_code == 2);
    CHECK(run_fhr({"oracle-fuzz", "--cmd", "prog {mesh} {out}", "--count", "0"}).exit_code == 2);
}
