// What the CGAL translation units of cgal_uv share: the mesh type, building it from the soup,
// the border halfedge handed to CGAL, reading the UV map back, and turning CGAL's error codes
// and exceptions into outcomes.
//
// Decisions:
// - The kernel is CGAL::Exact_predicates_inexact_constructions_kernel. Its points hold the same
//   doubles and its constructions do the same double arithmetic as Simple_cartesian<double> (the
//   kernel of CGAL's parameterization examples), so every weight and every solve is the one those
//   examples compute; its predicates are exact, which keeps the constrained triangulation and the
//   simplicity and one-to-one tests inside MVC_post_processor_3 and ARAP_parameterizer_3 robust on
//   nearly collinear UV points.
// - Vertex i of the soup is vertex i of the Surface_mesh (vertices are added in order and never
//   removed), and faces are added in the soup's order with the soup's corner order.
// - The border halfedge is PMP::longest_border's, as in CGAL's examples; on a disk it is the one
//   border, starting at its first border halfedge in halfedge order, so runs are deterministic.
// - The UV map starts at NaN: a vertex CGAL leaves untouched cannot pass as a UV of (0, 0).
//   A UV that is not finite after CGAL returned OK is a failure (code 4), never written.
// - CGAL's checks that stay on in release builds (CGAL_error, and preconditions unless
//   CGAL_NDEBUG) throw CGAL::Failure_exception; that is CGAL reporting a failure, so it becomes
//   code 4 with CGAL's message. Other exceptions are not caught.
// - What CGAL prints on std::cerr during a run is kept and appended to the one-line message (or,
//   after a success, given as a note), so an adapter's stderr holds one line per outcome.
#pragma once

#include "uv_job.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/Error_code.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>
#include <CGAL/assertions.h>
#include <CGAL/exceptions.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace cgal_uv {

namespace SMP = CGAL::Surface_mesh_parameterization;

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point_2 = Kernel::Point_2;
using Point_3 = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point_3>;
using vertex_descriptor = boost::graph_traits<SurfaceMesh>::vertex_descriptor;
using halfedge_descriptor = boost::graph_traits<SurfaceMesh>::halfedge_descriptor;
using face_descriptor = boost::graph_traits<SurfaceMesh>::face_descriptor;
using UvMap = SurfaceMesh::Property_map<vertex_descriptor, Point_2>;

// Returns the index of the first face CGAL refuses to add, or -1 when every face is added.
inline long build_surface_mesh(const TriangleSoup& soup, SurfaceMesh& sm) {
    // A disk has E = V + F − 1 edges.
    sm.reserve(static_cast<SurfaceMesh::size_type>(soup.vertex_count()),
               static_cast<SurfaceMesh::size_type>(soup.vertex_count() + soup.face_count()),
               static_cast<SurfaceMesh::size_type>(soup.face_count()));
    for (std::size_t i = 0; i < soup.vertex_count(); ++i)
        sm.add_vertex(Point_3(soup.xyz[3 * i], soup.xyz[3 * i + 1], soup.xyz[3 * i + 2]));
    for (std::size_t f = 0; f < soup.face_count(); ++f) {
        const auto corner = [&](int k) {
            return vertex_descriptor(static_cast<SurfaceMesh::size_type>(soup.tri[3 * f + k]));
        };
        if (sm.add_face(corner(0), corner(1), corner(2)) == SurfaceMesh::null_face()) return static_cast<long>(f);
    }
    return -1;
}

// The name and meaning of CGAL's error code, from the Error_code enumeration's documentation.
// CGAL 5.5's own get_error_message() lacks the text of ERROR_NO_TOPOLOGICAL_BALL, so from code 4
// on it gives the text of the next code (ERROR_BORDER_TOO_SHORT reads "requires a convex
// border"); cgal_uv names the codes itself.
inline std::string error_text(SMP::Error_code code) {
    const char* text = "unknown error code";
    switch (code) {
        case SMP::OK: text = "OK: success"; break;
        case SMP::ERROR_EMPTY_MESH: text = "ERROR_EMPTY_MESH: input mesh is empty"; break;
        case SMP::ERROR_NON_TRIANGULAR_MESH: text = "ERROR_NON_TRIANGULAR_MESH: input mesh is not triangular"; break;
        case SMP::ERROR_NO_TOPOLOGICAL_DISC:
            text = "ERROR_NO_TOPOLOGICAL_DISC: input mesh is not a topological disc";
            break;
        case SMP::ERROR_NO_TOPOLOGICAL_BALL:
            text = "ERROR_NO_TOPOLOGICAL_BALL: input mesh is not a topological ball";
            break;
        case SMP::ERROR_BORDER_TOO_SHORT:
            text = "ERROR_BORDER_TOO_SHORT: this border parameterization requires a longer border";
            break;
        case SMP::ERROR_NON_CONVEX_BORDER:
            text = "ERROR_NON_CONVEX_BORDER: this parameterization method requires a convex border";
            break;
        case SMP::ERROR_CANNOT_SOLVE_LINEAR_SYSTEM:
            text = "ERROR_CANNOT_SOLVE_LINEAR_SYSTEM: cannot solve linear system";
            break;
        case SMP::ERROR_NO_1_TO_1_MAPPING:
            text = "ERROR_NO_1_TO_1_MAPPING: parameterization failed: no one-to-one mapping";
            break;
        case SMP::ERROR_WRONG_PARAMETER:
            text = "ERROR_WRONG_PARAMETER: a method received an unexpected parameter";
            break;
    }
    return std::string("CGAL error ") + std::to_string(static_cast<int>(code)) + " " + text;
}

