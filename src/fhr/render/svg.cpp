// FHR §4 and §6 figures — the SVG writers (see svg.hpp): ψ_i(S_i) in its triangle and the
// rate–distortion plot.
#include <fhr/render/svg.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <vector>

#include <fhr/core/errors.hpp>
#include <fhr/render/figures.hpp>
#include <fhr/io/detail/atomic_file.hpp>

namespace fhr::render {
namespace {

[[noreturn]] void refuse(const std::string& what) { throw InvalidInput("svg: " + what); }

// x with two decimals, locale-free; −0.00 printed as 0.00.
std::string fixed(double x) {
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, x, std::chars_format::fixed, 2);
    std::string text(buffer, result.ptr);
    if (text == "-0.00") text = "0.00";
    return text;
}

// A tick label: the shortest text that reads back as the value rounded to 6 significant digits.
std::string label(double x) {
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, x, std::chars_format::general, 6);
    return std::string(buffer, result.ptr);
}

std::string header(int width, int height) {
    const std::string w = std::to_string(width), h = std::to_string(height);
    return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" "
           "width=\"" +
           w + "\" height=\"" + h + "\" viewBox=\"0 0 " + w + " " + h + "\">\n<rect width=\"" + w + "\" height=\"" + h +
           "\" fill=\"white\"/>\n";
}

std::string line(double x1, double y1, double x2, double y2, const std::string& attributes) {
    return "<line x1=\"" + fixed(x1) + "\" y1=\"" + fixed(y1) + "\" x2=\"" + fixed(x2) + "\" y2=\"" + fixed(y2) +
           "\" " + attributes + "/>\n";
}

std::string text(double x, double y, const std::string& anchor, const std::string& content,
                 const std::string& extra = "") {
    return "<text x=\"" + fixed(x) + "\" y=\"" + fixed(y) + "\" text-anchor=\"" + anchor + "\"" + extra + ">" +
           xml_escaped(content) + "</text>\n";
}

// REN-12: the axis step and the number of steps for data up to `max`.
struct Axis {
    double step = 1;
    int steps = 1;
    double end() const { return step * steps; }
};

Axis nice_axis(double max) {
    if (max == 0) max = 1;
    const double raw = max / 5;
    const double power = std::pow(10.0, std::floor(std::log10(raw)));
    Axis axis;
    for (const double m : {1.0, 2.0, 5.0, 10.0}) {
        axis.step = m * power;
        if (axis.step >= raw) break;
    }
    // The relative slack absorbs the rounding of max/step when max is itself a multiple of step.
    axis.steps = std::max(1, int(std::ceil(max / axis.step * (1 - 1e-12))));
    return axis;
}

}  // namespace

std::string xml_escaped(std::string_view text) {
    std::string out;
    for (const char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            default: out += c;
        }
    }
    return out;
}

