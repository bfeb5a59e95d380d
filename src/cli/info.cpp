// FHR cli — `fhr info`: the facts about T that the paper's method depends on (§1: a closed,
// orientable manifold triangulation; §2: its topology, χ = 2 − 2g, which the domain D must share).
// A file that is not a valid input still gets every count that can be computed, plus the reason.
#include <cstdio>
#include <numbers>
#include <optional>

#include <fhr/core/errors.hpp>
#include <fhr/core/geometry.hpp>
#include <fhr/core/topology.hpp>
#include <fhr/io/detail/json.hpp>
#include <fhr/io/read.hpp>
#include "cli/common.hpp"

namespace fhr::cli {
namespace {

struct Facts {
    std::size_t soup_points = 0, soup_polygons = 0;
    std::optional<TriMesh> mesh;  // built leniently (boundary, components, degeneracy allowed)
    std::string reason;           // why the file is not a valid input ("" if it is)
    BuildLog log;
};

void write_vec(io::JsonWriter& j, const Vec3& v) { j.begin_array().value(v.x()).value(v.y()).value(v.z()).end_array(); }

std::string print_human(const std::string& path, const Facts& f) {
    std::string s = path + "\n";
    auto line = [&](const char* key, const std::string& value) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "  %-16s", key);
        s += buf + value + "\n";
    };
    auto num = [](double x) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.6g", x);
        return std::string(buf);
    };
    if (!f.mesh) {
        line("points", std::to_string(f.soup_points));
        line("polygons", std::to_string(f.soup_polygons));
    } else {
        const TriMesh& m = *f.mesh;
        line("vertices", std::to_string(m.n_vertices()));
        line("edges", std::to_string(m.n_edges()));
        line("faces", std::to_string(m.n_faces()));
        line("euler", std::to_string(euler_characteristic(m)));
        line("genus", std::to_string(genus(m)));
        line("components", std::to_string(connected_components(m).count));
        line("boundary loops", std::to_string(boundary_loops(m).size()));
        const BoundingBox b = bounding_box(m);
        line("bounding box", "[" + num(b.min.x()) + ", " + num(b.min.y()) + ", " + num(b.min.z()) + "] .. [" +
                                 num(b.max.x()) + ", " + num(b.max.y()) + ", " + num(b.max.z()) + "], diagonal " +
                                 num(b.diagonal()));
        const EdgeLengthStats e = edge_length_stats(m);
        line("edge length", "min " + num(e.min) + ", mean " + num(e.mean) + ", median " + num(e.median) + ", max " +
                                num(e.max) + ", max/min " + num(e.max / e.min));
        const ShapeStats q = shape_stats(m);
        line("corner angle", "min " + num(q.min_angle * 180 / std::numbers::pi) + " deg, max " +
                                 num(q.max_angle * 180 / std::numbers::pi) + " deg");
        line("valence", "min " + std::to_string(q.min_valence) + ", max " + std::to_string(q.max_valence));
    }
    line("valid input", f.reason.empty() ? "yes" : "no: " + f.reason);
    return s;
}

std::string print_json(const std::string& path, const Facts& f) {
    io::JsonWriter j;
    j.begin_object().key("file").value(path);
    j.key("points").value(f.soup_points).key("polygons").value(f.soup_polygons);
    if (f.mesh) {
        const TriMesh& m = *f.mesh;
        j.key("vertices").value(m.n_vertices()).key("edges").value(m.n_edges()).key("faces").value(m.n_faces());
        j.key("euler_characteristic").value(euler_characteristic(m)).key("genus").value(genus(m));
        j.key("components").value(connected_components(m).count);
        j.key("boundary_loops").value(boundary_loops(m).size());
        const BoundingBox b = bounding_box(m);
        j.key("bounding_box").begin_object().key("min");
        write_vec(j, b.min);
        j.key("max");
        write_vec(j, b.max);
        j.key("diagonal").value(b.diagonal()).end_object();
        const EdgeLengthStats e = edge_length_stats(m);
        j.key("edge_length").begin_object().key("min").value(e.min).key("mean").value(e.mean);
        j.key("median").value(e.median).key("max").value(e.max).end_object();
        const ShapeStats q = shape_stats(m);
        j.key("corner_angle_deg").begin_object().key("min").value(q.min_angle * 180 / std::numbers::pi);
        j.key("max").value(q.max_angle * 180 / std::numbers::pi).end_object();
        j.key("valence").begin_object().key("min").value(q.min_valence).key("max").value(q.max_valence).end_object();
    }
    j.key("dropped_isolated_vertices").value(f.log.dropped_vertices);
    j.key("reoriented_faces").value(f.log.reoriented_faces);
    j.key("valid").value(f.reason.empty());
    if (f.reason.empty())
        j.key("reason").null();
    else
        j.key("reason").value(f.reason);
    j.end_object();
    return j.str();
}

}  // namespace

int run_info(const std::vector<std::string>& argv) {
    const Args args(argv, {"json", "triangulate"}, {});
    const std::string& path = args.single_positional("MESH");
    const PolygonSoup soup = io::read_soup(path);  // unreadable files: one-line error, exit 2
    Facts f;
    f.soup_points = soup.points.size();
    f.soup_polygons = soup.polygon_count();
    BuildOptions strict;
    strict.triangulate = args.flag("triangulate");
    try {
        f.mesh = build_trimesh(soup, strict, f.log);
    } catch (const InvalidInput& e) {
        f.reason = e.what();
        BuildOptions lenient = strict;
        lenient.refuse_degenerate = false;
        lenient.triangulate = true;  // topology does not depend on how polygons are split
        f.log = BuildLog();
        try {
            f.mesh = build_trimesh(soup, lenient, f.log);
        } catch (const InvalidInput&) {
            // Not even a manifold: only the soup's counts can be reported.
        }
    }
    print_warnings(f.log);
    std::fputs((args.flag("json") ? print_json(path, f) : print_human(path, f)).c_str(), stdout);
    if (!f.reason.empty()) {
        std::fprintf(stderr, "fhr: error: %s\n", f.reason.c_str());
        return 2;
    }
    return 0;
}

}  // namespace fhr::cli
