// FHR cli — `fhr oracle-fuzz --cmd 'PROGRAM {mesh} {out}' --count N [--family NAME|all]
// [--genus-max G] [--holes-max H] [--components-max C] [--seed S] [--keep DIR] [--timeout SECONDS]
// [--shard K/N] [--table FILE] [--topology closed|disk|any] [--kind param|atlas|vertex-map]` and
// `fhr oracle-fuzz --merge FILE... [--table FILE]`: fuzzing another implementation of the paper,
// or any program that writes a UV atlas, with fhr's oracle (spec/cli.md CLI-ORACLE-*). Random meshes
// T (src/fhr/generate) go to the program: by default of every embedded family (block,
// smooth, quality, valence, density, degenerate; immersed only when named), surfaces with up to 5
// boundary loops in up to 3 components (what `fhr run` and the oracle accept), with
// `--holes-max 0 --components-max 1` (or `--topology closed`) the closed connected surfaces of §1
// only, `--topology disk` disks only (the meshes CGAL's methods take). Whatever the program writes
// must be a `fhr-param 1` file that `fhr verify --mesh T` accepts (PARAM-1..11, src/fhr/exchange),
// or with `--kind atlas` a UV atlas it accepts (ATLAS-1..8), or with `--kind vertex-map` a folder
// holding a per-vertex map `map.vmap` of T onto its base mesh `D.off` that it accepts (VMAP-1..9,
// rule adjacent). Each failure is kept with its reason and shrunk. A campaign too long for one
// machine is split into shards whose tables merge into the unsharded run's (oracle_table.hpp).
//
// Pseudocode:
//   for i in 0 .. N−1 with i mod N' = K−1 (--shard K/N', default 1/1: every i):
//       recipe_i <- (family, genus, holes, components, faces, seed, noise) drawn from
//                   splitmix64(S, i) (deterministic, and from (S, i) alone, whatever the shard;
//                   the family from a stream of its own, so that a block draw of --family all
//                   is the recipe of --family block; holes and components drawn only when
//                   H > 0, C > 1; faces from the family's min_faces up; noise for block only)
//       outcome  <- judge(recipe_i): write T to a temporary mesh.off; /bin/sh -c CMD with {mesh}
//                   and {out} replaced by the shell-quoted paths; exit 0, then read {out}
//                   (PARAM-1) and verify it against T (PARAM-2..11); the first failure is the reason
//       if it failed: shrink(recipe_i) (below); keep mesh, output, reason and the smaller mesh
//       row i <- (family, recipe, outcome, the failure's kind and reason, the shrunk recipe)
//   print `M meshes, K failures`; write the rows as the table; exit 0 when K = 0, else 1
//
// Shrinking (greedy, as in delta debugging) keeps the recipe's family and knobs — they are what
// makes the mesh hard — and makes the rest smaller, in one order for every family: a candidate
// is "smaller" when it has fewer faces, or as many faces and fewer components, or as many of both
// and fewer holes, or a lower genus, or (block only: the one family with noise) the same of all
// four without noise. From the current smallest failing recipe, try in order, each with the same
// face count (one fewer when no hole is left and the count is odd) where the family can make it
// (faces >= min_faces(recipe)): each smaller number of components, from 1; each smaller number of
// holes, from 0; each lower genus, from 0; then min_faces(recipe), the face count halfway and
// three quarters of the way down to it, then 2 faces fewer, each with the recipe's seed and two
// more seeds (a smaller size is a different mesh, and a bug may need a lucky one); no noise. The
// first candidate that fails *the same way* (same check id, same exit code, a timeout or no
// output) becomes the current one and the search starts again; it ends when no candidate fails
// or after shrink_budget runs of the program. What a smaller recipe is, family by family (the
// knobs are kept, so each is as hard in its own way at any size; the floor is min_faces(recipe),
// which holds the family's own features):
//   block       the perforated slab of the genus and holes, re-triangulated with fewer faces, at
//               least two per unit square of its surface; then without noise
//   smooth      the same rounded and deformed slab (roundness, amplitude) sampled by fewer faces
//   quality     fewer needles, caps and slivers (bad_fraction is a share of the faces), the
//               thinnest as thin as before (smallest_angle_deg)
//   valence     fewer high-valence fans (one per component, each of valence >= high_valence) and
//               fewer valence-3 vertices (low_fraction is a share of the vertices)
//   density     the same graded and anisotropic refinement (edge_ratio, anisotropy) in fewer
//               faces around it
//   degenerate  fewer vertices on the same coarse grid (grid_cells): as exactly coplanar and
//               collinear, in fewer faces
//   immersed    (only by name) fewer faces around the bump pushed through the slab (depth)
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include <fhr/core/errors.hpp>
#include <fhr/exchange/fhr_param.hpp>
#include <fhr/exchange/atlas.hpp>
#include <fhr/exchange/vertex_map.hpp>
#include <fhr/exchange/verify.hpp>
#include <fhr/generate/random_mesh.hpp>
#include <fhr/io/detail/atomic_file.hpp>
#include <fhr/io/detail/number_text.hpp>
#include <fhr/io/read.hpp>
#include "cli/common.hpp"
#include "cli/oracle_table.hpp"

