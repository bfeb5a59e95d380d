// LIB-3 (spec/library.md): pipeline::run, the method end to end as one library call: §2–§5 on the
// fandisk with the paper's settings, every stage reported to the observer in order, the oracle's
// verdict and the wavelets in the result; options it cannot take are refused as InvalidInput; the
// independent tasks run on the caller's executor, with the same result on any number of threads;
// a caller's task runs beside the oracle on the file it judges (fhr run writes its files there,
// the same bytes as write_outputs after the run). REN-15: app::write_figures draws the
// boundary of a surface with holes in every figure. PART-10 with DIST-1: restricted paths kept a
// third of the gap away from the curves they were moved off leave no sliver strip on the bull.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <functional>
#include <filesystem>
#include <string>
#include <vector>

#include <fhr/core/errors.hpp>
#include <fhr/core/executor.hpp>
#include <fhr/app/outputs.hpp>
#include <fhr/exchange/distortion.hpp>
#include <fhr/generate/random_mesh.hpp>
#include <fhr/domain/domain.hpp>
#include <fhr/pipeline/detail/run_beside.hpp>
#include <fhr/pipeline/pipeline.hpp>
#include "render/png_reader.hpp"
#include "support/test_support.hpp"

using namespace fhr;

namespace {

struct Recorder final : pipeline::StageObserver {
    std::vector<std::string> in_total, after;
    void stage(std::string_view name, double seconds, bool total) override {
        CHECK(seconds >= 0);
        (total ? in_total : after).emplace_back(name);
    }
};

/// Runs every task through a ThreadPool of `threads` threads, counting the calls and tasks.
struct Counting final : Executor {
    explicit Counting(unsigned threads) : inner(threads) {}
    void for_each(std::size_t n, std::size_t grain, const std::function<void(std::size_t)>& task) override {
        ++calls;
        inner.for_each(n, grain, [&](std::size_t i) {
            ++tasks;
            task(i);
        });
    }
    ThreadPool inner;
    std::atomic<std::size_t> calls{0}, tasks{0};
};

}  // namespace

TEST_CASE("LIB-3: pipeline::run takes the fandisk through §2–§5 and reports each stage", "[pipeline][library]") {
    const std::string path = test::cgal_mesh("fandisk.off");
    const TriMesh T = test::load_mesh(path);
    Recorder stages;
    std::vector<std::string> progress;
    pipeline::RunOptions options;
    options.faces = 114;
    options.levels = 3;
    options.keep = {5, 20};
    options.method.observer = &stages;
    options.method.progress = [&](const std::string& line) { progress.push_back(line); };
    const pipeline::RunResult r = pipeline::run(T, options);
    CHECK(r.certified());
    CHECK(r.oracle.valid());
    CHECK(r.domain_faces_requested == 114);
    CHECK(r.parameterization.partition.domain.mesh.n_faces() == 114);
    CHECK(r.parameterization.domains_tried == 1);  // the map on §2's D meets the goals (CLI-RUN-9)
    CHECK(r.parameterization.graded_normal_rule == 0);
    CHECK(r.parameterization.graded_min_angle == 0);
    REQUIRE(r.wavelets);
    CHECK(r.wavelets->kept.size() == 2);
    CHECK(stages.in_total == std::vector<std::string>{"mesh_reduction", "geodesic_paths", "parameterization",
                                                      "verification", "refinement", "decomposition", "reconstruction"});
    CHECK(stages.after == std::vector<std::string>{"hausdorff"});
    CHECK(!progress.empty());

    // Without §5, and the refusals.
    pipeline::RunOptions plain;
    plain.faces = 114;
    CHECK_FALSE(pipeline::run(T, plain).wavelets);
    pipeline::RunOptions bad = plain;
    bad.keep = {5};
    CHECK_THROWS_AS(pipeline::run(T, bad), InvalidInput);  // kept percentages need levels
    bad.levels = 3;
    bad.keep = {120};
    CHECK_THROWS_AS(pipeline::run(T, bad), InvalidInput);
    bad = plain;
    bad.faces = 113;  // odd: §2 refuses it
    CHECK_THROWS_AS(pipeline::run(T, bad), InvalidInput);
}

