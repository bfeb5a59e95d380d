// The `fhr` command end to end (spec/cli.md): every bad-input class of spec/mesh.md and
// spec/formats.md gives one line `fhr: error: FILE[:LINE]: ...`, exit code 2, in under a second,
// and leaves no output file behind; `fhr info` reports the right topology for real meshes.
#include <catch2/catch.hpp>

#include <array>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <fhr/core/build.hpp>
#include <fhr/core/errors.hpp>
#include <fhr/generate/random_mesh.hpp>
#include <fhr/io/read.hpp>
#include <fhr/version.hpp>
#include "cli/common.hpp"
#include "support/test_support.hpp"

using fhr::test::run_fhr;
using fhr::test::temp_path;
using fhr::test::write_temp;
namespace fs = std::filesystem;

namespace {

struct BadInput {
    const char* name;  // the class of bad input
    const char* file;  // file name (its extension picks the reader)
    std::string content;
    const char* expect;  // a phrase the message must contain
};

const std::string tet_v = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
const std::string tet_f = "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

std::string off(const std::string& counts, const std::string& body) { return "OFF\n" + counts + "\n" + body; }

std::string binary_ply_truncated() {
    std::string s =
        "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
        "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n";
    s += std::string(20, '\0');  // 4 vertices need 48 bytes
    return s;
}

int count_lines(const std::string& s) {
    int n = 0;
    for (char c : s) n += c == '\n';
    return n;
}

const std::vector<BadInput>& bad_inputs() {
    static const std::vector<BadInput> cases{
        {"empty file", "empty.off", "", "empty"},
        {"header only", "header.off", "OFF\n", "count"},
        {"unknown format", "mesh.xyz", "OFF\n4 4 0\n" + tet_v + tet_f, "unknown format"},
        {"truncated text", "trunc.off", off("4 4 0", "0 0 0\n1 0 0\n"), "truncated"},
        {"truncated binary", "trunc.ply", binary_ply_truncated(), "truncated"},
        {"negative index", "neg.off", off("4 4 0", tet_v + "3 0 2 -1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"), "-1"},
        {"OBJ index 0", "zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 0 2 3\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
         "1-based"},
        {"index out of range", "range.off", off("4 4 0", tet_v + "3 0 2 7\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"), "7"},
        {"overflowing index", "overflow.off",
         off("4 4 0", tet_v + "3 0 2 99999999999999999999\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"), "range"},
        {"non-numeric", "word.off", off("4 4 0", "0 0 zero\n1 0 0\n0 1 0\n0 0 1\n" + tet_f), "zero"},
        {"number out of range", "huge.off", off("4 4 0", "0 0 1e400\n1 0 0\n0 1 0\n0 0 1\n" + tet_f), "range"},
        {"NaN coordinate", "nan.off", off("4 4 0", "0 0 nan\n1 0 0\n0 1 0\n0 0 1\n" + tet_f), "NaN"},
        {"Inf coordinate", "inf.off", off("4 4 0", "0 0 inf\n1 0 0\n0 1 0\n0 0 1\n" + tet_f), "inf"},
        {"absurd counts", "absurd.off", off("1000000000 2000000000 0", tet_v + tet_f), "count"},
        {"face with 2 vertices", "two.off", off("4 5 0", tet_v + tet_f + "2 0 1            \n"), "2 vertices"},
        {"repeated vertex", "repeat.off", off("4 5 0", tet_v + tet_f + "3 0 1 1\n"), "repeats vertex 1"},
        {"polygon", "quad.off", off("4 4 0", tet_v + "4 0 2 1 3\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"), "--triangulate"},
        {"duplicate faces", "dup.off", off("4 5 0", tet_v + tet_f + "3 3 2 1\n"), "duplicates"},
        {"degenerate triangle", "degen.off", off("4 4 0", "0 0 0\n1 0 0\n0 1 0\n0.5 0 0\n" + tet_f), "degenerate"},
        {"non-manifold edge", "nmedge.off", off("5 5 0", tet_v + "1 1 1\n" + tet_f + "3 1 2 4\n"), "non-manifold edge"},
        {"non-manifold vertex", "bowtie.off",
         off("7 8 0", tet_v + "-1 0 0\n0 -1 0\n0 0 -1\n" + tet_f + "3 0 4 5\n3 0 6 4\n3 0 5 6\n3 4 6 5\n"),
         "non-manifold vertex 0"},
        {"non-orientable", "moebius.off",
         off("6 6 0",
             "1 0 -0.2\n1.3 0 0.2\n-0.5 0.866 -0.15\n-0.65 1.1258 0.27\n-0.5 -0.866 -0.1\n-0.65 -1.1258 0.34\n"
             "3 0 2 1\n3 1 2 3\n3 2 4 3\n3 3 4 5\n3 4 1 5\n3 5 1 0\n"),
         "not orientable"},
        {"flat closed component", "flat2.obj",
         "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 5 0 0\nv 6 0 0\nv 5 1 0\nv 5.2 0.2 0\n"
         "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\nf 5 7 6\nf 5 6 8\nf 5 8 7\nf 6 7 8\n",
         "closed component at vertex 4 is flat"},
        {"coordinates that overflow lengths", "big.off", off("4 4 0", "0 0 0\n1e200 0 0\n0 1 0\n0 0 1\n" + tet_f),
         "overflow"},
        {"missing file", "does-not-exist.off", "", "cannot open"},
    };
    return cases;
}

}  // namespace

