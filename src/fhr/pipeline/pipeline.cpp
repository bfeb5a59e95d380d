// FHR §2–§4 — the method end to end (see pipeline.hpp for the pseudocode).
#include <fhr/core/detail/contract.hpp>
#include <fhr/core/detail/stopwatch.hpp>
#include <fhr/core/executor.hpp>
#include <fhr/pipeline/pipeline.hpp>

#include <algorithm>
#include <array>
#include <optional>
#include <tuple>
#include <type_traits>
#include <utility>

#include <fhr/core/errors.hpp>
#include <fhr/param/detail/dividing_edges.hpp>
#include <fhr/param/relax.hpp>
#include <fhr/pipeline/detail/corners.hpp>
#include <fhr/pipeline/detail/slide.hpp>
#include <fhr/pipeline/detail/straighten.hpp>

namespace fhr::pipeline {

bool Parameterization::certified() const {
    return std::all_of(certificates.begin(), certificates.end(), [](const param::Certificate& c) { return c.passed; });
}

GlobalMap::GlobalMap(const Parameterization& p) : p_(p) {
    FHR_DCHECK(p.certified() && p.disks.fits(p.partition.domain.mesh) && p.maps.fits(p.partition.domain.mesh));
    locators_.reserve(p.disks.size());
    for (DFaceId d : p.disks.ids()) locators_.emplace_back(p.disks[d], p.maps[d]);
}

Vec3 GlobalMap::phi(DFaceId d, const std::array<double, 3>& beta) const { return locators_.at(d).phi(beta); }

std::pair<DFaceId, std::array<double, 3>> GlobalMap::psi(RefinedFaceId f, const std::array<double, 3>& w) const {
    // ψ is linear on every face of T′ (eq. 2): the weights of its corners' images.
    std::array<double, 3> beta{0, 0, 0};
    for (int k = 0; k < 3; ++k)
        for (int r = 0; r < 3; ++r) beta[r] += w[k] * p_.face_beta[f][k][r];
    return {p_.face_patch[f], beta};
}

namespace {

// §4 for one patch: its dividing edges split, ψ_i, its certificate, and (beyond the paper, when
// asked) the relaxed map in its place when that is certified too (param/relax.hpp).
struct MappedPatch {
    param::Disk disk;
    param::PatchMap map;
    param::Certificate certificate;
    std::size_t split = 0;
    std::vector<std::uint32_t> origin;  // the triangle of the disk before the splits
    std::uint8_t relaxed = 0;
};

std::array<Vec3, 3> triangle_of(const TriMesh& D, FaceId d) {
    const auto corners = D.face_vertices(d);
    return {D.position(corners[0]), D.position(corners[1]), D.position(corners[2])};
}

MappedPatch map_one(const TriMesh& D, FaceId d, param::Disk disk, const Options& options, double power = 2) {
    MappedPatch out;
    out.disk = std::move(disk);
    out.split = param::split_dividing_edges(out.disk, &out.origin);
    try {
        out.map = param::map_patch(out.disk, options.map);
    } catch (const InvalidInput& e) {  // the patch is fhr's own (§3), not the caller's input
        throw InternalError("the patch of domain face " + std::to_string(d.idx()) +
                            " that §3 made is refused by §4: " + e.problem());
    }
    out.certificate = param::certify(out.disk, out.map);
    if (!options.relax || !out.certificate.passed) return out;
    param::RelaxOptions relax_options;
    relax_options.power = power;
    std::optional<param::PatchMap> psi = param::relax(out.disk, out.map, triangle_of(D, d), relax_options);
    if (!psi) return out;
    param::Certificate certificate = param::certify(out.disk, *psi);
    if (!certificate.passed) return out;  // rounding onto the 2^-53 grid turned an image over: the paper's map stays
    out.map = std::move(*psi);
    out.certificate = std::move(certificate);
    out.relaxed = 1;
    return out;
}

// ψ carried over from `before` to `disk`, when the two are one disk up to the order of their
// vertices and triangles (the same positions, triangles and boundary loop); else nothing.
std::optional<param::PatchMap> carried_over(const param::Disk& before, const param::PatchMap& psi,
                                            const param::Disk& disk) {
    const std::size_t n = disk.positions.size();
    if (before.positions.size() != n || before.triangles.size() != disk.triangles.size() ||
        before.boundary.size() != disk.boundary.size() || before.corners != disk.corners ||
        before.midpoints != disk.midpoints)
        return std::nullopt;
    auto by_position = [](const std::vector<Vec3>& p) {
        std::vector<std::uint32_t> order(p.size());
        for (std::uint32_t k = 0; k < order.size(); ++k) order[k] = k;
        std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
            return std::tie(p[a].x(), p[a].y(), p[a].z()) < std::tie(p[b].x(), p[b].y(), p[b].z());
        });
        return order;
    };
    const std::vector<std::uint32_t> a = by_position(before.positions), b = by_position(disk.positions);
    std::vector<std::uint32_t> to_before(n);
    for (std::size_t k = 0; k < n; ++k) {
        if (before.positions[a[k]] != disk.positions[b[k]]) return std::nullopt;
        to_before[b[k]] = a[k];
    }
    for (std::size_t p = 0; p < disk.boundary.size(); ++p)
        if (to_before[disk.boundary[p]] != before.boundary[p]) return std::nullopt;
    auto from_least = [](std::array<std::uint32_t, 3> t) {  // the same triangle, its least corner first
        std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
        return t;
    };
    std::vector<std::array<std::uint32_t, 3>> x, y;
    for (const auto& t : before.triangles) x.push_back(from_least(t));
    for (const auto& t : disk.triangles) y.push_back(from_least({to_before[t[0]], to_before[t[1]], to_before[t[2]]}));
    std::sort(x.begin(), x.end());
    std::sort(y.begin(), y.end());
    if (x != y) return std::nullopt;
    param::PatchMap out;
    out.beta.resize(n);
    for (std::size_t k = 0; k < n; ++k) out.beta[k] = psi.beta[to_before[k]];
    return out;
}