TEST_CASE("LIB-3: the tasks run on the caller's executor, bit-identical on 1 and 3 threads", "[pipeline][library]") {
    const std::string path = test::cgal_mesh("fandisk.off");
    const TriMesh T = test::load_mesh(path);
    pipeline::RunOptions options;
    options.faces = 114;
    options.levels = 2;
    options.keep = {10};
    Counting one(1), three(3);
    options.method.executor = &one;
    const pipeline::RunResult a = pipeline::run(T, options);
    options.method.executor = &three;
    const pipeline::RunResult b = pipeline::run(T, options);
    // paths (at least one round), patches (one task per domain face), the two Hausdorff brackets
    CHECK(one.calls >= 3);
    CHECK(one.tasks >= 114 + 2);
    CHECK(three.calls == one.calls);
    CHECK(three.tasks == one.tasks);
    REQUIRE(a.certified());
    CHECK(pipeline::to_param_file(a.parameterization) == pipeline::to_param_file(b.parameterization));
    REQUIRE(a.wavelets);
    REQUIRE(b.wavelets);
    CHECK(a.wavelets->remesh_positions == b.wavelets->remesh_positions);
    CHECK(a.wavelets->kept[0].positions == b.wavelets->kept[0].positions);
    CHECK(a.wavelets->remesh_hausdorff.lower() == b.wavelets->remesh_hausdorff.lower());
    CHECK(a.wavelets->remesh_hausdorff.upper() == b.wavelets->remesh_hausdorff.upper());
}

TEST_CASE(
    "LIB-3: the caller's tasks run beside the oracle on what param.fhrp holds and on §5's result; the files written "
    "there are write_outputs' bytes",
    "[pipeline][library]") {
    const TriMesh T = generate::random_mesh({1, 2400, 3, 0.1});
    pipeline::RunOptions options;
    options.faces = 80;
    options.levels = 1;
    options.keep = {20};
    const std::string beside = test::temp_path("run-beside"), after = test::temp_path("run-after");
    std::size_t calls = 0, wavelet_calls = 0;
    exchange::ParamFile seen;
    std::vector<Vec3> seen_remesh;
    pipeline::RunBeside tasks;
    tasks.beside_oracle = [&](const pipeline::Parameterization& p, const exchange::ParamFile& file) {
        ++calls;
        CHECK(p.refined_positions.empty());  // lent to the file meanwhile
        CHECK(p.face_beta.empty());
        seen = file;
        app::write_parameterization(beside, p, file, options.method.executor);
    };
    tasks.after_wavelets = [&](const wavelet::WaveletResult& w) {  // §5's meshes as soon as §5 is done
        ++wavelet_calls;
        seen_remesh = w.remesh_positions;
        app::write_wavelets(beside, w, options.method.executor);
    };
    const pipeline::RunResult r = pipeline::run(T, options, tasks);
    REQUIRE(r.certified());
    REQUIRE(r.wavelets);
    CHECK(calls == 1);
    CHECK(wavelet_calls == 1);
    CHECK(seen == pipeline::to_param_file(r.parameterization));
    CHECK(seen_remesh == r.wavelets->remesh_positions);
    // The rest written after the run, and everything written after it in another folder: the same bytes.
    const app::InputInfo input{.path = "generated", .vertices = T.n_vertices(), .faces = T.n_faces(), .genus = 1};
    const app::Timings timings;
    // The files written beside are not written again (a new file would have a new time).
    const auto written_at = [&](const char* name) { return std::filesystem::last_write_time(beside + "/" + name); };
    const auto param_at = written_at("param.fhrp"), remesh_at = written_at("remesh_L1.off");
    app::write_outputs(beside, input, r.parameterization, r.oracle, timings, options.method, &*r.wavelets,
                       {.parameterization = 0.25, .wavelets = 0.125});
    CHECK(written_at("param.fhrp") == param_at);
    CHECK(written_at("remesh_L1.off") == remesh_at);
    app::write_outputs(after, input, r.parameterization, r.oracle, timings, options.method, &*r.wavelets);
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(after))
        names.push_back(entry.path().filename().string());
    CHECK(names.size() == 9);  // five of the parameterization, two of §5 (D^1, 20 % kept), the report, the timings
    for (const std::string& name : names) {
        INFO(name);
        REQUIRE(std::filesystem::exists(beside + "/" + name));
        if (name != "timings.json") CHECK(test::read_file(beside + "/" + name) == test::read_file(after + "/" + name));
    }
    // "writing" adds both groups' seconds; "writing_beside_oracle" is them alone.
    CHECK(test::read_file(beside + "/timings.json").find("\"writing\"") != std::string::npos);
    CHECK(test::read_file(beside + "/timings.json").find("\"writing_beside_oracle\": 0.375") != std::string::npos);
    CHECK(test::read_file(after + "/timings.json").find("\"writing_beside_oracle\"") == std::string::npos);
    // One group alone: its seconds alone (the other group written here).
    const std::string one = test::temp_path("run-one-group");
    app::write_outputs(one, input, r.parameterization, r.oracle, timings, options.method, &*r.wavelets,
                       {.parameterization = 0.25, .wavelets = std::nullopt});
    CHECK(test::read_file(one + "/timings.json").find("\"writing_beside_oracle\": 0.25\n") != std::string::npos);
    CHECK(std::filesystem::exists(one + "/remesh_L1.off"));
    CHECK_FALSE(std::filesystem::exists(one + "/param.fhrp"));
    app::write_outputs(one, input, r.parameterization, r.oracle, timings, options.method, &*r.wavelets,
                       {.parameterization = std::nullopt, .wavelets = 0.125});
    CHECK(test::read_file(one + "/timings.json").find("\"writing_beside_oracle\": 0.125\n") != std::string::npos);
    CHECK(std::filesystem::exists(one + "/param.fhrp"));

    // A task that throws: the run throws it, once the oracle and §5 are done.
    tasks.beside_oracle = [](const pipeline::Parameterization&, const exchange::ParamFile&) {
        throw InvalidInput("out", 0, "cannot write");
    };
    CHECK_THROWS_AS(pipeline::run(T, options, tasks), InvalidInput);
    tasks.beside_oracle = nullptr;
    tasks.after_wavelets = [](const wavelet::WaveletResult&) { throw InvalidInput("out", 0, "cannot write"); };
    CHECK_THROWS_AS(pipeline::run(T, options, tasks), InvalidInput);
}