TEST_CASE("CLI-ERR-1: every bad-input class gives one line, exit code 2, in under a second", "[cli]") {
    for (const BadInput& c : bad_inputs()) {
        DYNAMIC_SECTION(c.name) {
            const std::string path =
                std::string(c.name) == "missing file" ? temp_path(c.file) : write_temp(c.file, c.content);
            const auto r = run_fhr({"info", path});
            INFO(r.err);
            CHECK(r.exit_code == 2);
            CHECK(r.seconds < 1.0);
            CHECK(count_lines(r.err) == 1);
            CHECK(r.err.rfind("fhr: error: " + path, 0) == 0);
            CHECK_THAT(r.err, Catch::Contains(c.expect, Catch::CaseSensitive::No));
        }
    }
}

TEST_CASE("CLI-ERR-2: a failed command leaves no output file behind", "[cli]") {
    for (const BadInput& c : bad_inputs()) {
        DYNAMIC_SECTION(c.name) {
            const std::string path =
                std::string(c.name) == "missing file" ? temp_path(c.file) : write_temp(c.file, c.content);
            const fs::path dir = fs::path(temp_path("out-" + std::string(c.file)));
            fs::create_directories(dir);
            const auto r = run_fhr({"convert", path, "--out", (dir / "result.off").string()});
            CHECK(r.exit_code == 2);
            CHECK(fs::is_empty(dir));
        }
    }
}

TEST_CASE("CLI-ERR-3: usage errors name the problem and exit with 2", "[cli]") {
    CHECK(run_fhr({}).exit_code == 2);
    const auto unknown = run_fhr({"frobnicate"});
    CHECK(unknown.exit_code == 2);
    CHECK_THAT(unknown.err, Catch::Contains("unknown command 'frobnicate'"));
    const auto option = run_fhr({"info", "--bogus", "x.off"});
    CHECK(option.exit_code == 2);
    CHECK_THAT(option.err, Catch::Contains("unknown option --bogus"));
    const auto faces = run_fhr({"generate", "--faces", "lots", "--out", temp_path("g.off")});
    CHECK(faces.exit_code == 2);
    CHECK_THAT(faces.err, Catch::Contains("--faces needs an integer"));
}

TEST_CASE("CLI-ERR-4: help and --version print on stdout and exit with 0", "[cli]") {
    for (const char* help : {"help", "--help", "-h"}) {
        const auto r = run_fhr({help});
        CHECK(r.exit_code == 0);
        CHECK(r.err.empty());
        for (const char* command : {"fhr info", "fhr generate", "fhr convert", "fhr decimate", "fhr attach",
                                    "fhr geodesic", "fhr run", "fhr verify", "fhr oracle-fuzz"})
            CHECK_THAT(r.out, Catch::Contains(std::string("  ") + command + " "));
    }
    for (const char* version : {"--version", "version"}) {
        const auto r = run_fhr({version});
        CHECK(r.exit_code == 0);
        CHECK(r.out == "fhr " + std::string(fhr::version) + "\n");
    }
}

