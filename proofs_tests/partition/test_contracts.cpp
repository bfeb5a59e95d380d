// §3's contracts, tested by breaking them: what embed(), extract_patches(), the region of T′ and
// the restricted path refuse, and the message a caller gets. Each function checks its input where
// a library user can get it wrong (paths that do not run between their edge's corners, a network
// that is not the one embed() made, a point the function cannot place); the refusal must name
// the element at fault (the domain edge, face or vertex), since that is all the caller has to go on.
//
// The fixture is the tetrahedron whose faces are finely and irregularly triangulated
// (test::refined_polyhedron, 6 × 6 lattice per face) with D = its four corners: each exact
// geodesic between two corners is the tetrahedron's edge, so every path is a chain of vertices of
// T along it, and the network satisfies (1) and (2) with four patches of 36 faces each.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <fhr/core/errors.hpp>
#include <fhr/partition/detail/region.hpp>
#include <fhr/partition/detail/restricted.hpp>
#include <fhr/partition/partition.hpp>
#include "partition/partition_checks.hpp"
#include "support/analytic_meshes.hpp"

using namespace fhr;
using partition::Conflict;

namespace {

// The message of the exception of type E that f throws ("accepted" when it throws nothing; an
// exception of another type propagates and fails the test).
template <class E>
std::string refusal(const std::function<void()>& f) {
    try {
        f();
    } catch (const E& e) {
        return e.what();
    }
    return "accepted";
}

struct Fixture {
    TriMesh T;
    domain::Domain D;
    std::vector<geodesic::GeodesicPath> paths;  // Γ of each edge of D, along its halfedge (e, 0)
    partition::Network network;                 // their embedding, (1) and (2) hold
    partition::Patches patches;
};

const Fixture& tetrahedron() {
    static const Fixture f = [] {
        Fixture x;
        x.T = test::refined_polyhedron(test::tetrahedron_corners, test::tetrahedron_faces, 6, 0.2, 7);
        x.D.mesh = TriMesh::from_triangles(test::tetrahedron_corners, test::tetrahedron_faces);
        for (std::uint32_t k = 0; k < 4; ++k) x.D.t_vertex.push_back(VertexId(k));
        x.paths = test::exact_paths(x.T, x.D);
        partition::Embedding e = partition::embed(x.T, x.D, x.paths);
        if (!e.conflicts.empty())
            throw std::logic_error("the fixture's network breaks (1)/(2): " + e.conflicts.front().describe());
        x.patches = partition::extract_patches(x.D, e.network);
        x.network = std::move(e.network);
        return x;
    }();
    return f;
}

// Every path of the fixture is a chain of at least four vertices of T (its tetrahedron edge's
// lattice points): the cases below cut and splice such chains.
bool chains_of_vertices(const Fixture& f) {
    return std::all_of(f.paths.begin(), f.paths.end(), [](const geodesic::GeodesicPath& p) {
        return p.points.size() >= 4 && std::all_of(p.points.begin(), p.points.end(), [](const SurfacePoint& q) {
                   return q.kind == SurfacePoint::Kind::vertex;
               });
    });
}

// A halfedge of T out of vertex v.
HalfedgeId out_of(const TriMesh& T, VertexId v) {
    HalfedgeId out;
    T.for_each_outgoing(v, [&](HalfedgeId h) {
        if (!out.valid()) out = h;
    });
    return out;
}

// A corner of the tetrahedron (vertex 0..3 of T) other than a and b.
VertexId other_corner(VertexId a, VertexId b) {
    VertexId::Index c = 0;
    while (c == a.idx() || c == b.idx()) ++c;
    return VertexId(c);
}

}  // namespace

// ---- embed(): the paths' contract (embed.hpp: "throws std::logic_error when a path breaks its contract") ----