// Beyond the paper: the curves beside poorly mapped patches moved (pipeline/detail/straighten.hpp),
// then §4 again for every patch whose disk changed. Most patches are their old disks up to order
// (T′ embedded again puts the pieces of a face of T cut by several curves in another order): their
// maps are carried over, unless `fresh` (every patch mapped again: a map whose curves slid cannot be
// mended patch by patch, a new chord-length side would meet its neighbour's slid one); every map
// made here with `straighten_options.power`, the MIPS energy's exponent (param/detail/mips.hpp).
// Whether the map, its moved pairs as they were scored, misses a percentile goal (goals_missed).
template <class Keep>
bool straighten_poor_patches(const TriMesh& T, Parameterization& out, const Options& options,
                             const std::vector<std::uint8_t>& relaxed, const Keep& keep, std::vector<PatchScore> scores,
                             const StraightenOptions& straighten_options, bool fresh = false) {
    const TriMesh& D = out.partition.domain.mesh;
    Executor& executor = executor_or_default(options.executor);
    const double power = straighten_options.power;
    const Evaluate evaluate = [&](FaceId d, param::Disk disk) {
        const MappedPatch m = map_one(D, d, std::move(disk), options, power);
        return m.certificate.passed ? score(m.disk, m.map, triangle_of(D, d)) : PatchScore{};
    };
    if (straighten(T, out.partition, executor, scores, evaluate, straighten_options) == 0) return goals_missed(scores);
    executor.for_each(D.n_faces(), 16, [&](std::size_t i) {
        const FaceId d(static_cast<FaceId::Index>(i));
        const DFaceId di(d);
        partition::Patch& patch = out.partition.patches.patch[d];
        const param::Disk& before = out.disks[di];
        if (fresh) return keep(i, map_one(D, d, std::move(patch.disk), options, power));
        if (before.midpoints == 0 && before.triangles == patch.disk.triangles &&
            before.boundary == patch.disk.boundary && before.positions == patch.disk.positions)
            return;  // the very same disk (and no dividing edge split): its map stands as it is
        MappedPatch m;
        m.disk = patch.disk;
        m.split = param::split_dividing_edges(m.disk, &m.origin);
        std::optional<param::PatchMap> psi = carried_over(out.disks[di], out.maps[di], m.disk);
        if (!psi) return keep(i, map_one(D, d, std::move(patch.disk), options, power));
        m.map = std::move(*psi);
        m.certificate = out.certificates[di];  // the same triangles, the same images
        m.relaxed = relaxed[i];
        keep(i, std::move(m));
    });
    return goals_missed(scores);
}

