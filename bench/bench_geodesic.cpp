// FHR bench — §3 geodesic paths (the paper's timing table row "geodesic paths"): the exact
// shortest path Γ(x_j, x_k) for every edge of the decimated domain D, by our ellipse search
// (src/fhr/geodesic/ellipse.hpp), against CGAL's Surface_mesh_shortest_path (Epick), which builds
// the whole single-source tree for every query. CGAL is used only in benchmarks and tests.
//
// Usage: bench_geodesic MESH FACES [CGAL_SOURCES]. T is loaded with our strict reader and builder, D is
// fhr::domain::decimate(T, FACES) (not timed). Timed, wall clock:
//   fhr   ellipse_shortest_path for every edge of D, one after another on one Workspace (total,
//         and per path; the workspace is made before the clock starts, its arrays on the first path);
//   CGAL  one tree per edge of D (one tree per pair of ends). Building a tree costs
//         the same whichever of its vertices is the source, so the tree is built once per
//         distinct source vertex, all of that source's targets are queried, and the time of
//         "one tree per pair" is the mean tree time times the number of edges. With CGAL_SOURCES,
//         only that many source vertices (evenly spread over the sorted list) get a CGAL tree:
//         a tree takes ~1 s on 90k faces, so a large domain would take many minutes.
// Checked: every length compared with CGAL agrees to 1e−9 relative (the largest deviation and
// the number of compared paths are printed). Also printed: windows per path (restricted searches
// plus certificate searches) and how each path was certified (paper_notes/ellipse.md).
// Output: one line per mesh, then `goal: geodesic paths >= 300x faster than CGAL on <mesh>:
// measured <ratio>x: met|NOT met` and `goal: every length equals CGAL's to 1e-9: ...`.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include <CGAL/Surface_mesh_shortest_path.h>

#include <fhr/core/errors.hpp>
#include <fhr/domain/decimate.hpp>
#include <fhr/geodesic/ellipse.hpp>
#include <fhr/geodesic/workspace.hpp>
#include "bench_support.hpp"

namespace {

using fhr::bench::Mesh;
using Traits = CGAL::Surface_mesh_shortest_path_traits<fhr::bench::Kernel, Mesh>;
using ShortestPath = CGAL::Surface_mesh_shortest_path<Traits>;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: bench_geodesic MESH FACES [CGAL_SOURCES]\n");
        return 2;
    }
    const std::string path = argv[1];
    const std::string name = path.substr(path.find_last_of('/') + 1);
    try {
        const fhr::TriMesh T = fhr::bench::load(path);
        fhr::domain::DecimateOptions options;
        options.target_faces = static_cast<std::size_t>(std::strtoull(argv[2], nullptr, 10));
        const fhr::domain::Domain D = fhr::domain::decimate(T, options);
        struct Pair {
            fhr::VertexId a, b;
            double ours = 0;
        };
        std::vector<Pair> pairs;
        for (const auto& [a, b] : fhr::domain::edge_endpoints(D)) pairs.push_back({a, b});
        using Certificate = fhr::geodesic::EllipsePath::Certificate;
        std::size_t windows = 0, grown = 0, by_border = 0, by_search = 0, replaced = 0, whole = 0;
        std::vector<fhr::geodesic::EllipsePath> results;
        results.reserve(pairs.size());
        fhr::geodesic::Workspace workspace;
        const auto t0 = Clock::now();
        for (Pair& p : pairs)
            results.push_back(fhr::geodesic::ellipse_shortest_path(T, p.a, p.b, {.workspace = &workspace}));
        const double ours_ms = ms_since(t0);
        for (std::size_t i = 0; i < pairs.size(); ++i) {
            const auto& r = results[i];
            pairs[i].ours = r.path.length;
            windows += r.windows_created + r.certificate_windows;
            grown += r.attempts > 1;
            by_border += r.certificate == Certificate::border;
            by_search += r.certificate == Certificate::search;
            replaced += r.certificate == Certificate::replaced;
            whole += r.certificate == Certificate::whole_mesh;
        }

        const Mesh sm = fhr::bench::to_cgal(T);
        std::map<std::uint32_t, std::vector<Pair*>> by_source;
        for (Pair& p : pairs) by_source[p.a.idx()].push_back(&p);
        const std::size_t max_sources = argc > 3 ? std::strtoull(argv[3], nullptr, 10) : by_source.size();
        const std::size_t stride = std::max<std::size_t>(1, by_source.size() / std::max<std::size_t>(1, max_sources));
        double tree_ms = 0, worst = 0;
        std::size_t trees = 0, compared = 0, index = 0;
        for (const auto& [source, group] : by_source) {
            if (index++ % stride != 0) continue;
            ++trees;
            const auto t1 = Clock::now();
            ShortestPath sp(sm);
            sp.add_source_point(Mesh::Vertex_index(source));
            sp.build_sequence_tree();
            tree_ms += ms_since(t1);
            for (const Pair* p : group) {
                const double theirs = sp.shortest_distance_to_source_points(Mesh::Vertex_index(p->b.idx())).first;
                worst = std::max(worst, std::abs(p->ours - theirs) / theirs);
                ++compared;
            }
        }
        const double cgal_ms = tree_ms / static_cast<double>(trees) * static_cast<double>(pairs.size());
        const double ratio = cgal_ms / ours_ms;
        std::printf(
            "%-22s T %7zu faces, D %4zu faces: %zu paths  fhr %9.2f ms (%.3f ms/path, %.0f windows/path, "
            "%zu needed K > 1.06; certified by the border %zu, by the search %zu, replaced %zu, whole mesh %zu)  "
            "CGAL one tree per path %10.1f ms (%.1f ms/tree)  CGAL/fhr %7.1fx  "
            "max relative length deviation %.2e over %zu compared paths\n",
            name.c_str(), T.n_faces(), D.mesh.n_faces(), pairs.size(), ours_ms, ours_ms / pairs.size(),
            static_cast<double>(windows) / pairs.size(), grown, by_border, by_search, replaced, whole, cgal_ms,
            tree_ms / static_cast<double>(trees), ratio, worst, compared);
        std::printf("goal: geodesic paths >= 300x faster than CGAL on %s: measured %.1fx: %s\n", name.c_str(), ratio,
                    ratio >= 300 ? "met" : "NOT met");
        std::printf("goal: every length equals CGAL's to 1e-9 on %s: measured %.2e: %s\n", name.c_str(), worst,
                    worst <= 1e-9 ? "met" : "NOT met");
        return 0;
    } catch (const fhr::Error& e) {
        std::fprintf(stderr, "fhr: error: %s\n", e.what());
        return 2;  // a bad input file or option
    }
}