TEST_CASE("PART-3: embed refuses a set of paths that is not one per edge of D, or flags that are not one per path",
          "[partition][contract]") {
    const Fixture& f = tetrahedron();
    std::vector<geodesic::GeodesicPath> few(f.paths.begin(), f.paths.end() - 1), many = f.paths;
    many.push_back(f.paths.front());
    for (const auto* paths : {&few, &many})
        CHECK(refusal<std::logic_error>([&] { (void)partition::embed(f.T, f.D, *paths); }) ==
              "embed: one path per edge of D is needed");
    const std::vector<std::uint8_t> flags(f.paths.size() - 1, 0);
    CHECK(refusal<std::logic_error>([&] { (void)partition::embed(f.T, f.D, f.paths, flags); }) ==
          "embed: one unsnapped flag per path");
    CHECK(refusal<std::logic_error>([&] { (void)partition::embed_curves(f.T, f.paths, flags); }) ==
          "embed: one unsnapped flag per curve");
    // The control: the same paths with one flag each are embedded, placed as given (none is snapped here).
    const std::vector<std::uint8_t> all(f.paths.size(), 1);
    CHECK(partition::embed(f.T, f.D, f.paths, all).conflicts.empty());
}

TEST_CASE("PART-3: embed refuses a path that does not run from x_j to x_k, naming its domain edge",
          "[partition][contract]") {
    const Fixture& f = tetrahedron();
    REQUIRE(chains_of_vertices(f));
    const std::uint32_t e = 2;
    const geodesic::GeodesicPath& p = f.paths[e];
    const HalfedgeId far =
        out_of(f.T, other_corner(p.points.front().vertex, p.points.back().vertex));  // away from its ends
    auto with = [&](std::vector<SurfacePoint> points) {
        std::vector<geodesic::GeodesicPath> paths = f.paths;
        paths[e].points = std::move(points);
        return refusal<std::logic_error>([&] { (void)partition::embed(f.T, f.D, paths); });
    };
    const std::string wrong_ends = "embed: the path of D edge 2 does not run from x_j to x_k";
    std::vector<SurfacePoint> reversed = p.points;
    std::reverse(reversed.begin(), reversed.end());
    CHECK(with({p.points.front()}) == wrong_ends);                                   // one point
    CHECK(with({SurfacePoint::on_edge(far, 0.5), p.points.back()}) == wrong_ends);   // starts inside an edge
    CHECK(with(reversed) == wrong_ends);                                             // from x_k to x_j
    CHECK(with({p.points.front(), SurfacePoint::on_edge(far, 0.5)}) == wrong_ends);  // ends inside an edge
    CHECK(with(std::vector<SurfacePoint>(p.points.begin(), p.points.end() - 1)) == wrong_ends);  // stops short of x_k
    // The control: the path itself runs from x_j to x_k.
    CHECK(with(p.points) == "accepted");
}

TEST_CASE("PART-3: embed refuses a path whose consecutive nodes share no face of T, naming its domain edge",
          "[partition][contract]") {
    const Fixture& f = tetrahedron();
    REQUIRE(chains_of_vertices(f));
    const std::uint32_t e = 1;
    const std::vector<SurfacePoint>& p = f.paths[e].points;
    const VertexId xj = p.front().vertex;
    auto with = [&](std::vector<SurfacePoint> points) {
        std::vector<geodesic::GeodesicPath> paths = f.paths;
        paths[e].points = std::move(points);
        return refusal<std::logic_error>([&] { (void)partition::embed(f.T, f.D, paths); });
    };
    // A lattice point skipped: x_j and the second point after it lie two steps apart along the edge.
    std::vector<SurfacePoint> skipped = p;
    skipped.erase(skipped.begin() + 1);
    REQUIRE_FALSE(f.T.find_halfedge(xj, skipped[1].vertex).valid());
    CHECK(with(skipped) == "embed: consecutive path vertices are not adjacent (D edge 1)");
    // A jump from x_j (or from a point of an edge of its faces) to a point of an edge far away.
    const HalfedgeId far = out_of(f.T, other_corner(xj, p.back().vertex));
    const HalfedgeId opposite = f.T.next(out_of(f.T, xj));  // the side of a face at x_j opposite it
    CHECK(with({p.front(), SurfacePoint::on_edge(far, 0.5), p.back()}) ==
          "embed: consecutive path nodes share no face (D edge 1)");
    CHECK(with({p.front(), SurfacePoint::on_edge(opposite, 0.5), SurfacePoint::on_edge(far, 0.5), p.back()}) ==
          "embed: consecutive path nodes share no face (D edge 1)");
    // A node inside a face: GeodesicPath's nodes are vertices and edge points only.
    const FaceId face = f.T.face(out_of(f.T, xj));
    CHECK(with({p.front(), SurfacePoint::in_face(face, {0.2, 0.3, 0.5}), p.back()}) ==
          "embed: a path node inside a face");
}