// Every patch's map scored (straighten.hpp), the uncertified ones left at their default.
std::vector<PatchScore> scores_of(const Parameterization& out, const Options& options) {
    const TriMesh& D = out.partition.domain.mesh;
    std::vector<PatchScore> scores(D.n_faces());
    executor_or_default(options.executor).for_each(D.n_faces(), 16, [&](std::size_t i) {
        const DFaceId d(static_cast<DFaceId::Index>(i));
        if (out.certificates[d].passed) scores[i] = score(out.disks[d], out.maps[d], triangle_of(D, FaceId(d)));
    });
    return scores;
}

// Σ over the patches of their part of the L2 stretch (the same normalisation for every map of T
// onto D: comparable between two).
double l2_energy(const std::vector<PatchScore>& scores) {
    double sum = 0;
    for (const PatchScore& s : scores) sum += s.l2_energy;
    return sum;
}

// The image area above σ₁/σ₂ = 10, then above 3, over all patches: what the percentile goals count
// (straighten.hpp's goals_missed), compared in that order.
std::array<double, 2> tail_areas(const std::vector<PatchScore>& scores) {
    std::array<double, 2> sum{0, 0};
    for (const PatchScore& s : scores) sum = {sum[0] + s.above_poor, sum[1] + s.above_tail};
    return sum;
}

// Beyond the paper: the curves' vertices slid along their domain edges (pipeline/detail/slide.hpp),
// longer where the map misses a percentile goal, kept when every changed patch is certified.
void slide_curves(Parameterization& out, const Options& options, bool missed, double power = 2) {
    SlideOptions slide_options;
    slide_options.missed = missed;
    slide_options.power = power;
    slide_options.image_weighted = options.image_weighted_sliding;
    std::vector<std::pair<DFaceId, param::PatchMap>> slid =
        slide(out.partition.domain.mesh, out.partition.patches, out.disks, out.maps,
              executor_or_default(options.executor), slide_options);
    std::vector<param::Certificate> certificates(slid.size());
    executor_or_default(options.executor).for_each(slid.size(), 4, [&](std::size_t i) {
        certificates[i] = param::certify(out.disks[slid[i].first], slid[i].second);
    });
    if (!std::all_of(certificates.begin(), certificates.end(), [](const param::Certificate& c) { return c.passed; }))
        return;  // MAP-8's other checks (slide() already put back what the grid turned over): as they were
    for (std::size_t i = 0; i < slid.size(); ++i) {
        out.maps[slid[i].first] = std::move(slid[i].second);
        out.certificates[slid[i].first] = std::move(certificates[i]);
    }
    out.slid_patches = slid.size();
}

// The largest σ₁/σ₂ of a map (spec/distortion.md's goal for it: 10³).
double worst_of(const std::vector<PatchScore>& scores) {
    double worst = 0;
    for (const PatchScore& s : scores) worst = std::max(worst, s.worst);
    return worst;
}

