// FHR §3 — the ellipse search for Γ(x_j, x_k) (see ellipse.hpp and paper_notes/ellipse.md).
#include <fhr/geodesic/ellipse.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include <fhr/core/errors.hpp>
#include <fhr/geodesic/detail/scratch.hpp>
#include <fhr/geodesic/detail/fast_marching.hpp>

namespace fhr::geodesic {
namespace {

/// The certificate search compares lengths of two runs of the exact algorithm, each carrying a
/// relative rounding error of about k·2⁻⁵² after k unfoldings (k <= 10⁴ on our meshes, so
/// <= 2.3·10⁻¹²): it prunes above L(1 + margin) and calls a path shorter only below L(1 − margin),
/// the exact algorithm's own filter_tolerance (paper_notes/exact_geodesics.md, "Tolerances").
constexpr double certificate_margin = 1e-11;

// A face is outside T_jk when the mask leaves it out (a real hole of T is not outside).
bool outside(const TriMesh& mesh, const FaceData<std::uint8_t>& mask, HalfedgeId h) {
    return !mesh.is_boundary(h) && !mask[mesh.face(h)];
}

// The paper's test: the path touches a vertex of the artificial boundary, or runs along an edge
// next to a left-out face.
bool touches_boundary(const TriMesh& mesh, const FaceData<std::uint8_t>& mask, const GeodesicPath& path) {
    for (const SurfacePoint& p : path.points) {
        if (p.kind == SurfacePoint::Kind::vertex) {
            bool touches = false;
            mesh.for_each_outgoing(p.vertex, [&](HalfedgeId h) { touches = touches || outside(mesh, mask, h); });
            if (touches) return true;
        } else if (p.kind == SurfacePoint::Kind::edge) {
            if (outside(mesh, mask, p.halfedge) || outside(mesh, mask, TriMesh::twin(p.halfedge))) return true;
        }
    }
    return false;
}

// Some face of T_jk has a neighbour of T outside it (a hole of T is no neighbour): T_jk has an
// artificial border, and a larger K can still add faces.
bool has_border(const TriMesh& mesh, const FaceData<std::uint8_t>& mask, const std::vector<FaceId>& in) {
    for (FaceId f : in) {
        const HalfedgeId h0 = mesh.halfedge(f);
        for (HalfedgeId h = h0;;) {
            if (outside(mesh, mask, TriMesh::twin(h))) return true;
            if ((h = mesh.next(h)) == h0) break;
        }
    }
    return false;
}

// The face mask of T_jk, borrowed clean (all zero) from the workspace (workspace.hpp): an array
// of #F entries per path would cost more than the ellipse on a large mesh. `in` lists the faces
// set to 1. The ellipse only grows with K (the fields are fixed, the bound grows), so the mask is
// only ever added to.
struct MaskScratch final : detail::ScratchBase {
    FaceData<std::uint8_t> mask;
    std::vector<FaceId> in;
    void fit(std::size_t n) { mask.resize(n, 0); }  // clean, so shrinking or growing keeps it clean
    void reset() noexcept {
        for (FaceId f : in) mask[f] = 0;
        detail::clear_buffer(in);
    }
};

// d_a from b at the vertices of a field, borrowed clean (INFINITY) from the workspace; `touched`
// lists the entries set.
struct FieldScratch final : detail::ScratchBase {
    std::vector<double> distance;
    std::vector<VertexId> touched;
    void fit(std::size_t n) {
        if (distance.size() < n) distance.resize(n, INFINITY);
    }
    void reset() noexcept {
        for (VertexId v : touched) distance[v.idx()] = INFINITY;
        detail::clear_buffer(touched);
    }
};

// d_a from both foci, up to the bound of the current ellipse: from the caller's fields while both
// reach the bound, else from fast-marching runs of this call, started when first needed and
// continued as K grows. Either way the same values (FastMarching is resumable and deterministic),
// so the same T_jk.
class Foci {
public:
    Foci(const TriMesh& mesh, VertexId a, VertexId b, const EllipseOptions& options, Workspace* workspace)
        : mesh_(mesh),
          a_(a),
          b_(b),
          workspace_(workspace),
          fields_(options.field_a && options.field_b && options.field_a->source == a && options.field_b->source == b),
          field_a_(options.field_a),
          field_b_(options.field_b) {}

    // D_a = d_a(a, b), from a's field when it holds b, else from a run from a stopped once b is final.
    double d_ab() {
        if (fields_)
            for (std::size_t i = 0; i < field_a_->vertices.size(); ++i)
                if (field_a_->vertices[i] == b_) return field_a_->distance[i];
        fields_ = false;
        start_runs();
        return from_a_->advance_to(b_);
    }

    // Calls f(v) for every vertex v with d_a(v, a) + d_a(v, b) <= bound.
    template <class F>
    void within(double bound, F f) {
        if (fields_ && field_a_->radius >= bound && field_b_->radius >= bound) {
            const detail::Borrowed<FieldScratch> from_b = detail::borrow<FieldScratch>(workspace_, mesh_.n_vertices());
            for (std::size_t i = 0; i < field_b_->vertices.size(); ++i) {
                if (!(field_b_->distance[i] <= bound)) continue;
                from_b->touched.push_back(field_b_->vertices[i]);
                from_b->distance[field_b_->vertices[i].idx()] = field_b_->distance[i];
            }
            for (std::size_t i = 0; i < field_a_->vertices.size(); ++i) {
                const VertexId v = field_a_->vertices[i];
                if (field_a_->distance[i] <= bound && field_a_->distance[i] + from_b->distance[v.idx()] <= bound) f(v);
            }
            return;
        }
        fields_ = false;
        start_runs();
        from_a_->advance(bound);
        from_b_->advance(bound);
        // Such a vertex has d_a(v, a) <= bound, so from_a has reached it.
        for (VertexId v : from_a_->finalized())
            if (from_a_->distance(v) + from_b_->distance(v) <= bound) f(v);
    }

private:
    const TriMesh& mesh_;
    const VertexId a_, b_;
    Workspace* const workspace_;
    bool fields_;
    const FocusField *field_a_, *field_b_;
    std::optional<FastMarching> from_a_, from_b_;

