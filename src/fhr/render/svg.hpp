// FHR §4 and §6 figures — two small SVG 1.1 plots (spec/render.md REN-11, REN-12):
//   • one patch's image ψ_i(S_i) inside its domain triangle T_i (§4: ψ_i maps the patch S_i one
//     to one onto T_i; the picture shows the image triangulation, as in Floater's papers);
//   • the rate–distortion plot of §6's compression (kept coefficients in percent against the
//     L2 and Hausdorff errors of the reconstruction).
// Numbers are printed with std::to_chars (locale-free), so the bytes depend only on the data.
#pragma once

#include <array>
#include <span>
#include <string>
#include <string_view>

#include <Eigen/Core>

namespace fhr::render {

/// `text` with &, <, > and " written as XML (and HTML) entities.
std::string xml_escaped(std::string_view text);

/// Barycentric coordinates (β0, β1, β2) of a point with respect to a domain triangle's corners,
/// as in the `fhr-param 1` exchange file (spec/param.md).
using Barycentric = std::array<double, 3>;

/// One triangle of ψ_i(S_i): the β of its three corners.
using ImageTriangle = std::array<Barycentric, 3>;

/// The SVG of ψ_i(S_i): the domain triangle with corners `corners` (any non-degenerate planar
/// triangle, e.g. T_i laid flat or an equilateral one) scaled to fit a size × size canvas with a
/// 5 % margin (y pointing up), each image triangle as one `<polygon>` with a thin stroke and no
/// fill, then the domain triangle as one `<polygon>` with a thick stroke: image.size() + 1
/// polygons over one white background `<rect>` (REN-11). Point β ↦ Σ_k β_k corners[k].
/// \throws InvalidInput when the corners are collinear or not finite, a β is not finite, or
///         size < 16.
std::string patch_svg(const std::array<Eigen::Vector2d, 3>& corners, std::span<const ImageTriangle> image,
                      int size = 600);

/// patch_svg(...) written atomically to `path`.
void write_patch_svg(const std::string& path, const std::array<Eigen::Vector2d, 3>& corners,
                     std::span<const ImageTriangle> image, int size = 600);

/// One reconstruction: the percentage of wavelet coefficients kept and its errors.
struct RatePoint {
    double kept_percent = 0;
    double l2 = 0, hausdorff = 0;
};

struct RatePlotLabels {
    std::string title = "Rate–distortion";
    std::string x = "wavelet coefficients kept (%)";
    std::string y = "error";
};

/// The SVG (640 × 420) of the errors against kept percent, points sorted by kept_percent. Each
/// axis runs from 0 to m = step · ⌈max/step⌉ (max its largest datum, 1 if that is 0), step the
/// smallest of 1, 2, 5, 10 times a power of ten with step ≥ max/5, ticks at 0, step, …, m
/// (4 to 6 ticks; REN-12). Elements: one white background `<rect>`; two axis `<line>`s;
/// one tick `<line>` and one `<text>` label per tick; the series L2 and Hausdorff as one
/// `<polyline>` each with one `<circle>` per point; a legend with one `<line>` and one `<text>`
/// per series; title and axis labels as `<text>` (XML-escaped).
/// \throws InvalidInput when `points` is empty or a value is negative or not finite.
std::string rate_distortion_svg(std::span<const RatePoint> points, const RatePlotLabels& labels = {});

/// REN-16: the legend of the distortion figure, 420 × 90: a colour bar of 60 `<rect>`s from
/// σ₁/σ₂ = 1 to 1000 on a log scale in anisotropy_colour (figures.hpp), a tick `<line>` and
/// `<text>` at 1, 3, 10, 30, 100, 300 and ≥ 1000, a grey square for degenerate faces, a title.
std::string anisotropy_legend_svg();

/// anisotropy_legend_svg() written atomically to `path`.
void write_anisotropy_legend_svg(const std::string& path);

/// rate_distortion_svg(...) written atomically to `path`.
void write_rate_distortion_svg(const std::string& path, std::span<const RatePoint> points,
                               const RatePlotLabels& labels = {});

}  // namespace fhr::render
