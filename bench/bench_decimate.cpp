// FHR bench — §2 mesh reduction (the parameter domain D by half-edge-collapse decimation; the
// paper's timing table row "mesh reduction"), measured in the same run against CGAL's
// Surface_mesh_simplification::edge_collapse doing the same job. CGAL is used here, in a
// benchmark-only program, and nowhere in src/ (paper_notes/library.md).
//
// Usage: bench_decimate MESH FACES [RUNS]. MESH is loaded once with our strict reader and builder
// (fhr::io::read_soup + fhr::build_trimesh); both decimations then start from that mesh in memory.
// Timed (wall clock, std::chrono::steady_clock, median and minimum of RUNS runs, default 5; the
// runs alternate fhr, CGAL, fhr, CGAL, ... so that load from other processes hits both alike):
//   fhr   fhr::domain::decimate(T, {FACES}): Garland–Heckbert quadrics (area-weighted), half-edge
//         collapses (the survivor keeps its position), link condition, no face turning by more
//         than 90°, no new corner below 1°. Its time includes decimate's own copy of T.
//   CGAL  edge_collapse on a CGAL::Surface_mesh<Epick::Point_3> copy of T (building and copying
//         that mesh is not timed), with
//           cost       GarlandHeckbert_plane_policies (classic GH plane quadrics, unit normals;
//                      quadrics initialised and summed by CGAL, (Q0 + Q1)(placement));
//           placement  Half_edge_placement below: the position of whichever endpoint of the edge
//                      has the lower combined quadric error (ties: p1), i.e. a half-edge collapse
//                      that keeps one of T's vertices, exactly the choice our decimate makes
//                      between an edge's two half-edges;
//           stop       Count_stop_predicate(3·FACES/2 + 1): it counts edges and stops once fewer
//                      than the threshold remain; a closed triangle mesh has E = 3F/2, and each
//                      collapse removes 3 edges and 2 faces, so it stops at exactly FACES faces;
//           filter     Bounded_normal_change_filter: no face normal may turn by 90° or more (our
//                      90° rule); CGAL also applies its built-in link condition and fold check.
//         CGAL's assertions are compiled out (CGAL_NDEBUG, as in a CGAL release build).
// Not timed: both results are checked to be valid closed manifolds with FACES faces and T's
// Euler characteristic, and their two-sided Hausdorff distance to T is computed with
// CGAL::Polygon_mesh_processing::bounded_error_symmetric_Hausdorff_distance (error bound 1e-5 of
// T's bounding-box diagonal) and printed relative to that diagonal.
//
// Output: one table line per (mesh, target), then
//   goal: decimation >= 3x faster than CGAL on <mesh> -> <target>: measured <ratio>x: met|NOT met
// Exit status: 0 when both decimations produced valid results (whether or not the goal is met),
// 1 when a result is invalid or misses the target, fhr's exit code on a fhr::Error.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

// GCC reports -Wmaybe-uninitialized inside Eigen when CGAL default-constructs a 4×4 quadric
// property (Surface_mesh::add_property_map); it is CGAL's and Eigen's code, not ours.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/distance.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Bounded_normal_change_filter.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/GarlandHeckbert_plane_policies.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>
#include <CGAL/boost/graph/helpers.h>
#include <boost/optional.hpp>
#pragma GCC diagnostic pop

#include "bench_support.hpp"

#include <fhr/core/build.hpp>
#include <fhr/core/errors.hpp>
#include <fhr/core/topology.hpp>
#include <fhr/domain/decimate.hpp>
#include <fhr/io/read.hpp>

namespace {

namespace SMS = CGAL::Surface_mesh_simplification;
namespace PMP = CGAL::Polygon_mesh_processing;
using fhr::bench::Kernel;
using fhr::bench::median;
using fhr::bench::Mesh;
using fhr::bench::min_of;
using fhr::bench::to_cgal;
using GH = SMS::GarlandHeckbert_plane_policies<Mesh, Kernel>;

// Half-edge collapse placement for CGAL: keep the endpoint with the lower combined quadric
// error (the cost CGAL then evaluates at that same point), ties to p1. Never a new position.
class Half_edge_placement {
public:
    explicit Half_edge_placement(const GH& gh) : gh_(gh) {}

