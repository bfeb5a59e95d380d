// FHR §5 — "the Hausdorff distance between Ω_T and the image f^j(Ω_D) will be small": the
// two-sided Hausdorff distance between two triangle meshes, bracketed from below and above, and
// the RMS distance between corresponding vertices.
//
// What is computed (directed, A → B; the two-sided distance is the larger of A → B and B → A):
//   d(p, B)   exact Euclidean distance from p to the union of B's triangles, up to rounding: the
//             closest point of each candidate triangle (core/geometry.hpp: the projection onto
//             its plane when inside, else the nearest point of its sides), candidates from a
//             bounding-volume tree (axis-aligned boxes, median splits) searched best-first
//   bounds    on a triangle (piece) with corners x_k, corner distances d_k and longest edge ℓ:
//             (Lipschitz) every point is within r of a corner, r = max_p min_k |p − x_k|: the
//             circumradius when no angle is obtuse, else where the perpendicular bisectors of the
//             two shorter sides meet the longest; r ≤ ℓ/√3 (at a point p inside, one of the
//             three angles the sides subtend at p is ≥ 120°, so ℓ² ≥ 3 min|p − x_k|²). d(·, B)
//             is 1-Lipschitz: sup ≤ max_k d_k + r;
//             (convexity) for any one triangle τ of B, d(·, τ) is convex, so on the piece it is
//             largest at a corner: sup ≤ max_k d(x_k, τ), tried for the corners' closest triangles.
//             (two triangles) when the corners' closest triangles τ₁ = (a, b, c) and τ₂ = (b, a, d)
//             share an edge: turn τ₂ about ab into τ₁'s plane, τ₂' = (b, a, d'), which moves no
//             point by more than h = |d − d'| (an affine map fixing a, b); when Q = τ₁ ∪ τ₂' is a
//             convex quadrilateral, d(·, Q) is convex and d(·, τ₁ ∪ τ₂) ≤ d(·, Q) + h, so
//             sup ≤ max_k min(d(x_k, τ₁), d(x_k, τ₂')) + h. This settles the pieces that straddle
//             an edge of B where A lies on B (a remesh of a flat region), which the one-triangle
//             bound can only settle at the resolution's size, piece by piece.
//             (a vertex fan) when the corners' closest triangles share a vertex v of B: flatten v's
//             fan into the plane through v normal to its area-weighted normal (moving no point by
//             more than the largest lift h of its link), then move each point of the fan's outline
//             (the link cycle; at a boundary vertex of B, v followed by the open link path) that is
//             straight (turn below 1e−9) onto the chord of its neighbouring corners (by at most ε,
//             measured). When the fan's triangles stay positively oriented and the corners make a
//             convex polygon P, the flat fan tiles P and d(·, fan) ≤ d(·, P) + h + ε with d(·, P)
//             convex: sup ≤ max_k d(x_k, P) + h + ε. This settles the pieces at the vertices of B,
//             inner or on its boundary.
//             The piece's bound is the smallest of these
//   search    lower <- max over A's vertices of d(v, B) (with priors, only the vertices whose
//             bound — the least prior of their triangles — can raise max(lower, known), largest
//             first, and those of the triangles not settled by their priors: directed_hausdorff);
//             then for each triangle of A (the 64
//             with the farthest corner first, to raise lower soon; then the others in A's own
//             order, whose neighbours' queries then find the tree's nodes in cache), branch and
//             bound: a piece whose bound is ≤ max(lower, known) is done (the bounds are tried
//             cheapest first, only while the least so far exceeds that; `known`, a lower bound of
//             what the caller reports, is 0 unless given); a piece whose bound exceeds its largest
//             corner distance by ≤ δ adds its bound to upper; any other piece is split 1-to-4 at
//             its edge midpoints (new distances, which may raise lower; a midpoint shared with a
//             neighbouring piece is evaluated once), down to at most max_depth splits
//   lower     = the largest distance evaluated: a point of A at that distance exists, so h(A, B) ≥ lower
//   priors    a triangle of A with a prior (an upper bound given by the caller) that is ≤ max(lower,
//             known) is done like a piece; otherwise the prior is one more bound of its root piece
//   upper     = max(lower, bounds of the pieces kept, bounds of the pieces done for being ≤ known):
//             h(A, B) ≤ upper, and max(upper, known) − max(lower, known) ≤ δ unless a piece reached
//             max_depth (then upper is still an upper bound)
#pragma once