TEST_CASE("PART-3: embed_curves refuses a curve that does not run between two vertices", "[partition][contract]") {
    const Fixture& f = tetrahedron();
    const geodesic::GeodesicPath& p = f.paths[0];
    const HalfedgeId h = out_of(f.T, p.points.front().vertex);
    auto curve = [&](std::vector<SurfacePoint> points) {
        const std::vector<geodesic::GeodesicPath> curves{f.paths[3], geodesic::GeodesicPath{std::move(points), 0}};
        return refusal<std::logic_error>([&] { (void)partition::embed_curves(f.T, curves); });
    };
    const std::string refused = "embed: a curve does not run between two vertices";
    CHECK(curve({p.points.front()}) == refused);
    CHECK(curve({SurfacePoint::on_edge(f.T.next(h), 0.5), p.points.front()}) == refused);
    CHECK(curve({p.points.front(), SurfacePoint::on_edge(f.T.next(h), 0.5)}) == refused);
    CHECK(curve(p.points) == "accepted");
}

// ---- embed(): conditions (1) and (2) reported, with the message the partition passes on ----

TEST_CASE("PART-4: a path through one point twice is a shared node of its own edge, described as such",
          "[partition][contract]") {
    const Fixture& f = tetrahedron();
    REQUIRE(chains_of_vertices(f));
    // D edge 4 goes x_j, v1, v2, back to v1 and v2 again, then on to x_k: not a simple curve.
    const std::uint32_t e = 4;
    std::vector<geodesic::GeodesicPath> paths = f.paths;
    std::vector<SurfacePoint>& p = paths[e].points;
    const SurfacePoint v1 = p[1], v2 = p[2];
    p.insert(p.begin() + 3, {v1, v2});
    const partition::Embedding emb = partition::embed(f.T, f.D, paths);
    REQUIRE(emb.conflicts.size() == 2);  // v1 and v2, each met twice
    for (const Conflict& c : emb.conflicts) {
        CHECK(c.kind == Conflict::Kind::shared_node);
        CHECK(c.d_edge_a == DEdgeId(e));
        CHECK(c.d_edge_b == DEdgeId(e));
        CHECK(c.describe() == "the path of domain edge 4 passes a point twice");
    }
    CHECK(emb.conflicts[0].near[0] == TVertexId(v1.vertex));
    CHECK(emb.conflicts[1].near[0] == TVertexId(v2.vertex));
}

TEST_CASE("PART-11: every kind of conflict is described by the domain edges and vertex it names",
          "[partition][contract]") {
    // These sentences are what a refused user domain is told (PART-11), one per conflicting pair.
    const auto described = [](Conflict::Kind kind, std::uint32_t a, std::uint32_t b, DVertexId v = {}) {
        return Conflict{kind, DEdgeId(a), DEdgeId(b), v, {}}.describe();
    };
    using K = Conflict::Kind;
    CHECK(described(K::shared_node, 3, 8) ==
          "the paths of domain edge 3 and domain edge 8 meet at a point that is not a common end");
    CHECK(described(K::shared_node, 5, 5) == "the path of domain edge 5 passes a point twice");
    CHECK(described(K::crossing, 0, 11) == "the paths of domain edge 0 and domain edge 11 cross");
    CHECK(described(K::through_corner, 7, 7, DVertexId(2)) ==
          "the path of domain edge 7 passes through the corner of domain vertex 2");
    CHECK(described(K::order, 6, 6, DVertexId(9)) ==
          "around domain vertex 9 the path of domain edge 6 is out of the domain's cyclic order");
}

// ---- extract_patches(): a network that is not the one embed() made for D (PART-6..8, checked all the same) ----