TEST_CASE("CLI-INFO-1: warnings for repaired input, exit code 0", "[cli]") {
    // An isolated vertex and one face turned the wrong way round.
    const std::string path =
        write_temp("repair.off", off("5 4 0", tet_v + "7 7 7\n3 0 1 2\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"));
    const auto r = run_fhr({"info", "--json", path});
    CHECK(r.exit_code == 0);
    CHECK_THAT(r.err, Catch::Contains("fhr: warning:") && Catch::Contains("dropped 1 isolated vertices") &&
                          Catch::Contains("re-oriented 1 faces"));
    CHECK_THAT(r.out, Catch::Contains("\"vertices\": 4") && Catch::Contains("\"genus\": 0") &&
                          Catch::Contains("\"valid\": true"));
    // The tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1): corners of 45°, 60° and 90°, valence 3.
    CHECK_THAT(r.out, Catch::Contains("\"valence\": {\n    \"min\": 3,\n    \"max\": 3") &&
                          Catch::Contains("\"corner_angle_deg\": {\n    \"min\": 45") &&
                          Catch::Contains("\"max\": 90"));
}

TEST_CASE("CLI-INFO-2: an invalid mesh still gets its counts and the reason", "[cli]") {
    // A cube of quadrilaterals (INV-IN-3): `fhr info` builds leniently, fan-triangulated, to report the topology.
    const std::string path =
        write_temp("cube_quads.off", off("8 6 0",
                                         "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
                                         "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n"));
    const auto r = run_fhr({"info", "--json", path});
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.out, Catch::Contains("\"faces\": 12") && Catch::Contains("\"genus\": 0") &&
                          Catch::Contains("\"valid\": false") && Catch::Contains("--triangulate"));
}

TEST_CASE("CLI-INFO-3: boundary loops and several components are valid input, reported by info", "[cli][boundary]") {
    const std::string open = write_temp("open3.off", off("4 3 0", tet_v + "3 0 2 1\n3 0 1 3\n3 0 3 2\n"));
    const auto r = run_fhr({"info", "--json", open});
    CHECK(r.exit_code == 0);
    CHECK_THAT(r.out, Catch::Contains("\"boundary_loops\": 1") && Catch::Contains("\"faces\": 3") &&
                          Catch::Contains("\"components\": 1") && Catch::Contains("\"valid\": true"));
    const std::string two = write_temp("two3.obj",
                                       "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 5 0 0\nv 6 0 0\nv 5 1 0\nv 5 0 1\n"
                                       "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\nf 5 7 6\nf 5 6 8\nf 5 8 7\nf 6 7 8\n");
    const auto t = run_fhr({"info", "--json", two});
    CHECK(t.exit_code == 0);
    CHECK_THAT(t.out, Catch::Contains("\"components\": 2") && Catch::Contains("\"boundary_loops\": 0") &&
                          Catch::Contains("\"valid\": true"));
}

namespace {

/// CLI-INFO-3 on one real mesh: `fhr info --json` gives its counts and genus.
void info_reports(const std::string& path, long vertices, long faces, long genus) {
    const auto r = run_fhr({"info", "--json", path});
    INFO(r.err);
    CHECK(r.exit_code == 0);
    CHECK_THAT(r.out, Catch::Contains("\"genus\": " + std::to_string(genus)));
    CHECK_THAT(r.out, Catch::Contains("\"vertices\": " + std::to_string(vertices)));
    CHECK_THAT(r.out, Catch::Contains("\"faces\": " + std::to_string(faces)));
}

}  // namespace

TEST_CASE("CLI-INFO-3: fhr info reports the right topology for the paper's and CGAL's meshes", "[cli][real]") {
    info_reports(fhr::test::cgal_mesh("fandisk.off"), 6475, 12946, 0);  // paper §6, Fig. 6
    info_reports(fhr::test::cgal_mesh("elephant.off"), 2775, 5558, 3);  // counts from its OFF header
}