    template <class Profile>
    boost::optional<typename Profile::Point> operator()(const Profile& profile) const {
        const auto q = (get(gh_.vcm(), profile.v0()) + get(gh_.vcm(), profile.v1())).eval();
        auto error = [&](const typename Profile::Point& p) {
            const Eigen::Vector4d x(p.x(), p.y(), p.z(), 1.0);
            return x.dot(q * x);
        };
        if (error(profile.p0()) < error(profile.p1())) return profile.p0();
        return profile.p1();
    }

private:
    const GH& gh_;
};

long euler_characteristic(const Mesh& sm) {
    return static_cast<long>(sm.number_of_vertices()) - static_cast<long>(sm.number_of_edges()) +
           static_cast<long>(sm.number_of_faces());
}

// One CGAL decimation of `sm` (modified in place) to `faces` faces; returns the wall time in ms.
double cgal_decimate(Mesh& sm, std::size_t faces) {
    const auto t0 = std::chrono::steady_clock::now();
    GH gh(sm);
    const Half_edge_placement placement(gh);
    const SMS::Bounded_normal_change_filter<> filter;
    const SMS::Count_stop_predicate<Mesh> stop(3 * faces / 2 + 1);
    SMS::edge_collapse(sm, stop, CGAL::parameters::get_cost(gh.get_cost()).get_placement(placement).filter(filter));
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    sm.collect_garbage();
    return ms;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: bench_decimate MESH FACES [RUNS]\n");
        return 2;
    }
    const std::string path = argv[1];
    const std::string name = path.substr(path.find_last_of('/') + 1);
    const std::size_t target = static_cast<std::size_t>(std::strtoull(argv[2], nullptr, 10));
    const int runs = argc > 3 ? std::max(1, std::atoi(argv[3])) : 5;
    try {
        const fhr::TriMesh T = fhr::bench::load(path);
        const long chi = fhr::euler_characteristic(T);
        const Mesh T_cgal = to_cgal(T);

        // Runs alternate (fhr, CGAL, fhr, CGAL, ...) so that load from other processes on the
        // machine falls on both sides alike. CGAL decimates a fresh copy of T each run (untimed).
        std::vector<double> fhr_ms, cgal_ms;
        fhr::domain::Domain D;
        Mesh C;
        for (int i = 0; i < runs; ++i) {
            const auto t0 = std::chrono::steady_clock::now();
            D = fhr::domain::decimate(T, fhr::domain::DecimateOptions{target});
            fhr_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
            C = T_cgal;
            cgal_ms.push_back(cgal_decimate(C, target));
        }

        // Validity of both results (not timed).
        bool ok = true;
        try {
            D.mesh.validate();
        } catch (const std::exception& e) {
            std::fprintf(stderr, "%s: fhr result invalid: %s\n", name.c_str(), e.what());
            ok = false;
        }
        const bool fhr_ok = ok && D.mesh.n_faces() == target && D.mesh.is_closed() && !D.mesh.has_garbage() &&
                            fhr::euler_characteristic(D.mesh) == chi;
        const bool cgal_ok = C.is_valid(false) && CGAL::is_valid_polygon_mesh(C) && CGAL::is_closed(C) &&
                             CGAL::is_triangle_mesh(C) && C.number_of_faces() == target &&
                             euler_characteristic(C) == chi;

        // Quality: two-sided Hausdorff distance to T, relative to T's bounding-box diagonal.
        const auto box = PMP::bbox(T_cgal);
        const double diag = std::sqrt(std::pow(box.xmax() - box.xmin(), 2) + std::pow(box.ymax() - box.ymin(), 2) +
                                      std::pow(box.zmax() - box.zmin(), 2));
        const double bound = 1e-5 * diag;
        const Mesh D_cgal = to_cgal(D.mesh);
        const double h_fhr =
            PMP::bounded_error_symmetric_Hausdorff_distance<CGAL::Sequential_tag>(T_cgal, D_cgal, bound);
        const double h_cgal = PMP::bounded_error_symmetric_Hausdorff_distance<CGAL::Sequential_tag>(T_cgal, C, bound);

        const double fm = median(fhr_ms), cm = median(cgal_ms), ratio = cm / fm;
        std::printf(
            "%-22s T %7zu faces -> %5zu  fhr median %9.2f ms (min %9.2f, %zu faces%s)  "
            "CGAL median %9.2f ms (min %9.2f, %zu faces%s)  runs %d  CGAL/fhr %6.2fx  "
            "Hausdorff/diag fhr %.5f CGAL %.5f\n",
            name.c_str(), T.n_faces(), target, fm, min_of(fhr_ms), D.mesh.n_faces(),
            fhr_ok ? ", closed manifold" : ", INVALID", cm, min_of(cgal_ms),
            static_cast<std::size_t>(C.number_of_faces()), cgal_ok ? ", closed manifold" : ", INVALID", runs, ratio,
            h_fhr / diag, h_cgal / diag);
        std::printf("goal: decimation >= 3x faster than CGAL on %s -> %zu: measured %.2fx: %s\n", name.c_str(), target,
                    ratio, ratio >= 3.0 ? "met" : "NOT met");
        return fhr_ok && cgal_ok ? 0 : 1;
    } catch (const fhr::Error& e) {
        std::fprintf(stderr, "fhr: error: %s\n", e.what());
        return 2;  // a bad input file or option
    }
}
