// FHR §3 — exact single-source geodesics on Ω_T by window propagation (Chen & Han 1990, as
// improved by Xin & Wang 2009, "ICH"). The paper computes every path Γ(x_j, x_k) of eq. (1) with
// Chen–Han's exact algorithm, restricted to the "ellipse" sub-mesh T_jk; this is that algorithm.
// Derivations, invariants and tolerances: paper_notes/exact_geodesics.md (GEO-1..GEO-9).
//
// Pseudocode (one min-queue for windows and vertex events; an event's key is a lower bound of
// any source-to-target path through it: its smallest distance plus the Euclidean distance to the
// nearest target, A*-style, or just its smallest distance when there are no targets):
//   d(v) <- ∞ for all v;  d(s) <- 0;  push vertex event (s, 0)
//   while the queue is not empty and (no targets or its smallest key < max over targets of d(t)):
//       pop the event with the smallest key
//       vertex event (v, δ), δ = d(v) (else stale: skip)       — v is the source or a pseudo-source
//           for every edge (v, u) of the sub-mesh: relax d(u) with δ + |vu|  (path along the edge)
//           for every face (v, a, b): push the window on [a, b] with source image v, σ = δ
//       window event w on edge (v1, v2), interval [b0, b1], source image I, σ; apex v3 of the
//       face it enters:
//           if the filtering rule proves w useless under the current d(v1), d(v2), d(v3): skip
//           if the ray I → v3 passes through [b0, b1]: relax d(v3) with σ + |I v3|
//           the rays through [b0, b1] cross into edges (v1, v3) and (v3, v2): push each nonempty
//           child window (unfolded into the next face), unless the filtering rule rejects it;
//           when v3 is already closer by a path entering the face at x* of this edge, the rays
//           between x* and v3's ray are dropped (Xin–Wang's "one angle, one split")
//       relax d(u) with δ: if δ < d(u), d(u) <- δ, remember how; if u is a pseudo-source (an
//           interior vertex with angle sum > 2π, or a boundary vertex: on a hole of T
//           or on the border of the sub-mesh), push (u, δ)
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <fhr/core/surface_point.hpp>
#include <fhr/core/trimesh.hpp>
#include <fhr/geodesic/workspace.hpp>

namespace fhr::geodesic {

/// A shortest path of eq. (1): straight in every face, bending only at pseudo-sources.
struct GeodesicPath {
    /// The source vertex, then the edge points (halfedge, t) and vertices it passes, then the
    /// target vertex. Consecutive points lie in a common face (or are the two ends of an edge).
    /// A crossing whose line passes within snap_tolerance · (longest edge at v) of the crossed
    /// edge's nearer end v, or misses the edge past v (v reached within cover_tolerance), is v.
    std::vector<SurfacePoint> points;
    double length = 0;  ///< the exact polyhedral distance (INFINITY when unreachable)
};

struct ExactStats {
    std::size_t windows_created = 0;     ///< windows that passed the filter and were queued
    std::size_t windows_propagated = 0;  ///< windows popped and unfolded into their next face
    std::size_t pseudo_sources = 0;      ///< vertex events expanded (the source included)
    /// With a face_mask: the smallest key (a lower bound of the length of any source-to-target
    /// path through that point, see propagate) among the events expanded so far that reached the
    /// mask's border: a window unfolded into a face whose next face is masked out (its key over
    /// the interval it would have had there), and a pseudo-source next to a masked-out face.
    /// INFINITY when none did. The ellipse certificate of §3 reads it (paper_notes/ellipse.md).
    double border_key = INFINITY;
    /// The smallest key left in the queue when propagate() last returned (INFINITY if empty):
    /// every event not yet expanded, and everything it can lead to, has at least this key.
    double stop_key = INFINITY;
};

struct ExactOptions {
    /// If set (size n_faces), only faces with mask[f] != 0 exist: the "ellipse" T_jk of §3. An
    /// edge between a masked-in and a masked-out face is a boundary edge, and its vertices are
    /// boundary vertices (pseudo-sources).
    const FaceData<std::uint8_t>* face_mask = nullptr;
    /// Events whose key exceeds this are never queued or expanded, so only paths no longer than
    /// it are searched: a target whose distance exceeds it may be left at a larger value (or
    /// INFINITY). A distance below it is exact as without the bound (the events of a path keep
    /// keys at most its length). The ellipse certificate uses it (paper_notes/ellipse.md).
    double prune_above = INFINITY;
    /// Optional: the reusable arrays (geodesic/workspace.hpp), held while the ExactGeodesic lives;
    /// without one the search allocates its own.
    Workspace* workspace = nullptr;
};

/// The relative tolerances of the algorithm; their derivations are in
/// paper_notes/exact_geodesics.md, "Tolerances".
/// A vertex within cover_tolerance · |edge| of a window's interval (measured where its ray
/// crosses the window's edge), plus the rounding of the unfolded coordinates (exact.cpp's
/// unfolding_rounding, which matters only on needles), is reached through the window.
inline constexpr double cover_tolerance = 1e-9;
/// A path passing within snap_tolerance · (its longest edge) of a vertex passes through it.
inline constexpr double snap_tolerance = 1e-9;

/// Exact single-source distances and shortest paths from one vertex of T.
class ExactGeodesic {
public:
    /// \pre mesh is valid without garbage, source is a vertex of it; a face_mask, when given,
    ///      has one entry per face and outlives this object; the mesh and the workspace (when
    ///      given) must outlive this object.
    /// \throws std::invalid_argument when the source is out of range or the mask has the wrong size.
    ExactGeodesic(const TriMesh& mesh, VertexId source, ExactOptions options = {});
    ~ExactGeodesic();
    ExactGeodesic(const ExactGeodesic&) = delete;
    ExactGeodesic& operator=(const ExactGeodesic&) = delete;