namespace {

// The fixture's network with `change` applied, cut into patches: the refusal, or "accepted".
std::string patches_of(const std::function<void(partition::Network&)>& change) {
    const Fixture& f = tetrahedron();
    partition::Network net = f.network;
    change(net);
    return refusal<PartitionFailure>([&] { (void)partition::extract_patches(f.D, net); });
}

// The torus of revolution (radii 3 and 1) as n × n squares, each cut into two triangles along
// the diagonal from (i, j) to (i + 1, j + 1); vertex (i, j) (indices mod n) is torus_vertex(n, i, j).
VertexId torus_vertex(int n, int i, int j) {
    return VertexId(static_cast<VertexId::Index>(((i % n + n) % n) * n + (j % n + n) % n));
}

TriMesh torus(int n) {
    std::vector<Vec3> positions;
    std::vector<Triangle> triangles;
    auto id = [&](int i, int j) { return torus_vertex(n, i, j).idx(); };
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const double u = 2 * std::numbers::pi * i / n, w = 2 * std::numbers::pi * j / n;
            positions.push_back({(3 + std::cos(w)) * std::cos(u), (3 + std::cos(w)) * std::sin(u), std::sin(w)});
            triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
            triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        }
    return TriMesh::from_triangles(std::move(positions), triangles);
}

// The D halfedges of face df of the fixture's D.
std::array<DHalfedgeId, 3> sides(FaceId df) {
    const TriMesh& m = tetrahedron().D.mesh;
    const HalfedgeId h = m.halfedge(df);
    return {DHalfedgeId(h), DHalfedgeId(m.next(h)), DHalfedgeId(m.next(m.next(h)))};
}

// An edge of T′ inside the patch of df (both its faces there, no curve on it) whose ends are on
// no curve either (interior == true) or whose first end is vertex v of a curve (else).
HalfedgeId inner_edge(FaceId df, VertexId v = {}) {
    const Fixture& f = tetrahedron();
    const TriMesh& M = f.network.mesh;
    auto off_curves = [&](VertexId u) { return !f.network.on_path[u].d_edge.valid() && !f.network.corner[u].valid(); };
    for (HalfedgeId h : M.halfedges()) {
        const FaceId a = M.face(h), b = M.face(TriMesh::twin(h));
        if (f.patches.patch_of_face[a] != df || f.patches.patch_of_face[b] != df || f.network.d_halfedge[h].valid())
            continue;
        if (v.valid() ? M.from(h) == v : off_curves(M.from(h)) && off_curves(M.to(h))) return h;
    }
    return {};
}

}  // namespace

TEST_CASE("PART-6, PART-7: extract_patches refuses regions that do not match D's faces one to one, naming the face",
          "[partition][contract]") {
    const Fixture& f = tetrahedron();
    CHECK(patches_of([](partition::Network&) {}) == "accepted");  // the control
    const EdgeId e(0);
    const FaceId left = f.D.mesh.face(TriMesh::halfedge(e, 0)), right = f.D.mesh.face(TriMesh::halfedge(e, 1));
    auto label_face = [&](const partition::Network& net, HalfedgeId h) {
        return f.D.mesh.face(HalfedgeId(net.d_halfedge[h]));
    };
    // The curve of D edge 0 unlabelled: its two patches are one region, bounded by both faces' curves.
    auto unlabel_edge_0 = [&](partition::Network& net) {
        for (HalfedgeId h : net.mesh.halfedges())
            if (net.d_halfedge[h].valid() && TriMesh::edge(net.d_halfedge[h]) == DEdgeId(e))
                net.d_halfedge[h] = DHalfedgeId();
    };
    const std::string merged = patches_of(unlabel_edge_0);
    CHECK((merged == "the patch of domain face " + std::to_string(left.idx()) + " runs into the patch of domain face " +
                         std::to_string(right.idx()) ||
           merged == "the patch of domain face " + std::to_string(right.idx()) +
                         " runs into the patch of domain face " + std::to_string(left.idx())));
    // ... and with the curves around the right face's patch relabelled to the left face: the right face has no region.
    CHECK(patches_of([&](partition::Network& net) {
              unlabel_edge_0(net);
              for (HalfedgeId h : net.mesh.halfedges())
                  if (net.d_halfedge[h].valid() && label_face(net, h) == right) net.d_halfedge[h] = sides(left)[0];
          }) == "the patch of domain face " + std::to_string(right.idx()) + " is empty");
    // No curve at all: one region, on no face of D.
    CHECK(patches_of([](partition::Network& net) { net.d_halfedge.assign(net.mesh.n_halfedges(), DHalfedgeId()); }) ==
          "a part of the surface is bounded by no geodesic path");
    // A face of T′ inside the patch of D face 2 ringed by labels of that face: the patch is two regions.
    const FaceId df(2);
    const HalfedgeId inner = inner_edge(df);
    REQUIRE(inner.valid());
    CHECK(patches_of([&](partition::Network& net) {
              HalfedgeId h = inner;
              for (int i = 0; i < 3; ++i, h = net.mesh.next(h)) {
                  net.d_halfedge[h] = sides(df)[0];
                  net.d_halfedge[TriMesh::twin(h)] = sides(df)[1];
              }
          }) == "the patch of domain face 2 falls apart into several pieces");
}

