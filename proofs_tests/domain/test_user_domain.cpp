// §2 user-given domains (paper §2, and §3 Fig. 4: points inside faces or on edges are inserted
// into T first). Properties over random meshes with random correspondences mixing vertices, edge
// points and several points in one face; every refusal of DOM-10..13 and FMT-CORR-*.
#include <catch2/catch.hpp>
#include <rapidcheck/catch.h>

#include <set>

#include <fhr/core/errors.hpp>
#include <fhr/core/geometry.hpp>
#include <fhr/core/topology.hpp>
#include <fhr/domain/user_domain.hpp>
#include <fhr/io/correspondence.hpp>
#include <fhr/testing/rapidcheck.hpp>
#include "support/test_support.hpp"

using namespace fhr;

namespace {

double total_area(const TriMesh& m) {
    double a = 0;
    for (FaceId f : m.faces()) a += face_area(m, f);
    return a;
}

io::CorrespondenceEntry entry(SurfacePoint p, std::uint64_t line) { return {p, line}; }

// A domain for T and a correspondence in which some entries are moved off T's vertices.
struct Setup {
    TriMesh T, D;
    std::vector<io::CorrespondenceEntry> x;
};

Setup make_setup(const TriMesh& T, std::size_t faces) {
    domain::DecimateOptions o;
    o.target_faces = faces;
    domain::Domain d = domain::decimate(T, o);
    Setup s{T, d.mesh, {}};
    for (VertexId j : d.t_vertex.ids()) s.x.push_back(entry(SurfacePoint::at_vertex(d.t_vertex[j]), j.idx() + 1));
    return s;
}

const domain::DomainSources names{"d.off", "d.corr"};

}  // namespace

TEST_CASE("DOM-10..13: attach_domain inserts face and edge points exactly (Fig. 4)", "[property][domain]") {
    rc::prop("random correspondences", [] {
        const fhr::testing::GeneratedMesh G = *fhr::testing::gen_closed_mesh(0, 3, 800);
        Setup s = make_setup(
            G, std::max<std::size_t>(2 * domain::min_closed_faces(G.options.genus), G.n_faces() / 4) & ~std::size_t(1));
        // Move some entries into faces (several may share one face) or onto edges.
        const std::uint32_t shared_face = *rc::gen::inRange<std::uint32_t>(0, static_cast<std::uint32_t>(G.n_faces()));
        std::size_t moved = 0;
        for (auto& e : s.x) {
            const int kind = *rc::gen::inRange(0, 4);
            if (kind == 0) continue;  // stays a vertex
            const auto w = *rc::gen::container<std::vector<int>>(3, rc::gen::inRange(0, 1000));
            const double sum = w[0] + w[1] + w[2];
            RC_PRE(sum > 0);
            std::array<double, 3> b{w[0] / sum, w[1] / sum, w[2] / sum};
            b[2] = 1 - b[0] - b[1];
            RC_PRE(b[2] >= 0);
            const FaceId f = kind == 3
                                 ? FaceId(shared_face)
                                 : FaceId(*rc::gen::inRange<std::uint32_t>(0, static_cast<std::uint32_t>(G.n_faces())));
            if (kind == 2) {  // on an edge: one weight zero
                b[0] = 0;
                b[1] = w[1] / std::max(1.0, double(w[1] + w[2]));
                b[2] = 1 - b[1];
            }
            e.point = SurfacePoint::in_face(f, b);
            ++moved;
        }
        std::vector<Vec3> expected;
        std::set<std::tuple<double, double, double>> distinct;
        for (const auto& e : s.x) {
            expected.push_back(position(G, e.point));
            distinct.insert({expected.back().x(), expected.back().y(), expected.back().z()});
        }
        RC_PRE(distinct.size() == s.x.size());  // DOM-12 is tested below
        TriMesh T = G;
        const domain::Domain d = domain::attach_domain(T, s.D, s.x, names);
        T.validate();
        RC_ASSERT(T.is_closed());
        RC_ASSERT(euler_characteristic(T) == euler_characteristic(G));
        std::size_t inserted = 0;
        for (std::size_t j = 0; j < s.x.size(); ++j) {
            const SurfacePoint c = canonical(G, s.x[j].point);
            inserted += c.kind != SurfacePoint::Kind::vertex;
            RC_ASSERT((T.position(d.t_vertex[VertexId(static_cast<VertexId::Index>(j))]) - expected[j]).norm() <=
                      1e-12 * (1 + expected[j].norm()));
        }
        RC_ASSERT(T.n_vertices() == G.n_vertices() + inserted);
        for (VertexId v : G.vertices()) RC_ASSERT(T.position(v) == G.position(v));    // T's vertices stay
        RC_ASSERT(std::abs(total_area(T) - total_area(G)) <= 1e-12 * total_area(G));  // Ω_T unchanged
        const std::set<VertexId> unique(d.t_vertex.begin(), d.t_vertex.end());
        RC_ASSERT(unique.size() == d.t_vertex.size());
        RC_ASSERT(moved <= s.x.size());
    });
}