std::string patch_svg(const std::array<Eigen::Vector2d, 3>& corners, std::span<const ImageTriangle> image, int size) {
    if (size < 16) refuse("canvas size " + std::to_string(size) + " < 16");
    for (const Eigen::Vector2d& c : corners)
        if (!c.allFinite()) refuse("a triangle corner is not finite");
    const Eigen::Vector2d e1 = corners[1] - corners[0], e2 = corners[2] - corners[0];
    if (!(std::abs(e1.x() * e2.y() - e1.y() * e2.x()) > 0)) refuse("the domain triangle's corners are collinear");
    const Eigen::Vector2d lo = corners[0].cwiseMin(corners[1]).cwiseMin(corners[2]);
    const Eigen::Vector2d hi = corners[0].cwiseMax(corners[1]).cwiseMax(corners[2]);
    const double margin = 0.05 * size, scale = (size - 2 * margin) / (hi - lo).maxCoeff();
    // Centred in the canvas, y up.
    const Eigen::Vector2d offset = (Eigen::Vector2d(size, size) - scale * (hi - lo)) / 2;
    const auto point = [&](const Barycentric& beta) {
        const Eigen::Vector2d p = beta[0] * corners[0] + beta[1] * corners[1] + beta[2] * corners[2];
        return fixed(offset.x() + scale * (p.x() - lo.x())) + "," + fixed(size - offset.y() - scale * (p.y() - lo.y()));
    };
    std::string out = header(size, size);
    out += "<g fill=\"none\" stroke=\"#3a5a8c\" stroke-width=\"0.6\" stroke-linejoin=\"round\">\n";
    for (std::size_t t = 0; t < image.size(); ++t) {
        for (const Barycentric& beta : image[t])
            for (const double b : beta)
                if (!std::isfinite(b)) refuse("image triangle " + std::to_string(t) + " has a β that is not finite");
        out +=
            "<polygon points=\"" + point(image[t][0]) + " " + point(image[t][1]) + " " + point(image[t][2]) + "\"/>\n";
    }
    out += "</g>\n<polygon points=\"" + point({1, 0, 0}) + " " + point({0, 1, 0}) + " " + point({0, 0, 1}) +
           "\" fill=\"none\" stroke=\"black\" stroke-width=\"2\" stroke-linejoin=\"round\"/>\n</svg>\n";
    return out;
}

void write_patch_svg(const std::string& path, const std::array<Eigen::Vector2d, 3>& corners,
                     std::span<const ImageTriangle> image, int size) {
    io::write_file_atomically(path, patch_svg(corners, image, size));
}

std::string rate_distortion_svg(std::span<const RatePoint> points, const RatePlotLabels& labels) {
    if (points.empty()) refuse("rate–distortion plot of no points");
    for (std::size_t i = 0; i < points.size(); ++i) {
        const RatePoint& p = points[i];
        for (const double v : {p.kept_percent, p.l2, p.hausdorff})
            if (!(v >= 0) || !std::isfinite(v))
                refuse("point " + std::to_string(i) + " has a negative or non-finite value");
    }
    std::vector<RatePoint> sorted(points.begin(), points.end());
    std::stable_sort(sorted.begin(), sorted.end(),
                     [](const RatePoint& a, const RatePoint& b) { return a.kept_percent < b.kept_percent; });
    double x_max = 0, y_max = 0;
    for (const RatePoint& p : sorted) {
        x_max = std::max(x_max, p.kept_percent);
        y_max = std::max({y_max, p.l2, p.hausdorff});
    }
    const Axis x_axis = nice_axis(x_max), y_axis = nice_axis(y_max);

    constexpr int width = 640, height = 420;
    constexpr double left = 80, right = 610, top = 50, bottom = 360;  // the plot area
    const auto sx = [&](double x) { return left + (right - left) * x / x_axis.end(); };
    const auto sy = [&](double y) { return bottom - (bottom - top) * y / y_axis.end(); };

    std::string out = header(width, height);
    out += "<g font-family=\"sans-serif\" font-size=\"13\" fill=\"black\">\n";
    out += text(width / 2.0, 28, "middle", labels.title, " font-size=\"16\"");
    out += text((left + right) / 2, height - 14, "middle", labels.x);
    out += text(20, (top + bottom) / 2, "middle", labels.y,
                " transform=\"rotate(-90 20 " + fixed((top + bottom) / 2) + ")\"");
    const std::string axis_style = "stroke=\"black\" stroke-width=\"1.2\"";
    out += line(left, bottom, right, bottom, axis_style);
    out += line(left, bottom, left, top, axis_style);
    for (int k = 0; k <= x_axis.steps; ++k) {
        const double value = k * x_axis.step, x = sx(value);
        out += line(x, bottom, x, bottom + 6, axis_style);
        out += text(x, bottom + 22, "middle", label(value));
    }
    for (int k = 0; k <= y_axis.steps; ++k) {
        const double value = k * y_axis.step, y = sy(value);
        out += line(left - 6, y, left, y, axis_style);
        out += text(left - 10, y + 4, "end", label(value));
    }
    struct Series {
        const char* name;
        const char* colour;
        double RatePoint::*value;
    };
    const Series series[2] = {{"L2", "#1f5fa8", &RatePoint::l2}, {"Hausdorff", "#c0392b", &RatePoint::hausdorff}};
    for (int s = 0; s < 2; ++s) {
        std::string polyline =
            "<polyline fill=\"none\" stroke=\"" + std::string(series[s].colour) + "\" stroke-width=\"2\" points=\"";
        std::string circles;
        for (std::size_t i = 0; i < sorted.size(); ++i) {
            const double x = sx(sorted[i].kept_percent), y = sy(sorted[i].*series[s].value);
            if (i > 0) polyline += ' ';
            polyline += fixed(x);
            polyline += ',';
            polyline += fixed(y);
            circles += "<circle cx=\"" + fixed(x) + "\" cy=\"" + fixed(y) + "\" r=\"3.5\" fill=\"" + series[s].colour +
                       "\"/>\n";
        }
        out += polyline + "\"/>\n" + circles;
        const double legend_y = top + 14 + 20 * s;
        out += line(right - 150, legend_y - 4, right - 120, legend_y - 4,
                    "stroke=\"" + std::string(series[s].colour) + "\" stroke-width=\"2\"");
        out += text(right - 112, legend_y, "start", series[s].name);
    }
    out += "</g>\n</svg>\n";
    return out;
}