TEST_CASE(
    "PART-8: extract_patches refuses a patch whose boundary is not its three curves once around a disk, naming the "
    "face",
    "[partition][contract]") {
    const Fixture& f = tetrahedron();
    const FaceId df(0);
    const EdgeId e(
        TriMesh::edge(sides(df)[0]));  // a curve on the boundary of patch 0 (face 0 is the lower of its faces)
    REQUIRE(f.D.mesh.face(HalfedgeId(TriMesh::twin(sides(df)[0]))).idx() > df.idx());
    // Every label moved to the next face of D: the regions are still one per face, but each
    // patch's curves now have another face's patch on their left.
    CHECK(patches_of([&](partition::Network& net) {
              for (DHalfedgeId& label : net.d_halfedge)
                  if (label.valid()) label = sides(FaceId((f.D.mesh.face(HalfedgeId(label)).idx() + 1) % 4))[0];
          }) == "the patch of domain face 0 is not on the left of its curves");
    // A lattice point left out of the curve: two of its consecutive vertices are not joined by an edge of T′.
    CHECK(patches_of([&](partition::Network& net) {
              std::vector<VertexId>& path = net.path[DEdgeId(e)];
              path.erase(path.begin() + static_cast<std::ptrdiff_t>(path.size() / 2));
          }) == "the patch of domain face 0 is not on the left of its curves");
    // A spur: the curve goes from one of its vertices v into the patch to w and back to v.
    const VertexId v = f.network.path[DEdgeId(e)][2];
    const HalfedgeId spur = inner_edge(df, v);
    REQUIRE(spur.valid());
    CHECK(patches_of([&](partition::Network& net) {
              std::vector<VertexId>& path = net.path[DEdgeId(e)];
              path.insert(path.begin() + 3, {net.mesh.to(spur), v});
          }) == "the patch of domain face 0 touches itself on its boundary");
    // A slit inside the patch, labelled on both sides with the face's own halfedges: a second boundary.
    const HalfedgeId slit = inner_edge(df);
    REQUIRE(slit.valid());
    CHECK(patches_of([&](partition::Network& net) {
              net.d_halfedge[slit] = sides(df)[0];
              net.d_halfedge[TriMesh::twin(slit)] = sides(df)[1];
          }) == "the patch of domain face 0 has a second boundary loop");
}

TEST_CASE("PART-8: extract_patches refuses a patch with a handle (one boundary loop, not a disk)",
          "[partition][contract]") {
    // T′: a torus of 8 × 8 squares, each cut into two triangles. D: the two triangles of a pillow
    // (three vertices, faces (0, 1, 2) and (0, 2, 1)). Its curves ring one face F of the torus:
    // face 0's patch is F, a disk; face 1's is the rest, a torus with a hole (χ = −1).
    const int n = 8;
    domain::Domain D;
    D.mesh = TriMesh::from_triangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, std::vector<Triangle>{{0, 1, 2}, {0, 2, 1}});
    partition::Network net;
    net.mesh = torus(n);
    const std::array<VertexId, 3> ring{torus_vertex(n, 0, 0), torus_vertex(n, 1, 0),
                                       torus_vertex(n, 1, 1)};  // face 0 of T′
    net.d_halfedge = HalfedgeData<DHalfedgeId>(net.mesh, DHalfedgeId());
    net.path = IdVector<DEdgeId, std::vector<VertexId>>(D.mesh, {});
    for (EdgeId e : D.mesh.edges()) {
        const HalfedgeId dh = TriMesh::halfedge(e, 0);
        const VertexId a = ring[D.mesh.from(dh).idx()], b = ring[D.mesh.to(dh).idx()];
        const HalfedgeId h = net.mesh.find_halfedge(a, b);
        net.d_halfedge[h] = DHalfedgeId(dh);
        net.d_halfedge[TriMesh::twin(h)] = DHalfedgeId(TriMesh::twin(dh));
        net.path[DEdgeId(e)] = {a, b};
    }
    // The curves of face 0 run around F with F on their left.
    REQUIRE(net.mesh.face(net.mesh.find_halfedge(ring[0], ring[1])) == FaceId(0));
    CHECK(refusal<PartitionFailure>([&] { (void)partition::extract_patches(D, net); }) ==
          "the patch of domain face 1 is not a topological disk");
}