TEST_CASE("CLI-INFO-3: fhr info reports the horse's topology (paper §6)", "[cli][real][shared]") {
    FHR_SHARED_MESH_OR_SKIP(path, "horse.off");
    info_reports(path, 48485, 96966, 0);
}

TEST_CASE("CLI-INFO-3: fhr info reports the rocker's topology", "[cli][real][shared]") {
    FHR_SHARED_MESH_OR_SKIP(path, "rocker.off");
    info_reports(path, 9397, 18794, 1);
}

TEST_CASE("CLI-GEN-1: fhr generate writes meshes that fhr info accepts, with the requested genus", "[cli]") {
    for (int g : {0, 1, 2, 3, 4}) {
        DYNAMIC_SECTION("genus " << g) {
            const std::string out = temp_path("gen" + std::to_string(g) + ".ply");
            const auto gen = run_fhr({"generate", "--genus", std::to_string(g), "--faces", "2000", "--seed",
                                      std::to_string(17 + g), "--noise", "0.1", "--out", out});
            INFO(gen.err);
            REQUIRE(gen.exit_code == 0);
            const auto r = run_fhr({"info", "--json", out});
            INFO(r.err);
            CHECK(r.exit_code == 0);
            CHECK(r.err.empty());
            CHECK_THAT(r.out, Catch::Contains("\"genus\": " + std::to_string(g)) &&
                                  Catch::Contains("\"faces\": 2000") && Catch::Contains("\"valid\": true"));
        }
    }
}

TEST_CASE(
    "CLI-GEN-2, GEN-7: --holes and --components: the file of generate_command's command holds exactly random_mesh's "
    "mesh, and fhr info counts it",
    "[cli]") {
    const std::vector<fhr::generate::RandomMeshOptions> recipes{
        {1, 501, 5, 0.1, 3, 2}, {0, 400, 6, 0.0, 5, 3}, {2, 900, 7, 0.25, 0, 3}, {0, 13, 8, 0.0, 1, 1}};
    for (const fhr::generate::RandomMeshOptions& o : recipes) {
        DYNAMIC_SECTION(fhr::generate::generate_command(o)) {
            const std::string out = temp_path("holes.off");
            // The words of the command (the path has no spaces), without the leading `fhr`.
            std::vector<std::string> args;
            std::istringstream words(fhr::generate::generate_command(o, out));
            for (std::string w; words >> w;) args.push_back(w);
            args.erase(args.begin());
            const auto gen = run_fhr(args);
            INFO(gen.err);
            REQUIRE(gen.exit_code == 0);
            fhr::BuildLog log;
            const fhr::TriMesh back =
                fhr::build_trimesh(fhr::io::read_soup(out), {.require_closed = false, .require_connected = false}, log);
            const fhr::TriMesh expected = fhr::generate::random_mesh(o);
            CHECK(back.positions() == expected.positions());
            CHECK(back.triangles() == expected.triangles());
            // fhr info counts them (whether it calls them a valid input is spec/mesh.md's business).
            const auto r = run_fhr({"info", "--json", out});
            CHECK_THAT(r.out, Catch::Contains("\"faces\": " + std::to_string(o.faces)) &&
                                  Catch::Contains("\"genus\": " + std::to_string(o.genus)) &&
                                  Catch::Contains("\"boundary_loops\": " + std::to_string(o.holes)) &&
                                  Catch::Contains("\"components\": " + std::to_string(o.components)));
        }
    }
}

