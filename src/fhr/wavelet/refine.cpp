// FHR §5 — dyadic refinement (Fig. 5) and the samples f^J(v) = φ(v) (see refine.hpp).
#include <fhr/wavelet/refine.hpp>

#include <stdexcept>
#include <string>

#include <fhr/core/errors.hpp>

namespace fhr::wavelet {
namespace {

using Beta = std::array<double, 3>;

// The midpoint of two dyadic coordinate triples: halving a multiple of 2^−(j−1) in [0, 1] is exact.
Beta average(const Beta& a, const Beta& b) { return {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2])}; }

// One 1-to-4 split of `coarse` (paper §5, Fig. 5), carrying the corner coordinates along.
TriMesh split_once(const TriMesh& coarse, const std::vector<std::array<Beta, 3>>& coarse_beta,
                   std::vector<std::array<Beta, 3>>& fine_beta) {
    const std::uint32_t nv = static_cast<std::uint32_t>(coarse.n_vertices());
    std::vector<Vec3> positions = coarse.positions();
    positions.reserve(coarse.n_vertices() + coarse.n_edges());
    for (EdgeId e : coarse.edges()) {
        const HalfedgeId h = TriMesh::halfedge(e, 0);
        positions.push_back(0.5 * (coarse.position(coarse.from(h)) + coarse.position(coarse.to(h))));
    }
    std::vector<Triangle> triangles;
    triangles.reserve(4 * coarse.n_faces());
    fine_beta.clear();
    fine_beta.reserve(4 * coarse.n_faces());
    for (FaceId f : coarse.faces()) {
        // h0 = a→b, h1 = b→c, h2 = c→a, so face_vertices(f) = (a, b, c).
        const HalfedgeId h0 = coarse.halfedge(f), h1 = coarse.next(h0), h2 = coarse.next(h1);
        const std::uint32_t a = coarse.from(h0).idx(), b = coarse.from(h1).idx(), c = coarse.from(h2).idx();
        const std::uint32_t ab = nv + TriMesh::edge(h0).idx(), bc = nv + TriMesh::edge(h1).idx(),
                            ca = nv + TriMesh::edge(h2).idx();
        const std::array<Beta, 3>& B = coarse_beta[f.idx()];
        const Beta Bab = average(B[0], B[1]), Bbc = average(B[1], B[2]), Bca = average(B[2], B[0]);
        triangles.push_back({a, ab, ca});
        fine_beta.push_back({B[0], Bab, Bca});
        triangles.push_back({ab, b, bc});
        fine_beta.push_back({Bab, B[1], Bbc});
        triangles.push_back({ca, bc, c});
        fine_beta.push_back({Bca, Bbc, B[2]});
        triangles.push_back({ab, bc, ca});
        fine_beta.push_back({Bab, Bbc, Bca});
    }
    TriMesh fine = TriMesh::from_triangles(std::move(positions), triangles);
    // corner_beta is indexed in face_vertices order; from_triangles keeps the order it is given.
    for (FaceId g : fine.faces()) {
        const auto v = fine.face_vertices(g);
        const Triangle& t = triangles[g.idx()];
        if (v[0].idx() != t[0] || v[1].idx() != t[1] || v[2].idx() != t[2])
            throw InternalError("wavelet::refine: from_triangles changed the corner order of face " +
                                std::to_string(g.idx()));
    }
    return fine;
}

}  // namespace

Refinement refine(const TriMesh& D, int J) {
    if (J < 0) throw InvalidInput("dyadic refinement: the level J = " + std::to_string(J) + " is negative");
    if (D.has_garbage() || D.n_faces() == 0)
        throw InvalidInput("dyadic refinement: the domain D must be a triangulation with a face and without garbage");
    std::size_t faces = D.n_faces();
    for (int j = 0; j < J; ++j) {
        faces *= 4;
        if (faces > max_refined_faces)
            throw InvalidInput("dyadic refinement: D^" + std::to_string(J) + " would have more than " +
                               std::to_string(max_refined_faces) + " faces");
    }
    Refinement r;
    r.levels.reserve(static_cast<std::size_t>(J) + 1);
    r.levels.push_back(D);
    std::vector<std::array<Beta, 3>> beta(D.n_faces(), {Beta{1, 0, 0}, Beta{0, 1, 0}, Beta{0, 0, 1}});
    std::vector<std::array<Beta, 3>> next;
    for (int j = 1; j <= J; ++j) {
        r.levels.push_back(split_once(r.levels.back(), beta, next));
        beta.swap(next);
    }
    const TriMesh& fine = r.levels.back();
    const unsigned shift = 2 * static_cast<unsigned>(J);
    r.location.assign(fine.n_vertices(), DomainPoint{});
    for (FaceId g : fine.faces()) {
        const auto v = fine.face_vertices(g);
        for (int c = 0; c < 3; ++c) {
            DomainPoint& p = r.location[v[c].idx()];
            if (!p.face.valid()) p = DomainPoint{FaceId(g.idx() >> shift), beta[g.idx()][c]};
        }
    }
    r.corner_beta = std::move(beta);
    return r;
}

std::vector<Vec3> sample(const Refinement& r, const DomainMap& phi, Executor* executor) {
    // The vertices face by face of D (a counting sort): consecutive locations then fall in one
    // patch of φ, whose data stays in cache (at 10⁶ triangles, in vertex order, each
    // block of samples touched patches all over T′). Each sample is phi's either way.
    std::vector<std::uint32_t> start(r.levels.front().n_faces() + 1, 0);
    for (const DomainPoint& p : r.location) ++start[p.face.idx() + 1];
    for (std::size_t d = 1; d < start.size(); ++d) start[d] += start[d - 1];
    std::vector<std::uint32_t> order(r.location.size());
    for (std::uint32_t v = 0; v < order.size(); ++v) order[start[r.location[v].face.idx()]++] = v;
    std::vector<Vec3> f(r.location.size());
    constexpr std::size_t block = 4096;  // point locations per task
    for_each_block(executor_or_default(executor), f.size(), block, 1, [&](std::size_t first, std::size_t end) {
        for (std::size_t i = first; i < end; ++i) {
            const std::uint32_t v = order[i];
            f[v] = phi(r.location[v].face, r.location[v].beta);
        }
    });
    return f;
}

}  // namespace fhr::wavelet