    void start_runs() {
        if (from_a_) return;
        from_a_.emplace(mesh_, std::span(&a_, 1), true, workspace_);
        from_b_.emplace(mesh_, std::span(&b_, 1), true, workspace_);
    }
};

}  // namespace

FocusField focus_field(const TriMesh& mesh, VertexId source, std::span<const VertexId> partners, double K, double reach,
                       Workspace* workspace) {
    FastMarching run(mesh, std::span(&source, 1), true, workspace);
    double farthest = 0;
    for (VertexId p : partners)
        if (const double d = run.advance_to(p); std::isfinite(d)) farthest = std::max(farthest, d);
    FocusField field;
    field.source = source;
    field.radius = reach * K * farthest;
    run.advance(field.radius);
    field.vertices.assign(run.finalized().begin(), run.finalized().end());
    field.distance.reserve(field.vertices.size());
    for (VertexId v : field.vertices) field.distance.push_back(run.distance(v));
    return field;
}

EllipsePath ellipse_shortest_path(const TriMesh& mesh, VertexId a, VertexId b, const EllipseOptions& options) {
    const std::size_t nv = mesh.n_vertices();
    if (a.idx() >= nv || b.idx() >= nv)
        throw InvalidInput("vertex " + std::to_string(std::max(a.idx(), b.idx())) + " is out of range (the mesh has " +
                           std::to_string(nv) + " vertices)");
    if (a == b) throw InvalidInput("the two vertices are the same (" + std::to_string(a.idx()) + ")");
    if (!(options.K > 1)) throw InvalidInput("K must be greater than 1");
    // Every search below borrows from one workspace: the caller's, or this call's own (declared
    // first, so that it outlives the searches).
    Workspace own;
    Workspace* const workspace = options.workspace ? options.workspace : &own;
    // d_a(a, b), then d_a from both foci for each ellipse (the caller's fields, or runs of this call).
    Foci foci(mesh, a, b, options, workspace);
    const double d_ab = foci.d_ab();
    if (!std::isfinite(d_ab)) throw InvalidInput("the two vertices are not connected");
    const detail::Borrowed<MaskScratch> scratch = detail::borrow<MaskScratch>(workspace, mesh.n_faces());
    FaceData<std::uint8_t>& mask = scratch->mask;
    EllipsePath result;
    for (double K = options.K;; K = 1 + 2 * (K - 1)) {
        const double bound = K * d_ab;
        // T_jk: the faces around every vertex with d_a(v, a) + d_a(v, b) <= K·D_a. Earlier
        // attempts' faces stay in.
        foci.within(bound, [&](VertexId v) {
            mesh.for_each_outgoing(v, [&](HalfedgeId h) {
                if (mesh.is_boundary(h)) return;
                std::uint8_t& in = mask[mesh.face(h)];
                if (!in) scratch->in.push_back(mesh.face(h));
                in = 1;
            });
        });
        const std::size_t faces = scratch->in.size();
        const bool everything = faces == mesh.n_faces();
        ExactGeodesic restricted(mesh, a, {.face_mask = everything ? nullptr : &mask, .workspace = workspace});
        restricted.propagate(std::span(&b, 1));
        GeodesicPath path = restricted.path_to(b);
        const double L = path.length;
        result.attempts += 1;
        result.windows_created += restricted.stats().windows_created;
        result.K = K;
        result.ellipse_faces = faces;
        if (everything) {
            result.path = std::move(path);
            result.certificate = EllipsePath::Certificate::whole_mesh;
            return result;
        }
        // No path inside T_jk: grow K, unless T_jk is already a's whole component (on a mesh of
        // several). Then b, connected to a by fast marching, was lost by the exact search itself
        // (rounding: paper_notes/exact_geodesics.md, "Needles"); growing K could only repeat it,
        // forever. The empty path falls through to the border certificate, which holds with
        // B = ∞ (nothing is left queued, no border): the caller sees length ∞ and no points.
        if (!std::isfinite(L) && has_border(mesh, mask, scratch->in)) continue;
        if (touches_boundary(mesh, mask, path)) continue;  // the paper's rule: grow K
        // Certificate 1 (paper_notes/ellipse.md): every path that leaves T_jk is at least
        // min(border_key, stop_key) long.
        if (std::min(restricted.stats().border_key, restricted.stats().stop_key) >= L) {
            result.path = std::move(path);
            result.certificate = EllipsePath::Certificate::border;
            return result;
        }
        // Certificate 2: the exact search on all of T, pruned above L (1 + filter margin), sees only
        // {p : d(a, p) + |p − b| <= L(1 + margin)}; what it finds shorter than L is the distance on T.
        ExactOptions whole;
        whole.prune_above = L * (1 + certificate_margin);
        whole.workspace = workspace;
        ExactGeodesic search(mesh, a, whole);
        search.propagate(std::span(&b, 1));
        result.certificate_windows = search.stats().windows_created;
        if (search.distance(b) < L * (1 - certificate_margin)) {
            result.path = search.path_to(b);
            result.certificate = EllipsePath::Certificate::replaced;
        } else {
            result.path = std::move(path);
            result.certificate = EllipsePath::Certificate::search;
        }
        return result;
    }
}

}  // namespace fhr::geodesic