// The thorough path's tries, in order: the MIPS energy's exponent p (param/detail/mips.hpp) of every
// map it makes, whether the stars move first, and whether it starts from the best map so far (its
// curves moved again, every patch mapped afresh) instead of from the map before the path. A larger
// p weighs the most anisotropic faces more, its minimum nearer the map whose worst face is least
// (paper_notes/distortion_causes.md).
struct Try {
    double power;
    bool stars;
    bool from_best;
};
constexpr std::array<Try, 6> thorough_tries{
    {{2, false, false}, {2, true, false}, {4, false, false}, {8, false, false}, {4, false, true}, {8, false, true}}};

// Beyond the paper, where the map misses a percentile goal: for each try in turn while the best so
// far misses a goal, thorough sweeps of moved curves (straighten.hpp) from the map as it was or
// from the best so far, then the sliding. A try is a candidate only when its L2 stretch ends no
// higher than the map's before them (so never above the paper map's); it replaces the best so far
// when it has less image area above σ₁/σ₂ = 3, no more above 10, and no worse a worst face than the
// best's or 10³. `state` (the map and its per-patch bookkeeping) is left as the best try made it,
// or as it was.
template <class Keep, class State>
bool thorough_path(const TriMesh& T, Parameterization& out, const Options& options,
                   const std::vector<std::uint8_t>& relaxed, const Keep& keep, const std::vector<PatchScore>& scores,
                   State state) {
    using Copy = std::tuple<
        std::remove_reference_t<decltype(std::get<0>(state))>, std::remove_reference_t<decltype(std::get<1>(state))>,
        std::remove_reference_t<decltype(std::get<2>(state))>, std::remove_reference_t<decltype(std::get<3>(state))>>;
    constexpr double worst_goal = 1e3;
    const Copy saved = state;
    std::optional<Copy> best;
    std::vector<PatchScore> best_scores;
    StraightenOptions straighten_options;
    straighten_options.thorough = true;
    for (const PatchScore& s : scores) straighten_options.growth_from += s.faces;
    for (const Try& t : thorough_tries) {
        if (best && !goals_missed(best_scores)) break;
        if (t.from_best && !best) continue;  // the same as the try from the map before the path
        state = t.from_best ? *best : saved;
        straighten_options.stars = t.stars;
        straighten_options.power = t.power;
        const bool missed = straighten_poor_patches(T, out, options, relaxed, keep, t.from_best ? best_scores : scores,
                                                    straighten_options, t.from_best);
        slide_curves(out, options, missed, t.power);
        std::vector<PatchScore> now = scores_of(out, options);
        if (!(l2_energy(now) <= l2_energy(scores))) continue;
        if (best) {
            const std::array<double, 2> a = tail_areas(now), b = tail_areas(best_scores);
            if (!(a[1] < b[1] && a[0] <= b[0] && worst_of(now) <= std::max(worst_of(best_scores), worst_goal)))
                continue;
        }
        best = Copy(state);
        best_scores = std::move(now);
    }
    state = best ? std::move(*best) : saved;
    return best.has_value();
}

// Beyond the paper: where the map misses a percentile goal, the thorough path first; where it is
// not kept, and everywhere else, the sweeps as they are. Where those leave a map that met the goals
// missing one (the sliding lowers the L2 stretch, and may move image area above σ₁/σ₂ = 3), the
// thorough path from there.
template <class Keep, class State>
void improve(const TriMesh& T, Parameterization& out, const Options& options, const std::vector<std::uint8_t>& relaxed,
             const Keep& keep, State state) {
    std::vector<PatchScore> scores = scores_of(out, options);
    out.unmoved.l2_energy = l2_energy(scores);
    for (const PatchScore& s : scores) out.unmoved.faces += s.faces;
    const bool missed = goals_missed(scores);
    if (missed && thorough_path(T, out, options, relaxed, keep, scores, state)) return;
    slide_curves(out, options, straighten_poor_patches(T, out, options, relaxed, keep, std::move(scores), {}));
    if (missed) return;
    const std::vector<PatchScore> after = scores_of(out, options);
    if (goals_missed(after)) thorough_path(T, out, options, relaxed, keep, after, state);
}

