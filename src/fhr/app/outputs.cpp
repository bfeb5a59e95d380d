// FHR §6 — the files of `fhr run` (see outputs.hpp).
#include <fhr/app/outputs.hpp>

#include <fhr/app/atlas.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <numeric>
#include <optional>

#include <fhr/core/detail/stopwatch.hpp>
#include <fhr/core/errors.hpp>
#include <fhr/exchange/distortion.hpp>
#include <fhr/exchange/verdict.hpp>
#include <fhr/io/detail/atomic_file.hpp>
#include <fhr/io/detail/json.hpp>
#include <fhr/io/detail/number_text.hpp>
#include <fhr/io/write.hpp>
#include <fhr/pipeline/run.hpp>
#include <fhr/render/figures.hpp>
#include <fhr/render/svg.hpp>
#include <fhr/wavelet/detail/compress.hpp>
#include <fhr/wavelet/detail/filter_bank.hpp>

namespace fhr::app {

using pipeline::Options;
using pipeline::Parameterization;

namespace {

// The percentage as a file-name part: 5 -> "5", 2.5 -> "2.5".
std::string percent_name(double p) {
    std::string s;
    io::append_number(s, p);
    return s;
}

void write_wavelet_report(io::JsonWriter& j, const wavelet::WaveletResult& w) {
    j.key("remesh").begin_object();
    j.key("level")
        .value(w.levels)
        .key("vertices")
        .value(w.remesh_positions.size())
        .key("faces")
        .value(w.remesh_faces.size());
    j.key("hausdorff").value(w.remesh_hausdorff.lower()).key("hausdorff_upper_bound").value(w.remesh_hausdorff.upper());
    j.key("hausdorff_relative_to_bbox_diagonal").value(w.hausdorff_relative).end_object();
    j.key("wavelet").begin_object();
    j.key("coefficients").value(w.coefficients).key("reconstruction_max_error").value(w.reconstruction_max_error);
    j.key("reconstruction_max_error_relative")
        .value(w.max_abs_coordinate > 0 ? w.reconstruction_max_error / w.max_abs_coordinate : 0.0);
    j.key("kept").begin_array();
    for (const auto& k : w.kept) {
        j.begin_object().key("percent").value(k.percent).key("count").value(k.count).key("l2_error").value(k.l2_error);
        j.key("hausdorff")
            .value(k.hausdorff.lower())
            .key("hausdorff_upper_bound")
            .value(k.hausdorff.upper())
            .end_object();
    }
    j.end_array().end_object();
}

}  // namespace

std::vector<exchange::FaceStretch> face_stretches(const Parameterization& p) {
    const TriMesh& D = p.partition.domain.mesh;
    const std::vector<Triangle> domain_faces = D.triangles();  // the corner order of the β (param.fhrp)
    std::vector<exchange::FaceStretch> stretches(p.refined_faces.size());
    for (RefinedFaceId f : p.face_patch.ids()) {
        const Triangle& d = domain_faces[p.face_patch[f].idx()];
        std::array<Vec3, 3> q;
        for (int c = 0; c < 3; ++c)
            q[c] = p.face_beta[f][c][0] * D.position(VertexId(d[0])) +
                   p.face_beta[f][c][1] * D.position(VertexId(d[1])) +
                   p.face_beta[f][c][2] * D.position(VertexId(d[2]));
        const Triangle& t = p.refined_faces[f.idx()];
        stretches[f.idx()] = exchange::face_stretch(q[0], q[1], q[2], p.refined_positions[t[0]],
                                                    p.refined_positions[t[1]], p.refined_positions[t[2]]);
    }
    return stretches;
}

namespace {

/// A patch and its faces' anisotropy σ₁/σ₂ (DIST-1, UV in its domain triangle onto T′).
struct PatchAnisotropy {
    std::uint32_t patch;
    double max;
    std::uint64_t above_10;
};

/// σ₁/σ₂ of every face of the final T′ (DIST-1), 0 for a degenerate face.
std::vector<double> face_anisotropy(const Parameterization& p) {
    const std::vector<exchange::FaceStretch> stretches = face_stretches(p);
    std::vector<double> ratio(stretches.size(), 0);
    for (std::size_t f = 0; f < stretches.size(); ++f)
        if (!stretches[f].degenerate) ratio[f] = stretches[f].sigma1 / stretches[f].sigma2;
    return ratio;
}

/// The `count` patches whose worst face is the most anisotropic, worst first (ties: lower patch).
std::vector<PatchAnisotropy> worst_patches(const Parameterization& p, std::size_t count) {
    std::vector<PatchAnisotropy> patches(p.partition.domain.mesh.n_faces());
    for (std::uint32_t d = 0; d < patches.size(); ++d) patches[d] = {d, 0, 0};
    const std::vector<double> ratio = face_anisotropy(p);
    for (std::size_t f = 0; f < ratio.size(); ++f) {
        PatchAnisotropy& a = patches[p.face_patch[RefinedFaceId(static_cast<RefinedFaceId::Index>(f))].idx()];
        a.max = std::max(a.max, ratio[f]);
        a.above_10 += ratio[f] > 10;
    }
    const std::size_t kept = std::min(count, patches.size());
    std::partial_sort(patches.begin(), patches.begin() + static_cast<std::ptrdiff_t>(kept), patches.end(),
                      [](const PatchAnisotropy& a, const PatchAnisotropy& b) {
                          return a.max != b.max ? a.max > b.max : a.patch < b.patch;
                      });
    patches.resize(kept);
    return patches;
}

// report.json's `input` and `domain` sections.
void write_input_and_domain(io::JsonWriter& j, const InputInfo& input, const Parameterization& p) {
    const partition::Partition& P = p.partition;
    const TriMesh& D = P.domain.mesh;
    j.key("input").begin_object();
    j.key("path").value(input.path).key("vertices").value(input.vertices).key("faces").value(input.faces);
    j.key("genus")
        .value(input.genus)
        .key("boundary_loops")
        .value(input.boundary_loops)
        .key("components")
        .value(input.components)
        .end_object();

    j.key("domain").begin_object();
    j.key("vertices").value(D.n_vertices()).key("edges").value(D.n_edges()).key("faces").value(D.n_faces());
    j.key("faces_asked").value(input.domain_faces_asked).key("faces_requested").value(input.domain_faces_requested);
    j.key("retries")
        .value(P.retries)
        .key("vertices_added")
        .value(P.vertices_added)
        .key("kept_vertices")
        .value(P.kept.size());
    j.key("conflicts_resolved").value(P.resolved.size());
    j.key("graded_normal_rule").value(p.graded_normal_rule).key("graded_min_angle").value(p.graded_min_angle);
    j.key("domains_tried").value(p.domains_tried).end_object();
}

// report.json's `partition` section.
void write_partition(io::JsonWriter& j, const Parameterization& p) {
    const partition::Partition& P = p.partition;
    std::size_t windows = 0, max_attempts = 0;
    double max_K = 0, total_length = 0;
    for (const auto& path : P.paths) {
        windows += path.windows_created;
        max_attempts = std::max(max_attempts, path.attempts);
        max_K = std::max(max_K, path.K);
        total_length += path.path.length;
    }
    j.key("partition").begin_object();
    j.key("paths").value(P.paths.size()).key("total_length").value(total_length);
    j.key("max_K").value(max_K).key("max_attempts").value(max_attempts).key("windows_created").value(windows);
    j.key("max_snap_distance").value(P.network.max_snap_distance);
    std::size_t restricted = 0, boundary_curves = 0, straightened = 0;
    double restricted_length = 0, excess = 0, separation = 0;
    for (EdgeId e : P.curves.ids()) {
        boundary_curves += P.curves[e].kind == partition::CurveKind::boundary;
        straightened += P.curves[e].kind == partition::CurveKind::straightened;
        if (P.curves[e].kind != partition::CurveKind::restricted) continue;
        ++restricted;
        restricted_length += P.paths[e].path.length;
        excess += P.paths[e].path.length - P.curves[e].geodesic_length;
        separation = std::max(separation, P.curves[e].separation_bound);
    }
    j.key("geodesic_edges")
        .value(P.curves.size() - restricted - boundary_curves - straightened)
        .key("restricted_edges")
        .value(restricted);
    j.key("boundary_edges").value(boundary_curves).key("straightened_edges").value(straightened);
    j.key("restricted_length").value(restricted_length).key("restricted_excess").value(excess);
    j.key("max_separation_bound").value(separation).key("keep_start_faces").value(P.keep_start_faces);
    j.key("restricted").begin_array();
    for (EdgeId e : P.curves.ids()) {
        const partition::CurveInfo& c = P.curves[e];
        if (c.kind != partition::CurveKind::restricted) continue;
        j.begin_object().key("domain_edge").value(e.idx()).key("length").value(P.paths[e].path.length);
        j.key("geodesic_length").value(c.geodesic_length).key("shortest_restricted").value(c.shortest);
        j.key("separation_bound").value(c.separation_bound).key("reason").value(c.reason).end_object();
    }
    j.end_array();
    j.key("refined_vertices").value(p.refined_positions.size()).key("refined_faces").value(p.refined_faces.size());
    j.key("corner_vertices").value(p.corner_vertices);
    j.key("dividing_edges_split").value(p.dividing_edges_split).end_object();
}

// report.json's `parameterization` section: the certificates, the oracle's verdict, the distortion.
void write_parameterization(io::JsonWriter& j, const Parameterization& p, const exchange::VerifyReport& oracle,
                            const Options& options) {
    std::size_t flipped = 0, boundary = 0;
    double min_angle = std::numeric_limits<double>::infinity();
    for (const auto& c : p.certificates) {
        flipped += c.flipped_triangles;
        boundary += c.boundary_violations;
        min_angle = std::min(min_angle, c.min_image_angle_degrees);
    }
    j.key("parameterization").begin_object();
    j.key("patches").value(p.disks.size());
    j.key("weights").value(param::name(options.map.weights)).key("solver").value(param::name(options.map.solver));
    j.key("map").value(options.relax ? "relaxed" : "paper").key("relaxed_patches").value(p.relaxed_patches);
    j.key("slid_patches").value(p.slid_patches).key("image_weighted_sliding").value(p.image_weighted_sliding);
    j.key("certified").value(p.certified() && oracle.valid());
    j.key("flipped_triangles").value(flipped).key("boundary_violations").value(boundary);
    j.key("min_image_angle_degrees").value(min_angle);
    const auto first =
        std::find_if(p.certificates.begin(), p.certificates.end(), [](const auto& c) { return !c.passed; });
    if (first != p.certificates.end())
        j.key("first_failure")
            .value("patch " + std::to_string(std::distance(p.certificates.begin(), first)) + ": " +
                   first->first_failure->describe());
    j.key("oracle").begin_object();
    j.key("valid").value(oracle.valid()).key("checks").begin_array();
    for (const auto& c : oracle.checks) {
        j.begin_object().key("id").value(c.id).key("status").value(exchange::to_string(c.status));
        j.key("checked").value(c.checked).key("failures").value(c.failures);
        if (!c.first_failure.empty()) j.key("first_failure").value(c.first_failure);
        j.end_object();
    }
    j.end_array().end_object();
    // DIST-* of the map (spec/distortion.md), as `fhr verify` measures it, and the patches with the
    // most anisotropic faces.
    j.key("distortion").begin_object();
    exchange::write_distortion_fields(j, oracle.distortion);
    j.key("worst_patches").begin_array();
    for (const auto& w : worst_patches(p, 5))
        j.begin_object()
            .key("patch")
            .value(w.patch)
            .key("max_anisotropy")
            .value(w.max)
            .key("faces_above_10")
            .value(w.above_10)
            .end_object();
    j.end_array().end_object();
    j.end_object();
}

}  // namespace

std::string report_json(const InputInfo& input, const Parameterization& p, const exchange::VerifyReport& oracle,
                        const Options& options, const wavelet::WaveletResult* wavelets) {
    io::JsonWriter j;
    j.begin_object();
    write_input_and_domain(j, input, p);
    write_partition(j, p);
    write_parameterization(j, p, oracle, options);
    if (wavelets) write_wavelet_report(j, *wavelets);
    j.end_object();
    return j.str();
}

std::string timings_json(const Timings& timings) {
    io::JsonWriter j;
    j.begin_object();
    double total = 0;
    for (const auto& [stage, seconds] : timings.stages) {
        j.key(stage).value(seconds);
        total += seconds;
    }
    j.key("total").value(total);
    for (const auto& [measure, seconds] : timings.after_total) j.key(measure).value(seconds);
    j.end_object();
    return j.str();
}

std::vector<RateStep> rate_steps(const TriMesh& T, const TriMesh& D, const wavelet::WaveletResult& w) {
    std::vector<RateStep> steps;
    const auto has = [&](double p) {
        return std::any_of(steps.begin(), steps.end(), [&](const auto& q) { return q.percent == p; });
    };
    for (const auto& k : w.kept)
        if (!has(k.percent)) steps.push_back({k.percent, k.count, k.l2_error, k.hausdorff.lower(), k.positions});
    const wavelet::FilterBank bank(wavelet::refine(D, w.levels));
    const wavelet::Decomposition d = bank.decompose(w.remesh_positions);
    const std::vector<Triangle> t_faces = T.triangles();
    wavelet::HausdorffOptions ho;
    ho.resolution = 1e-4 * w.bbox_diagonal;
    for (const double p : {1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0}) {
        if (has(p)) continue;
        const std::size_t count = wavelet::kept_count(w.coefficients, p);
        std::vector<Vec3> f = bank.reconstruct(wavelet::keep_largest(bank, d, count));
        const double l2 = wavelet::rms_distance(w.remesh_positions, f);
        const double h = wavelet::hausdorff(T.positions(), t_faces, f, w.remesh_faces, ho).lower();
        steps.push_back({p, count, l2, h, std::move(f)});
    }
    std::stable_sort(steps.begin(), steps.end(),
                     [](const RateStep& x, const RateStep& y) { return x.percent < y.percent; });
    return steps;
}

namespace {

// The files of write_parameterization, each written in parts on the executor's threads
// (io::FileParts). `file` must outlive the writers.
std::vector<std::function<void()>> parameterization_files(const std::string& base, const Parameterization& p,
                                                          const exchange::ParamFile& file, Executor* executor) {
    std::vector<std::function<void()>> files;
    files.emplace_back([&, base, executor] {
        io::write_obj(base + "textured.obj", file.surface_vertices, p.refined_faces, ChartAtlas(file), executor);
    });
    files.emplace_back([&, base, executor] { exchange::write_param(base + "param.fhrp", file, executor); });
    files.emplace_back([&, base, executor] {
        io::write_ply(base + "refined.ply", file.surface_vertices, p.refined_faces, p.face_patch.values(), executor);
    });
    files.emplace_back([&, base, executor] {
        const partition::Partition& P = p.partition;
        std::vector<std::vector<std::uint32_t>> lines;
        for (const auto& path : P.network.path) {
            auto& line = lines.emplace_back();
            for (VertexId v : path) line.push_back(v.idx());
        }
        std::vector<std::string> kinds;  // each curve's kind (report.json's partition.restricted lists why)
        for (const partition::CurveInfo& c : P.curves) kinds.push_back(partition::name(c.kind));
        io::write_obj_polylines(base + "geodesics.obj", P.network.mesh.positions(), lines, kinds, executor);
    });
    files.emplace_back([&, base, executor] {
        io::write_off(base + "domain.off", p.partition.domain.mesh.positions(), p.partition.domain.mesh.triangles(),
                      executor);
    });
    return files;
}

// §5's meshes: D^J through φ and each kept percentage's reconstruction. `wavelets` must outlive
// the writers.
std::vector<std::function<void()>> wavelet_files(const std::string& base, const wavelet::WaveletResult& wavelets,
                                                 Executor* executor) {
    std::vector<std::function<void()>> files;
    files.emplace_back([&wavelets, base, executor] {
        io::write_off(base + "remesh_L" + std::to_string(wavelets.levels) + ".off", wavelets.remesh_positions,
                      wavelets.remesh_faces, executor);
    });
    for (const auto& k : wavelets.kept)
        files.emplace_back([&wavelets, &k, base, executor] {
            io::write_off(base + "wavelet_keep" + percent_name(k.percent) + ".off", k.positions, wavelets.remesh_faces,
                          executor);
        });
    return files;
}

std::string folder(const std::string& dir) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throw InvalidInput(dir, 0, "cannot create the output folder: " + ec.message());
    return dir + "/";
}

}  // namespace

