// FHR bench — what the benchmark programs share: loading T with the strict reader and builder,
// T as a CGAL::Surface_mesh (for the CGAL oracles; benchmark-only, never in src/), and medians.
#pragma once

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <fhr/io/read.hpp>

namespace fhr::bench {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

inline TriMesh load(const std::string& path) { return io::read_mesh(path); }

/// The same vertices (same indices) and triangles as a CGAL::Surface_mesh.
inline Mesh to_cgal(const TriMesh& m) {
    Mesh sm;
    sm.reserve(static_cast<Mesh::size_type>(m.n_vertices()), static_cast<Mesh::size_type>(m.n_edges()),
               static_cast<Mesh::size_type>(m.n_faces()));
    for (const Vec3& p : m.positions()) sm.add_vertex(Point(p.x(), p.y(), p.z()));
    for (const Triangle& t : m.triangles()) {
        const Mesh::Face_index f =
            sm.add_face(Mesh::Vertex_index(t[0]), Mesh::Vertex_index(t[1]), Mesh::Vertex_index(t[2]));
        if (f == Mesh::null_face()) throw std::runtime_error("CGAL::Surface_mesh refused a face of T");
    }
    return sm;
}

inline double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

inline double min_of(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

}  // namespace fhr::bench