TEST_CASE("DOM-10, DOM-11, DOM-12: bad correspondences are refused with the entry and line", "[unit][domain]") {
    const TriMesh T = generate::random_closed_mesh({1, 300, 4, 0.1});
    Setup s = make_setup(T, 40);
    SECTION("DOM-10 wrong count") {
        auto x = s.x;
        x.pop_back();
        TriMesh t = T;
        CHECK_THROWS_WITH(domain::attach_domain(t, s.D, x, names),
                          Catch::Contains("has 19 entries but the domain d.off has 20 vertices"));
    }
    SECTION("DOM-11 another topology") {
        const TriMesh sphere = generate::random_closed_mesh({0, 36, 1, 0.0});
        std::vector<io::CorrespondenceEntry> x;
        for (std::uint32_t j = 0; j < sphere.n_vertices(); ++j)
            x.push_back(entry(SurfacePoint::at_vertex(VertexId(j)), j + 1));
        TriMesh t = T;
        CHECK_THROWS_WITH(domain::attach_domain(t, sphere, x, names),
                          Catch::Contains("Euler characteristic 2 (genus 0) but the mesh has 0 (genus 1)"));
    }
    SECTION("DOM-12 two entries on one vertex, also when one is written as a face point") {
        auto x = s.x;
        x[5].point = x[2].point;
        TriMesh t = T;
        CHECK_THROWS_WITH(domain::attach_domain(t, s.D, x, names),
                          Catch::Contains("entry 5 (line 6) names the same point of the mesh as entry 2 (line 3)"));
        // Vertex x[2] as a face point with weights (1, 0, 0) at its corner.
        const VertexId v = x[2].point.vertex;
        const FaceId f = T.face(T.out(v));
        const auto c = T.face_vertices(f);
        std::array<double, 3> b{};
        b[std::find(c.begin(), c.end(), v) - c.begin()] = 1;
        auto y = s.x;
        y[7].point = SurfacePoint::in_face(f, b);
        TriMesh t2 = T;
        CHECK_THROWS_WITH(domain::attach_domain(t2, s.D, y, names), Catch::Contains("names the same point"));
    }
}

TEST_CASE("FMT-CORR: the correspondence reader refuses malformed lines", "[unit][domain][io]") {
    auto refused = [](const std::string& text, const std::string& expect) {
        INFO(text);
        CHECK_THROWS_WITH(io::parse_correspondence(text, "c.corr", 10, 16), Catch::Contains(expect));
    };
    const auto ok = io::parse_correspondence("# comment\n3\n f 2 0.25 0.25 0.5 \r\n\n9\n", "c.corr", 10, 16);
    REQUIRE(ok.size() == 3);
    CHECK(ok[0].point.kind == SurfacePoint::Kind::vertex);
    CHECK(ok[1].point.kind == SurfacePoint::Kind::face);
    CHECK(ok[1].line == 3);
    CHECK(ok[1].point.bary == std::array<double, 3>{0.25, 0.25, 0.5});
    refused("3\n10\n", "c.corr:2: entry 1: index 10 out of range");
    refused("-1\n", "negative index -1");
    refused("99999999999999999999999\n", "out of range");
    refused("vertex\n", "expected a vertex index or 'f FACE b0 b1 b2'");
    refused("f 16 0.2 0.3 0.5\n", "index 16 out of range");
    refused("f 1 -0.2 0.7 0.5\n", "not in [0, 1]");
    refused("f 1 0.2 0.3 0.4\n", "sum to");
    refused("f 1 0.2 0.3 nan\n", "c.corr:1");
    refused("f 1 0.2 0.3\n", "expected");
    refused("4 5\n", "c.corr:1");
    refused("", "empty");
}