void write_rate_distortion_svg(const std::string& path, std::span<const RatePoint> points,
                               const RatePlotLabels& labels) {
    io::write_file_atomically(path, rate_distortion_svg(points, labels));
}

std::string anisotropy_legend_svg() {
    constexpr int width = 420, height = 90, bars = 60;
    constexpr double left = 20, right = 380, top = 30, bottom = 50;
    const auto hex = [](const Colour& c) {
        char buffer[8];
        std::snprintf(buffer, sizeof buffer, "#%02x%02x%02x", static_cast<int>(std::lround(255 * c[0])),
                      static_cast<int>(std::lround(255 * c[1])), static_cast<int>(std::lround(255 * c[2])));
        return std::string(buffer);
    };
    std::string out = header(width, height);
    out += "<g font-family=\"sans-serif\" font-size=\"12\" fill=\"black\">\n";
    out += text(left, 18, "start", "anisotropy σ₁/σ₂ of each face of T′ (log scale)");
    for (int k = 0; k < bars; ++k) {  // bar k: log10 of the ratio at its middle
        const double x0 = left + (right - left) * k / bars, x1 = left + (right - left) * (k + 1) / bars;
        out += "<rect x=\"" + fixed(x0) + "\" y=\"" + fixed(top) + "\" width=\"" + fixed(x1 - x0 + 0.01) +
               "\" height=\"" + fixed(bottom - top) + "\" fill=\"" +
               hex(anisotropy_colour(std::pow(10.0, 3.0 * (k + 0.5) / bars))) + "\"/>\n";
    }
    for (const double tick : {1.0, 3.0, 10.0, 30.0, 100.0, 300.0, 1000.0}) {
        const double x = left + (right - left) * std::log10(tick) / 3;
        out += line(x, bottom, x, bottom + 5, "stroke=\"black\" stroke-width=\"1\"");
        out += text(x, bottom + 18, "middle", tick == 1000.0 ? "≥ 1000" : label(tick));
    }
    out += "<rect x=\"392\" y=\"" + fixed(top) + "\" width=\"20\" height=\"" + fixed(bottom - top) + "\" fill=\"" +
           hex(anisotropy_colour(0)) + "\"/>\n";
    out += text(402, bottom + 18, "middle", "degenerate", " font-size=\"9\"");
    out += "</g>\n</svg>\n";
    return out;
}

void write_anisotropy_legend_svg(const std::string& path) { io::write_file_atomically(path, anisotropy_legend_svg()); }

}  // namespace fhr::render
