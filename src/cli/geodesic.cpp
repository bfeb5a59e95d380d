// FHR cli — `fhr geodesic MESH SRC DST`: one shortest geodesic Γ(x_j, x_k) of paper §3 (eq. 1),
// found by the ellipse search (src/fhr/geodesic/ellipse.hpp): its exact length, its points, the K that
// was used and the work done.
#include <charconv>
#include <cstdio>

#include <fhr/geodesic/ellipse.hpp>
#include <fhr/io/detail/json.hpp>
#include "cli/common.hpp"

namespace fhr::cli {
namespace {

VertexId vertex_argument(const std::string& text, const std::string& what) {
    long long v = -1;
    const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
    if (r.ec != std::errc() || r.ptr != text.data() + text.size() || v < 0 || v > INT32_MAX)
        usage_error(what + " must be a vertex index, got '" + text + "'");
    return VertexId(static_cast<VertexId::Index>(v));
}

const char* kind_name(SurfacePoint::Kind k) {
    switch (k) {
        case SurfacePoint::Kind::vertex: return "vertex";
        case SurfacePoint::Kind::edge: return "edge";
        case SurfacePoint::Kind::face: return "face";
    }
    return "";
}

}  // namespace

int run_geodesic(const std::vector<std::string>& argv) {
    const Args args(argv, {"json"}, {"K"});
    if (args.positional().size() != 3) usage_error("fhr geodesic takes MESH SRC DST");
    const TriMesh T = load_mesh(args.positional()[0], BuildOptions{});
    const VertexId a = vertex_argument(args.positional()[1], "SRC"), b = vertex_argument(args.positional()[2], "DST");
    geodesic::EllipseOptions options;
    options.K = args.real("K", options.K, 1.0, 1e6);
    const geodesic::EllipsePath r = geodesic::ellipse_shortest_path(T, a, b, options);
    io::JsonWriter j;
    j.begin_object().key("source").value(a.idx()).key("target").value(b.idx());
    j.key("length").value(r.path.length).key("K").value(r.K).key("attempts").value(r.attempts);
    j.key("ellipse_faces").value(r.ellipse_faces).key("windows_created").value(r.windows_created);
    j.key("points").begin_array();
    for (const SurfacePoint& p : r.path.points) {
        const Vec3 x = position(T, p);
        j.begin_object().key("kind").value(kind_name(p.kind));
        if (p.kind == SurfacePoint::Kind::vertex)
            j.key("vertex").value(p.vertex.idx());
        else
            j.key("edge")
                .value(TriMesh::edge(p.halfedge).idx())
                .key("from")
                .value(T.from(p.halfedge).idx())
                .key("to")
                .value(T.to(p.halfedge).idx())
                .key("t")
                .value(p.t);
        j.key("xyz").begin_array().value(x.x()).value(x.y()).value(x.z()).end_array().end_object();
    }
    j.end_array().end_object();
    if (args.flag("json")) {
        std::fputs(j.str().c_str(), stdout);
        return 0;
    }
    std::printf(
        "geodesic %u -> %u: length %.17g\n  K %g after %zu ellipse(s) of which the last has %zu faces; "
        "%zu windows\n  %zu points:\n",
        a.idx(), b.idx(), r.path.length, r.K, r.attempts, r.ellipse_faces, r.windows_created, r.path.points.size());
    for (const SurfacePoint& p : r.path.points) {
        const Vec3 x = position(T, p);
        if (p.kind == SurfacePoint::Kind::vertex)
            std::printf("    vertex %u  (%.17g, %.17g, %.17g)\n", p.vertex.idx(), x.x(), x.y(), x.z());
        else
            std::printf("    edge %u-%u t=%.17g  (%.17g, %.17g, %.17g)\n", T.from(p.halfedge).idx(),
                        T.to(p.halfedge).idx(), p.t, x.x(), x.y(), x.z());
    }
    return 0;
}

}  // namespace fhr::cli