void write_parameterization(const std::string& dir, const Parameterization& p, const exchange::ParamFile& file,
                            Executor* executor) {
    for (const auto& write : parameterization_files(folder(dir), p, file, executor)) write();
}

void write_wavelets(const std::string& dir, const wavelet::WaveletResult& wavelets, Executor* executor) {
    for (const auto& write : wavelet_files(folder(dir), wavelets, executor)) write();
}

RunTexts write_outputs(const std::string& dir, const InputInfo& input, const Parameterization& p,
                       const exchange::VerifyReport& oracle, const Timings& timings, const Options& options,
                       const wavelet::WaveletResult* wavelets, const WrittenBeside& written) {
    const auto start = detail::Clock::now();
    const std::string base = folder(dir);
    // Each file is written in parts on every thread (io::FileParts).
    std::optional<exchange::ParamFile> file;
    std::vector<std::function<void()>> files;
    if (!written.parameterization)
        files = parameterization_files(base, p, file.emplace(pipeline::to_param_file(p)), options.executor);
    if (wavelets && !written.wavelets)
        for (auto& f : wavelet_files(base, *wavelets, options.executor)) files.push_back(std::move(f));
    for (const auto& write : files) write();
    RunTexts texts;
    texts.report = report_json(input, p, oracle, options, wavelets);
    io::write_file_atomically(base + "report.json", texts.report);
    // "writing": every file above and the report, and those written beside the oracle;
    // timings.json itself is a few hundred bytes.
    const double beside = written.parameterization.value_or(0) + written.wavelets.value_or(0);
    Timings with_writing = timings;
    with_writing.stage("writing", detail::seconds_since(start) + beside, false);
    if (written.parameterization || written.wavelets) with_writing.stage("writing_beside_oracle", beside, false);
    texts.timings = timings_json(with_writing);
    io::write_file_atomically(base + "timings.json", texts.timings);
    return texts;
}