extern char** environ;

namespace fhr::cli {
namespace {

namespace fs = std::filesystem;

/// Runs of the program spent on shrinking one failure.
constexpr int shrink_budget = 40;
/// The largest face count above min_faces(recipe) of a drawn mesh: modest, so that a slow
/// implementation still gets through hundreds of meshes.
constexpr std::uint64_t extra_faces_max = 600;
/// Bytes of the program's stderr kept in a reason.
constexpr std::size_t stderr_tail = 600;

/// splitmix64 (Steele, Lea, Flood 2014): a fully specified stream, so the recipes are the same on
/// every platform.
class SplitMix {
public:
    explicit SplitMix(std::uint64_t state) : state_(state) {}
    std::uint64_t next() {
        std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    /// In [0, n); the bias of the modulo is below n / 2^64, irrelevant for a test recipe.
    std::uint64_t below(std::uint64_t n) { return next() % n; }

private:
    std::uint64_t state_;
};

using Recipe = generate::RandomMeshOptions;
using generate::Family;

/// The least face count of the recipe's family, genus, holes and components (its faces ignored),
/// at least `faces_min` (`--faces-min`: the size the program works at): min_faces(recipe) or
/// faces_min, made even without holes (a closed mesh has an even face count).
std::size_t least_faces(const Recipe& r, std::size_t faces_min) {
    const std::size_t least = std::max(generate::min_faces(r), faces_min);
    return least + (r.holes == 0 ? least % 2 : 0);
}

/// The ranges recipes are drawn from: [0, genus], [holes_min, holes], [1, components].
struct Ranges {
    int genus = 2, holes = 5, components = 3, holes_min = 0;
};

/// `--topology`: the surfaces the program accepts. closed: no hole, one component; disk: genus 0,
/// one hole, one component (CGAL's methods); any: the ranges as given.
enum class Topology { any, closed, disk };

/// Whether `r` has the topology (shrinking keeps it).
bool has_topology(const Recipe& r, Topology t) {
    if (t == Topology::closed) return r.holes == 0 && r.components == 1;
    if (t == Topology::disk) return r.genus == 0 && r.holes == 1 && r.components == 1;
    return true;
}

/// What a program writes (`--kind`): a `fhr-param 1` file (spec/param.md), a UV atlas
/// (spec/atlas.md), or a folder with a per-vertex map and its base mesh (spec/vertex_map.md).
enum class OutputKind { param, atlas, vertex_map };

/// How outputs are judged: the program, its time limit, what it writes and the topology every
/// mesh keeps.
struct Judging {
    std::string cmd;
    double timeout = 60;
    OutputKind kind = OutputKind::param;
    Topology topology = Topology::any;
    std::size_t faces_min = 0;  ///< `--faces-min`: no mesh drawn or shrunk below it
    /// The output's name in a run folder: the adapters of atlases write OBJ, of per-vertex maps a folder.
    const char* out_name() const {
        return kind == OutputKind::atlas ? "out.obj" : kind == OutputKind::vertex_map ? "out" : "out.fhrp";
    }
};

/// Mesh i of the run with seed S: the family asked for, or (nullptr: `--family all`) one of the
/// embedded families drawn from a stream of its own, so that the other draws do not depend on it;
/// genus, holes and components in their ranges (holes and components drawn only when their range
/// has more than one value, so `--family block --holes-max 0 --components-max 1` draws the closed
/// recipes with no draw spent on holes or components), faces in [least_faces, least_faces + 600] (even without
/// holes), a seed that `fhr generate --seed` accepts (< 2^63), for block noise 0, 0.05, 0.1 or
/// 0.25; the family's knobs at their defaults.
Recipe draw_recipe(std::uint64_t seed, std::uint64_t i, const Ranges& ranges, const Family* family,
                   std::size_t faces_min) {
    const std::uint64_t stream = SplitMix(seed).next() ^ (i * 0xD1B54A32D192ED03ull);
    SplitMix r(stream);
    Recipe o;
    o.family = family ? *family
                      : generate::embedded_families[SplitMix(stream ^ 0x6A09E667F3BCC909ull)
                                                        .below(std::size(generate::embedded_families))];
    o.genus = static_cast<int>(r.below(static_cast<std::uint64_t>(ranges.genus) + 1));
    if (ranges.holes > ranges.holes_min)
        o.holes = ranges.holes_min +
                  static_cast<int>(r.below(static_cast<std::uint64_t>(ranges.holes - ranges.holes_min) + 1));
    else
        o.holes = ranges.holes_min;
    if (ranges.components > 1)
        o.components = 1 + static_cast<int>(r.below(static_cast<std::uint64_t>(ranges.components)));
    const std::uint64_t step = o.holes == 0 ? 2 : 1;  // F is even without holes
    o.faces = least_faces(o, faces_min) + step * r.below(extra_faces_max / step + 1);
    o.seed = r.next() >> 1;
    constexpr double noises[] = {0.0, 0.05, 0.1, 0.25};
    if (o.family == Family::block) o.noise = noises[r.below(4)];
    return o;
}

/// "F faces, genus g", then ", holes b" and ", components c" unless closed and connected.
std::string size_of(const Recipe& o) {
    std::string s = std::to_string(o.faces) + " faces, genus " + std::to_string(o.genus);
    if (o.holes != 0) s += ", holes " + std::to_string(o.holes);
    if (o.components != 1) s += ", components " + std::to_string(o.components);
    return s;
}

/// POSIX shell single quotes: nothing inside is special except the quote itself.
std::string shell_quote(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

std::string substitute(std::string cmd, const std::string& mesh, const std::string& out) {
    for (const auto& [key, value] :
         {std::pair<std::string, std::string>{"{mesh}", shell_quote(mesh)}, {"{out}", shell_quote(out)}}) {
        for (std::size_t at = cmd.find(key); at != std::string::npos; at = cmd.find(key, at + value.size()))
            cmd.replace(at, key.size(), value);
    }
    return cmd;
}

struct Outcome {
    bool ok = true;
    std::string kind;  ///< what "fails the same way" compares: "PARAM-8", "exit 3", "signal 11", "timeout", "no output"
    std::string reason;            ///< one line (the program's stderr tail follows on further lines)
    std::string distortion = "-";  ///< the output's figures when the oracle read it (TableRow::distortion)
};

/// `l2 X p99 Y max Z` (DIST-4, DIST-7; %.6g), or "-" when every face was degenerate or nothing was measured.
std::string distortion_text(const exchange::Distortion& d) {
    if (!d.l2_stretch || !d.anisotropy_p99 || !d.anisotropy_max) return "-";
    char text[96];
    std::snprintf(text, sizeof text, "l2 %.6g p99 %.6g max %.6g", *d.l2_stretch, *d.anisotropy_p99, *d.anisotropy_max);
    return text;
}

std::string tail_of(const fs::path& file) {
    std::string s;
    try {
        s = io::read_bytes(file.string());
    } catch (const InvalidInput&) {
        return "";
    }
    if (s.size() > stderr_tail) s = "…" + s.substr(s.size() - stderr_tail);
    return s;
}

/// Runs `/bin/sh -c command` in its own process group with stdout and stderr to files in `dir`;
/// after `timeout` seconds the group is killed. Returns the wait status, or −1 on a timeout.
int run_shell(const std::string& command, const fs::path& dir, double timeout) {
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 1, (dir / "stdout").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, 2, (dir / "stderr").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawnattr_t attr;
    posix_spawnattr_init(&attr);
    posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);
    posix_spawnattr_setpgroup(&attr, 0);
    std::string sh = "/bin/sh", c = "-c", cmd = command;
    char* argv[] = {sh.data(), c.data(), cmd.data(), nullptr};
    pid_t pid = 0;
    const int err = posix_spawn(&pid, "/bin/sh", &actions, &attr, argv, environ);
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attr);
    if (err != 0) throw InvalidInput("/bin/sh", 0, "cannot start the shell");
    const auto start = std::chrono::steady_clock::now();
    int status = 0;
    while (::waitpid(pid, &status, WNOHANG) == 0) {
        if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > timeout) {
            ::kill(-pid, SIGKILL);
            ::waitpid(pid, &status, 0);
            return -1;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return status;
}

/// Generates the recipe's mesh in `dir`, runs the program on it and judges its output.
Outcome judge(const Recipe& recipe, const Judging& how, const fs::path& dir) {
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path mesh = dir / "mesh.off", out = dir / how.out_name();
    save_mesh(mesh.string(), generate::random_mesh(recipe));
    const double timeout = how.timeout;
    const int status = run_shell(substitute(how.cmd, mesh.string(), out.string()), dir, timeout);
    Outcome o;
    o.ok = false;
    const std::string err = tail_of(dir / "stderr");
    const std::string err_lines = err.empty() ? "" : "\n" + err;
    if (status == -1) {
        o.kind = "timeout";
        o.reason = "the program ran longer than " + std::to_string(static_cast<long>(timeout)) + " s" + err_lines;
        return o;
    }
    if (WIFSIGNALED(status)) {
        o.kind = "signal " + std::to_string(WTERMSIG(status));
        o.reason = "the program was killed by signal " + std::to_string(WTERMSIG(status)) + err_lines;
        return o;
    }
    if (WEXITSTATUS(status) != 0) {
        o.kind = "exit " + std::to_string(WEXITSTATUS(status));
        o.reason = "the program exited with code " + std::to_string(WEXITSTATUS(status)) + err_lines;
        return o;
    }
    const bool folder = how.kind == OutputKind::vertex_map;
    if (folder ? !fs::is_regular_file(out / "map.vmap") || !fs::is_regular_file(out / "D.off")
               : !fs::is_regular_file(out)) {
        o.kind = "no output";
        o.reason = std::string("the program exited with code 0 but wrote no ") +
                   (folder ? "map.vmap and D.off in the folder {out}" : "file at {out}") + err_lines;
        return o;
    }
    std::optional<TriMesh> T;
    if (!folder) T = load_mesh(mesh.string(), BuildOptions{});
    std::vector<exchange::CheckResult> checks;
    try {
        if (how.kind == OutputKind::atlas) {
            exchange::AtlasReport r = exchange::verify_atlas(exchange::read_atlas(out.string()), &*T);
            checks = std::move(r.checks);
            o.distortion = distortion_text(r.distortion);
        } else if (how.kind == OutputKind::param) {
            exchange::VerifyReport r = exchange::verify(exchange::read_param(out.string()), &*T);
            checks = std::move(r.checks);
            o.distortion = distortion_text(r.distortion);
        } else {
            const PolygonSoup t = io::read_soup(mesh.string()), d = io::read_soup((out / "D.off").string());
            const exchange::VertexMapFile map =
                exchange::read_vertex_map((out / "map.vmap").string(), std::nullopt, t.points.size(), d.points.size());
            exchange::VertexMapReport r = exchange::verify_vertex_map(map, t, d);
            checks = std::move(r.checks);
            o.distortion = distortion_text(r.distortion);
        }
    } catch (const InvalidInput& e) {
        o.kind = how.kind == OutputKind::atlas ? "ATLAS-1" : how.kind == OutputKind::param ? "PARAM-1" : "VMAP-1";
        o.reason = o.kind + ": " + e.what();
        return o;
    }
    if (const exchange::CheckResult* bad = exchange::first_judged_failure(checks)) {
        o.kind = bad->id;
        o.reason = bad->id + ": " + bad->first_failure;
        return o;
    }
    o.ok = true;
    return o;
}

/// Fewer faces, then fewer components, then fewer holes, then lower genus, then less noise.
bool smaller(const Recipe& a, const Recipe& b) {
    if (a.faces != b.faces) return a.faces < b.faces;
    if (a.components != b.components) return a.components < b.components;
    if (a.holes != b.holes) return a.holes < b.holes;
    if (a.genus != b.genus) return a.genus < b.genus;
    return a.noise < b.noise;
}

/// The candidates tried from `r`, in order (see the file comment), each of the topology.
std::vector<Recipe> shrink_candidates(const Recipe& r, Topology topology, std::size_t faces_min) {
    std::vector<Recipe> c;
    // r with one of components, holes, genus lowered to v, when the generator can make it.
    const auto lowered = [&](int Recipe::*knob, int v) {
        Recipe x = r;
        x.*knob = v;
        if (x.holes == 0) x.faces -= x.faces % 2;
        if (x.faces >= least_faces(x, faces_min) && has_topology(x, topology)) c.push_back(x);
    };
    for (int k = 1; k < r.components; ++k) lowered(&Recipe::components, k);
    for (int h = 0; h < r.holes; ++h) lowered(&Recipe::holes, h);
    for (int g = 0; g < r.genus; ++g) lowered(&Recipe::genus, g);
    const std::size_t least = least_faces(r, faces_min), excess = (r.faces - least) / 2;
    for (std::size_t faces : {least, least + 2 * (excess / 2), least + 2 * (excess * 3 / 4), r.faces - 2}) {
        if (faces >= r.faces || faces < least) continue;
        for (std::uint64_t k = 0; k < 3; ++k) {
            Recipe x = r;
            x.faces = faces;
            x.seed = k == 0 ? r.seed : SplitMix(r.seed + k).next() >> 1;
            c.push_back(x);
        }
    }
    if (r.noise != 0) {
        Recipe x = r;
        x.noise = 0;
        c.push_back(x);
    }
    return c;
}

struct Shrunk {
    Recipe recipe;
    Outcome outcome;
    int runs = 0;
};

Shrunk shrink(const Recipe& failing, const Outcome& failure, const Judging& how, const fs::path& dir) {
    Shrunk best{failing, failure, 0};
    bool progress = true;
    while (progress && best.runs < shrink_budget) {
        progress = false;
        for (const Recipe& candidate : shrink_candidates(best.recipe, how.topology, how.faces_min)) {
            if (best.runs >= shrink_budget) break;
            if (!smaller(candidate, best.recipe)) continue;
            ++best.runs;
            const Outcome o = judge(candidate, how, dir);
            if (!o.ok && o.kind == failure.kind) {
                best.recipe = candidate;
                best.outcome = o;
                progress = true;
                break;
            }
        }
    }
    return best;
}

/// Keeps one failure: DIR/mesh-<i>/{mesh.off, out.fhrp, out.obj or the folder out (when written), reason.txt, smaller.off}.
void keep_failure(const fs::path& keep, std::uint64_t i, const Recipe& recipe, const Outcome& outcome,
                  const fs::path& run_dir, const Shrunk& shrunk, const Judging& how) {
    const std::string& cmd = how.cmd;
    const fs::path dir = keep / ("mesh-" + std::to_string(i));
    fs::remove_all(dir);  // a folder of an earlier run with the same name
    fs::create_directories(dir);
    fs::copy_file(run_dir / "mesh.off", dir / "mesh.off", fs::copy_options::overwrite_existing);
    if (fs::exists(run_dir / how.out_name()))
        fs::copy(run_dir / how.out_name(), dir / how.out_name(),
                 fs::copy_options::overwrite_existing | fs::copy_options::recursive);
    save_mesh((dir / "smaller.off").string(), generate::random_mesh(shrunk.recipe));
    std::string text = "command: " + cmd + "\n";
    text += "mesh.off: " + generate::generate_command(recipe) + " (" + size_of(recipe) + ")\n";
    text += "reason: " + outcome.reason + "\n";
    text += "smaller.off: " + generate::generate_command(shrunk.recipe) + " (" + size_of(shrunk.recipe) + "; " +
            std::to_string(shrunk.runs) + " shrinking runs)\n";
    text += "smaller reason: " + shrunk.outcome.reason + "\n";
    io::write_file_atomically((dir / "reason.txt").string(), text);
}

/// The first line of a reason, for the one-line report.
std::string first_line(const std::string& s) { return s.substr(0, s.find('\n')); }

struct TempDir {
    fs::path path;
    TempDir() {
        std::string pattern = (fs::temp_directory_path() / "fhr-oracle-fuzz-XXXXXX").string();
        if (!::mkdtemp(pattern.data())) throw InvalidInput(pattern, 0, "cannot create a temporary folder");
        path = pattern;
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
};

/// `fhr oracle-fuzz --merge FILE... [--table OUT]`: the shards' tables as the unsharded run's
/// (CLI-ORACLE-9); its failures and summary on stdout, the exit code of that run.
int merge(const Args& args) {
    for (const char* name : {"cmd", "count", "family", "genus-max", "holes-max", "components-max", "seed", "keep",
                             "timeout", "shard", "topology", "kind", "faces-min"})
        if (args.get(name)) usage_error(std::string("--merge takes table files and --table only (not --") + name + ")");
    const oracle::Table merged = oracle::merge_tables(args.positional());
    std::uint64_t failures = 0;
    for (const oracle::TableRow& row : merged.rows) {
        if (!row.failed()) continue;
        ++failures;
        std::printf("mesh %llu: %s: FAILED: %s; smaller: %s\n", static_cast<unsigned long long>(row.index),
                    row.recipe.c_str(), row.reason.c_str(), row.smaller.c_str());
    }
    if (const auto out = args.get("table")) io::write_file_atomically(*out, oracle::table_text(merged));
    std::printf("%llu meshes, %llu failures\n", static_cast<unsigned long long>(merged.rows.size()),
                static_cast<unsigned long long>(failures));
    return failures == 0 ? 0 : 1;
}

}  // namespace

int run_oracle_fuzz(const std::vector<std::string>& argv) {
    const Args args(argv, {"merge"},
                    {"cmd", "count", "family", "genus-max", "holes-max", "components-max", "seed", "keep", "timeout",
                     "shard", "table", "topology", "kind", "faces-min"});
    if (args.flag("merge")) return merge(args);
    if (!args.positional().empty())
        usage_error("fhr oracle-fuzz takes no positional arguments (but table files with --merge)");
    const std::string cmd = args.require("cmd");
    if (cmd.find("{mesh}") == std::string::npos || cmd.find("{out}") == std::string::npos)
        usage_error("--cmd must contain {mesh} and {out}");
    args.require("count");
    const auto count = static_cast<std::uint64_t>(args.integer("count", 0, 1, 1'000'000));
    const std::string family_arg = args.get("family").value_or("all");
    const Family named = family_arg == "all" ? Family::block : generate::parse_family(family_arg);
    const Family* family = family_arg == "all" ? nullptr : &named;
    Ranges ranges{static_cast<int>(args.integer("genus-max", 2, 0, 20)),
                  static_cast<int>(args.integer("holes-max", 5, 0, 100)),
                  static_cast<int>(args.integer("components-max", 3, 1, 20))};
    const std::string topology_arg = args.get("topology").value_or("any"),
                      kind_arg = args.get("kind").value_or("param");
    Judging how;
    if (topology_arg == "closed") {
        how.topology = Topology::closed;
        ranges.holes = 0;
        ranges.components = 1;
    } else if (topology_arg == "disk") {
        how.topology = Topology::disk;
        ranges = Ranges{.genus = 0, .holes = 1, .components = 1, .holes_min = 1};
    } else if (topology_arg != "any") {
        usage_error("--topology must be closed, disk or any, not '" + topology_arg + "'");
    }
    if (kind_arg != "param" && kind_arg != "atlas" && kind_arg != "vertex-map")
        usage_error("--kind must be param, atlas or vertex-map, not '" + kind_arg + "'");
    how.kind = kind_arg == "atlas"        ? OutputKind::atlas
               : kind_arg == "vertex-map" ? OutputKind::vertex_map
                                          : OutputKind::param;
    const auto seed = static_cast<std::uint64_t>(args.integer("seed", 1, 0, INT64_MAX));
    const fs::path keep = args.get("keep").value_or("oracle-fuzz-failures");
    const double timeout = args.real("timeout", 60.0, 0.1, 86400.0);
    how.cmd = cmd;
    how.timeout = timeout;
    how.faces_min = static_cast<std::size_t>(args.integer("faces-min", 0, 0, 1'000'000));
    const oracle::Shard shard = args.get("shard") ? oracle::parse_shard(*args.get("shard")) : oracle::Shard{};
    std::string timeout_text;  // the shortest decimal that reads back as the timeout: 60 and 60.0 alike
    io::append_number(timeout_text, timeout);
    oracle::Table table{{cmd, std::to_string(count), std::to_string(seed), family_arg, std::to_string(ranges.genus),
                         std::to_string(ranges.holes), std::to_string(ranges.components), timeout_text, topology_arg,
                         kind_arg, std::to_string(how.faces_min)},
                        shard,
                        {}};

    const TempDir tmp;
    const fs::path run_dir = tmp.path / "run", shrink_dir = tmp.path / "shrink";
    std::uint64_t failures = 0;
    for (std::uint64_t i = shard.k - 1; i < count; i += shard.n) {
        const Recipe recipe = draw_recipe(seed, i, ranges, family, how.faces_min);
        const Outcome outcome = judge(recipe, how, run_dir);
        oracle::TableRow row{i,
                             generate::family_name(recipe.family),
                             generate::generate_command(recipe),
                             "",
                             "",
                             "",
                             outcome.distortion};
        std::printf("mesh %llu: %s: ", static_cast<unsigned long long>(i), row.recipe.c_str());
        if (outcome.ok) {
            std::printf("valid\n");
        } else {
            ++failures;
            const Shrunk shrunk = shrink(recipe, outcome, how, shrink_dir);
            keep_failure(keep, i, recipe, outcome, run_dir, shrunk, how);
            row.check = outcome.kind;
            row.reason = first_line(outcome.reason);
            row.smaller = generate::generate_command(shrunk.recipe, "smaller.off");
            std::printf("FAILED: %s; smaller: %s; kept in %s\n", row.reason.c_str(), size_of(shrunk.recipe).c_str(),
                        (keep / ("mesh-" + std::to_string(i))).string().c_str());
        }
        table.rows.push_back(std::move(row));
        std::fflush(stdout);
    }
    if (const auto out = args.get("table")) io::write_file_atomically(*out, oracle::table_text(table));
    std::printf("%llu meshes, %llu failures", static_cast<unsigned long long>(table.rows.size()),
                static_cast<unsigned long long>(failures));
    if (shard.n > 1)
        std::printf(" (shard %s of %llu meshes)", shard.text().c_str(), static_cast<unsigned long long>(count));
    std::printf("\n");
    return failures == 0 ? 0 : 1;
}

}  // namespace fhr::cli
