// FHR generate — guarded local edits for the valence and density families (detail/editor.hpp):
// each edit is described as the faces it removes and the triangles it adds, offered to the
// EmbeddingGuard, and applied only if accepted, with the guard told which faces changed.
#include <fhr/generate/detail/editor.hpp>

#include <array>

#include <fhr/core/topology.hpp>

namespace fhr::generate::detail {

GuardedEditor::GuardedEditor(TriMesh m) : m_(std::move(m)), guard_(m_, 0) {
    const Components comps = connected_components(m_);
    components_ = comps.count;
    component_.assign(comps.vertex_component.begin(), comps.vertex_component.end());
}

namespace {

TriangleAt at(VertexId a, VertexId b, VertexId c, const Vec3& pa, const Vec3& pb, const Vec3& pc) {
    return {{a, b, c}, {pa, pb, pc}};
}

}  // namespace

bool GuardedEditor::flip(EdgeId e) {
    if (!m_.is_flip_ok(e)) return false;
    const HalfedgeId h = TriMesh::halfedge(e, 0), o = TriMesh::halfedge(e, 1);
    const VertexId a = m_.from(h), b = m_.to(h), c = m_.to(m_.next(h)), d = m_.to(m_.next(o));
    const auto& p = [&](VertexId v) -> const Vec3& { return m_.position(v); };
    const std::array<FaceId, 2> removed{m_.face(h), m_.face(o)};
    const std::array<TriangleAt, 2> added{at(a, d, c, p(a), p(d), p(c)), at(d, b, c, p(d), p(b), p(c))};
    if (!guard_.accepts(m_, removed, added)) return false;
    for (FaceId f : removed) guard_.remove(m_, f);
    m_.flip(e);
    for (FaceId f : removed) guard_.insert(m_, f);
    return true;
}

VertexId GuardedEditor::split_face(FaceId f, const Vec3& x) {
    const auto v = m_.face_vertices(f);
    const VertexId n(static_cast<VertexId::Index>(m_.n_vertices()));
    const auto& p = [&](VertexId u) -> const Vec3& { return m_.position(u); };
    const std::array<FaceId, 1> removed{f};
    const std::array<TriangleAt, 3> added{at(v[0], v[1], n, p(v[0]), p(v[1]), x),
                                          at(v[1], v[2], n, p(v[1]), p(v[2]), x),
                                          at(v[2], v[0], n, p(v[2]), p(v[0]), x)};
    if (!guard_.accepts(m_, removed, added)) return VertexId();
    const std::uint32_t comp = component_[v[0].idx()];
    const std::size_t faces_before = m_.n_faces();
    guard_.remove(m_, f);
    const VertexId added_vertex = m_.split_face(f, x);
    component_.push_back(comp);
    guard_.insert(m_, f);
    for (std::size_t g = faces_before; g < m_.n_faces(); ++g) guard_.insert(m_, FaceId(static_cast<FaceId::Index>(g)));
    return added_vertex;
}

VertexId GuardedEditor::split_edge(EdgeId e, const Vec3& x) {
    const HalfedgeId h = TriMesh::halfedge(e, 0), o = TriMesh::halfedge(e, 1);
    const VertexId a = m_.from(h), b = m_.to(h), c = m_.to(m_.next(h)), d = m_.to(m_.next(o));
    const VertexId n(static_cast<VertexId::Index>(m_.n_vertices()));
    const auto& p = [&](VertexId u) -> const Vec3& { return m_.position(u); };
    // split_edge's four triangles: (a, m, c), (m, b, c) from face(h); (b, m, d), (m, a, d) from face(o).
    const std::array<FaceId, 2> removed{m_.face(h), m_.face(o)};
    const std::array<TriangleAt, 4> added{at(a, n, c, p(a), x, p(c)), at(n, b, c, x, p(b), p(c)),
                                          at(b, n, d, p(b), x, p(d)), at(n, a, d, x, p(a), p(d))};
    if (!guard_.accepts(m_, removed, added)) return VertexId();
    const std::uint32_t comp = component_[a.idx()];
    const std::size_t faces_before = m_.n_faces();
    for (FaceId f : removed) guard_.remove(m_, f);
    const VertexId added_vertex = m_.split_edge(e, x);
    component_.push_back(comp);
    for (FaceId f : removed) guard_.insert(m_, f);
    for (std::size_t g = faces_before; g < m_.n_faces(); ++g) guard_.insert(m_, FaceId(static_cast<FaceId::Index>(g)));
    return added_vertex;
}

TriMesh GuardedEditor::finish() {
    // Counting sort by component: vertices, then faces (a face's component is its first vertex's).
    const std::size_t nv = m_.n_vertices(), C = components_;
    std::vector<std::size_t> first(C + 1, 0);
    for (std::size_t v = 0; v < nv; ++v) ++first[component_[v] + 1];
    for (std::size_t c = 0; c < C; ++c) first[c + 1] += first[c];
    std::vector<std::uint32_t> renumbered(nv);
    std::vector<Vec3> positions(nv);
    for (std::size_t v = 0; v < nv; ++v) {
        const std::size_t slot = first[component_[v]]++;
        renumbered[v] = static_cast<std::uint32_t>(slot);
        positions[slot] = m_.positions()[v];
    }
    const std::vector<Triangle> old = m_.triangles();
    std::vector<std::size_t> face_first(C + 1, 0);
    for (const Triangle& t : old) ++face_first[component_[t[0]] + 1];
    for (std::size_t c = 0; c < C; ++c) face_first[c + 1] += face_first[c];
    std::vector<Triangle> triangles(old.size());
    for (const Triangle& t : old)
        triangles[face_first[component_[t[0]]]++] = {renumbered[t[0]], renumbered[t[1]], renumbered[t[2]]};
    m_ = TriMesh();
    component_.clear();
    return TriMesh::from_triangles(std::move(positions), triangles);
}

}  // namespace fhr::generate::detail