#include <fhr/core/geometry.hpp>

#include <cstddef>
#include <span>
#include <utility>
#include <vector>

#include <fhr/core/executor.hpp>
#include <fhr/core/trimesh.hpp>

namespace fhr::wavelet {

/// A bounding-volume tree over a triangle soup, for distance queries.
class TriangleTree {
public:
    /// \pre every index < positions.size(). Keeps its own copy.
    TriangleTree(std::span<const Vec3> positions, std::span<const Triangle> triangles);
    /// The same triangles at other positions, in `other`'s hierarchy with its boxes refitted
    /// (a reconstruction of f^J moves its vertices a little, and refitting costs a pass
    /// where building sorts); `other` is taken over (pass a copy to keep it). Any hierarchy gives
    /// the same distances; one whose boxes fit loosely only prunes less.
    /// \pre positions.size() equals other's position count.
    TriangleTree(TriangleTree other, std::span<const Vec3> positions);

    struct Hit {
        double distance;  ///< |p − point|
        std::uint32_t triangle;
        Vec3 point;  ///< the closest point
    };
    /// The closest point of the soup to p. `hint`: a triangle to start from (any valid index
    /// speeds up queries at nearby points; the answer does not depend on it).
    /// \pre at least one triangle.
    Hit closest(const Vec3& p, std::uint32_t hint = 0) const;
    /// |p − closest point of triangle t|. \pre t < the number of triangles.
    double distance_to(const Vec3& p, std::uint32_t t) const;
    /// An upper bound of d(·, t1 ∪ t2) on the triangle x (the two-triangle bound of the file
    /// header), or +∞ when t1 and t2 do not share an edge or do not make a convex quadrilateral
    /// with a margin. \pre t1, t2 < the number of triangles.
    double pair_bound(const Vec3 (&x)[3], std::uint32_t t1, std::uint32_t t2) const;
    /// An upper bound of d(·, the triangles at vertex v) on the triangle x (the vertex-fan bound
    /// of the file header), or +∞ when v's fan is not a disk (a closed fan, or an open one at a
    /// boundary vertex) that flattens to a convex polygon. \pre v < the number of positions.
    double fan_bound(const Vec3 (&x)[3], std::uint32_t v) const;
    /// The vertices of triangle t. \pre t < the number of triangles.
    const Triangle& triangle(std::uint32_t t) const { return triangles_[t]; }

private:
    struct Node {
        Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
        std::uint32_t first = 0, count = 0;  ///< leaf: triangles order_[first, first + count); inner: count = 0
        std::uint32_t left = 0, right = 0;   ///< inner: children
    };
    std::vector<Vec3> positions_;
    std::vector<Triangle> triangles_;
    std::vector<std::uint32_t> order_;
    std::vector<Node> nodes_;
    struct LeafTriangle {
        Vec3 corner[3], lo, hi;
    };
    std::vector<LeafTriangle> leaf_;  ///< triangle order_[i]'s corners and box
    std::vector<std::uint32_t> fan_start_,
        fan_;  ///< the triangles at vertex v: fan_[fan_start_[v] .. fan_start_[v + 1])
    struct Extent {
        Vec3 lo, hi, centroid;  ///< a triangle's box and centroid
    };
    std::uint32_t build(std::uint32_t first, std::uint32_t count, const std::vector<Extent>& extent,
                        std::vector<std::pair<double, std::uint32_t>>& keys);
    void fit_leaves();  ///< leaf_ from positions_ and order_
};

struct HausdorffOptions {
    /// δ: the bracket width sought, upper − lower ≤ δ. 0: 1e−4 times the diagonal of the bounding
    /// box of both meshes.
    double resolution = 0;
    /// The most 1-to-4 splits of one triangle of A (pieces of 4^−max_depth its size).
    unsigned max_depth = 16;
    /// A lower bound of the distance the caller reports, when that is the larger of this one and
    /// another already bracketed (the two-sided distance: the other direction's lower). A piece
    /// whose bound is at most `known` is not refined further: the result still brackets h(A, B),
    /// but only max(upper, known) − max(lower, known) ≤ δ is sought (the direction from a
    /// remesh to T, whose vertices lie on T, would be resolved down to δ far below the
    /// distance from T to the remesh, which is what the two-sided distance reports).
    double known = 0;
    /// Per triangle of A, an upper bound of sup d(·, B) on it, or empty: a triangle whose prior is
    /// settled (≤ max(lower, known)) is done without a search, and the prior bounds its piece.
    /// A reconstruction f′ of the same triangles as f^J, whose directed search found
    /// per triangle an upper bound U of d(·, T) (DirectedHausdorff::triangle_upper), has on each
    /// triangle d(·, T) ≤ U + its corners' largest displacement |f′ − f^J| (1-Lipschitz, and the
    /// displacement is linear on the triangle).
    std::span<const double> prior{};
    /// For the two-sided hausdorff(): the same per triangle of B, for B → A.
    std::span<const double> prior_back{};
};

/// h(A, B) = sup_{p ∈ A} d(p, B), bracketed: lower ≤ h(A, B) ≤ upper, and
/// max(upper, known) − max(lower, known) ≤ δ (HausdorffOptions).
struct DirectedHausdorff {
    double lower = 0;              ///< max over the samples: h(A, B) ≥ lower
    double upper = 0;              ///< h(A, B) ≤ upper
    std::size_t samples = 0;       ///< distances d(p, B) evaluated
    Vec3 farthest = Vec3::Zero();  ///< a point of A at distance `lower`
    /// Per triangle of A: an upper bound of sup d(·, B) on it (the largest bound of its pieces
    /// where the search ended, or its prior).
    std::vector<double> triangle_upper;
};

struct Hausdorff {
    DirectedHausdorff a_to_b, b_to_a;
    double resolution = 0;                                                 ///< δ used
    double lower() const { return std::max(a_to_b.lower, b_to_a.lower); }  ///< the reported distance
    double upper() const { return std::max(a_to_b.upper, b_to_a.upper); }
};

/// The directed distance from mesh A to the triangles of `B` (the search of the file header).
/// \pre A has a triangle; options.resolution > 0.
/// A's triangles are searched in eight fixed blocks, each with its own lower bound from the
/// vertices on, as tasks on `executor` (default_executor() when null); the same result on any
/// number of threads.
DirectedHausdorff directed_hausdorff(std::span<const Vec3> a_positions, std::span<const Triangle> a_triangles,
                                     const TriangleTree& B, const HausdorffOptions& options,
                                     Executor* executor = nullptr);

/// The two-sided Hausdorff distance between two triangle meshes (any topology, soups too): A to B
/// first, then B to A searched only down to the first's lower (HausdorffOptions::known), so that
/// lower() ≤ h ≤ upper() with upper() − lower() ≤ δ; each direction's bracket holds its own
/// distance, the second's only as narrow as the first's lower asks.
/// \pre both have a triangle, every index in range.
Hausdorff hausdorff(std::span<const Vec3> a_positions, std::span<const Triangle> a_triangles,
                    std::span<const Vec3> b_positions, std::span<const Triangle> b_triangles,
                    const HausdorffOptions& options = {}, Executor* executor = nullptr);
/// The same, with A's and B's trees built by the caller (one tree serving several distances).
/// \pre A and B are the trees of (a_positions, a_triangles) and (b_positions, b_triangles), each
///      with a triangle; options.resolution > 0.
Hausdorff hausdorff(std::span<const Vec3> a_positions, std::span<const Triangle> a_triangles, const TriangleTree& A,
                    std::span<const Vec3> b_positions, std::span<const Triangle> b_triangles, const TriangleTree& B,
                    const HausdorffOptions& options, Executor* executor = nullptr);

/// (Σ_v |a_v − b_v|² / n)^½: the RMS distance between corresponding vertices.
/// \pre a.size() == b.size() > 0.
double rms_distance(std::span<const Vec3> a, std::span<const Vec3> b);

}  // namespace fhr::wavelet