void write_figures(const std::string& dir, const TriMesh& T, const Parameterization& p, int up_axis,
                   const wavelet::WaveletResult* wavelets, const std::vector<RateStep>& rate) {
    const std::string base = dir + "/figures/";
    std::error_code ec;
    std::filesystem::create_directories(base, ec);
    if (ec) throw InvalidInput(base, 0, "cannot create the figures folder: " + ec.message());
    const partition::Partition& P = p.partition;
    const render::FigureSize size;
    render::ViewDirection view;
    view.up_axis = up_axis;
    const render::Camera camera = render::figure_camera(T.positions(), size, view);
    const std::vector<Triangle> t_faces = T.triangles(), d_faces = P.domain.mesh.triangles();
    const render::MeshData t{T.positions(), t_faces}, d{P.domain.mesh.positions(), d_faces};
    render::write_fig6(base + "fig6.png", camera, t, d, size);
    // The network by each curve's kind: geodesic, restricted, boundary (an arc of T's boundary),
    // straightened (drawn as the restricted ones: not geodesics).
    std::array<std::vector<std::vector<std::uint32_t>>, 4> lines;
    for (DEdgeId e : P.network.path.ids()) {
        auto& line = lines[static_cast<std::size_t>(P.curves[EdgeId(e)].kind)].emplace_back();
        for (VertexId v : P.network.path[e]) line.push_back(v.idx());
    }
    // The checkerboard coordinates: (β1, β2) of every corner, the same square cells in every patch.
    std::vector<Eigen::Vector2d> uv;
    uv.reserve(3 * p.refined_faces.size());
    for (const auto& face : p.face_beta)
        for (const auto& beta : face) uv.emplace_back(beta[1], beta[2]);
    const auto straightened = static_cast<std::size_t>(partition::CurveKind::straightened);
    lines[static_cast<std::size_t>(partition::CurveKind::restricted)].insert(
        lines[static_cast<std::size_t>(partition::CurveKind::restricted)].end(), lines[straightened].begin(),
        lines[straightened].end());
    lines[straightened].clear();
    const auto paths_of = [&](partition::CurveKind kind) {
        return render::PathData{P.network.mesh.positions(), lines[static_cast<std::size_t>(kind)]};
    };
    render::write_fig7(base + "fig7.png", camera, t, paths_of(partition::CurveKind::geodesic),
                       paths_of(partition::CurveKind::restricted), paths_of(partition::CurveKind::boundary),
                       {p.refined_positions, p.refined_faces}, uv, size);
    // Beyond the paper: T′ coloured by each face's anisotropy (REN-16), with its legend.
    std::vector<std::vector<std::uint32_t>> every_curve;
    for (const auto& kind : lines) every_curve.insert(every_curve.end(), kind.begin(), kind.end());
    render::write_distortion_figure(base + "distortion.png", camera, {p.refined_positions, p.refined_faces},
                                    face_anisotropy(p), {P.network.mesh.positions(), every_curve}, size);
    render::write_anisotropy_legend_svg(base + "distortion_legend.svg");
    if (wavelets) {
        // Fig. 8: D^J (the refined domain, flat) and f^J(Ω_D); Fig. 9: two compressed surfaces.
        const wavelet::Refinement r = wavelet::refine(P.domain.mesh, wavelets->levels);
        const TriMesh& dj = r.levels.back();
        const std::vector<Triangle> dj_faces = dj.triangles();
        render::write_fig8(base + "fig8.png", camera, {dj.positions(), dj_faces},
                           {wavelets->remesh_positions, wavelets->remesh_faces}, size);
        if (wavelets->kept.size() >= 2)
            render::write_fig9(base + "fig9.png", camera, {wavelets->kept[0].positions, wavelets->remesh_faces},
                               {wavelets->kept[1].positions, wavelets->remesh_faces}, size);
        render::RatePlotLabels labels;
        labels.title = "Rate–distortion: f^" + std::to_string(wavelets->levels) + " from the largest of " +
                       std::to_string(wavelets->coefficients) + " wavelet coefficients";
        labels.y = "error (L2: RMS over the vertices of D^J; Hausdorff: to T)";
        std::vector<render::RatePoint> points;
        for (const RateStep& step : rate.empty() ? rate_steps(T, P.domain.mesh, *wavelets) : rate)
            points.push_back({step.percent, step.l2, step.hausdorff});
        render::write_rate_distortion_svg(base + "rate_distortion.svg", points, labels);
    }
    // ψ_i(S_i) inside an equilateral triangle for the first patch and the one with the most faces.
    const std::array<Eigen::Vector2d, 3> corners{Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0),
                                                 Eigen::Vector2d(0.5, std::sqrt(3.0) / 2)};
    DFaceId largest(0);
    for (DFaceId d : p.disks.ids())
        if (p.disks[d].triangles.size() > p.disks[largest].triangles.size()) largest = d;
    for (DFaceId d : {DFaceId(0), largest}) {
        std::vector<render::ImageTriangle> image;
        for (RefinedFaceId f : p.face_patch.ids())
            if (p.face_patch[f] == d) image.push_back(p.face_beta[f]);
        render::write_patch_svg(base + "patch" + std::to_string(d.idx()) + ".svg", corners, image);
    }
}

}  // namespace fhr::app
