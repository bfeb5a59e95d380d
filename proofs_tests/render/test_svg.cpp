// FHR §4 and §6 figures — the SVG writers (spec/render.md REN-11, REN-12): well-formed
// documents (balanced tags, checked by a small tag parser), the expected number of elements,
// coordinates inside the canvas, nice axis ticks, escaping, determinism, atomic writes, refusals.
#include <catch2/catch.hpp>

#include <cmath>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <fhr/core/errors.hpp>
#include <fhr/render/figures.hpp>
#include <fhr/render/svg.hpp>
#include "support/test_support.hpp"

using namespace fhr;
using namespace fhr::render;

namespace {

// Checks that every tag is closed in order (comments, the XML declaration and self-closing tags
// allowed) and that no bare '<' or '&' appears in text. Returns "" or the first problem.
std::string tag_problem(const std::string& xml) {
    std::vector<std::string> open;
    std::size_t at = 0;
    while (at < xml.size()) {
        if (xml[at] == '&') {
            const std::size_t end = xml.find(';', at);
            const std::string entity = xml.substr(at, end == std::string::npos ? 1 : end - at + 1);
            if (entity != "&amp;" && entity != "&lt;" && entity != "&gt;" && entity != "&quot;") return "bare &";
            at = end + 1;
            continue;
        }
        if (xml[at] != '<') {
            ++at;
            continue;
        }
        const std::size_t end = xml.find('>', at);
        if (end == std::string::npos) return "unterminated tag";
        const std::string tag = xml.substr(at + 1, end - at - 1);
        at = end + 1;
        if (tag.empty()) return "empty tag";
        if (tag[0] == '?' || tag[0] == '!') continue;
        if (tag.find('<') != std::string::npos) return "'<' inside a tag";
        if (tag[0] == '/') {
            if (open.empty() || open.back() != tag.substr(1)) return "unbalanced </" + tag.substr(1) + ">";
            open.pop_back();
        } else if (tag.back() != '/') {
            open.push_back(tag.substr(0, tag.find(' ')));
        }
    }
    if (!open.empty()) return "<" + open.back() + "> never closed";
    return "";
}

std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

// All numbers in `points="…"`, `x1="…"` and the like.
std::vector<double> coordinates(const std::string& svg, const std::string& attribute) {
    std::vector<double> out;
    const std::regex pattern(attribute + "=\"([^\"]*)\"");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), pattern); it != std::sregex_iterator(); ++it) {
        std::string value = (*it)[1];
        for (char& c : value)
            if (c == ',') c = ' ';
        std::istringstream in(value);
        for (double x; in >> x;) out.push_back(x);
    }
    return out;
}

const std::array<Eigen::Vector2d, 3> equilateral{Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0),
                                                 Eigen::Vector2d(0.5, std::sqrt(3.0) / 2)};

// The one-to-four split of the triangle: 4 image triangles.
std::vector<ImageTriangle> four_triangles() {
    const Barycentric a{1, 0, 0}, b{0, 1, 0}, c{0, 0, 1}, ab{0.5, 0.5, 0}, bc{0, 0.5, 0.5}, ca{0.5, 0, 0.5};
    return {{a, ab, ca}, {ab, b, bc}, {ca, bc, c}, {ab, bc, ca}};
}

}  // namespace

TEST_CASE("REN-11: the patch SVG is well-formed with one polygon per image triangle plus the domain triangle",
          "[unit][render]") {
    const std::vector<ImageTriangle> image = four_triangles();
    const std::string svg = patch_svg(equilateral, image, 400);
    CHECK(tag_problem(svg) == "");
    CHECK(svg.rfind("<?xml", 0) == 0);
    CHECK(count(svg, "<svg ") == 1);
    CHECK(count(svg, "<polygon ") == image.size() + 1);
    CHECK(count(svg, "<rect ") == 1);
    // Every point lies in the canvas with the 5 % margin (to the printed precision).
    const std::vector<double> xy = coordinates(svg, "points");
    REQUIRE(xy.size() == 2 * 3 * (image.size() + 1));
    for (const double v : xy) {
        CHECK(v >= 20 - 0.01);
        CHECK(v <= 380 + 0.01);
    }
    // The last polygon is the domain triangle; corner 0 at the bottom left (y points up).
    const std::size_t last = xy.size() - 6;
    CHECK(xy[last] == Approx(20));
    CHECK(xy[last + 2] == Approx(380));
    CHECK(xy[last + 1] == xy[last + 3]);
    CHECK(xy[last + 5] < xy[last + 1]);
    CHECK(patch_svg(equilateral, image, 400) == svg);
}