// §3 and each patch's first map (§4, relaxed under Options::relax): what the improvement of the
// default map and the final T′ start from, with the per-patch bookkeeping both keep up to date.
struct FirstMaps {
    Parameterization out;
    std::vector<std::size_t> split;                  // per patch: its dividing edges split
    std::vector<std::vector<std::uint32_t>> origin;  // per patch: the triangle before the splits
    std::vector<std::uint8_t> relaxed;               // per patch: its map is the relaxed one
    double mapping = 0;                              // the seconds of the first maps
};

void keep_patch(FirstMaps& m, std::size_t i, MappedPatch mapped) {
    const DFaceId d(static_cast<DFaceId::Index>(i));
    m.split[i] = mapped.split;
    m.origin[i] = std::move(mapped.origin);
    m.relaxed[i] = mapped.relaxed;
    m.out.maps[d] = std::move(mapped.map);
    m.out.certificates[d] = std::move(mapped.certificate);
    m.out.disks[d] = std::move(mapped.disk);
}

FirstMaps first_maps(const TriMesh& T, domain::Domain D, const Options& options) {
    auto say = [&](const std::string& line) {
        if (options.progress) options.progress(line);
    };
    FirstMaps m;
    Parameterization& out = m.out;

    // §3: one geodesic per edge of D, T′, conditions (1) and (2), the patches.
    say("geodesic paths: " + std::to_string(D.mesh.n_edges()) + " domain edges");
    const auto paths = detail::Clock::now();
    partition::PartitionOptions po;
    po.progress = options.progress;
    po.keep_domain = options.keep_domain;
    po.executor = options.executor;
    out.partition = partition::partition(T, std::move(D), po);
    if (options.observer) options.observer->stage("geodesic_paths", detail::seconds_since(paths), true);
    const partition::Partition& P = out.partition;
    say("partition: " + std::to_string(P.network.mesh.n_faces()) + " faces in T′, " +
        std::to_string(P.patches.patch.size()) + " patches, " + std::to_string(P.retries) + " retries");

    // §4: each patch onto its triangle, certified.
    const auto mapping = detail::Clock::now();
    const std::size_t n_patches = P.patches.patch.size();
    out.disks = IdVector<DFaceId, param::Disk>(P.domain.mesh, {});
    out.maps = IdVector<DFaceId, param::PatchMap>(P.domain.mesh, {});
    out.certificates = IdVector<DFaceId, param::Certificate>(P.domain.mesh, {});
    FHR_DCHECK(out.disks.size() == n_patches);
    m.split.assign(n_patches, 0);
    m.origin.assign(n_patches, {});
    m.relaxed.assign(n_patches, 0);
    const TriMesh& Dm = P.domain.mesh;
    executor_or_default(options.executor).for_each(n_patches, 16, [&](std::size_t i) {
        const FaceId d(static_cast<FaceId::Index>(i));  // each task its own patch
        keep_patch(m, i, map_one(Dm, d, std::move(out.partition.patches.patch[d].disk), options));
    });
    m.mapping = detail::seconds_since(mapping);
    return m;
}

