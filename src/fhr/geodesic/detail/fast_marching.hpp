// FHR §3 — the approximate geodesic distance d_a: Kimmel–Sethian fast marching on T.
//
// Paper §3: the exact path Γ(x_j, x_k) is searched only inside the "ellipse" T_jk, the triangles
// with a vertex v such that d_a(v, x_j) + d_a(v, x_k) <= K · d_a(x_j, x_k), K = 1.06, where d_a is
// computed "by the method of Kimmel and Sethian [14]" (Computing geodesic paths on manifolds,
// PNAS 95, 1998). The choices the paper leaves open are in paper_notes/fast_marching.md.
//
// Pseudocode (Sethian's fast marching with the Kimmel–Sethian triangle update):
//   d(v) <- ∞ for all v;  push (0, s) for every source s
//   while the heap is not empty:
//       look at the smallest (d, v) (ties: lowest vertex index; a vertex is in the heap once)
//       if d > max_distance: stop
//       pop it; make v final (append to `finalized`)
//       for every neighbour w of v that is not final:   relax(w, d(v) + |vw|)      (edge update)
//       for every triangle (v, b, c) at v, for each of its two other vertices (say c, the other b)
//       that is not final:                               relax(c, triangle(c; v, b))
//       for every obtuse corner c whose virtual vertex is v: the same triangle update of c
//   relax(c, t): t <- max(t, d(v)); if t < d(c): d(c) <- t, push (t, c) or move c's entry up
//       (only rounding can make the max act: a value that lowers d(c) comes from an update
//       that uses d(v), and each update is >= its inputs in exact arithmetic. So vertices are
//       accepted in non-decreasing order, which early stopping relies on.)
//   triangle(c; a, b), using only final values:
//       angle at c <= 90°: planar(c; a, b) when a and b are both final (see planar_update)
//       obtuse angle at c (Kimmel–Sethian §4): unfold the triangles beyond edge ab into the plane
//       of (c, a, b) until a vertex p falls into the section at c (the directions within 90° of
//       both ca and cb), at most max_unfold_steps triangles; the virtual edge cp splits the angle
//       into two non-obtuse ones: the smallest of d(p) + |cp|, planar(c; a, p), planar(c; p, b)
//       for those of a, b, p that are final. Without such a p only the edge updates remain.
#pragma once

#include <cmath>
#include <memory>
#include <span>
#include <vector>

#include <fhr/core/trimesh.hpp>
#include <fhr/geodesic/workspace.hpp>

