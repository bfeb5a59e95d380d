// The plain interface between cgal_uv's reader/writer (main.cpp, read_mesh.cpp) and the
// translation units that include CGAL (disk_check.cpp, fixed_border.cpp, free_border.cpp,
// mvc_post.cpp). No CGAL header is included here, so main.cpp and read_mesh.cpp compile in
// seconds and the CGAL units compile in parallel, each with only the parameterizers it needs.
//
// A mesh travels as a triangle soup: the input's vertex positions and triangles, in the input's
// order. Vertex i of the soup is vertex i of every CGAL mesh built from it, so the UV written for
// vertex i is CGAL's UV of the input's vertex i.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace cgal_uv {

struct TriangleSoup {
    std::vector<double> xyz;         // 3 per vertex, finite
    std::vector<std::uint32_t> tri;  // 3 per face, each < number of vertices, corners as in the file
    std::size_t vertex_count() const { return xyz.size() / 3; }
    std::size_t face_count() const { return tri.size() / 3; }
};

// What a step gives back: code 0 (done), 3 (not applicable: the mesh is not a disk) or 4 (CGAL
// reported a failure), with a one-line message for codes 3 and 4; note: on code 0, what CGAL
// printed on std::cerr, if anything (one line).
struct Outcome {
    int code = 0;
    std::string message;
    std::string note = {};
};

enum class Border { circle, square };
enum class FixedWeights { tutte, conformal, authalic, mean_value };
enum class FreeMethod { lscm, arap };

// disk_check.cpp: code 3 unless the soup is an oriented 2-manifold triangle mesh with one
// component, one boundary loop and Euler characteristic 1, every vertex in a face.
Outcome check_disk(const TriangleSoup& soup);
// CGAL_VERSION_STR of the headers cgal_uv is compiled with.
const char* cgal_version();

// Each fills uv (2 per vertex, vertex order of the soup) on code 0. The soup has passed check_disk.
Outcome run_fixed_border(FixedWeights weights, Border border, const TriangleSoup& soup,
                         std::vector<double>& uv);                                              // fixed_border.cpp
Outcome run_free_border(FreeMethod method, const TriangleSoup& soup, std::vector<double>& uv);  // free_border.cpp
Outcome run_lscm_mvc_post(const TriangleSoup& soup, std::vector<double>& uv);                   // mvc_post.cpp

// read_mesh.cpp: reads OFF, OBJ or PLY (chosen by the extension). On failure returns false and
// sets error to one line naming the file (and line or element) and the problem.
bool read_mesh(const std::string& path, TriangleSoup& soup, std::string& error);

}  // namespace cgal_uv