// The default map improved (Options::relax), then the final T′ assembled.
Parameterization completed(const TriMesh& T, FirstMaps m, const Options& options) {
    auto say = [&](const std::string& line) {
        if (options.progress) options.progress(line);
    };
    Parameterization& out = m.out;
    const partition::Partition& P = out.partition;
    const std::size_t n_patches = P.patches.patch.size();
    const auto param = detail::Clock::now();
    auto keep = [&](std::size_t i, MappedPatch mapped) { keep_patch(m, i, std::move(mapped)); };
    if (options.relax) improve(T, out, options, m.relaxed, keep, std::tie(out, m.split, m.origin, m.relaxed));
    out.image_weighted_sliding = options.relax && options.image_weighted_sliding;
    for (std::size_t s : m.split) out.dividing_edges_split += s;
    for (std::uint8_t r : m.relaxed) out.relaxed_patches += r;
    // The final T′: the vertices of T′ of §3, then each patch's dividing-edge midpoints; faces
    // patch by patch, each with the β of its corners.
    const TriMesh& M = P.network.mesh;
    out.refined_positions.assign(M.positions().begin(), M.positions().end());
    std::size_t faces = 0;  // exactly: at 10⁶ faces, growing by doubling would leave a third of face_beta unused
    for (const param::Disk& disk : out.disks) faces += disk.triangles.size();
    out.refined_faces.reserve(faces);
    out.face_patch.reserve(faces);
    out.face_beta.reserve(faces);
    out.face_t.reserve(faces);
    for (DFaceId d : out.disks.ids()) {
        const param::Disk& disk = out.disks[d];
        const partition::Patch& patch = P.patches.patch[FaceId(d)];
        std::vector<std::uint32_t> global(disk.positions.size());
        for (std::size_t v = 0; v < disk.positions.size(); ++v) {
            if (v < patch.vertices.size()) {
                global[v] = patch.vertices[v].idx();
            } else {
                global[v] = static_cast<std::uint32_t>(out.refined_positions.size());
                out.refined_positions.push_back(disk.positions[v]);
            }
        }
        for (std::size_t i = 0; i < disk.triangles.size(); ++i) {
            const auto& t = disk.triangles[i];
            out.refined_faces.push_back({global[t[0]], global[t[1]], global[t[2]]});
            out.face_patch.push_back(d);
            out.face_t.push_back(P.network.t_face[patch.faces[m.origin[d.idx()][i]]]);
            out.face_beta.push_back({out.maps[d].beta[t[0]], out.maps[d].beta[t[1]], out.maps[d].beta[t[2]]});
        }
    }
    if (options.observer) options.observer->stage("parameterization", m.mapping + detail::seconds_since(param), true);
    const std::size_t failed = static_cast<std::size_t>(std::count_if(
        out.certificates.begin(), out.certificates.end(), [](const param::Certificate& c) { return !c.passed; }));
    say("parameterization: " + std::to_string(n_patches) + " patches, " + std::to_string(out.dividing_edges_split) +
        " dividing edges split, " + (options.relax ? std::to_string(out.relaxed_patches) + " relaxed, " : "") +
        (failed ? std::to_string(failed) + " NOT certified" : std::string("all certified")));
    return std::move(out);
}

}  // namespace

Parameterization parameterize(const TriMesh& T, domain::Domain D, const Options& options) {
    return completed(T, first_maps(T, std::move(D), options), options);
}