TEST_CASE("REN-15: write_figures draws the boundary of a surface with holes in both panels of Figs. 6-9",
          "[pipeline][render]") {
    // Two boundary loops; §2–§5 on it, then the figures.
    const TriMesh T = generate::random_mesh({0, 1200, 5, 0.1, 2});
    pipeline::RunOptions options;
    options.faces = 60;
    options.levels = 2;
    options.keep = {5, 20};
    const pipeline::RunResult r = pipeline::run(T, options);
    REQUIRE(r.certified());
    REQUIRE(r.wavelets);
    std::size_t boundary_curves = 0;
    for (const partition::CurveInfo& c : r.parameterization.partition.curves)
        boundary_curves += c.kind == partition::CurveKind::boundary;
    CHECK(boundary_curves > 0);
    const std::string dir = test::temp_path("boundary-run-figures");
    std::filesystem::create_directories(dir);
    app::write_figures(dir, T, r.parameterization, 1, &*r.wavelets);
    for (const char* name : {"fig6", "fig7", "fig8", "fig9"}) {
        INFO(name);
        const render::Image image =
            render::reader::decode_png(test::read_file(dir + "/figures/" + name + ".png")).image;
        int left = 0, right = 0;  // pixels of the boundary's green (visible or hidden)
        for (int y = 0; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x) {
                const render::Rgb8 c = image.at(x, y);
                if (c.g > c.r + 60 && c.g > c.b + 60) ++(x < image.width / 2 ? left : right);
            }
        CHECK(left > 50);
        CHECK(right > 50);
    }
}

TEST_CASE(
    "LIB-3: from 2^18 faces of T on, the oracle and §5 make their parts of T in their own stages: a certified run",
    "[pipeline][library]") {
    // Below 2^18 faces run() prepares the oracle's side of T and §5's tree of T beside §2's
    // decimation (the other tests); from 2^18 on each stage makes its own, for the memory.
    const TriMesh T = generate::random_mesh({0, std::size_t{1} << 18, 7, 0.1});
    REQUIRE(T.n_faces() == std::size_t{1} << 18);
    pipeline::RunOptions options;
    options.faces = 2000;
    options.levels = 1;
    const pipeline::RunResult r = pipeline::run(T, options);
    CHECK(r.certified());
    REQUIRE(r.oracle.checks.size() == 10u);
    CHECK(r.oracle.checks.back().id == "PARAM-11");
    CHECK(r.oracle.checks.back().status == exchange::CheckStatus::pass);
    REQUIRE(r.wavelets);
    CHECK(r.wavelets->remesh_hausdorff.lower() > 0);
    CHECK(r.wavelets->remesh_hausdorff.lower() <= r.wavelets->remesh_hausdorff.upper());
}

