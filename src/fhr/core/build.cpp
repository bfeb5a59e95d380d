// FHR core — the input rules of spec/mesh.md, checked in this order (the first broken one is
// reported, naming file, line and element in the soup's own numbering, 0-based):
//   INV-IN-1  coordinates finite and |x| <= 1e150 (squared lengths cannot overflow)
//   INV-IN-2  every face has at least 3 vertices, none repeated
//   INV-IN-3  faces are triangles (or --triangulate: fan from the first vertex)
//   INV-IN-12 no isolated vertices (else dropped, with a warning)
//   INV-IN-4  no two faces have the same vertex set
//   INV-IN-5  no triangle is degenerate (its corners exactly collinear; exact predicate)
//   INV-IN-6  every edge lies in at most two faces
//   INV-IN-7  the surface is orientable
//   INV-IN-8  faces are consistently oriented, outward (else re-oriented, with a warning)
//   INV-IN-9  every vertex is manifold: its faces form one fan
//   INV-IN-10 no boundary, when asked for (BuildOptions::require_closed)
//   INV-IN-11 one connected component, when asked for (BuildOptions::require_connected)
//   INV-IN-13 no closed component is flat (its vertices are not all in one plane)
#include <fhr/core/build.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include <fhr/core/detail/edge_table.hpp>
#include <fhr/core/errors.hpp>
#include <fhr/core/geometry.hpp>
#include <fhr/core/detail/predicates.hpp>
#include <fhr/core/topology.hpp>

namespace fhr {
namespace {

class Builder {
public:
    Builder(const PolygonSoup& soup, const BuildOptions& options, BuildLog& log)
        : soup_(soup), options_(options), log_(log) {}

    TriMesh run() {
        check_coordinates();
        collect_triangles();
        if (tris_.empty()) fail(0, "no faces");
        drop_isolated_vertices();
        detail::EdgeTable table = detail::build_edge_table(positions_.size(), tris_);
        check_duplicates(table);
        if (options_.refuse_degenerate) check_degenerate();
        check_edge_manifold(table);
        if (orient(table)) table = detail::build_edge_table(positions_.size(), tris_);  // corners moved
        TriMesh mesh = TriMesh::from_triangles(std::move(positions_), tris_, table);
        if (const std::uint32_t v = detail::first_non_manifold_vertex(mesh, tris_); v != UINT32_MAX)
            fail_vertex(v, "non-manifold vertex " + vname(v) + ": its faces form more than one fan");
        check_closed_and_connected(mesh);
        log_.vertex_origin = VertexData<std::uint32_t>(std::move(origin_));
        return mesh;
    }

private:
    const PolygonSoup& soup_;
    const BuildOptions& options_;
    BuildLog& log_;
    std::vector<Triangle> tris_;              // in soup point numbering until drop_isolated_vertices
    std::vector<std::uint32_t> tri_polygon_;  // soup polygon of each triangle
    std::vector<Vec3> positions_;
    std::vector<std::uint32_t> origin_;  // soup point of each kept vertex
    std::size_t components_ = 0;         // connected components, counted by orient()

    [[noreturn]] void fail(std::uint64_t line, const std::string& what) const {
        throw InvalidInput(soup_.source, line, what);
    }
    std::uint64_t polygon_line(std::size_t p) const { return soup_.polygon_line.empty() ? 0 : soup_.polygon_line[p]; }
    std::uint64_t point_line(std::size_t v) const { return soup_.point_line.empty() ? 0 : soup_.point_line[v]; }
    [[noreturn]] void fail_face(std::uint32_t t, const std::string& what) const {
        fail(polygon_line(tri_polygon_[t]), what);
    }
    // After drop_isolated_vertices, mesh vertex v is soup point origin_[v]; messages use soup numbers.
    std::uint32_t soup_vertex(std::uint32_t v) const { return origin_.empty() ? v : origin_[v]; }
    std::string vname(std::uint32_t v) const { return std::to_string(soup_vertex(v)); }
    [[noreturn]] void fail_vertex(std::uint32_t v, const std::string& what) const {
        fail(point_line(soup_vertex(v)), what);
    }
    std::string fname(std::uint32_t t) const { return "face " + std::to_string(tri_polygon_[t]); }
    std::string tri_vertices(std::uint32_t t) const {
        return vname(tris_[t][0]) + ", " + vname(tris_[t][1]) + ", " + vname(tris_[t][2]);
    }