// CGAL's exception text spans several lines (kind, expression, file, line, explanation); the
// adapters report one line.
inline std::string one_line(std::string text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
    std::string out;
    for (char c : text) {
        if (c == '\n')
            out += "; ";
        else
            out += c;
    }
    return out;
}

// While alive, keeps what CGAL writes to std::cerr (ARAP_parameterizer_3 prints "Could not solve
// linear system" before returning its error), so that the adapter's stderr stays one line.
class CerrCapture {
public:
    CerrCapture() : old_(std::cerr.rdbuf(buffer_.rdbuf())) {}
    ~CerrCapture() { std::cerr.rdbuf(old_); }
    CerrCapture(const CerrCapture&) = delete;
    CerrCapture& operator=(const CerrCapture&) = delete;
    std::string text() const { return one_line(buffer_.str()); }

private:
    std::ostringstream buffer_;
    std::streambuf* old_;
};

// Appends what CGAL printed, if anything, to an outcome's message.
inline Outcome with_printed(Outcome outcome, const CerrCapture& capture) {
    const std::string printed = capture.text();
    if (!printed.empty()) {
        if (outcome.code == 0)
            outcome.note = "CGAL printed: " + printed;
        else
            outcome.message += " (CGAL printed: " + printed + ")";
    }
    return outcome;
}

// Copies CGAL's UV map into uv (2 per vertex); code 4 when a UV is not finite.
inline Outcome copy_uv(const SurfaceMesh& sm, const UvMap& uvmap, std::vector<double>& uv) {
    uv.assign(2 * sm.number_of_vertices(), 0.0);
    std::size_t bad = 0, first_bad = 0;
    for (vertex_descriptor v : sm.vertices()) {
        const Point_2& p = uvmap[v];
        const std::size_t i = static_cast<std::size_t>(v.idx());
        uv[2 * i] = p.x();
        uv[2 * i + 1] = p.y();
        if (!std::isfinite(p.x()) || !std::isfinite(p.y())) {
            if (bad++ == 0) first_bad = i;
        }
    }
    if (bad != 0)
        return {4, "CGAL returned OK but " + std::to_string(bad) + " of " + std::to_string(sm.number_of_vertices()) +
                       " vertices have a UV that is not finite (the first: vertex " + std::to_string(first_bad) + ")"};
    return {};
}

// Builds the mesh, gives `solve(sm, border_halfedge, uvmap)` a NaN-initialised UV map, and turns
// its Error_code (or a CGAL exception) into an outcome; on code 0, uv holds the map.
template <class Solve>
Outcome run_on_mesh(const TriangleSoup& soup, std::vector<double>& uv, Solve&& solve) {
    const CerrCapture capture;
    try {
        SurfaceMesh sm;
        if (const long f = build_surface_mesh(soup, sm); f >= 0)
            return {3, "not an oriented 2-manifold: CGAL's Surface_mesh refuses face " + std::to_string(f), {}};
        const halfedge_descriptor bhd = CGAL::Polygon_mesh_processing::longest_border(sm).first;
        if (bhd == SurfaceMesh::null_halfedge()) return {3, "not a disk: the mesh has no border", {}};
        const double nan = std::numeric_limits<double>::quiet_NaN();
        UvMap uvmap = sm.add_property_map<vertex_descriptor, Point_2>("v:uv", Point_2(nan, nan)).first;
        const SMP::Error_code status = solve(sm, bhd, uvmap);
        if (status != SMP::OK) return with_printed({4, error_text(status), {}}, capture);
        return with_printed(copy_uv(sm, uvmap, uv), capture);
    } catch (const CGAL::Failure_exception& e) {
        return with_printed({4, one_line(e.what()), {}}, capture);
    }
}

}  // namespace cgal_uv