namespace {

// What another_domain weighs of a map, from its own scores (straighten.hpp): σ₁/σ₂'s 99th and
// 99.9th percentiles weighted by image area (the rule of spec/distortion.md DIST-9), its worst
// face, its L2 energy, and whether it misses a percentile goal.
struct Tail {
    bool missed;  // a goal of spec/distortion.md: the percentiles' (goals_missed) or the worst face's
    double p99, p999, worst, l2;
};

constexpr double p999_goal = 10, worst_goal = 1e3;  // spec/distortion.md's goals

Tail tail_of(const Parameterization& p, const Options& options) {
    const TriMesh& D = p.partition.domain.mesh;
    std::vector<std::vector<std::array<double, 2>>> per_patch(D.n_faces());
    std::vector<PatchScore> scores(D.n_faces());
    executor_or_default(options.executor).for_each(D.n_faces(), 16, [&](std::size_t i) {
        const DFaceId d(static_cast<DFaceId::Index>(i));
        scores[i] = score(p.disks[d], p.maps[d], triangle_of(D, FaceId(d)), {}, &per_patch[i]);
    });
    std::vector<std::array<double, 2>> faces;
    for (const auto& f : per_patch) faces.insert(faces.end(), f.begin(), f.end());
    std::sort(faces.begin(), faces.end());
    double area = 0;
    for (const auto& f : faces) area += f[1];
    auto percentile = [&](double q) {
        double sum = 0;
        for (const auto& f : faces)
            if ((sum += f[1]) >= q * area) return f[0];
        return faces.empty() ? 0.0 : faces.back()[0];
    };
    const double worst = worst_of(scores);
    return {goals_missed(scores) || !(worst <= worst_goal), percentile(0.99), percentile(0.999), worst,
            l2_energy(scores)};
}

// The share of a map's image area above σ₁/σ₂ = 3 (what the 99th percentile's goal bounds by 1 %),
// by its patches' scores; 1 where a patch is not certified (scores_of leaves it out).
double share_above_tail(const Parameterization& p, const Options& options) {
    double above = 0, area = 0;
    for (const PatchScore& s : scores_of(p, options)) {
        if (!s.certified) return 1;
        above += s.above_tail;
        area += s.image_area;
    }
    return area > 0 ? above / area : 1;
}

// T refined at D's vertices (another_domain's last tries): the map on it, its faces named by T's.
Parameterization mapped_refined(const TriMesh& T, CornerRefinement refined, const Options& options) {
    Parameterization q = completed(refined.mesh, first_maps(refined.mesh, refined.domain, options), options);
    for (RefinedFaceId f : q.face_t.ids()) q.face_t[f] = refined.parent[q.face_t[f].idx()];
    q.corner_vertices = refined.mesh.n_vertices() - T.n_vertices();
    q.corner_refined_t = std::move(refined.mesh);
    return q;
}

// D mapped again with the sliding weighed by image area (another_domain's last tries).
Parameterization mapped_by_image(const TriMesh& T, const domain::Domain& D, Options options) {
    options.image_weighted_sliding = true;
    return completed(T, first_maps(T, D, options), options);
}

}  // namespace

