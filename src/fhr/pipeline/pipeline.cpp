// FHR §2–§4 — the method end to end (see pipeline.hpp for the pseudocode).
#include <fhr/core/detail/contract.hpp>
#include <fhr/core/detail/stopwatch.hpp>
#include <fhr/core/executor.hpp>
#include <fhr/pipeline/pipeline.hpp>

#include <algorithm>
#include <optional>
#include <utility>

#include <fhr/core/errors.hpp>
#include <fhr/param/detail/dividing_edges.hpp>
#include <fhr/param/relax.hpp>

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

// Beyond the paper: patch d's certified map replaced by its relaxed one when that one is certified
// too (param/relax.hpp); `relaxed` says whether it was.
void relax_patch(const TriMesh& D, FaceId d, const param::Disk& disk, Parameterization& out, std::uint8_t& relaxed) {
    const auto corners = D.face_vertices(d);
    const DFaceId i(d);
    std::optional<param::PatchMap> psi =
        param::relax(disk, out.maps[i], {D.position(corners[0]), D.position(corners[1]), D.position(corners[2])});
    if (!psi) return;
    param::Certificate certificate = param::certify(disk, *psi);
    if (!certificate.passed) return;  // rounding onto the 2^-53 grid turned an image over: the paper's map stays
    out.maps[i] = std::move(*psi);
    out.certificates[i] = std::move(certificate);
    relaxed = 1;
}

}  // namespace

Parameterization parameterize(const TriMesh& T, domain::Domain D, const Options& options) {
    auto say = [&](const std::string& line) {
        if (options.progress) options.progress(line);
    };
    Parameterization out;

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
    const auto param = detail::Clock::now();
    const std::size_t n_patches = P.patches.patch.size();
    out.disks = IdVector<DFaceId, param::Disk>(P.domain.mesh, {});
    out.maps = IdVector<DFaceId, param::PatchMap>(P.domain.mesh, {});
    out.certificates = IdVector<DFaceId, param::Certificate>(P.domain.mesh, {});
    FHR_DCHECK(out.disks.size() == n_patches);
    std::vector<std::size_t> split(n_patches, 0);
    std::vector<std::vector<std::uint32_t>> origin(n_patches);  // per patch: the triangle before the splits
    std::vector<std::uint8_t> relaxed(n_patches, 0);
    executor_or_default(options.executor).for_each(n_patches, 16, [&](std::size_t i) {
        const DFaceId d(static_cast<DFaceId::Index>(i));
        param::Disk disk = std::move(out.partition.patches.patch[FaceId(d)].disk);  // each task its own patch
        split[i] = param::split_dividing_edges(disk, &origin[i]);
        try {
            out.maps[d] = param::map_patch(disk, options.map);
        } catch (const InvalidInput& e) {  // the patch is fhr's own (§3), not the caller's input
            throw InternalError("the patch of domain face " + std::to_string(i) +
                                " that §3 made is refused by §4: " + e.problem());
        }
        out.certificates[d] = param::certify(disk, out.maps[d]);
        if (options.relax && out.certificates[d].passed) relax_patch(P.domain.mesh, FaceId(d), disk, out, relaxed[i]);
        out.disks[d] = std::move(disk);
    });
    for (std::size_t s : split) out.dividing_edges_split += s;
    for (std::uint8_t r : relaxed) out.relaxed_patches += r;
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
            out.face_t.push_back(P.network.t_face[patch.faces[origin[d.idx()][i]]]);
            out.face_beta.push_back({out.maps[d].beta[t[0]], out.maps[d].beta[t[1]], out.maps[d].beta[t[2]]});
        }
    }
    if (options.observer) options.observer->stage("parameterization", detail::seconds_since(param), true);
    const std::size_t failed = static_cast<std::size_t>(std::count_if(
        out.certificates.begin(), out.certificates.end(), [](const param::Certificate& c) { return !c.passed; }));
    say("parameterization: " + std::to_string(n_patches) + " patches, " + std::to_string(out.dividing_edges_split) +
        " dividing edges split, " + (options.relax ? std::to_string(out.relaxed_patches) + " relaxed, " : "") +
        (failed ? std::to_string(failed) + " NOT certified" : std::string("all certified")));
    return out;
}

}  // namespace fhr::pipeline
