// FHR §3 — the patches S_i of T′ (see patches.hpp for the pseudocode).
#include <fhr/core/detail/contract.hpp>
#include <fhr/partition/patches.hpp>
#include <fhr/partition/detail/cut_disk.hpp>

#include <algorithm>
#include <string>

#include <fhr/core/errors.hpp>

namespace fhr::partition {
namespace {

[[noreturn]] void fail(FaceId d_face, const std::string& what) {
    throw PartitionFailure("the patch of domain face " + std::to_string(d_face.idx()) + " " + what);
}

// The regions of T′: faces joined across edges without a path; `region` per face of T′, and per
// region the face of D on the left of its curves (each region must see one).
struct Regions {
    std::vector<std::int32_t> region;
    std::vector<FaceId> region_face;
};

Regions regions(const domain::Domain& D, const Network& net) {
    const TriMesh& M = net.mesh;
    Regions out{std::vector<std::int32_t>(M.n_faces(), -1), {}};
    std::vector<FaceId> stack;
    for (FaceId f : M.faces()) {
        if (out.region[f.idx()] >= 0) continue;
        const std::int32_t r = static_cast<std::int32_t>(out.region_face.size());
        out.region_face.emplace_back();
        out.region[f.idx()] = r;
        stack.push_back(f);
        while (!stack.empty()) {
            const FaceId g = stack.back();
            stack.pop_back();
            HalfedgeId h = M.halfedge(g);
            for (int i = 0; i < 3; ++i, h = M.next(h)) {
                const DHalfedgeId dh = net.d_halfedge[h];
                if (dh.valid()) {
                    // R lies on the left of h, and D's face on the left of the D halfedge is T_i.
                    const FaceId df = D.mesh.face(HalfedgeId(dh));
                    FaceId& known = out.region_face[static_cast<std::size_t>(r)];
                    if (!known.valid())
                        known = df;
                    else if (known != df)
                        fail(df, "runs into the patch of domain face " + std::to_string(known.idx()));
                    continue;
                }
                const FaceId n = M.face(TriMesh::twin(h));
                if (out.region[n.idx()] < 0) {
                    out.region[n.idx()] = r;
                    stack.push_back(n);
                }
            }
        }
    }
    return out;
}

// Patch df's disk on its own: the curves of D's halfedges around T_i = (v_j, v_k, v_l), from x_j.
void make_disk(const domain::Domain& D, const Network& net, FaceId df, Patch& p, std::vector<std::int32_t>& local) {
    std::array<std::vector<VertexId>, 3> curves;
    HalfedgeId dh = D.mesh.halfedge(df);
    for (std::size_t c = 0; c < 3; ++c, dh = D.mesh.next(dh)) {
        curves[c] = net.path[DEdgeId(TriMesh::edge(dh))];
        if (dh.idx() & 1u) std::reverse(curves[c].begin(), curves[c].end());
    }
    Outcome<Patch> cut =
        cut_disk(net.mesh, net.d_halfedge, std::move(p.faces), {curves[0], curves[1], curves[2]}, local);
    if (!cut) fail(df, cut.why());
    p = std::move(cut.value());
}

}  // namespace

Outcome<Patch> cut_disk(const TriMesh& M, const HalfedgeData<DHalfedgeId>& labels, std::vector<FaceId> faces,
                        const std::array<std::span<const VertexId>, 3>& sides, std::vector<std::int32_t>& local) {
    Patch p;
    p.faces = std::move(faces);
    auto local_of = [&](VertexId v) {
        if (local[v.idx()] < 0) {
            local[v.idx()] = static_cast<std::int32_t>(p.vertices.size());
            p.vertices.push_back(v);
            p.disk.positions.push_back(M.position(v));
        }
        return static_cast<std::uint32_t>(local[v.idx()]);
    };
    std::size_t boundary_halfedges = 0;
    for (FaceId f : p.faces) {
        HalfedgeId h = M.halfedge(f);
        std::array<std::uint32_t, 3> tri{};
        for (int i = 0; i < 3; ++i, h = M.next(h)) {
            tri[static_cast<std::size_t>(i)] = local_of(M.from(h));
            if (labels[h].valid()) ++boundary_halfedges;
        }
        p.disk.triangles.push_back(tri);
    }
    auto why = [&](const char* what) {
        for (VertexId v : p.vertices) local[v.idx()] = -1;
        return Outcome<Patch>::failure(what);
    };
    std::vector<VertexId> loop;
    for (std::size_t c = 0; c < 3; ++c) {
        p.disk.corners[c] = loop.size();
        loop.insert(loop.end(), sides[c].begin(), sides[c].end() - 1);
    }
    for (std::size_t i = 0; i < loop.size(); ++i) {
        const HalfedgeId h = M.find_halfedge(loop[i], loop[(i + 1) % loop.size()]);
        if (!h.valid() || !std::binary_search(p.faces.begin(), p.faces.end(), M.face(h)))
            return why("is not on the left of its curves");
        if (local[loop[i].idx()] < 0) return why("has a corner or curve vertex outside it");
        p.disk.boundary.push_back(static_cast<std::uint32_t>(local[loop[i].idx()]));
    }
    // Theorem (Euler): a connected triangulated surface with one boundary loop of L edges,
    // V vertices and F faces is a disk iff V − (3F + L)/2 + F = 1.
    std::vector<std::uint32_t> sorted = p.disk.boundary;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) return why("touches itself on its boundary");
    if (boundary_halfedges != loop.size()) return why("has a second boundary loop");
    const long V = static_cast<long>(p.vertices.size()), F = static_cast<long>(p.faces.size()),
               L = static_cast<long>(loop.size());
    if (2 * V - (3 * F + L) + 2 * F != 2) return why("is not a topological disk");
    for (VertexId v : p.vertices) local[v.idx()] = -1;
    return p;
}