    void check_coordinates() const {  // INV-IN-1
        for (std::size_t v = 0; v < soup_.points.size(); ++v) {
            const Vec3& p = soup_.points[v];
            if (!p.allFinite()) fail(point_line(v), "vertex " + std::to_string(v) + " has a non-finite coordinate");
            if (p.cwiseAbs().maxCoeff() > max_coordinate)
                fail(point_line(v), "vertex " + std::to_string(v) +
                                        " has a coordinate above 1e150 in magnitude: lengths would overflow");
        }
    }

    void collect_triangles() {  // INV-IN-2, INV-IN-3
        tris_.reserve(soup_.polygon_count());
        tri_polygon_.reserve(soup_.polygon_count());
        for (std::size_t p = 0; p < soup_.polygon_count(); ++p) {
            const std::uint32_t n = soup_.polygon_size(p);
            const std::uint32_t* idx = soup_.polygon(p);
            const auto name = [p] { return "face " + std::to_string(p); };
            if (n < 3)
                fail(polygon_line(p), name() + " has " + std::to_string(n) + " vertices (at least 3 are needed)");
            for (std::uint32_t i = 0; i < n; ++i)
                for (std::uint32_t j = i + 1; j < n; ++j)
                    if (idx[i] == idx[j]) fail(polygon_line(p), name() + " repeats vertex " + std::to_string(idx[i]));
            if (n > 3 && !options_.triangulate)
                fail(polygon_line(p), name() + " has " + std::to_string(n) +
                                          " vertices: only triangles are accepted (use --triangulate)");
            for (std::uint32_t i = 1; i + 1 < n; ++i) {
                tris_.push_back({idx[0], idx[i], idx[i + 1]});
                tri_polygon_.push_back(static_cast<std::uint32_t>(p));
            }
        }
    }

    // INV-IN-4: two faces with the same vertex set share all their edges, so it suffices to
    // compare the faces around each edge (sorted, so a huge fan still costs O(d log d)).
    void check_duplicates(const detail::EdgeTable& table) const {
        std::vector<std::pair<Triangle, std::uint32_t>> around;
        for (std::uint32_t e = 0; e < table.n_edges(); ++e) {
            const std::uint32_t degree = table.edge_degree(e);
            if (degree < 2) continue;
            const std::uint32_t* c = &table.edge_corners[table.edge_offsets[e]];
            if (degree == 2) {  // the usual case: two faces on the edge, the same set when their third vertices are
                const std::uint32_t a = c[0] / 3, b = c[1] / 3;
                if (tris_[a][(c[0] + 2) % 3] == tris_[b][(c[1] + 2) % 3])
                    fail_face(std::max(a, b), "faces " + std::to_string(tri_polygon_[std::min(a, b)]) + " and " +
                                                  std::to_string(tri_polygon_[std::max(a, b)]) +
                                                  " are duplicates (vertices " + tri_vertices(std::max(a, b)) + ")");
                continue;
            }
            around.clear();
            for (std::uint32_t i = table.edge_offsets[e]; i < table.edge_offsets[e + 1]; ++i) {
                const std::uint32_t t = table.edge_corners[i] / 3;
                Triangle k = tris_[t];
                std::sort(k.begin(), k.end());
                around.emplace_back(k, t);
            }
            std::sort(around.begin(), around.end());
            for (std::size_t i = 1; i < around.size(); ++i)
                if (around[i].first == around[i - 1].first) {
                    const std::uint32_t a = around[i - 1].second, b = around[i].second;
                    fail_face(b, "faces " + std::to_string(tri_polygon_[a]) + " and " +
                                     std::to_string(tri_polygon_[b]) + " are duplicates (vertices " + tri_vertices(b) +
                                     ")");
                }
        }
    }