// ---- the region of T′ cut out on its own, and the restricted path in it (partition/region.hpp, restricted.hpp) ----

TEST_CASE("PART-10: a region refuses a curve that leaves the faces around it, and a point inside a face",
          "[partition][contract][keep]") {
    const Fixture& f = tetrahedron();
    const VertexId x0(0);
    const FaceId at_x0 = f.T.face(out_of(f.T, x0));
    // A face of T and an edge of T whose two ends are in the piece T_S around that face but which
    // is not (near a corner of the tetrahedron, whose three lattice faces leave such an edge).
    std::vector<FaceId> touched;
    std::optional<EdgeId> outside;
    for (FaceId t : f.T.faces()) {
        touched = {t};
        const partition::Region region = partition::Region::cut_out(f.T, touched, {}).value();
        for (EdgeId E : f.T.edges()) {
            const HalfedgeId h = TriMesh::halfedge(E, 0);
            const std::optional<VertexId> a = region.find_sub(f.T.from(h)), b = region.find_sub(f.T.to(h));
            if (a && b && !region.sub().find_halfedge(*a, *b).valid()) outside = E;  // both ends in T_S, the edge not
            if (outside) break;
        }
        if (outside) break;
    }
    REQUIRE(outside);
    const HalfedgeId across = TriMesh::halfedge(*outside, 0);
    const geodesic::GeodesicPath leaves{{SurfacePoint::at_vertex(f.T.from(across)), SurfacePoint::on_edge(across, 0.5),
                                         SurfacePoint::at_vertex(f.T.to(across))},
                                        0};
    const geodesic::GeodesicPath through_face{
        {SurfacePoint::at_vertex(x0), SurfacePoint::in_face(at_x0, {0.2, 0.3, 0.5})}, 0};
    const std::vector<FaceId> at_corner{at_x0};
    using Case = std::pair<const geodesic::GeodesicPath*, const std::vector<FaceId>*>;
    for (const Case& c : {Case{&leaves, &touched}, Case{&through_face, &at_corner}}) {
        const std::vector<FaceId>* faces = c.second;
        const std::vector<partition::RegionCurve> curves{{c.first, false}};
        const Outcome<partition::Region> region = partition::Region::cut_out(f.T, *faces, curves);
        REQUIRE_FALSE(region.ok());
        CHECK(region.why() == "a curve leaves the faces around the region");
    }
    // A point of T_S inside a face has no place as a vertex or edge point of T: a caller's bug.
    const partition::Region region = partition::Region::cut_out(f.T, touched, {}).value();
    CHECK(refusal<InternalError>([&] {
              (void)region.in_t(SurfacePoint::in_face(FaceId(0), {0.2, 0.3, 0.5}));
          }) == "region: a point inside a face");
}

TEST_CASE("PART-10: a region whose curve runs along T's boundary has no side beyond it",
          "[partition][contract][keep][boundary]") {
    // A flat 4 × 4 grid (with boundary); the curve runs along its boundary edge from (1, 0) to (0, 0).
    const int n = 4;
    std::vector<Vec3> positions;
    std::vector<Triangle> triangles;
    auto id = [&](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) positions.push_back({double(i), double(j), 0});
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
            triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        }
    const TriMesh T = TriMesh::from_triangles(positions, triangles);
    const VertexId a(id(1, 0)), b(id(0, 0));
    REQUIRE_FALSE(T.face(T.find_halfedge(a, b)).valid());  // a -> b has no face on its left
    const geodesic::GeodesicPath along{{SurfacePoint::at_vertex(a), SurfacePoint::at_vertex(b)}, 1};
    const std::vector<FaceId> touched{T.face(T.find_halfedge(b, a))};
    const std::vector<partition::RegionCurve> curves{{&along, true}};
    const partition::Region region = partition::Region::cut_out(T, touched, curves).value();
    CHECK(region.side(0, true).why() == "a curve on the border of the faces around the region");
    // Its right side is T_S's faces, which one curve does not enclose.
    CHECK(region.side(0, false).why() == "the curves do not enclose the region");
}

