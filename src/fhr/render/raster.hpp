// FHR §6 figures — a small deterministic CPU rasterizer for the pictures of Figures 6–9
// (spec/render.md REN-4..10): triangle meshes in a z-buffer, flat or Gouraud shading under a
// fixed headlight, optional per-face colours or a procedural checkerboard through per-corner
// texture coordinates (Figure 7 right: T′ with a checkerboard over each patch through φ),
// mesh outlines and polylines (the geodesic network, Figure 7 left) drawn over the surface with
// a depth bias, supersampled for anti-aliasing, on a white background.
//
// Pipeline of render_panel():
//   1. every point p → view space (x, y, w): w the depth along the viewing direction
//   2. each triangle clipped against the near plane w ≥ near (Sutherland–Hodgman), fanned
//   3. vertices → sample space (supersampled viewport) by the perspective division; 1/w and the
//      attributes divided by w are affine in screen space, so barycentric interpolation of them
//      is perspective-correct
//   4. for every sample centre inside the triangle (edge functions, boundary included): if its
//      depth w is strictly less than the buffer's, shade it and store colour and depth
//   5. after all triangles: the outline edges of meshes with `outline`, then the boundary edges of
//      meshes with `boundary` (edges of exactly one triangle: the boundary of a surface with
//      holes), then the polylines, as segments of constant width in pixels, each sample
//      within half the width of the segment drawn when its depth is at most the buffer's depth
//      plus Camera::depth_bias (lines never write depth). Lines with a hidden style (the
//      boundary; polylines that ask) first get their parts behind the surface — the samples
//      failing that test — drawn in it, before any visible part of any line
//      (so a boundary behind the surface still shows, faintly, and never over a visible line)
//   6. each output pixel = the rounded mean of its supersample × supersample samples
// Deterministic: one thread, a fixed order of operations (-ffp-contract=off), no uninitialized
// memory; the same input gives the same pixels.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include <fhr/core/polygon_soup.hpp>
#include <fhr/core/trimesh.hpp>
#include <fhr/render/image.hpp>