    void drop_isolated_vertices() {  // INV-IN-12
        std::vector<std::uint32_t> remap(soup_.points.size(), UINT32_MAX);
        for (const Triangle& t : tris_)
            for (auto v : t) remap[v] = 0;
        for (std::uint32_t v = 0; v < remap.size(); ++v) {
            if (remap[v] == UINT32_MAX) continue;
            remap[v] = static_cast<std::uint32_t>(origin_.size());
            origin_.push_back(v);
            positions_.push_back(soup_.points[v]);
        }
        const std::size_t dropped = soup_.points.size() - origin_.size();
        if (dropped > 0) {
            const auto first = std::find(remap.begin(), remap.end(), UINT32_MAX) - remap.begin();
            log_.dropped_vertices = dropped;
            log_.warnings.push_back(soup_.source + ": dropped " + std::to_string(dropped) +
                                    " isolated vertices (first: vertex " + std::to_string(first) + ")");
        }
        for (Triangle& t : tris_)
            for (auto& v : t) v = remap[v];
    }

    void check_degenerate() const {  // INV-IN-5
        for (std::uint32_t t = 0; t < tris_.size(); ++t) {
            const Triangle& v = tris_[t];
            if (collinear(positions_[v[0]], positions_[v[1]], positions_[v[2]]))
                fail_face(t, fname(t) + " is degenerate: its vertices " + tri_vertices(t) + " are collinear");
        }
    }

    void check_edge_manifold(const detail::EdgeTable& table) const {  // INV-IN-6
        for (std::uint32_t e = 0; e < table.n_edges(); ++e) {
            const std::uint32_t deg = table.edge_degree(e);
            if (deg <= 2) continue;
            const std::uint32_t* c = &table.edge_corners[table.edge_offsets[e]];
            std::string faces;
            for (std::uint32_t i = 0; i < deg; ++i) faces += (i ? ", " : "") + std::to_string(tri_polygon_[c[i] / 3]);
            fail_face(c[2] / 3, "non-manifold edge (" + vname(detail::corner_tail(tris_, c[0])) + ", " +
                                    vname(detail::corner_head(tris_, c[0])) + ") is shared by " + std::to_string(deg) +
                                    " faces (" + faces + ")");
        }
    }

    // INV-IN-7, INV-IN-8: give every face of a component the orientation of its lowest face
    // (breadth-first over shared edges); a contradiction means the surface is not orientable.
    // A closed component with negative volume is then turned inside out, so normals face outward.
    // Returns whether any face was turned.
    bool orient(const detail::EdgeTable& table) {
        const std::size_t nf = tris_.size();
        std::vector<std::int8_t> flip(nf, -1);
        std::vector<std::uint32_t> queue, component_faces;
        std::size_t changed = 0;
        components_ = 0;
        std::uint32_t first_changed = UINT32_MAX;
        for (std::uint32_t root = 0; root < nf; ++root) {
            if (flip[root] >= 0) continue;
            ++components_;
            flip[root] = 0;
            queue.assign(1, root);
            bool closed = true;
            for (std::size_t qi = 0; qi < queue.size(); ++qi) {
                const std::uint32_t f = queue[qi];
                for (std::uint32_t k = 0; k < 3; ++k) {
                    const std::uint32_t c = 3 * f + k, e = table.corner_edge[c];
                    if (table.edge_degree(e) == 1) {
                        closed = false;
                        continue;
                    }
                    const std::uint32_t* pair = &table.edge_corners[table.edge_offsets[e]];
                    const std::uint32_t o = pair[0] == c ? pair[1] : pair[0], g = o / 3;
                    const bool same_direction = detail::corner_tail(tris_, c) == detail::corner_tail(tris_, o);
                    const std::int8_t want = static_cast<std::int8_t>(flip[f] ^ (same_direction ? 1 : 0));
                    if (flip[g] < 0) {
                        flip[g] = want;
                        queue.push_back(g);
                    } else if (flip[g] != want) {
                        fail_face(g, "the surface is not orientable (contradiction at edge (" +
                                         vname(detail::corner_tail(tris_, c)) + ", " +
                                         vname(detail::corner_head(tris_, c)) + ") between faces " +
                                         std::to_string(tri_polygon_[f]) + " and " + std::to_string(tri_polygon_[g]) +
                                         ")");
                    }
                }
            }
            if (closed && component_volume(queue, flip) < 0)
                for (std::uint32_t f : queue) flip[f] ^= 1;
            for (std::uint32_t f : queue)
                if (flip[f]) {
                    ++changed;
                    first_changed = std::min(first_changed, f);
                }
        }
        for (std::uint32_t f = 0; f < nf; ++f)
            if (flip[f]) std::swap(tris_[f][1], tris_[f][2]);
        if (changed > 0) {
            log_.reoriented_faces = changed;
            log_.warnings.push_back(soup_.source + ": re-oriented " + std::to_string(changed) +
                                    " faces to a consistent outward orientation (first: face " +
                                    std::to_string(tri_polygon_[first_changed]) + ")");
        }
        return changed > 0;
    }