TEST_CASE("PART-10: the restricted path refuses an end outside its region, naming both vertices of T",
          "[partition][contract][keep]") {
    const Fixture& f = tetrahedron();
    // The region: the patch of D face 0, bounded by its three curves (each with the patch on its left).
    std::vector<geodesic::GeodesicPath> ring;
    for (DHalfedgeId dh : sides(FaceId(0))) {
        geodesic::GeodesicPath p = f.paths[TriMesh::edge(dh).idx()];
        if (dh.idx() & 1u) std::reverse(p.points.begin(), p.points.end());
        ring.push_back(p);
    }
    std::vector<partition::RegionCurve> curves;
    for (const auto& p : ring) curves.push_back({&p, true});
    std::vector<FaceId> all;
    for (FaceId t : f.T.faces()) all.push_back(t);
    const partition::Region region = partition::Region::cut_out(f.T, all, curves).value();
    const FaceData<std::uint8_t> inside = region.side(0, true).value();
    const VertexId from = ring[0].points.front().vertex, to = ring[0].points.back().vertex;
    const VertexId apart =
        VertexId(6 - from.idx() - to.idx() - ring[1].points.back().vertex.idx());  // the corner not on face 0
    // The control: between two corners of the patch, the restricted shortest length is the
    // tetrahedron's edge, which bounds the patch (the curve touches it and is separated from it).
    const partition::RestrictedPath r = partition::restricted_path(region, inside, from, to).value();
    const double edge = (f.T.position(to) - f.T.position(from)).norm();
    CHECK(std::abs(r.shortest - edge) <= 1e-12 * edge);
    CHECK(r.path.points.front().vertex == from);
    CHECK(r.path.points.back().vertex == to);
    CHECK(r.path.length <= r.shortest + r.separation_bound + 1e-12 * edge);
    CHECK(refusal<PartitionFailure>([&] { (void)partition::restricted_path(region, inside, from, apart); }) ==
          "restricted path: vertex " + std::to_string(apart.idx()) + " cannot be reached from vertex " +
              std::to_string(from.idx()) + " inside the region the other curves leave free");
}

// ---- partition(): a domain given by the user whose geodesics break (1) (PART-11) ----

namespace {

// On the icosphere of level 3, the tetrahedron over the four vertices nearest to the points at
// polar angle θ and azimuths 0, 1.4, 3.3, 4.6 (a convex quadrilateral around the pole): the
// geodesics of its diagonals, D edges [x_0, x_2] and [x_1, x_3], cross; no other pair conflicts.
// The two diagonals, as D's edge ids.
struct Quadrilateral {
    TriMesh T;
    domain::Domain D;
    EdgeId diagonal_a, diagonal_b;
};

Quadrilateral quadrilateral(double theta) {
    Quadrilateral q{test::icosphere(3), {}, {}, {}};
    std::vector<Vec3> corners;
    for (double phi : {0.0, 1.4, 3.3, 4.6}) {
        const Vec3 d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
        VertexId best(0);
        for (VertexId v : q.T.vertices())
            if ((q.T.position(v) - d).norm() < (q.T.position(best) - d).norm()) best = v;
        q.D.t_vertex.push_back(best);
        corners.push_back(q.T.position(best));
    }
    q.D.mesh = TriMesh::from_triangles(corners, test::tetrahedron_faces);
    const EdgeId a = TriMesh::edge(q.D.mesh.find_halfedge(VertexId(0), VertexId(2)));
    const EdgeId b = TriMesh::edge(q.D.mesh.find_halfedge(VertexId(1), VertexId(3)));
    q.diagonal_a = std::min(a, b);
    q.diagonal_b = std::max(a, b);
    return q;
}

std::string crossing_of(const Quadrilateral& q) {
    return "the paths of domain edge " + std::to_string(q.diagonal_a.idx()) + " and domain edge " +
           std::to_string(q.diagonal_b.idx()) + " cross";
}

}  // namespace