namespace {

std::ptrdiff_t count_curves(const pipeline::RunResult& r, partition::CurveKind kind) {
    const auto& curves = r.parameterization.partition.curves;
    return std::count_if(curves.begin(), curves.end(), [&](const partition::CurveInfo& c) { return c.kind == kind; });
}

}  // namespace

TEST_CASE("PART-10, DIST-1: the bull's restricted paths leave no sliver strip: its worst face below 10^3",
          "[pipeline][distortion]") {
    // At 122 domain faces the bull's domain is kept with restricted paths. Separated by 10⁻⁴ of an
    // edge of T from the curves they touched, they left strips that far wide, with σ₁/σ₂ up to
    // 3.7·10⁵; a third of the gap to the next vertex of T′ leaves 4·10² (paper_notes/distortion_causes.md).
    // The paper's map: the restricted curves as §3 left them (the default map moves some).
    const TriMesh T = test::load_mesh(test::cgal_mesh("bull.off"));
    pipeline::RunOptions options;
    options.faces = 122;
    options.method.relax = false;
    const pipeline::RunResult r = pipeline::run(T, options);
    REQUIRE(r.certified());
    CHECK(count_curves(r, partition::CurveKind::restricted) > 0);
    const exchange::Distortion d = exchange::summarize(app::face_stretches(r.parameterization));
    REQUIRE(d.anisotropy_max);
    CHECK(*d.anisotropy_max < 1e3);
}

namespace {

// A corpus mesh run on §2's D of `faces` faces with the default map, then with the paper's. D is
// given, so the default map is the one on that D (no other domain is tried: CLI-RUN-9).
std::pair<pipeline::RunResult, pipeline::RunResult> default_and_paper(const char* name, std::size_t faces) {
    const TriMesh T = test::load_mesh(test::cgal_mesh(name));
    pipeline::RunOptions options;
    options.domain = domain::decimate(T, {.target_faces = faces});
    pipeline::RunResult moved = pipeline::run(T, options);
    options.domain = domain::decimate(T, {.target_faces = faces});
    options.method.relax = false;
    return {std::move(moved), pipeline::run(T, options)};
}

// p's D is T decimated under `rule` (graded), and its map meets all three goals where the map on
// §2's D misses, with an L2 stretch never above the paper map's on §2's D and T′ at most a quarter
// larger.
void kept_graded_domain(const TriMesh& T, const pipeline::Parameterization& p, const char* name,
                        const domain::DecimateOptions& rule) {
    const domain::Domain graded = domain::decimate(T, rule);
    CHECK(p.partition.domain.t_vertex == graded.t_vertex);
    CHECK(p.partition.domain.mesh.triangles() == graded.mesh.triangles());
    const exchange::Distortion a = exchange::summarize(app::face_stretches(p));
    REQUIRE((a.anisotropy_p99 && a.anisotropy_p999 && a.anisotropy_max && a.l2_stretch));
    CHECK(*a.anisotropy_p99 <= 3);
    CHECK(*a.anisotropy_p999 <= 10);
    CHECK(*a.anisotropy_max <= 1e3);
    const auto [on_d, paper] = default_and_paper(name, rule.target_faces);
    const exchange::Distortion b = exchange::summarize(app::face_stretches(paper.parameterization));
    const exchange::Distortion c = exchange::summarize(app::face_stretches(on_d.parameterization));
    REQUIRE((b.l2_stretch && c.anisotropy_p99));
    CHECK(*c.anisotropy_p99 > 3);  // the map on §2's D misses
    CHECK(*a.l2_stretch <= *b.l2_stretch);
    CHECK(p.refined_faces.size() <= 1.25 * paper.parameterization.refined_faces.size());
}

}  // namespace

