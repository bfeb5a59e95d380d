// cgal_uv: runs one of CGAL's Surface_mesh_parameterization methods on a disk-shaped triangle
// mesh and writes the UV map as an OBJ atlas, so that `fhr verify` can judge CGAL's maps. It is
// called by the adapters peers/cgal-* (one per method) as
//   cgal_uv --adapter NAME METHOD MESH OUT      or      cgal_uv --adapter NAME METHOD --help
//
// Exit codes: 0 OUT written; 2 usage error, unreadable MESH or unwritable OUT; 3 not applicable
// (MESH is not a disk: one component, one boundary loop, genus 0); 4 CGAL reported a failure (its
// error code's text, or the check CGAL's code failed). Every error is one line `NAME: error: ...`
// on stderr. A crash is whatever the process gives.
//
// Decisions:
// - OUT is written to OUT.tmp-PID and renamed into place, so OUT is complete or absent.
// - `v` lines are the input's positions printed with %.17g, which reads back as the same double,
//   so the atlas's surface is bit for bit the input (the oracle welds corners by exact position
//   and compares the atlas with the input).
// - One `vt` per vertex, in vertex order and also printed with %.17g: CGAL computes one UV per
//   vertex, and every face corner refers to its vertex's UV (`f a/a b/b c/c`), so the atlas is
//   one chart without seams.
// - Faces keep the input's order and each face its corners' order, so face i of the atlas is face
//   i of the input and its winding is the input's; the UV orientation is CGAL's.
// - The first line is a comment naming the adapter, the method, CGAL's classes and CGAL's version.
#include "uv_job.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>
#include <string_view>
#include <unistd.h>
#include <vector>