TEST_CASE(
    "CLI-GEN-3, CLI-GEN-4: out-of-range --holes, --components, face counts, families and knobs are refused in "
    "one line, exit code 2",
    "[cli]") {
    struct Refused {
        std::vector<std::string> options;
        const char* expect;
    };
    const std::vector<Refused> cases{
        {{"--holes", "-1"}, "option --holes must be in [0, 10000], got -1"},
        {{"--holes", "10001"}, "option --holes must be in [0, 10000], got 10001"},
        {{"--components", "0"}, "option --components must be in [1, 10000], got 0"},
        {{"--components", "10001"}, "option --components must be in [1, 10000], got 10001"},
        {{"--holes", "two"}, "option --holes needs an integer, got 'two'"},
        {{"--holes", "5", "--faces", "33"}, "genus 0 with 5 holes needs at least 34 faces (got 33)"},
        {{"--components", "2", "--faces", "25"}, "the face count must be even without holes (got 25)"},
        // CLI-GEN-4: families and their knobs
        {{"--family", "spiky"}, "unknown family 'spiky'"},
        {{"--roundness", "0.2"}, "--roundness is a knob of the smooth family, not of block"},
        {{"--family", "quality", "--depth", "2"}, "--depth is a knob of the immersed family, not of quality"},
        {{"--family", "valence", "--high-valence", "60.5"}, "--high-valence must be an integer (got 60.5)"},
        {{"--family", "smooth", "--noise", "0.1"}, "the noise is a knob of the block family only"},
    };
    for (const Refused& c : cases) {
        DYNAMIC_SECTION(c.expect) {
            const fs::path dir = fs::path(temp_path("gen-refused"));
            fs::remove_all(dir);
            fs::create_directories(dir);
            std::vector<std::string> args{"generate"};
            args.insert(args.end(), c.options.begin(), c.options.end());
            args.insert(args.end(), {"--out", (dir / "mesh.off").string()});
            const auto r = run_fhr(args);
            CHECK(r.exit_code == 2);
            CHECK(count_lines(r.err) == 1);
            CHECK_THAT(r.err, Catch::StartsWith("fhr: error: ") && Catch::Contains(c.expect));
            CHECK(fs::is_empty(dir));
        }
    }
}

TEST_CASE("CLI-GEN-5: --min-faces prints min_faces of the recipe and writes nothing", "[cli]") {
    const std::array<std::array<int, 3>, 5> recipes{{{0, 0, 1}, {2, 0, 1}, {0, 5, 1}, {3, 5, 3}, {1, 0, 2}}};
    for (const auto& [genus, holes, components] : recipes) {
        const auto r = run_fhr({"generate", "--genus", std::to_string(genus), "--holes", std::to_string(holes),
                                "--components", std::to_string(components), "--min-faces"});
        INFO(r.err);
        CHECK(r.exit_code == 0);
        CHECK(r.out == std::to_string(fhr::generate::min_faces(genus, holes, components)) + "\n");
    }
    CHECK(run_fhr({"generate", "--genus", "-1", "--min-faces"}).exit_code == 2);
    CHECK(run_fhr({"generate", "--family", "nonsense", "--min-faces"}).exit_code == 2);
}

TEST_CASE("CLI-GEN-5: --min-faces of each family is min_faces(options) (needs every family)", "[cli]") {
    for (const fhr::generate::Family family : fhr::generate::embedded_families) {
        fhr::generate::RandomMeshOptions o;
        o.family = family;
        o.genus = 2;
        o.holes = 1;
        o.components = 2;
        const auto r = run_fhr({"generate", "--family", fhr::generate::family_name(family), "--genus", "2", "--holes",
                                "1", "--components", "2", "--min-faces"});
        INFO(fhr::generate::family_name(family) << ": " << r.err);
        CHECK(r.exit_code == 0);
        CHECK(r.out == std::to_string(fhr::generate::min_faces(o)) + "\n");
    }
}

TEST_CASE("CLI-CONVERT-1: convert round-trips every writable format", "[cli]") {
    const std::string src = write_temp("conv.off", off("4 4 0", tet_v + tet_f));
    for (const char* ext : {"off", "obj", "ply"}) {
        DYNAMIC_SECTION(ext) {
            const std::string out = temp_path(std::string("conv.") + ext);
            REQUIRE(run_fhr({"convert", src, "--out", out}).exit_code == 0);
            const auto r = run_fhr({"info", "--json", out});
            CHECK(r.exit_code == 0);
            CHECK_THAT(r.out, Catch::Contains("\"vertices\": 4") && Catch::Contains("\"faces\": 4"));
        }
    }
}