TEST_CASE("REN-12: the rate–distortion plot has nice ticks, two series and a legend", "[unit][render]") {
    const std::vector<RatePoint> points{{20, 0.0121, 0.047}, {5, 0.03, 0.041}, {10, 0.02, 0.044}};
    RatePlotLabels labels;
    labels.title = "fandisk <J = 3> & friends";
    const std::string svg = rate_distortion_svg(points, labels);
    CHECK(tag_problem(svg) == "");
    CHECK(count(svg, "<polyline ") == 2);
    CHECK(count(svg, "<circle ") == 2 * points.size());
    // x: max 20 → step 5, ticks 0..20 (5); y: max 0.047 → step 0.01, ticks 0..0.05 (6).
    // Lines: 2 axes + 5 + 6 ticks + 2 legend samples.
    CHECK(count(svg, "<line ") == 2 + 5 + 6 + 2);
    for (const char* tick : {">0<", ">5<", ">10<", ">15<", ">20<", ">0.01<", ">0.02<", ">0.03<", ">0.04<", ">0.05<"})
        CHECK(count(svg, tick) == std::size_t{1} + (std::string(tick) == ">0<"));
    CHECK(count(svg, ">L2<") == 1);
    CHECK(count(svg, ">Hausdorff<") == 1);
    CHECK(count(svg, "fandisk &lt;J = 3&gt; &amp; friends") == 1);
    // The series are drawn in order of kept percent: the L2 polyline's x coordinates increase.
    const std::regex polyline("<polyline [^>]*points=\"([^\"]*)\"");
    std::smatch match;
    REQUIRE(std::regex_search(svg, match, polyline));
    std::istringstream in(match[1].str());
    double previous = -1;
    for (std::string pair; in >> pair;) {
        const double x = std::stod(pair.substr(0, pair.find(',')));
        CHECK(x > previous);
        previous = x;
    }
    // All coordinates inside the 640 × 420 canvas.
    for (const char* attribute : {"x1", "x2", "cx"})
        for (const double v : coordinates(svg, attribute)) CHECK((v >= 0 && v <= 640));
    for (const char* attribute : {"y1", "y2", "cy"})
        for (const double v : coordinates(svg, attribute)) CHECK((v >= 0 && v <= 420));
}

TEST_CASE("REN-12: axis ends for data of any scale, and all-zero errors", "[unit][render]") {
    // y max 1 → step 0.2, ticks 0..1 (6); x max 100 → step 20 (6 ticks): 2 + 6 + 6 + 2 lines.
    const std::vector<RatePoint> unit{{100, 1, 0.5}};
    CHECK(count(rate_distortion_svg(unit), "<line ") == 16);
    // max/5 exactly a power of ten: the step is that power (the multiple 1, not 2). x max 50 → step
    // 10, y max 5 → step 1: 6 ticks each, 2 + 6 + 6 + 2 lines.
    const std::vector<RatePoint> round{{50, 5, 0.5}};
    const std::string round_svg = rate_distortion_svg(round);
    CHECK(count(round_svg, "<line ") == 16);
    CHECK(count(round_svg, ">10<") == 1);
    CHECK(count(round_svg, ">1<") == 1);
    // All errors zero: the y axis runs to 1.
    const std::vector<RatePoint> zero{{100, 0, 0}, {50, 0, 0}};
    const std::string svg = rate_distortion_svg(zero);
    CHECK(tag_problem(svg) == "");
    CHECK(count(svg, ">1<") == 1);
    // Tiny errors: labels in exponent form where the shortest text needs it.
    const std::vector<RatePoint> tiny{{5, 3e-7, 4.2e-7}};
    const std::string tiny_svg = rate_distortion_svg(tiny);
    CHECK(count(tiny_svg, ">5e-07<") == 1);  // step 1e-7, ticks 0..5e-7
}