    double component_volume(const std::vector<std::uint32_t>& faces, const std::vector<std::int8_t>& flip) const {
        const Vec3 c = positions_[tris_[faces[0]][0]];
        double six_v = 0;
        for (std::uint32_t f : faces) {
            const Triangle& t = tris_[f];
            const double v = (positions_[t[0]] - c).dot((positions_[t[1]] - c).cross(positions_[t[2]] - c));
            six_v += flip[f] ? -v : v;
        }
        return six_v;
    }

    void check_closed_and_connected(const TriMesh& mesh) const {  // INV-IN-10, INV-IN-11
        if (options_.require_closed) {
            const auto loops = boundary_loops(mesh);
            if (!loops.empty()) {
                const HalfedgeId h = loops.front();
                fail(0, "the mesh has boundary (" + std::to_string(loops.size()) + " boundary loop" +
                            (loops.size() > 1 ? "s" : "") + ", the first through edge (" + vname(mesh.from(h).idx()) +
                            ", " + vname(mesh.to(h).idx()) + ")): the method needs a closed surface");
            }
        }
        if (options_.require_connected) {
            if (components_ > 1) {  // found by orient(); connected_components names a vertex
                const Components comp = connected_components(mesh);
                const auto other = std::find_if(comp.vertex_component.begin(), comp.vertex_component.end(),
                                                [](std::uint32_t c) { return c != 0; }) -
                                   comp.vertex_component.begin();
                fail(0, "the mesh has " + std::to_string(comp.count) + " connected components (vertex " +
                            vname(static_cast<std::uint32_t>(other)) + " is not connected to vertex " + vname(0) + ")");
            }
        }
        check_not_flat(mesh);
    }

    // INV-IN-13: a closed component with every vertex in one plane (exact orient3d) encloses no
    // volume: its faces cover a flat region twice, front and back, which §3 cannot partition. (A
    // component with boundary may be flat: a disk in the plane is a surface like any other.)
    void check_not_flat(const TriMesh& mesh) const {
        const Components comp = connected_components(mesh);
        std::vector<std::uint8_t> open(comp.count, 0), off_plane(comp.count, 0);
        std::vector<FaceId> first(comp.count);
        for (HalfedgeId h : mesh.halfedges())
            if (mesh.is_boundary(h)) open[comp.vertex_component[mesh.from(h)]] = 1;
        for (FaceId f : mesh.faces()) {
            FaceId& lowest = first[comp.vertex_component[mesh.face_vertices(f)[0]]];
            if (!lowest.valid()) lowest = f;
        }
        for (VertexId v : mesh.vertices()) {
            const std::uint32_t c = comp.vertex_component[v];
            if (open[c] || off_plane[c]) continue;
            const auto corners = mesh.face_vertices(first[c]);
            off_plane[c] = orient3d(mesh.position(corners[0]), mesh.position(corners[1]), mesh.position(corners[2]),
                                    mesh.position(v)) != 0;
        }
        for (std::uint32_t c = 0; c < comp.count; ++c) {
            if (open[c] || off_plane[c]) continue;
            std::size_t n = 0, lowest = comp.vertex_component.size();
            for (std::size_t v = comp.vertex_component.size(); v-- > 0;)
                if (comp.vertex_component[VertexId(static_cast<VertexId::Index>(v))] == c) ++n, lowest = v;
            fail(0, (comp.count == 1 ? std::string("the closed surface")
                                     : "the closed component at vertex " + vname(static_cast<std::uint32_t>(lowest))) +
                        " is flat: all " + std::to_string(n) + " vertices lie in the plane of face " +
                        std::to_string(first[c].idx()) + ", so its faces cover a flat region twice");
        }
    }
};

}  // namespace

TriMesh build_trimesh(const PolygonSoup& soup, const BuildOptions& options, BuildLog& log) {
    return Builder(soup, options, log).run();
}

}  // namespace fhr