Patches extract_patches(const domain::Domain& D, const Network& net, Executor* executor) {
    const TriMesh& M = net.mesh;
    FHR_DCHECK(net.path.fits(D.mesh) && net.d_halfedge.fits(M));
    const Regions r = regions(D, net);
    // Each D face has exactly one region.
    std::vector<std::int32_t> region_of_d(D.mesh.n_faces(), -1);
    for (std::size_t i = 0; i < r.region_face.size(); ++i) {
        const FaceId df = r.region_face[i];
        if (!df.valid()) throw PartitionFailure("a part of the surface is bounded by no geodesic path");
        if (region_of_d[df.idx()] >= 0) fail(df, "falls apart into several pieces");
        region_of_d[df.idx()] = static_cast<std::int32_t>(i);
    }
    for (FaceId df : D.mesh.faces())
        if (region_of_d[df.idx()] < 0) fail(df, "is empty");
    Patches out;
    out.patch.resize(D.mesh.n_faces());
    out.patch_of_face.resize(M.n_faces());
    for (FaceId f : M.faces()) {
        const FaceId df = r.region_face[static_cast<std::size_t>(r.region[f.idx()])];
        out.patch_of_face[f] = df;
        out.patch[df].faces.push_back(f);
    }
    // Each patch's disk on its own (one thread's 16 ms of the horse's 1,000 patches), in a few
    // blocks of D's faces, each with its own scratch; a failure is thrown from the lowest block at
    // its first patch, as one pass in order would.
    const std::size_t n = D.mesh.n_faces(), block = std::max<std::size_t>(1, (n + 15) / 16);
    for_each_block(executor_or_default(executor), n, block, 1, [&](std::size_t first, std::size_t end) {
        std::vector<std::int32_t> local(M.n_vertices(), -1);
        for (std::size_t d = first; d < end; ++d) {
            const FaceId df(static_cast<FaceId::Index>(d));
            make_disk(D, net, df, out.patch[df], local);
        }
    });
    return out;
}

}  // namespace fhr::partition
