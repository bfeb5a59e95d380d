// FHR bench — the inputs of the scaling series (bench/run_bench.py --scaling): a real mesh made
// 4, 16, 64, … times finer by midpoint (1 → 4) subdivision. Each edge gets a new vertex at its
// midpoint and each triangle (a, b, c) becomes (a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca):
// the surface is exactly the same point set (every new vertex lies on an edge of T), the
// genus and every corner angle are kept, and the face count is multiplied by 4 per round, so the
// whole pipeline (§2 decimation, §3 paths, §4 parameterization, §5 wavelets) can be timed against
// the size n of T alone.
//
// Usage: subdivide MESH ROUNDS OUT.ply. MESH is read with the strict reader and builder; OUT is
// written atomically as binary PLY (exact doubles, and the quickest format to read back).
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <fhr/core/errors.hpp>
#include <fhr/io/read.hpp>
#include <fhr/io/write.hpp>

namespace {

/// One round of midpoint subdivision: vertex n_vertices + e is the midpoint of edge e.
fhr::TriMesh subdivide(const fhr::TriMesh& T) {
    const std::size_t nv = T.n_vertices();
    std::vector<fhr::Vec3> positions = T.positions();
    positions.reserve(nv + T.n_edges());
    for (const fhr::EdgeId e : T.edges()) {
        const fhr::HalfedgeId h = fhr::TriMesh::halfedge(e, 0);
        positions.push_back(0.5 * (T.position(T.from(h)) + T.position(T.to(h))));
    }
    std::vector<fhr::Triangle> triangles;
    triangles.reserve(4 * T.n_faces());
    for (const fhr::FaceId f : T.faces()) {
        // Halfedge h_k runs from corner k to corner k+1; m_k is its midpoint.
        const fhr::HalfedgeId h0 = T.halfedge(f), h1 = T.next(h0), h2 = T.next(h1);
        const std::uint32_t a = T.from(h0).idx(), b = T.from(h1).idx(), c = T.from(h2).idx();
        auto mid = [&](fhr::HalfedgeId h) { return static_cast<std::uint32_t>(nv + fhr::TriMesh::edge(h).idx()); };
        const std::uint32_t ab = mid(h0), bc = mid(h1), ca = mid(h2);
        triangles.insert(triangles.end(), {{a, ab, ca}, {ab, b, bc}, {ca, bc, c}, {ab, bc, ca}});
    }
    return fhr::TriMesh::from_triangles(std::move(positions), triangles);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: subdivide MESH ROUNDS OUT.ply\n");
        return 2;
    }
    try {
        fhr::TriMesh T = fhr::io::read_mesh(argv[1]);
        for (int round = std::atoi(argv[2]); round > 0; --round) T = subdivide(T);
        fhr::io::write_ply(argv[3], T.positions(), T.triangles());
        std::printf("%s: %zu faces\n", argv[3], T.n_faces());
        return 0;
    } catch (const fhr::Error& e) {
        std::fprintf(stderr, "fhr: error: %s\n", e.what());
        return 2;  // a bad input file or option
    }
}
