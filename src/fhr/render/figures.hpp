// FHR §6 — Figures 6–9 of the paper as two-panel PNGs (spec/render.md REN-13; how they are made:
// paper_notes/figures.md):
//   Fig. 6  the fine triangulation T (left) and the coarse domain triangulation D (right)
//   Fig. 7  the geodesic paths on Ω_T (left) and the parameterization of Ω_T over Ω_D (right):
//           T′ with a checkerboard over each patch S_i through φ (per-corner uv of ψ_i)
//   Fig. 8  the dyadic refinement D³ (left) and the approximation f³(Ω_D) of Ω_T (right)
//   Fig. 9  wavelet reconstructions of f³ from 5 % (left) and 20 % (right) of the coefficients
// Beyond the paper: a surface with boundary shows its boundary in every panel, thick and
// green (REN-15).
// Data only: positions, triangles, index lists and uv arrays; no dependence on the pipeline.
// One camera for both panels (and, when the caller passes the same one, for every figure), so
// left and right panels show the surface from the same place at the same scale.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include <fhr/render/raster.hpp>

namespace fhr::render {

/// The whole figure's size in pixels; each panel is half of it (the left panel width/2 rounded
/// down, the right one the rest).
struct FigureSize {
    int width = 1200, height = 600;
    /// The aspect ratio to pass to camera_for: (width / 2) / height.
    double panel_aspect() const { return double(width / 2) / double(height); }
};

/// The two panels rendered side by side into one width × height image.
/// \throws InvalidInput as render_panel(), and when width < 2.
Image render_two_panels(const Camera& camera, const Panel& left, const Panel& right, int width, int height,
                        const RenderStyle& style = {});

/// render_two_panels(...) written atomically as PNG to `path` (REN-1..3, REN-13).
void write_two_panel_png(const std::string& path, const Camera& camera, const Panel& left, const Panel& right,
                         int width, int height, const RenderStyle& style = {});

/// A triangle mesh: #V positions, #F triangles (indices < #V, counter-clockwise seen from outside).
struct MeshData {
    std::span<const Vec3> positions;
    std::span<const Triangle> triangles;
};

/// Polylines: each path lists indices into `points` (e.g. the vertices of T′ along one
/// geodesic curve Γ(x_j, x_k), or the points of the path on T).
struct PathData {
    std::span<const Vec3> points;
    std::span<const std::vector<std::uint32_t>> paths;
};

/// camera_for(bounds_of(positions), size.panel_aspect(), view): the camera of a figure framing a
/// surface (pass T's positions to give every figure the same view).
Camera figure_camera(std::span<const Vec3> positions, const FigureSize& size = {}, const ViewDirection& view = {});

// In every panel the boundary of a surface with holes is drawn as thick lines of
// RenderStyle::boundary_colour (REN-15): the edges of exactly one triangle of each mesh, and in
// Fig. 7 (left) the boundary curves of D (partition::CurveKind::boundary) on T.

/// Fig. 6: T flat-shaded (left), D flat-shaded with its edges outlined (right); both boundaries drawn.
void write_fig6(const std::string& path, const Camera& camera, const MeshData& t, const MeshData& d,
                const FigureSize& size = {});

/// Fig. 7: T flat-shaded with the network drawn over it (left): the domain edges that are exact
/// geodesics in red, those that are restricted shortest paths (keeping D) in gold, the boundary
/// curves (arcs of T's boundary) thick in the boundary colour; T′ flat-shaded with the
/// checkerboard (8 × 8 cells over the unit square) at the per-corner uv and its boundary drawn (right).
/// \param corner_uv  3·#F(t_prime) coordinates, corner k of triangle f at 3f + k; for patch S_i,
///                   the image ψ_i in the unit square, e.g. (β1, β2) of the exchange file.
void write_fig7(const std::string& path, const Camera& camera, const MeshData& t, const PathData& geodesics,
                const PathData& restricted, const PathData& boundary, const MeshData& t_prime,
                std::span<const Eigen::Vector2d> corner_uv, const FigureSize& size = {});

/// Fig. 8: D³ flat-shaded with its edges outlined (left), f³(Ω_D) flat-shaded (right); both boundaries drawn.
void write_fig8(const std::string& path, const Camera& camera, const MeshData& d3, const MeshData& f3,
                const FigureSize& size = {});

/// REN-16: the colour of a face whose map has anisotropy σ₁/σ₂ = `ratio` (spec/distortion.md
/// DIST-7) on a log scale: log10(ratio)/3 through blue (1, the shape kept), green (10), yellow
/// (100) to red (1000 and more), linear between them (a ratio rounded below 1 is 1); grey for a
/// degenerate face (a ratio of 0, or not finite).
Colour anisotropy_colour(double ratio);

/// REN-16, the distortion figure (beyond the paper): T′ flat-shaded, each face in
/// anisotropy_colour of its σ₁/σ₂ (left); the same with the network of curves drawn over it, to
/// show where the stretched faces lie against the patches' sides (right).
/// \pre ratio.size() is T′'s face count.
void write_distortion_figure(const std::string& path, const Camera& camera, const MeshData& t_prime,
                             std::span<const double> ratio, const PathData& curves, const FigureSize& size = {});

/// Fig. 9: two reconstructions of f³ flat-shaded (left: 5 %, right: 20 % in the paper); boundaries drawn.
void write_fig9(const std::string& path, const Camera& camera, const MeshData& left, const MeshData& right,
                const FigureSize& size = {});

}  // namespace fhr::render