Parameterization another_domain(const TriMesh& T, Parameterization p, const domain::DecimateOptions& decimated_with,
                                const Options& options) {
    if (!options.relax || p.partition.domain.mesh.n_faces() > coarse_domain_faces) return p;
    Tail best = tail_of(p, options);
    if (!best.missed) return p;
    const auto start = detail::Clock::now();
    const Parameterization::Unmoved bound = p.unmoved;
    const double most_faces = (1 + StraightenOptions{}.thorough_growth) * static_cast<double>(bound.faces);
    Options quiet = options;
    quiet.observer = nullptr;  // the stages of the first domain are the ones timed; these are `other_domains`
    quiet.progress = nullptr;  // one line per D mapped in full
    // The domains parameterized so far, by their vertices and faces: a rule that never bound gives
    // a D already tried, whose map would be the same.
    std::vector<std::pair<std::vector<VertexId>, std::vector<Triangle>>> seen{
        {{p.partition.domain.t_vertex.begin(), p.partition.domain.t_vertex.end()},
         p.partition.domain.mesh.triangles()}};
    // T decimated again under `rule`: its D, unless it has other faces or was tried already.
    auto again = [&](const DomainRule& rule) -> std::optional<domain::Domain> {
        domain::DecimateOptions graded = decimated_with;
        graded.first_normal_deviation_deg = rule.normal;
        graded.first_min_angle_deg = rule.min_angle;
        graded.best_effort = true;
        domain::Domain D = domain::decimate(T, graded);
        if (D.mesh.n_faces() != p.partition.domain.mesh.n_faces()) return std::nullopt;
        std::pair<std::vector<VertexId>, std::vector<Triangle>> key{{D.t_vertex.begin(), D.t_vertex.end()},
                                                                    D.mesh.triangles()};
        if (std::find(seen.begin(), seen.end(), key) != seen.end()) return std::nullopt;
        seen.push_back(std::move(key));
        return D;
    };
    // A map made whole, of the D of `rule`: kept when it is a candidate and better.
    auto consider = [&](Parameterization q, const DomainRule& rule) {
        const Tail tail = tail_of(q, options);
        if (!q.certified() || !(tail.l2 <= bound.l2_energy) ||
            static_cast<double>(q.refined_faces.size()) > most_faces ||
            q.partition.domain.mesh.n_faces() != p.partition.domain.mesh.n_faces())  // the domain asked for
            return;
        const bool better = !tail.missed || (tail.p99 < best.p99 && tail.p999 <= std::max(best.p999, p999_goal) &&
                                             tail.worst <= std::max(best.worst, worst_goal));
        if (!better) return;
        q.graded_normal_rule = rule.normal;
        q.graded_min_angle = rule.min_angle;
        q.unmoved = bound;
        p = std::move(q);
        best = tail;
    };
    // The map on `rule`'s D made whole and judged.
    auto judge = [&](const DomainRule& rule, FirstMaps maps) {
        if (options.progress)
            options.progress("domain again, the normal rule from " + std::to_string(static_cast<int>(rule.normal)) +
                             "°, the angle rule from " + std::to_string(static_cast<int>(rule.min_angle)) +
                             "°: the map on D misses a goal");
        consider(completed(T, std::move(maps), quiet), rule);
    };
    // The first rules' D's mapped in turn.
    for (std::size_t r = 0; r < mapped_rules && best.missed; ++r)
        if (std::optional<domain::Domain> D = again(domain_rules[r]))
            judge(domain_rules[r], first_maps(T, std::move(*D), quiet));
    // The other rules' D's screened by their first maps, the mapped_rules best (by their share of
    // image area above σ₁/σ₂ = 3; ties: the earlier rule) then mapped in turn.
    struct Screened {
        double share;
        DomainRule rule;
        FirstMaps maps;
    };
    std::vector<Screened> ranked;
    for (std::size_t r = mapped_rules; r < domain_rules.size() && best.missed; ++r) {
        std::optional<domain::Domain> D = again(domain_rules[r]);
        if (!D) continue;
        FirstMaps maps = first_maps(T, std::move(*D), quiet);
        const double share = share_above_tail(maps.out, options);
        const auto at = std::find_if(ranked.begin(), ranked.end(), [&](const Screened& c) { return share < c.share; });
        if (at - ranked.begin() < static_cast<std::ptrdiff_t>(mapped_rules))
            ranked.insert(at, Screened{share, domain_rules[r], std::move(maps)});
        if (ranked.size() > mapped_rules) ranked.pop_back();
    }
    for (Screened& c : ranked)
        if (best.missed) judge(c.rule, std::move(c.maps));
    // Last, the best D so far on T refined at its vertices, then (on T) with the sliding weighed by
    // image area.
    std::optional<CornerRefinement> refined;
    if (best.missed) refined = refine_corners(T, p.partition.domain);
    if (refined) {
        if (options.progress) options.progress("corners refined: the map on D misses a goal");
        consider(mapped_refined(T, std::move(*refined), quiet), {p.graded_normal_rule, p.graded_min_angle});
    }
    const bool weighted = best.missed && p.corner_vertices == 0;
    if (weighted) {
        if (options.progress) options.progress("sliding weighed by image area: the map on D misses a goal");
        consider(mapped_by_image(T, p.partition.domain, quiet), {p.graded_normal_rule, p.graded_min_angle});
    }
    p.domains_tried = seen.size();
    if (options.observer && (seen.size() > 1 || refined || weighted))  // another D or T was tried (CLI-RUN-3)
        options.observer->stage("other_domains", detail::seconds_since(start), true);
    return p;
}

}  // namespace fhr::pipeline