    /// Propagates until d(t) is final for every t in `targets` (early stop; the order is
    /// goal-directed, so other vertices' distances need not be final yet), or until the whole
    /// (sub-)mesh is done when `targets` is empty. May be called again, with other targets, to
    /// continue.
    void propagate(std::span<const VertexId> targets = {});

    /// The current distance of v (INFINITY if not reached); final for the vertices propagate()
    /// was asked for.
    double distance(VertexId v) const { return dist_[v.idx()]; }

    /// The shortest path from the source to `target`, traced back through the windows and
    /// pseudo-sources that gave its distance. An unreachable target gives no points and
    /// length INFINITY.
    /// \pre propagate() has finished for target (or for the whole mesh).
    GeodesicPath path_to(VertexId target) const;

    const ExactStats& stats() const { return stats_; }

private:
    /// A window: an interval of edge(h) whose points are reached by straight rays (in the
    /// unfolding) from the source image I = (sx, sy) of the pseudo-source `pseudo`. Coordinates
    /// are in h's frame: from(h) at (0, 0), to(h) at (|h|, 0), face(h) (the face the window
    /// enters next) in y > 0 and I in y < 0. Every point x of [b0, b1] is at distance
    /// sigma + |I x| along a path through the window's ancestors.
    struct Window {
        HalfedgeId h;
        VertexId pseudo;
        std::uint32_t parent;  ///< index in windows_, or no_parent for a pseudo-source's window
        double b0, b1, sx, sy, sigma;
    };
    /// How a vertex got its current distance.
    struct Via {
        enum class Kind : std::uint8_t { none, source, edge, window } kind = Kind::none;
        std::uint32_t index = 0;  ///< the previous vertex (edge) or the window (window)
    };
    struct Event {
        double key;           ///< a lower bound of the distance to the nearest goal through it
        double dist;          ///< a vertex event's d(v) when pushed (stale when it changed since)
        std::uint32_t seq;    ///< insertion order: ties pop deterministically
        std::uint32_t index;  ///< vertex or window index
        bool is_vertex;
        bool operator>(const Event& o) const { return key != o.key ? key > o.key : seq > o.seq; }
    };
    static constexpr std::uint32_t no_parent = 0xffffffffu;

    /// Vertex kinds, computed when first needed; saddles and boundary vertices are pseudo-sources.
    static constexpr std::uint8_t unknown = 0, plain = 1, saddle = 2, boundary_vertex = 3;
    /// The per-vertex arrays and the reusable buffers (exact.cpp), borrowed clean from the
    /// options' workspace (geodesic/workspace.hpp) so that a search costs what it touches, not
    /// O(#V), and handed back to it by the deleter.
    struct Scratch;
    struct ScratchDeleter {
        Workspace* workspace;
        void operator()(Scratch* s) const noexcept;
    };

    const TriMesh& mesh_;
    ExactOptions options_;
    std::unique_ptr<Scratch, ScratchDeleter> scratch_;
    std::vector<double>& dist_;
    std::vector<Via>& via_;
    std::vector<std::uint8_t>& kind_;
    std::vector<Window>& windows_;
    std::vector<Event>& heap_;
    std::vector<double> fan_;  ///< expand_vertex's corner angles, reused
    std::vector<Vec3> goals_;  ///< positions of the current targets
    std::uint32_t seq_ = 0;
    ExactStats stats_;

    bool face_exists(FaceId f) const;
    bool masked_out(FaceId f) const;
    void note_border(const Window& candidate);
    std::uint8_t vertex_kind(VertexId v);
    double vertex_key(VertexId v, double d) const;
    double window_key(const Window& w) const;
    void push_vertex(VertexId v);
    void relax(VertexId v, double d, Via via);
    struct Frame;
    static Frame frame(const TriMesh& m, HalfedgeId h);
    bool useless(const Window& w, const Frame& f) const;
    void push_window(const Window& w);
    void expand_vertex(VertexId v);
    void propagate_window(std::uint32_t index);
};

}  // namespace fhr::geodesic