TEST_CASE("DOM-7: fhr decimate writes the domain and its correspondence, byte-identical on a rerun", "[cli][domain]") {
    const std::string mesh = temp_path("dec-in.off");
    REQUIRE(run_fhr({"generate", "--genus", "2", "--faces", "3000", "--seed", "9", "--noise", "0.2", "--out", mesh})
                .exit_code == 0);
    const std::string a = temp_path("dec-a.off"), b = temp_path("dec-b.off");
    REQUIRE(run_fhr({"decimate", mesh, "--faces", "200", "--out", a}).exit_code == 0);
    REQUIRE(run_fhr({"decimate", mesh, "--faces", "200", "--out", b}).exit_code == 0);
    CHECK(fhr::test::read_file(a) == fhr::test::read_file(b));
    const std::string corr = fhr::test::read_file(temp_path("dec-a.correspondence"));
    const std::string corr_b = fhr::test::read_file(temp_path("dec-b.correspondence"));
    CHECK(corr.substr(corr.find('\n')) == corr_b.substr(corr_b.find('\n')));  // all but the comment naming the file
    const auto info = run_fhr({"info", "--json", a});
    CHECK_THAT(info.out, Catch::Contains("\"faces\": 200") && Catch::Contains("\"genus\": 2"));
    // One index per domain vertex: V = F/2 + χ = 100 − 2.
    int entries = 0;
    for (std::size_t p = 0; (p = corr.find('\n', p)) != std::string::npos; ++p) ++entries;
    CHECK(entries == 1 + 98);  // the comment line and 98 indices
    // --vertices N means F = 2(N − χ).
    const std::string c = temp_path("dec-c.off");
    REQUIRE(run_fhr({"decimate", mesh, "--vertices", "98", "--out", c}).exit_code == 0);
    CHECK(fhr::test::read_file(c) == fhr::test::read_file(a));
}

TEST_CASE("DOM-9: fhr decimate refuses requests that cannot be met, leaving no file", "[cli][domain]") {
    const std::string mesh = temp_path("dec-bad.off");
    REQUIRE(run_fhr({"generate", "--genus", "1", "--faces", "500", "--seed", "2", "--out", mesh}).exit_code == 0);
    const std::vector<std::pair<std::string, std::string>> requests{
        {"101", "odd"},
        {"502", "more than the mesh has (500)"},
        {"12", "fewer than a closed surface of genus 1 needs (at least 14)"}};
    for (const auto& [faces, expect] : requests) {
        const fs::path dir = temp_path("dec-bad-" + faces);
        fs::create_directories(dir);
        const auto r = run_fhr({"decimate", mesh, "--faces", faces, "--out", (dir / "d.off").string()});
        CHECK(r.exit_code == 2);
        CHECK(count_lines(r.err) == 1);
        CHECK_THAT(r.err, Catch::Contains(expect));
        CHECK(fs::is_empty(dir));
    }
}

TEST_CASE("DOM-10..13: fhr attach inserts a user-given domain's points, and refuses bad correspondences",
          "[cli][domain]") {
    const std::string mesh = temp_path("att.off"), dom = temp_path("att-d.off");
    REQUIRE(run_fhr({"generate", "--genus", "1", "--faces", "600", "--seed", "4", "--out", mesh}).exit_code == 0);
    REQUIRE(run_fhr({"decimate", mesh, "--faces", "60", "--out", dom}).exit_code == 0);
    const std::string corr = fhr::test::read_file(temp_path("att-d.correspondence"));
    // Replace the first two entries by a face point and an edge point.
    std::string lines = corr.substr(corr.find('\n') + 1);
    lines = lines.substr(lines.find('\n') + 1);
    lines = lines.substr(lines.find('\n') + 1);
    const std::string good = write_temp("att-good.corr", "f 7 0.2 0.3 0.5\nf 9 0 0.25 0.75\n" + lines);
    const std::string refined = temp_path("att-r.off");
    const auto r = run_fhr({"attach", mesh, "--domain", dom, "--correspondence", good, "--out", refined});
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Catch::Contains("2 points inserted"));
    const auto info = run_fhr({"info", "--json", refined});
    CHECK_THAT(info.out, Catch::Contains("\"vertices\": 302") && Catch::Contains("\"genus\": 1"));
    const std::vector<std::pair<std::string, std::string>> bad{
        {"3\n", "has 1 entries but the domain"},
        {"f 7 0.2 0.3 0.6\n" + lines + "1\n", "sum to"},
        {"f 7 0.2 0.3 0.5\n" + lines + "9999\n", "index 9999 out of range"},
    };
    for (const auto& [text, expect] : bad) {
        const std::string path = write_temp("att-bad.corr", text);
        const fs::path dir = temp_path("att-bad-out");
        fs::create_directories(dir);
        const auto e =
            run_fhr({"attach", mesh, "--domain", dom, "--correspondence", path, "--out", (dir / "x.off").string()});
        CHECK(e.exit_code == 2);
        CHECK(count_lines(e.err) == 1);
        CHECK_THAT(e.err, Catch::Contains(expect));
        CHECK(fs::is_empty(dir));
    }
}