namespace fhr::geodesic {

struct FastMarchingOptions {
    /// Stop once every vertex whose distance is <= max_distance is final (see fast_marching).
    double max_distance = INFINITY;
    /// Kimmel–Sethian §4: split obtuse angles by unfolding. Off: obtuse corners get the edge
    /// updates only (Dijkstra-like there); kept as an option to measure what unfolding buys.
    bool unfold = true;
    /// Optional: the reusable arrays (geodesic/workspace.hpp); without one the run allocates its own.
    Workspace* workspace = nullptr;
};

/// Unfolding gives up after this many triangles (the triangle at the corner not counted). The
/// section at a corner of angle θ is 180° − θ wide, so how far the search must go grows without
/// bound as θ → 180°; a virtual vertex many triangles away would also make a poor planar update.
/// Measured (paper_notes/fast_marching.md): on the horse 95.7 % of the searches end in the first
/// unfolded triangle, 99.0 % within 3, 99.7 % within 5; 2 of 20,844 need more (17 and 19).
inline constexpr int max_unfold_steps = 16;

struct DistanceField {
    /// #V: the fast-marching distance of every final vertex, INFINITY for every other vertex.
    VertexData<double> distance;
    /// The final vertices in the order they were accepted: distances non-decreasing. Of the
    /// vertices in the band at the same time, equal distances go by increasing index; a vertex
    /// whose new value equals the one just accepted (a front parallel to an edge) comes after it.
    std::vector<VertexId> finalized;
};

/// Kimmel–Sethian fast marching from `sources` (each at distance 0) over the edges and faces of
/// `mesh`.
/// \pre mesh is valid without garbage (boundaries are allowed: a boundary edge is not crossed
///      by unfolding).
/// \post `finalized` holds exactly the vertices whose distance is <= options.max_distance (every
///       vertex reachable from a source when max_distance is infinite), and each of their
///       distances is bitwise the value a run without max_distance gives; every other vertex has
///       distance INFINITY. d >= 0, sources have 0, d(v) <= d(w) + |vw| for every edge (v, w)
///       with v and w final. With one source, d(v) is at least the straight-line distance to it
///       (tested, not proved: the planar update overestimates a point source's circular front);
///       with several, not always: adjacent sources act like the segment between them.
///       The result depends only on the mesh, the sources (as a set) and the options.
///       Cost: O(#V) for the returned distance array, plus O(k log k) for the k vertices within
///       the final front (the run's own arrays come from options.workspace, see FastMarching).
/// \throws InvalidInput when a source is not a vertex of the mesh, or max_distance is NaN.
DistanceField fast_marching(const TriMesh& mesh, std::span<const VertexId> sources,
                            const FastMarchingOptions& options = {});

/// A fast-marching run that can be continued (§3 needs d_a(x_j, x_k) first, then the field up to
/// K·d_a(x_j, x_k), then, when K grows, a little further: one run serves all three). After
/// advance(r) it has accepted exactly the vertices `fast_marching(mesh, sources, {r, unfold})`
/// accepts, in the same order and with bitwise the same values; advance_to(t) stops right after
/// t is accepted. Either may be called again to continue: every call performs the next steps of
/// the one full run, so any sequence of calls yields a prefix of it.
/// Its per-vertex arrays come from the caller's `workspace` (geodesic/workspace.hpp), held until
/// the run is destroyed: constructing a run costs O(1) once the workspace has served a mesh as
/// large, not O(#V), and its work is proportional to the vertices reached. Without a workspace
/// the run allocates and fills its own arrays, O(#V).
class FastMarching {
public:
    /// \pre mesh valid without garbage, sources are vertices of it; the mesh and the workspace
    ///      (when given) outlive the run.
    /// \throws InvalidInput when a source is not a vertex of the mesh.
    FastMarching(const TriMesh& mesh, std::span<const VertexId> sources, bool unfold = true,
                 Workspace* workspace = nullptr);
    ~FastMarching();
    FastMarching(const FastMarching&) = delete;
    FastMarching& operator=(const FastMarching&) = delete;

    /// Accepts vertices while the smallest band value is <= max_distance.
    /// \throws InvalidInput when max_distance is NaN.
    void advance(double max_distance);
    /// Accepts vertices until `target` is final or nothing is left (none when it is final
    /// already); returns distance(target).
    double advance_to(VertexId target);
    /// The distance of a final vertex, INFINITY for every other vertex.
    double distance(VertexId v) const;
    /// The final vertices in acceptance order (distances non-decreasing).
    std::span<const VertexId> finalized() const;

    struct State;

private:
    std::unique_ptr<State> state_;
};

/// The Kimmel–Sethian planar update (1998, the update on one triangle): the value at c of the plane
/// wave t(x) = n·x + const with |n| = 1 that takes d_a at a and d_b at b, where e_a = a − c and
/// e_b = b − c. It is returned only when causal — the characteristic −n reaching c comes from
/// inside the triangle (−n is a non-negative combination of e_a and e_b) — and INFINITY
/// otherwise (also when no unit-slope plane fits, |d_b − d_a| > |ab|, or the triangle is
/// degenerate). The triangle may lie anywhere in R³: only lengths and angles enter.
/// \pre the angle at c is at most 90° (e_a · e_b >= 0); then a causal value is >= max(d_a, d_b).
double planar_update(const Vec3& e_a, const Vec3& e_b, double d_a, double d_b);

}  // namespace fhr::geodesic