TEST_CASE(
    "CLI-RUN-9, DOM-24, DIST-7: where the map on §2's D misses a goal, a D decimated under the graded normal rule "
    "is tried, and kept when its map meets the goals",
    "[pipeline][distortion]") {
    // The handle at the corpus's 24 faces: its map on §2's D misses (99th percentile 4.37), the one
    // on the D of the rule graded from 45° meets all three goals (paper_notes/distortion_causes.md).
    const TriMesh T = test::load_mesh(test::cgal_mesh("handle.off"));
    pipeline::RunOptions options;
    options.faces = 24;
    Recorder stages;
    options.method.observer = &stages;
    const pipeline::RunResult r = pipeline::run(T, options);
    REQUIRE(r.certified());
    CHECK(stages.in_total == std::vector<std::string>{"mesh_reduction", "geodesic_paths", "parameterization",
                                                      "other_domains", "verification"});
    const pipeline::Parameterization& p = r.parameterization;
    CHECK(p.domains_tried == 2);
    CHECK(p.graded_normal_rule == 45);
    CHECK(p.graded_min_angle == 0);
    CHECK(domain::decimate(T, {.target_faces = 24}).t_vertex !=
          domain::decimate(T, {.target_faces = 24, .first_normal_deviation_deg = 45}).t_vertex);
    kept_graded_domain(T, p, "handle.off", {.target_faces = 24, .first_normal_deviation_deg = 45});
}

TEST_CASE(
    "CLI-RUN-9, DOM-25, DIST-7: where no graded normal rule's D meets the goals, the D's of the other rules are "
    "screened by their first maps and the best mapped",
    "[pipeline][distortion]") {
    // The rotor at the corpus's 28 faces: its maps on §2's D and on the four graded normal rules'
    // D's miss (99th percentile 3.96 at best); the D of the normal rule from 20° with the angle rule
    // from 10° meets all three goals (paper_notes/distortion_causes.md).
    const TriMesh T = test::load_mesh(test::cgal_mesh("rotor.off"));
    pipeline::RunOptions options;
    options.faces = 28;
    const pipeline::RunResult r = pipeline::run(T, options);
    REQUIRE(r.certified());
    const pipeline::Parameterization& p = r.parameterization;
    CHECK(p.domains_tried > 1 + pipeline::mapped_rules);  // the first rules' D's, then screened ones
    CHECK(p.graded_normal_rule == 20);
    CHECK(p.graded_min_angle == 10);
    kept_graded_domain(T, p, "rotor.off",
                       {.target_faces = 28, .first_normal_deviation_deg = 20, .first_min_angle_deg = 10});
}

TEST_CASE(
    "CLI-RUN-9, DIST-4, DIST-7: moving the curves of poor patches and sliding their vertices lowers the worst "
    "face, the 99th percentile and the L2 stretch, certified and continuous",
    "[pipeline][distortion]") {
    // The bull, a cow and a genus-2 femur at the corpus's sizes: restricted curves squeezed beside
    // others bound patches far from their triangles' shapes (paper_notes/distortion_causes.md).
    // The slid vertices give up chord length (PARAM-10, reported as info), not continuity (PARAM-7).
    for (const auto& [name, faces] :
         {std::pair<const char*, std::size_t>{"bull.off", 122}, {"cow.off", 58}, {"femur.off", 76}}) {
        CAPTURE(name);
        const auto [moved, paper] = default_and_paper(name, faces);
        REQUIRE(moved.certified());
        REQUIRE(moved.oracle.valid());
        CHECK(count_curves(moved, partition::CurveKind::straightened) > 0);
        CHECK(count_curves(paper, partition::CurveKind::straightened) == 0);
        const exchange::Distortion a = exchange::summarize(app::face_stretches(moved.parameterization));
        const exchange::Distortion b = exchange::summarize(app::face_stretches(paper.parameterization));
        REQUIRE((a.anisotropy_max && b.anisotropy_max && a.l2_stretch && b.l2_stretch));
        CHECK(*a.anisotropy_max < *b.anisotropy_max);
        CHECK(*a.l2_stretch < *b.l2_stretch);
        CHECK(*a.anisotropy_p99 < *b.anisotropy_p99);
        CHECK(moved.parameterization.slid_patches > 0);
        CHECK(paper.parameterization.slid_patches == 0);
        auto status = [](const pipeline::RunResult& r, const std::string& id) {
            for (const exchange::CheckResult& c : r.oracle.checks)
                if (c.id == id) return c.status;
            FAIL("no check " << id);
            return exchange::CheckStatus::skipped;
        };
        CHECK(status(moved, "PARAM-7") == exchange::CheckStatus::pass);
        CHECK(status(moved, "PARAM-10") == exchange::CheckStatus::info);
        CHECK(status(paper, "PARAM-10") == exchange::CheckStatus::pass);
        // T′ grows by at most a quarter.
        CHECK(moved.parameterization.refined_faces.size() <= 1.25 * paper.parameterization.refined_faces.size());
    }
}