TEST_CASE("GEO-E2: fhr geodesic prints the path, and refuses bad vertex indices", "[cli][geodesic]") {
    const std::string mesh = temp_path("geo.off");
    REQUIRE(run_fhr({"generate", "--genus", "1", "--faces", "800", "--seed", "8", "--noise", "0.1", "--out", mesh})
                .exit_code == 0);
    const auto r = run_fhr({"geodesic", mesh, "3", "200", "--json"});
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Catch::Contains("\"length\": ") && Catch::Contains("\"K\": ") &&
                          Catch::Contains("\"windows_created\": ") && Catch::Contains("\"vertex\": 200"));
    for (const auto& [src, dst, expect] : std::vector<std::tuple<std::string, std::string, std::string>>{
             {"3", "100000", "out of range"}, {"3", "3", "the same"}, {"x", "3", "SRC must be a vertex index"}}) {
        const auto e = run_fhr({"geodesic", mesh, src, dst});
        CHECK(e.exit_code == 2);
        CHECK(count_lines(e.err) == 1);
        CHECK_THAT(e.err, Catch::Contains(expect));
    }
}

TEST_CASE("LIB-2: the library's errors carry no exit code; the command maps each kind to spec/cli.md's",
          "[cli][unit]") {
    CHECK(fhr::cli::exit_code_of(fhr::InvalidInput("mesh.off", 3, "a face repeats vertex 1")) == 2);
    CHECK(fhr::cli::exit_code_of(fhr::PartitionFailure("conditions (1)/(2) of §3 fail")) == 3);
    CHECK(fhr::cli::exit_code_of(fhr::NumericalFailure("the solve missed its tolerance")) == 4);
    CHECK(fhr::cli::exit_code_of(fhr::InternalError("a patch §3 made is refused by §4")) == 70);
    CHECK(fhr::cli::exit_code_of(std::logic_error("a broken precondition")) == 70);
}

TEST_CASE(
    "CLI-DECIMATE-1, CLI-RUN-7: with boundary --vertices is refused, --corner-angle is taken; fhr run says why D is "
    "larger",
    "[cli][boundary]") {
    const std::string mesh = temp_path("holes2.off");
    REQUIRE(run_fhr({"generate", "--genus", "0", "--holes", "2", "--faces", "401", "--seed", "3", "--out", mesh})
                .exit_code == 0);
    const auto by_vertices = run_fhr({"decimate", mesh, "--vertices", "20", "--out", temp_path("d.off")});
    CHECK(by_vertices.exit_code == 2);
    CHECK_THAT(by_vertices.err, Catch::Contains("--vertices needs a closed surface"));
    CHECK(
        run_fhr({"decimate", mesh, "--faces", "40", "--corner-angle", "200", "--out", temp_path("d.off")}).exit_code ==
        2);
    CHECK(run_fhr({"decimate", mesh, "--faces", "40", "--corner-angle", "90", "--out", temp_path("d.off")}).exit_code ==
          0);
    // Asked for 2 faces: the two loops (an annulus needs at least 6) give more, and the run says so.
    const auto r = run_fhr({"run", mesh, "--faces", "2", "--out", temp_path("run-holes2")});
    CHECK(r.exit_code == 0);
    CHECK_THAT(r.err, Catch::Contains("(2 asked;"));
}
