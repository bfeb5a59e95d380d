// Beyond the paper (§3, keeping the domain): a region of T′ cut out on its own (see region.hpp).
#include <fhr/partition/detail/region.hpp>

#include <algorithm>
#include <iterator>

#include <fhr/core/errors.hpp>
#include <fhr/partition/detail/cut_disk.hpp>

namespace fhr::partition {
namespace {

// The faces of S: `touched`, the faces around their vertices, and all faces of any vertex whose
// faces in S form more than one fan (sorted).
std::vector<FaceId> closed_faces(const TriMesh& T, std::span<const FaceId> touched) {
    std::vector<FaceId> faces;
    auto add_star = [&](VertexId v) {
        T.for_each_outgoing(v, [&](HalfedgeId h) {
            if (T.face(h).valid()) faces.push_back(T.face(h));
        });
    };
    std::vector<VertexId> whole;  // the vertices whose stars are in S (sorted)
    for (FaceId f : touched)
        for (VertexId v : T.face_vertices(f)) whole.push_back(v);
    std::sort(whole.begin(), whole.end());
    whole.erase(std::unique(whole.begin(), whole.end()), whole.end());
    for (VertexId v : whole) add_star(v);
    for (bool grown = true; grown;) {
        std::sort(faces.begin(), faces.end());
        faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
        // Only a vertex whose star was not added whole can have several fans.
        std::vector<VertexId> all, vertices;
        for (FaceId f : faces)
            for (VertexId v : T.face_vertices(f)) all.push_back(v);
        std::sort(all.begin(), all.end());
        all.erase(std::unique(all.begin(), all.end()), all.end());
        std::set_difference(all.begin(), all.end(), whole.begin(), whole.end(), std::back_inserter(vertices));
        const std::size_t before = faces.size();
        for (VertexId v : vertices) {
            // Fans: the faces in S that follow a face not in S around v.
            std::size_t fans = 0;
            bool previous = false, first = false, seen = false;
            T.for_each_outgoing(v, [&](HalfedgeId h) {
                const FaceId f = T.face(h);
                const bool in = f.valid() && std::binary_search(faces.begin(),
                                                                faces.begin() + static_cast<std::ptrdiff_t>(before), f);
                if (!seen)
                    first = in, seen = true;
                else if (in && !previous)
                    ++fans;
                previous = in;
            });
            if (first && !previous) ++fans;
            if (fans > 1) add_star(v);
        }
        grown = faces.size() > before;
    }
    return faces;
}

}  // namespace

Outcome<Region> Region::cut_out(const TriMesh& T, std::span<const FaceId> touched,
                                std::span<const RegionCurve> curves) {
    Region r(T);
    r.t_face_ = closed_faces(T, touched);
    for (FaceId f : r.t_face_)
        for (VertexId v : T.face_vertices(f)) r.sub_of_.emplace_back(v.idx(), 0);
    std::sort(r.sub_of_.begin(), r.sub_of_.end());
    r.sub_of_.erase(std::unique(r.sub_of_.begin(), r.sub_of_.end()), r.sub_of_.end());
    std::vector<Vec3> positions;
    for (std::size_t i = 0; i < r.sub_of_.size(); ++i) {
        r.sub_of_[i].second = static_cast<VertexId::Index>(i);
        r.t_vertex_.emplace_back(r.sub_of_[i].first);
        positions.push_back(T.position(r.t_vertex_.back()));
    }
    std::vector<Triangle> triangles;
    for (FaceId f : r.t_face_) {
        const auto v = T.face_vertices(f);
        triangles.push_back({r.in_sub(v[0]).idx(), r.in_sub(v[1]).idx(), r.in_sub(v[2]).idx()});
    }
    r.sub_ = TriMesh::from_triangles(std::move(positions), triangles);
    for (const RegionCurve& c : curves)
        if (Outcome<std::monostate> converted = r.convert(c); !converted)
            return Outcome<Region>::failure(converted.why());
    if (Outcome<std::monostate> cut = r.recut(); !cut) return Outcome<Region>::failure(cut.why());
    return r;
}

Outcome<std::monostate> Region::add(const RegionCurve& curve) {
    if (Outcome<std::monostate> converted = convert(curve); !converted) return converted;
    return recut();
}

Outcome<std::monostate> Region::convert(const RegionCurve& c) {
    geodesic::GeodesicPath p;
    p.length = c.path->length;
    for (const SurfacePoint& q : c.path->points) {
        if (q.kind == SurfacePoint::Kind::vertex) {
            const std::optional<VertexId> v = find_sub(q.vertex);
            if (!v)
                return Outcome<std::monostate>::failure(
                    "a curve passes a vertex of T outside the faces around the region");
            p.points.push_back(SurfacePoint::at_vertex(*v));
            continue;
        }
        HalfedgeId h;
        if (q.kind == SurfacePoint::Kind::edge) {
            const std::optional<VertexId> a = find_sub(T_.from(q.halfedge)), b = find_sub(T_.to(q.halfedge));
            if (a && b) h = sub_.find_halfedge(*a, *b);
        }
        if (!h.valid()) return Outcome<std::monostate>::failure("a curve leaves the faces around the region");
        p.points.push_back(SurfacePoint::on_edge(h, q.t));
    }
    for (std::size_t i = 1; i < p.points.size(); ++i)
        if (!share_face(sub_, p.points[i - 1], p.points[i]))
            return Outcome<std::monostate>::failure("a curve leaves the faces around the region");
    curves_.push_back(std::move(p));
    unsnapped_.push_back(!c.snapped);
    return std::monostate{};
}

Outcome<std::monostate> Region::recut() {
    cut_ = embed_curves(sub_, curves_, unsnapped_);
    if (!cut_.conflicts.empty())
        return Outcome<std::monostate>::failure("the curves around a region conflict: " +
                                                cut_.conflicts.front().describe());
    return std::monostate{};
}

std::optional<VertexId> Region::find_sub(VertexId v) const {
    const auto it = std::lower_bound(sub_of_.begin(), sub_of_.end(), std::make_pair(v.idx(), VertexId::Index{0}));
    if (it == sub_of_.end() || it->first != v.idx()) return std::nullopt;
    return VertexId(it->second);
}

VertexId Region::in_sub(VertexId v) const {
    const std::optional<VertexId> s = find_sub(v);
    if (!s)
        throw InternalError("region: vertex " + std::to_string(v.idx()) +
                            " of T is outside the faces around the region");
    return *s;
}

SurfacePoint Region::in_t(const SurfacePoint& p) const {
    if (p.kind == SurfacePoint::Kind::vertex) return SurfacePoint::at_vertex(in_t(p.vertex));
    if (p.kind != SurfacePoint::Kind::edge) throw InternalError("region: a point inside a face");
    return SurfacePoint::on_edge(T_.find_halfedge(in_t(sub_.from(p.halfedge)), in_t(sub_.to(p.halfedge))), p.t);
}

Outcome<FaceData<std::uint8_t>> Region::side(std::size_t curve, bool left) const {
    const Network& net = cut_.network;
    const TriMesh& M = net.mesh;
    const auto& path = net.path.at(DEdgeId(static_cast<DEdgeId::Index>(curve)));
    const HalfedgeId h = M.find_halfedge(path[0], path[1]);
    const FaceId seed = M.face(left ? h : TriMesh::twin(h));
    FaceData<std::uint8_t> mask(M.n_faces(), 0);
    std::vector<FaceId> stack{seed};
    if (!seed.valid())
        return Outcome<FaceData<std::uint8_t>>::failure("a curve on the border of the faces around the region");
    mask[seed] = 1;
    while (!stack.empty()) {
        const FaceId f = stack.back();
        stack.pop_back();
        HalfedgeId g = M.halfedge(f);
        for (int i = 0; i < 3; ++i, g = M.next(g)) {
            if (net.d_halfedge[g].valid()) continue;
            const FaceId n = M.face(TriMesh::twin(g));
            if (!n.valid()) return Outcome<FaceData<std::uint8_t>>::failure("the curves do not enclose the region");
            if (!mask[n]) {
                mask[n] = 1;
                stack.push_back(n);
            }
        }
    }
    return mask;
}

Outcome<Patch> Region::patch(const FaceData<std::uint8_t>& mask,
                             const std::array<std::pair<std::size_t, bool>, 3>& sides) const {
    const Network& net = cut_.network;
    std::vector<FaceId> faces;
    for (FaceId f : net.mesh.faces())
        if (mask[f]) faces.push_back(f);
    std::array<std::vector<VertexId>, 3> curves;
    for (std::size_t c = 0; c < 3; ++c) {
        curves[c] = net.path.at(DEdgeId(static_cast<DEdgeId::Index>(sides[c].first)));
        if (sides[c].second) std::reverse(curves[c].begin(), curves[c].end());
    }
    std::vector<std::int32_t> local(net.mesh.n_vertices(), -1);
    return cut_disk(net.mesh, net.d_halfedge, std::move(faces), {curves[0], curves[1], curves[2]}, local);
}

std::vector<FaceId> Region::t_faces(const FaceData<std::uint8_t>& mask) const {
    std::vector<FaceId> faces;
    for (FaceId f : cut_.network.t_face.ids())
        if (mask[f]) faces.push_back(t_face_[cut_.network.t_face[f].idx()]);
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    return faces;
}

}  // namespace fhr::partition