TEST_CASE(
    "PART-11: a given domain whose diagonals cross is kept with a restricted path, and refused naming the pair in the "
    "paper-only mode",
    "[partition][contract][given]") {
    const Quadrilateral q = quadrilateral(0.35);
    const partition::Embedding e = partition::embed(q.T, q.D, test::exact_paths(q.T, q.D));
    REQUIRE(e.conflicts.size() == 1);
    CHECK(e.conflicts[0].kind == Conflict::Kind::crossing);
    CHECK(e.conflicts[0].describe() == crossing_of(q));
    // Kept (the default): D exactly, certified by the checks of PART-1..8 and PART-10.
    const partition::Partition P = partition::partition(q.T, q.D);
    CHECK(P.retries == 0);
    CHECK(test::partition_violation(q.T, P) == "");
    CHECK(test::keep_violation(q.T, q.D, P) == "");
    // The paper-only mode changes only a decimated D: a given one is refused, the pair named once,
    // with no word of keeping it (it was not tried).
    partition::PartitionOptions paper;
    paper.keep_domain = false;
    CHECK(refusal<PartitionFailure>([&] { (void)partition::partition(q.T, q.D, paper); }) ==
          "conditions (1)/(2) of §3 fail for the given domain: " + crossing_of(q));
}

TEST_CASE("PART-11: a given domain whose vertices §2 cannot reach is kept directly", "[partition][contract][given]") {
    // θ = 1.2: the four corners lie nearly on one circle, so the tetrahedron over them is almost
    // flat; decimating the sphere down to them would turn faces over, and §2 stops above them.
    // The direct start needs no decimation: the crossing's later edge becomes a restricted path in
    // the polygon the other five leave (the decimation, which could not reach q's corners, is never
    // asked for).
    const Quadrilateral q = quadrilateral(1.2);
    const partition::Partition P = partition::partition(q.T, q.D);
    CHECK(P.retries == 0);
    CHECK(test::partition_violation(q.T, P) == "");
    CHECK(test::keep_violation(q.T, q.D, P) == "");
    CHECK(std::count_if(P.curves.begin(), P.curves.end(),
                        [](const partition::CurveInfo& c) { return c.kind == partition::CurveKind::restricted; }) == 1);
}

TEST_CASE("PART-10: the curve kinds have the names the report and geodesics.obj use", "[partition][contract]") {
    CHECK(std::string(partition::name(partition::CurveKind::geodesic)) == "geodesic");
    CHECK(std::string(partition::name(partition::CurveKind::restricted)) == "restricted");
    CHECK(std::string(partition::name(partition::CurveKind::boundary)) == "boundary");
}

TEST_CASE("PART-11: a given domain of another genus than T is refused, saying that §2 cannot reach it",
          "[partition][contract][given]") {
    // A tetrahedron (genus 0) over four vertices of a torus, in convex position around a spot so
    // that its diagonals' geodesics conflict: §2 cannot decimate a torus to 4 faces.
    const int n = 24;
    const TriMesh T = torus(n);
    domain::Domain D;
    std::vector<Vec3> corners;
    for (const auto& [i, j] : {std::pair{0, 0}, std::pair{7, 2}, std::pair{8, 7}, std::pair{2, 6}}) {
        D.t_vertex.push_back(torus_vertex(n, i, j));
        corners.push_back(T.position(D.t_vertex.back()));
    }
    D.mesh = TriMesh::from_triangles(corners, test::tetrahedron_faces);
    REQUIRE_FALSE(partition::embed(T, D, test::exact_paths(T, D)).conflicts.empty());
    const std::string what = refusal<PartitionFailure>([&] { (void)partition::partition(T, D); });
    const std::string head = "conditions (1)/(2) of §3 fail for the given domain: ";
    const std::string tail =
        "; and the domain cannot be kept: §2 cannot decimate T to the domain's vertices: "
        "--faces 4 is fewer than a closed surface of genus 1 needs (at least 14)";
    CHECK(what.substr(0, head.size()) == head);
    REQUIRE(what.size() > tail.size());
    CHECK(what.substr(what.size() - tail.size()) == tail);
}