TEST_CASE("CLI-RUN-9, DIST-7: where the map misses a percentile goal, the thorough path's tries meet all three goals",
          "[pipeline][distortion]") {
    // Corpus meshes at its sizes whose maps missed the 99th-percentile goal before the thorough
    // sweeps (poly2x²: 3.12, cross: 11.1), and two that missed it with the squared MIPS energy alone
    // and meet it with the 4th and 8th powers' tries (tripod: 3.04, whose first map met the goals
    // and the sweeps after it did not; spool: 3.52) (paper_notes/distortion_causes.md): certified,
    // continuous, the L2 stretch below the paper map's and T′ at most a quarter larger.
    for (const char* name : {"poly2x^2+y^2-0.062500.off", "cross.off", "tripod.off", "spool.off"}) {
        CAPTURE(name);
        const auto [moved, paper] = default_and_paper(name, 24);
        REQUIRE(moved.certified());
        REQUIRE(moved.oracle.valid());
        const exchange::Distortion a = exchange::summarize(app::face_stretches(moved.parameterization));
        const exchange::Distortion b = exchange::summarize(app::face_stretches(paper.parameterization));
        REQUIRE((a.anisotropy_p99 && a.anisotropy_p999 && a.anisotropy_max && a.l2_stretch && b.l2_stretch));
        CHECK(*a.anisotropy_p99 <= 3);
        CHECK(*a.anisotropy_p999 <= 10);
        CHECK(*a.anisotropy_max <= 1e3);
        CHECK(*a.l2_stretch <= *b.l2_stretch);
        CHECK(moved.parameterization.refined_faces.size() <= 1.25 * paper.parameterization.refined_faces.size());
    }
}

TEST_CASE("CLI-RUN-9, DIST-7: where the thorough sweeps still miss, moving whole stars first brings the tail down",
          "[pipeline][distortion]") {
    // Two corpus meshes at its sizes whose thorough sweeps alone left the 99th percentile far above
    // 3 (pinion: 255, mpi_triang: 24.9; paper_notes/distortion_causes.md, "Stars"): with the stars
    // of the corners whose angles are split far from D's proportions moved first, below `bound`;
    // certified, continuous, the L2 stretch below the paper map's, T′ at most a quarter larger.
    for (const auto& [name, bound] : {std::pair<const char*, double>{"pinion.off", 6}, {"mpi_triang.off", 16}}) {
        CAPTURE(name);
        const auto [moved, paper] = default_and_paper(name, 28);
        REQUIRE(moved.certified());
        REQUIRE(moved.oracle.valid());
        const exchange::Distortion a = exchange::summarize(app::face_stretches(moved.parameterization));
        const exchange::Distortion b = exchange::summarize(app::face_stretches(paper.parameterization));
        REQUIRE((a.anisotropy_p99 && a.anisotropy_max && a.l2_stretch && b.l2_stretch));
        CHECK(*a.anisotropy_p99 < bound);
        CHECK(*a.anisotropy_max <= 1e3);
        CHECK(*a.l2_stretch <= *b.l2_stretch);
        CHECK(moved.parameterization.refined_faces.size() <= 1.25 * paper.parameterization.refined_faces.size());
    }
}