namespace {

using namespace cgal_uv;

enum class Family { fixed, free, post };

struct Method {
    const char* name;
    Family family;
    FixedWeights weights;
    Border border;
    FreeMethod free_method;
    const char* classes;  // CGAL's classes, for the comment line and the help
    const char* map;      // what the method computes
    const char* border_text;
    const char* promise;  // what CGAL promises about the result
};

constexpr const char* circle_text =
    "fixed on the circle of centre (0.5, 0.5) and radius 0.5, its vertices spaced by arc length "
    "(Circular_border_arc_length_parameterizer_3), starting at the first border halfedge";
constexpr const char* square_text =
    "fixed on the square [0, 1]^2, its vertices spaced by arc length "
    "(Square_border_arc_length_parameterizer_3); the corners are the border's first vertex and "
    "the vertices nearest to 1/4, 1/2 and 3/4 of its length. CGAL walks the square the other way "
    "round from the circle, so the map is mirrored (every triangle clockwise in UV), and a triangle "
    "whose three vertices land on one side of the square is degenerate";

const Method methods[] = {
    {"tutte", Family::fixed, FixedWeights::tutte, Border::circle, FreeMethod::lscm,
     "Barycentric_mapping_parameterizer_3 + Circular_border_arc_length_parameterizer_3",
     "Tutte's barycentric map: every interior vertex at the mean of its neighbours (uniform weights)", circle_text,
     "a one-to-one map (Tutte's theorem: positive weights, convex border); CGAL does not check the result"},
    {"tutte-square", Family::fixed, FixedWeights::tutte, Border::square, FreeMethod::lscm,
     "Barycentric_mapping_parameterizer_3 + Square_border_arc_length_parameterizer_3",
     "Tutte's barycentric map: every interior vertex at the mean of its neighbours (uniform weights)", square_text,
     "a one-to-one map when no triangle and no interior edge has all its vertices on one side of the "
     "square (Tutte's theorem); CGAL does not check the result"},
    {"conformal", Family::fixed, FixedWeights::conformal, Border::circle, FreeMethod::lscm,
     "Discrete_conformal_map_parameterizer_3 + Circular_border_arc_length_parameterizer_3",
     "the discrete conformal (harmonic) map of Eck et al.: cotangent weights", circle_text,
     "nothing about validity: cotangent weights are negative at obtuse angles, so triangles may flip; "
     "CGAL does not check the result"},
    {"conformal-square", Family::fixed, FixedWeights::conformal, Border::square, FreeMethod::lscm,
     "Discrete_conformal_map_parameterizer_3 + Square_border_arc_length_parameterizer_3",
     "the discrete conformal (harmonic) map of Eck et al.: cotangent weights", square_text,
     "nothing about validity: cotangent weights are negative at obtuse angles, so triangles may flip; "
     "CGAL does not check the result"},
    {"authalic", Family::fixed, FixedWeights::authalic, Border::circle, FreeMethod::lscm,
     "Discrete_authalic_parameterizer_3 + Circular_border_arc_length_parameterizer_3",
     "the discrete authalic map of Desbrun, Meyer and Alliez: area-preserving weights", circle_text,
     "nothing about validity: the authalic weights can be negative, so triangles may flip; CGAL does not "
     "check the result"},
    {"authalic-square", Family::fixed, FixedWeights::authalic, Border::square, FreeMethod::lscm,
     "Discrete_authalic_parameterizer_3 + Square_border_arc_length_parameterizer_3",
     "the discrete authalic map of Desbrun, Meyer and Alliez: area-preserving weights", square_text,
     "nothing about validity: the authalic weights can be negative, so triangles may flip; CGAL does not "
     "check the result"},
    {"mvc", Family::fixed, FixedWeights::mean_value, Border::circle, FreeMethod::lscm,
     "Mean_value_coordinates_parameterizer_3 + Circular_border_arc_length_parameterizer_3",
     "Floater's mean value coordinates map: mean value weights", circle_text,
     "a one-to-one map (positive weights, convex border); CGAL does not check the result"},
    {"mvc-square", Family::fixed, FixedWeights::mean_value, Border::square, FreeMethod::lscm,
     "Mean_value_coordinates_parameterizer_3 + Square_border_arc_length_parameterizer_3",
     "Floater's mean value coordinates map: mean value weights", square_text,
     "a one-to-one map when no triangle and no interior edge has all its vertices on one side of the "
     "square; CGAL does not check the result"},
    {"lscm", Family::free, FixedWeights::tutte, Border::circle, FreeMethod::lscm,
     "LSCM_parameterizer_3 + Two_vertices_parameterizer_3", "the least squares conformal map of Levy et al. (2002)",
     "free; two vertices are pinned (Two_vertices_parameterizer_3: the extreme vertices along the "
     "longest axis of the bounding box, at (0, 0.5) and (1, 0.5))",
     "nothing: \"a one-to-one mapping is not guaranteed\"; the border may overlap itself"},
    {"arap", Family::free, FixedWeights::tutte, Border::circle, FreeMethod::arap,
     "ARAP_parameterizer_3 (lambda 1000, 50 iterations, tolerance 1e-6)",
     "the local/global as-rigid-as-possible map of Liu et al. (2008), started from CGAL's mean value map on "
     "a circle; when the result has flipped triangles CGAL runs MVC_post_processor_3 on it",
     "free; one vertex is pinned",
     "nothing: \"a one-to-one mapping is not guaranteed\"; CGAL fails (ERROR_NON_CONVEX_BORDER) when the "
     "post-processor is needed and the border is not a simple polygon"},
    {"lscm-mvc-post", Family::post, FixedWeights::tutte, Border::circle, FreeMethod::lscm,
     "LSCM_parameterizer_3 + MVC_post_processor_3",
     "the least squares conformal map, then CGAL's free boundary linear post-processor (Karni, Gotsman "
     "and Gortler 2005): the convex hull of LSCM's border is triangulated around the mesh, the hull's "
     "vertices stay where LSCM put them and a mean value system over the mesh and the added triangles "
     "moves every other vertex. The weights come from LSCM's UV positions, so where LSCM's border is "
     "convex the result is LSCM's map again",
     "free (LSCM with two pinned vertices), then made convex by the post-processor",
     "nothing explicit; the post-processor is meant \"to attempt to obtain a valid final embedding\"; CGAL "
     "fails (ERROR_NON_CONVEX_BORDER) when LSCM's border is not a simple polygon"},
};

std::string program = "cgal_uv";

int error(int code, const std::string& message) {
    std::fprintf(stderr, "%s: error: %s\n", program.c_str(), message.c_str());
    return code;
}

// Prints `label` and `text` wrapped at 100 columns, continuation lines indented under the text.
void print_wrapped(const char* label, const std::string& text) {
    const std::string indent(std::strlen(label), ' ');
    std::string line = label;
    std::size_t pos = 0;
    bool first_word = true;
    while (pos < text.size()) {
        std::size_t end = text.find(' ', pos);
        if (end == std::string::npos) end = text.size();
        const std::string word = text.substr(pos, end - pos);
        pos = end + 1;
        if (!first_word && line.size() + 1 + word.size() > 100) {
            std::printf("%s\n", line.c_str());
            line = indent + word;
        } else {
            line += (first_word ? "" : " ") + word;
        }
        first_word = false;
    }
    std::printf("%s\n", line.c_str());
}

void print_help(const Method& m) {
    std::printf(
        "usage: %s MESH OUT\n"
        "\n"
        "Runs CGAL %s's Surface_mesh_parameterization on MESH (OFF, OBJ or PLY: a triangle mesh that is\n"
        "a topological disk) and writes OUT, a UV atlas in OBJ: a comment line, `v x y z` per vertex (the\n"
        "input's positions, %%.17g, bit for bit), `vt u v` per vertex (CGAL's UV, %%.17g), `f a/a b/b c/c`\n"
        "per face in the input's face and corner order (one chart, no seams).\n"
        "\n",
        program.c_str(), cgal_version());
    print_wrapped("method:  ", std::string(m.map) + ".");
    print_wrapped("CGAL:    ", m.classes);
    print_wrapped("border:  ", std::string(m.border_text) + ".");
    print_wrapped("CGAL promises: ", std::string(m.promise) + ".");
    std::printf(
        "\n"
        "exit codes: 0 OUT written; 2 usage error, unreadable MESH or unwritable OUT; 3 not applicable\n"
        "(MESH is not one component with one boundary loop and genus 0); 4 CGAL reported a failure.\n"
        "The compiled program is $FHR_PEERS_BIN/cgal_uv, else build/peers/cgal_uv of the repository.\n");
}

void print_methods() {
    std::printf(
        "usage: cgal_uv [--adapter NAME] METHOD MESH OUT | cgal_uv [--adapter NAME] METHOD --help\n"
        "methods (CGAL %s):\n",
        cgal_version());
    for (const Method& m : methods) std::printf("  %-18s %s\n", m.name, m.classes);
}

// Writes the atlas to OUT.tmp-PID and renames it to OUT; false with `problem` set on failure.
bool write_atlas(const std::string& out, const std::string& header, const TriangleSoup& soup,
                 const std::vector<double>& uv, std::string& problem) {
    std::string text = header;
    text.reserve(text.size() + soup.vertex_count() * 110 + soup.face_count() * 40);
    char buffer[160];
    for (std::size_t i = 0; i < soup.vertex_count(); ++i) {
        const int n = std::snprintf(buffer, sizeof buffer, "v %.17g %.17g %.17g\n", soup.xyz[3 * i],
                                    soup.xyz[3 * i + 1], soup.xyz[3 * i + 2]);
        text.append(buffer, static_cast<std::size_t>(n));
    }
    for (std::size_t i = 0; i < soup.vertex_count(); ++i) {
        const int n = std::snprintf(buffer, sizeof buffer, "vt %.17g %.17g\n", uv[2 * i], uv[2 * i + 1]);
        text.append(buffer, static_cast<std::size_t>(n));
    }
    for (std::size_t f = 0; f < soup.face_count(); ++f) {
        const unsigned a = soup.tri[3 * f] + 1, b = soup.tri[3 * f + 1] + 1, c = soup.tri[3 * f + 2] + 1;
        const int n = std::snprintf(buffer, sizeof buffer, "f %u/%u %u/%u %u/%u\n", a, a, b, b, c, c);
        text.append(buffer, static_cast<std::size_t>(n));
    }
    const std::string tmp = out + ".tmp-" + std::to_string(static_cast<long>(getpid()));
    std::FILE* file = std::fopen(tmp.c_str(), "wb");
    if (!file) {
        problem = "cannot write " + out + ": " + std::strerror(errno);
        return false;
    }
    const bool written = std::fwrite(text.data(), 1, text.size(), file) == text.size();
    const int write_errno = errno;
    const bool closed = std::fclose(file) == 0;
    if (!written || !closed) {
        problem = "cannot write " + out + ": " + std::strerror(written ? errno : write_errno);
        std::remove(tmp.c_str());
        return false;
    }
    if (std::rename(tmp.c_str(), out.c_str()) != 0) {
        problem = "cannot write " + out + ": " + std::strerror(errno);
        std::remove(tmp.c_str());
        return false;
    }
    return true;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    if (args.size() >= 2 && args[0] == "--adapter") {
        program = args[1];
        args.erase(args.begin(), args.begin() + 2);
    }
    if (args.empty() || args[0] == "--help" || args[0] == "-h") {
        print_methods();
        return args.empty() ? 2 : 0;
    }
    const Method* method = nullptr;
    for (const Method& m : methods)
        if (args[0] == m.name) method = &m;
    if (!method) return error(2, "unknown method '" + args[0] + "' (cgal_uv --help lists them)");
    args.erase(args.begin());
    if (program == "cgal_uv") program = std::string("cgal_uv ") + method->name;

    for (const std::string& a : args)
        if (a == "--help" || a == "-h") {
            print_help(*method);
            return 0;
        }
    if (args.size() != 2) return error(2, "usage: " + program + " MESH OUT (or --help)");
    for (const std::string& a : args)
        if (a.size() > 1 && a[0] == '-')
            return error(2, "unknown option '" + a + "' (usage: " + program + " MESH OUT)");
    const std::string& mesh_path = args[0];
    const std::string& out_path = args[1];
    if (out_path.empty()) return error(2, "OUT is empty");

    TriangleSoup soup;
    std::string problem;
    if (!read_mesh(mesh_path, soup, problem)) return error(2, problem);

    Outcome outcome = check_disk(soup);
    std::vector<double> uv;
    if (outcome.code == 0) {
        switch (method->family) {
            case Family::fixed: outcome = run_fixed_border(method->weights, method->border, soup, uv); break;
            case Family::free: outcome = run_free_border(method->free_method, soup, uv); break;
            case Family::post: outcome = run_lscm_mvc_post(soup, uv); break;
        }
    }
    if (outcome.code != 0) return error(outcome.code, mesh_path + ": " + outcome.message);
    if (!outcome.note.empty())
        std::fprintf(stderr, "%s: note: %s: %s\n", program.c_str(), mesh_path.c_str(), outcome.note.c_str());

    const std::string header = "# " + program + ": cgal_uv " + method->name + ", CGAL " + cgal_version() +
                               " Surface_mesh_parameterization " + method->classes + "\n";
    if (!write_atlas(out_path, header, soup, uv, problem)) return error(2, problem);
    return 0;
}