TEST_CASE("REN-11, REN-12: writers are atomic and bad input is refused", "[unit][render]") {
    const std::vector<ImageTriangle> image = four_triangles();
    const std::string patch = fhr::test::temp_path("patch.svg"), plot = fhr::test::temp_path("plot.svg");
    write_patch_svg(patch, equilateral, image);
    CHECK(fhr::test::read_file(patch) == patch_svg(equilateral, image));
    const std::vector<RatePoint> points{{5, 1, 2}, {20, 0.5, 1}};
    write_rate_distortion_svg(plot, points);
    CHECK(fhr::test::read_file(plot) == rate_distortion_svg(points));

    const std::array<Eigen::Vector2d, 3> collinear{Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1), Eigen::Vector2d(2, 2)};
    CHECK_THROWS_AS(patch_svg(collinear, image), InvalidInput);
    std::vector<ImageTriangle> nan_image = image;
    nan_image[1][2][0] = std::nan("");
    CHECK_THROWS_AS(patch_svg(equilateral, nan_image), InvalidInput);
    CHECK_THROWS_AS(patch_svg(equilateral, image, 8), InvalidInput);
    CHECK_THROWS_AS(rate_distortion_svg({}), InvalidInput);
    const std::vector<RatePoint> negative{{5, -1, 0}};
    CHECK_THROWS_AS(rate_distortion_svg(negative), InvalidInput);
    CHECK_THROWS_AS(write_patch_svg(fhr::test::temp_path("no/such/dir/p.svg"), equilateral, image), InvalidInput);
}

TEST_CASE("REN-16: the anisotropy colours: blue 1, green 10, yellow 100, red from 1000, grey when degenerate",
          "[unit][render]") {
    using fhr::render::anisotropy_colour;
    using fhr::render::Colour;
    const auto near = [](const Colour& a, const Colour& b) { return (a - b).cwiseAbs().maxCoeff() < 1e-12; };
    CHECK(near(anisotropy_colour(1), Colour(0.19, 0.35, 0.80)));
    CHECK(near(anisotropy_colour(10), Colour(0.20, 0.72, 0.38)));
    CHECK(near(anisotropy_colour(100), Colour(0.98, 0.80, 0.15)));
    CHECK(near(anisotropy_colour(1000), Colour(0.80, 0.10, 0.10)));
    CHECK(near(anisotropy_colour(1e9), anisotropy_colour(1000)));     // clamped above
    CHECK(near(anisotropy_colour(1 - 1e-15), anisotropy_colour(1)));  // rounding below 1
    CHECK(near(anisotropy_colour(std::sqrt(10.0)),
               (Colour(0.19, 0.35, 0.80) + Colour(0.20, 0.72, 0.38)) / 2));  // log-linear
    for (const double bad : {0.0, -1.0, std::nan(""), HUGE_VAL})
        CHECK(near(anisotropy_colour(bad), Colour(0.6, 0.6, 0.6)));
}

TEST_CASE("REN-16: the distortion legend is one colour bar with its ticks and the degenerate swatch",
          "[unit][render]") {
    const std::string svg = fhr::render::anisotropy_legend_svg();
    CHECK(svg.rfind("<?xml", 0) == 0);
    CHECK(svg.find("</svg>") != std::string::npos);
    const auto count = [&](const std::string& what) {
        int n = 0;
        for (std::size_t at = svg.find(what); at != std::string::npos; at = svg.find(what, at + 1)) ++n;
        return n;
    };
    CHECK(count("<rect") == 1 + 60 + 1);  // background, the bar, the degenerate swatch
    CHECK(count("<line") == 7);
    for (const char* tick : {">1<", ">3<", ">10<", ">30<", ">100<", ">300<", ">≥ 1000<", ">degenerate<"})
        CHECK(svg.find(tick) != std::string::npos);
    // The first bar, at log10 ratio 0.025: blue + 0.025 (green − blue) = (0.19025, 0.35925, 0.7895) · 255.
    CHECK(svg.find("fill=\"#315cc9\"") != std::string::npos);
    const std::string path = fhr::test::temp_path("legend.svg");
    fhr::render::write_anisotropy_legend_svg(path);
    CHECK(fhr::test::read_file(path) == svg);
}