namespace {

// A pillow: the unit square [0, 1]² as a flat lattice of n × n squares on top (z = 0) and a bulging
// one below, glued along the square's sides (closed, genus 0). Top vertex (i, j) is i·(n + 1) + j.
TriMesh pillow(int n, const std::function<Vec3(int, int)>& top) {
    std::vector<Vec3> positions;
    std::vector<Triangle> faces;
    auto top_id = [&](int i, int j) { return static_cast<std::uint32_t>(i * (n + 1) + j); };
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) positions.push_back(top(i, j));
    std::vector<std::uint32_t> bottom((n + 1) * (n + 1));
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) {
            const bool side = i == 0 || j == 0 || i == n || j == n;
            if (side) {
                bottom[i * (n + 1) + j] = top_id(i, j);
                continue;
            }
            const double x = double(i) / n, y = double(j) / n;
            bottom[i * (n + 1) + j] = static_cast<std::uint32_t>(positions.size());
            positions.push_back({x, y, -0.5 * std::sin(M_PI * x) * std::sin(M_PI * y)});
        }
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const std::uint32_t a = top_id(i, j), b = top_id(i + 1, j), c = top_id(i + 1, j + 1), d = top_id(i, j + 1);
            faces.push_back({a, b, c});  // counter-clockwise seen from above: outward on top
            faces.push_back({a, c, d});
            const auto at = [&](int u, int v) { return bottom[u * (n + 1) + v]; };
            // Reversed below, across the other diagonal (the top's may join two vertices of the sides).
            faces.push_back({at(i + 1, j), at(i, j), at(i, j + 1)});
            faces.push_back({at(i + 1, j), at(i, j + 1), at(i + 1, j + 1)});
        }
    return TriMesh::from_triangles(std::move(positions), faces);
}

}  // namespace

TEST_CASE("PART-3 snapping, DIST-1: a curve passing 1e-14 or 1e-8 from a vertex of T leaves no sliver in the map",
          "[pipeline][distortion]") {
    // D: the square's corners, the top's centre and the bottom's; the curve from the top's centre to
    // the corner (0, 0) is the diagonal y = x, and the lattice vertex (n/4, n/4) is moved `off` away
    // from it. Left as it is, the curve would cross that vertex's edges `off` from it and cut faces
    // that thin out of T′. At 1e-14 the exact geodesic goes through the vertex (shorter by 1e-28
    // the other way: below rounding); at 1e-8 (1.1e-7 of the edges there) it passes the vertex and
    // is snapped onto it (PART-3: within snap_fraction = 1e-6 of an edge; at 1e-7, 1.1e-6 of an
    // edge, it is not). Either way the vertex is on the curve and no face of the map is a sliver.
    const int n = 16;
    for (const double off : {1e-14, 1e-8}) {
        CAPTURE(off);
        const TriMesh T = pillow(n, [&](int i, int j) {
            const Vec3 p(double(i) / n, double(j) / n, 0);
            return i == n / 4 && j == n / 4 ? Vec3(p.x() + off / std::sqrt(2.0), p.y() - off / std::sqrt(2.0), 0) : p;
        });
        const auto top = [&](int i, int j) { return VertexId(static_cast<VertexId::Index>(i * (n + 1) + j)); };
        VertexId below;  // the bottom's centre
        for (VertexId v : T.vertices())
            if (T.position(v).x() == 0.5 && T.position(v).y() == 0.5 && T.position(v).z() < 0) below = v;
        REQUIRE(below.valid());
        const std::array<VertexId, 6> x{top(0, 0), top(n, 0), top(n, n), top(0, n), top(n / 2, n / 2), below};
        domain::Domain D;
        std::vector<Vec3> corners;
        for (VertexId v : x) corners.push_back(T.position(v));
        D.mesh = TriMesh::from_triangles(
            corners, std::vector<Triangle>{
                         {4, 0, 1}, {4, 1, 2}, {4, 2, 3}, {4, 3, 0}, {5, 1, 0}, {5, 2, 1}, {5, 3, 2}, {5, 0, 3}});
        for (VertexId v : x) D.t_vertex.push_back(v);
        const pipeline::Parameterization p = pipeline::parameterize(T, D, {});
        REQUIRE(p.certified());
        REQUIRE(p.partition.domain.mesh.n_faces() == 8);  // D kept
        const HalfedgeId diagonal = p.partition.domain.mesh.find_halfedge(VertexId(4), VertexId(0));
        REQUIRE(diagonal.valid());
        const auto& curve = p.partition.network.path[DEdgeId(TriMesh::edge(diagonal))];
        CHECK(std::find(curve.begin(), curve.end(), top(n / 4, n / 4)) != curve.end());
        if (off > 1e-10) CHECK(p.partition.network.max_snap_distance > 0);
        const exchange::Distortion d = exchange::summarize(app::face_stretches(p));
        REQUIRE(d.anisotropy_max);
        CHECK(*d.anisotropy_max <= 1e3);
    }
}
