// FHR §6 — Figures 6–9 as two-panel PNGs (see figures.hpp and paper_notes/figures.md), and beyond
// the paper the distortion figure (REN-16).
#include <fhr/render/figures.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <fhr/core/errors.hpp>
#include <fhr/render/png.hpp>

namespace fhr::render {
namespace {

// A mesh flat-shaded, its edges outlined when asked, its boundary drawn unless the caller draws
// it as curves (Fig. 7 left) — REN-15.
MeshView shaded(const MeshData& mesh, bool outline, bool boundary = true) {
    MeshView view;
    view.positions = mesh.positions;
    view.triangles = mesh.triangles;
    view.outline = outline;
    view.boundary = boundary;
    return view;
}

PolylineView lines_of(const PathData& data, const Colour& colour, double width_pixels) {
    PolylineView lines;
    lines.points = data.points;
    lines.paths = data.paths;
    lines.colour = colour;
    lines.width_pixels = width_pixels;
    return lines;
}

// The boundary curves drawn as a mesh's boundary is (RenderStyle's boundary and hidden boundary).
PolylineView boundary_lines(const PathData& data) {
    const RenderStyle style;
    PolylineView lines = lines_of(data, style.boundary_colour, style.boundary_width_pixels);
    lines.hidden_colour = style.hidden_boundary_colour;
    lines.hidden_width_pixels = style.hidden_boundary_width_pixels;
    return lines;
}

Panel panel_of(const MeshView& mesh) { return Panel{{mesh}, {}}; }

}  // namespace

Image render_two_panels(const Camera& camera, const Panel& left, const Panel& right, int width, int height,
                        const RenderStyle& style) {
    if (width < 2) throw InvalidInput("render: a two-panel figure needs a width ≥ 2");
    const int left_width = width / 2, right_width = width - left_width;
    const Image a = render_panel(left, camera, left_width, height, style);
    const Image b = render_panel(right, camera, right_width, height, style);
    Image out(width, height, Rgb8{});
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < left_width; ++x) out.set(x, y, a.at(x, y));
        for (int x = 0; x < right_width; ++x) out.set(left_width + x, y, b.at(x, y));
    }
    return out;
}

void write_two_panel_png(const std::string& path, const Camera& camera, const Panel& left, const Panel& right,
                         int width, int height, const RenderStyle& style) {
    write_png(path, render_two_panels(camera, left, right, width, height, style));
}

Camera figure_camera(std::span<const Vec3> positions, const FigureSize& size, const ViewDirection& view) {
    return camera_for(bounds_of(positions), size.panel_aspect(), view);
}

void write_fig6(const std::string& path, const Camera& camera, const MeshData& t, const MeshData& d,
                const FigureSize& size) {
    write_two_panel_png(path, camera, panel_of(shaded(t, false)), panel_of(shaded(d, true)), size.width, size.height);
}

void write_fig7(const std::string& path, const Camera& camera, const MeshData& t, const PathData& geodesics,
                const PathData& restricted, const PathData& boundary, const MeshData& t_prime,
                std::span<const Eigen::Vector2d> corner_uv, const FigureSize& size) {
    const PolylineView red;  // the default polyline colour and width
    Panel left = panel_of(shaded(t, false, false));
    left.polylines = {lines_of(geodesics, red.colour, red.width_pixels),
                      lines_of(restricted, Colour(0.95, 0.72, 0.05), red.width_pixels), boundary_lines(boundary)};
    MeshView textured = shaded(t_prime, false);
    textured.corner_uv = corner_uv;
    write_two_panel_png(path, camera, left, panel_of(textured), size.width, size.height);
}

void write_fig8(const std::string& path, const Camera& camera, const MeshData& d3, const MeshData& f3,
                const FigureSize& size) {
    write_two_panel_png(path, camera, panel_of(shaded(d3, true)), panel_of(shaded(f3, false)), size.width, size.height);
}

void write_fig9(const std::string& path, const Camera& camera, const MeshData& left, const MeshData& right,
                const FigureSize& size) {
    write_two_panel_png(path, camera, panel_of(shaded(left, false)), panel_of(shaded(right, false)), size.width,
                        size.height);
}

Colour anisotropy_colour(double ratio) {
    if (!(ratio > 0) || !std::isfinite(ratio)) return Colour(0.6, 0.6, 0.6);
    const std::array<Colour, 4> stops{Colour(0.19, 0.35, 0.80), Colour(0.20, 0.72, 0.38), Colour(0.98, 0.80, 0.15),
                                      Colour(0.80, 0.10, 0.10)};
    // 0..3: one stop per factor of ten (a ratio a rounding below 1, as σ₁ = σ₂ may give, is 1)
    const double t = std::clamp(std::log10(ratio), 0.0, 3.0);
    const int k = std::min(static_cast<int>(t), 2);
    return stops[k] + (t - k) * (stops[k + 1] - stops[k]);
}

void write_distortion_figure(const std::string& path, const Camera& camera, const MeshData& t_prime,
                             std::span<const double> ratio, const PathData& curves, const FigureSize& size) {
    std::vector<Colour> colours(ratio.size());
    std::transform(ratio.begin(), ratio.end(), colours.begin(), anisotropy_colour);
    MeshView coloured = shaded(t_prime, false);
    coloured.face_colours = colours;
    Panel right = panel_of(coloured);
    right.polylines.push_back(lines_of(curves, Colour(0.1, 0.1, 0.1), 1.2));
    write_two_panel_png(path, camera, panel_of(coloured), right, size.width, size.height);
}

}  // namespace fhr::render