namespace fhr::render {

/// r, g, b in [0, 1] (sRGB values; the rasterizer does no gamma conversion).
using Colour = Eigen::Vector3d;

/// An axis-aligned bounding box.
struct Bounds {
    Vec3 min, max;
};

/// The bounding box of `points`. \throws InvalidInput when `points` is empty or a coordinate is
/// not finite.
Bounds bounds_of(std::span<const Vec3> points);

/// The smallest box holding both.
Bounds merged(const Bounds& a, const Bounds& b);

/// A perspective camera. The image's horizontal field of view follows from fov_y and the
/// aspect ratio of the viewport it renders to.
struct Camera {
    Vec3 eye = Vec3(0, 0, 1), target = Vec3::Zero(), up = Vec3::UnitY();
    double fov_y_degrees = 30;
    double near = 1e-3;     ///< clipping distance along the viewing direction, > 0
    double depth_bias = 0;  ///< world units a line may lie behind the surface and still show
};

/// Where the camera looks from: azimuth about the up axis and elevation above the plane
/// perpendicular to it, in degrees (a 3/4 view by default); `up_axis` 0, 1 or 2 is x, y or z.
struct ViewDirection {
    double azimuth_degrees = 35, elevation_degrees = 25;
    int up_axis = 1;
};

/// The camera that frames `bounds` for a viewport of the given aspect ratio (width / height):
/// looking at the box's centre from `view`, fov_y 30°, at the smallest distance at which all
/// eight corners of the box project inside the central 90 % of the viewport in both directions
/// (REN-8, so every point in the box projects at least 5 % of the size away from the border);
/// near = 1 % of the distance to the box's nearest corner; depth_bias = 0.5 % of the box's
/// diagonal. The same camera for every panel of a figure makes left and right panels match.
/// \throws InvalidInput when aspect is not finite and positive, up_axis is not 0..2, or the box
///         is empty or not finite.
Camera camera_for(const Bounds& bounds, double aspect, const ViewDirection& view = {});

enum class Shading {
    flat,    ///< one normal per triangle: its facets show (what the paper's figures show)
    gouraud  ///< light computed at the vertices (area-weighted vertex normals), interpolated
};

/// A triangle mesh to draw. Spans are views: the caller keeps the data alive during render_panel().
struct MeshView {
    std::span<const Vec3> positions;      ///< #V
    std::span<const Triangle> triangles;  ///< #F, indices < #V
    /// empty, or 3·#F texture coordinates: corner k of triangle f at 3f + k. When given, the
    /// surface colour is the checkerboard of RenderStyle at the interpolated (u, v).
    std::span<const Eigen::Vector2d> corner_uv;
    /// empty, or #F colours (ignored when corner_uv is given).
    std::span<const Colour> face_colours;
    Colour colour = Colour(0.72, 0.76, 0.84);  ///< the colour when neither of the above is given
    Shading shading = Shading::flat;
    bool outline = false;  ///< draw every edge as a thin line (RenderStyle)
    /// draw the boundary edges — those of exactly one triangle — as thick lines of
    /// RenderStyle::boundary_colour (REN-15); a closed mesh has none
    bool boundary = false;
};

/// Polylines over the surfaces: paths[i] lists indices into `points`, drawn as consecutive
/// segments (a path of one point draws a dot).
struct PolylineView {
    std::span<const Vec3> points;
    std::span<const std::vector<std::uint32_t>> paths;
    Colour colour = Colour(0.85, 0.10, 0.08);
    double width_pixels = 1.6;  ///< in output pixels
    /// > 0: the parts behind the surface are drawn too, this wide in hidden_colour (step 5)
    double hidden_width_pixels = 0;
    Colour hidden_colour = Colour(0.6, 0.6, 0.6);
};

/// What one panel shows.
struct Panel {
    std::vector<MeshView> meshes;
    std::vector<PolylineView> polylines;
};

/// The procedural texture of Figure 7 (right): cells × cells squares over the unit square,
/// cell (i, j) = (⌊u·cells⌋, ⌊v·cells⌋) dark when i + j is odd.
struct Checkerboard {
    int cells = 8;
    Colour light = Colour(0.96, 0.93, 0.84), dark = Colour(0.16, 0.30, 0.58);
};

struct RenderStyle {
    int supersample = 3;  ///< samples per pixel in each direction, 1..8
    Colour background = Colour(1, 1, 1);
    Colour outline_colour = Colour(0.2, 0.2, 0.24);
    double outline_width_pixels = 0.5;
    Colour boundary_colour = Colour(0.0, 0.62, 0.30);  ///< green: unlike the surface, outlines and the network
    double boundary_width_pixels = 2.4;
    /// the parts of the boundary behind the surface: thinner and paler
    Colour hidden_boundary_colour = Colour(0.45, 0.80, 0.55);
    double hidden_boundary_width_pixels = 1.0;
    Checkerboard checker;
};

/// The checkerboard's colour at (u, v) (REN-7).
Colour checker_colour(const Checkerboard& checker, double u, double v);

/// Renders `panel` seen by `camera` into a width × height image (steps 1–6 above).
/// Shading (REN-6): a headlight from the camera, raised and moved to the left by a fixed amount;
/// colour = albedo · (0.3 + 0.6 |n·l|) + 0.15 |n·h|^32 (two-sided; h the half vector between
/// l and the viewing direction), clamped to [0, 1].
/// \pre the camera's eye ≠ target and up is not parallel to the viewing direction.
/// \throws InvalidInput when width or height is < 1, supersample is not in 1..8, an index is out
///         of range, a span has the wrong size, or a position, uv or colour is not finite.
Image render_panel(const Panel& panel, const Camera& camera, int width, int height, const RenderStyle& style = {});

}  // namespace fhr::render
