// FHR §6 figures — the rasterizer and Figures 6–9 (spec/render.md REN-4..10, REN-13): the
// z-buffer independent of draw order, perspective-correct texture coordinates, the checkerboard,
// flat and Gouraud shading, polylines over the surface thanks to the depth bias (and hidden
// behind it), near-plane clipping, camera framing, determinism, the boundary of a surface with
// holes (REN-15), and the two-panel figures.
#include <catch2/catch.hpp>
#include <rapidcheck/catch.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include <fhr/core/errors.hpp>
#include <fhr/generate/random_mesh.hpp>
#include <fhr/render/figures.hpp>
#include <fhr/render/png.hpp>
#include <fhr/render/raster.hpp>
#include "render/png_reader.hpp"
#include "support/test_support.hpp"

using namespace fhr;
using namespace fhr::render;

namespace {

constexpr double pi = std::numbers::pi;

// The pinhole projection of raster.hpp written out again: normalized device coordinates
// (−1..1 across the viewport, y up) and the depth along the viewing direction.
struct Projected {
    double nx, ny, w;
};

Projected project(const Camera& c, const Vec3& p, double aspect) {
    const Vec3 f = (c.target - c.eye).normalized();
    const Vec3 r = f.cross(c.up).normalized();
    const Vec3 u = r.cross(f);
    const Vec3 v = p - c.eye;
    const double t = std::tan(c.fov_y_degrees * pi / 360);
    return {v.dot(r) / (v.dot(f) * t * aspect), v.dot(u) / (v.dot(f) * t), v.dot(f)};
}

// The pixel (column, row) where p appears in a width × height image; it must be in the image.
std::pair<int, int> pixel_of(const Camera& c, const Vec3& p, int width, int height) {
    const Projected q = project(c, p, double(width) / height);
    const int x = int(std::floor((q.nx + 1) / 2 * width)), y = int(std::floor((1 - q.ny) / 2 * height));
    REQUIRE((x >= 0 && x < width && y >= 0 && y < height));
    return {x, y};
}

Camera front_camera(double distance = 5) {
    Camera c;
    c.eye = Vec3(0, 0, distance);
    c.target = Vec3::Zero();
    c.up = Vec3::UnitY();
    c.depth_bias = 0.01;
    return c;
}

// Two triangles of the square [−s, s]² at height z, counter-clockwise seen from +z, with uv
// (0,0), (1,0), (1,1), (0,1) at its corners.
struct Square {
    std::vector<Vec3> positions;
    std::vector<Triangle> triangles{{0, 1, 2}, {0, 2, 3}};
    std::vector<Eigen::Vector2d> uv{{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}};
    Square(double s, double z, double tilt_radians = 0) {
        for (const auto& [x, y] : {std::pair{-s, -s}, {s, -s}, {s, s}, {-s, s}})
            positions.emplace_back(x, y * std::cos(tilt_radians), z + y * std::sin(tilt_radians));
    }
    MeshView view() const {
        MeshView m;
        m.positions = positions;
        m.triangles = triangles;
        return m;
    }
};

// A pixel of a lit, pure-coloured surface: one channel well above the other two.
bool dominant(int x, int y, int z) { return x > y + 60 && x > z + 60; }
bool red(Rgb8 c) { return dominant(c.r, c.g, c.b); }
bool green(Rgb8 c) { return dominant(c.g, c.r, c.b); }
bool blue(Rgb8 c) { return dominant(c.b, c.r, c.g); }
bool white(Rgb8 c) { return c.r == 255 && c.g == 255 && c.b == 255; }

}  // namespace

TEST_CASE("REN-5: the nearer triangle wins at every pixel, whatever the draw order", "[unit][render]") {
    const Square near_square(0.6, 1), far_square(1.0, -1);
    const std::vector<Colour> red_colour{Colour(1, 0, 0)}, blue_colour{Colour(0, 0, 1)};
    MeshView near_view = near_square.view(), far_view = far_square.view();
    near_view.colour = Colour(1, 0, 0);
    far_view.colour = Colour(0, 0, 1);
    const Camera camera = front_camera();
    const Image near_first = render_panel(Panel{{near_view, far_view}, {}}, camera, 120, 90);
    const Image far_first = render_panel(Panel{{far_view, near_view}, {}}, camera, 120, 90);
    CHECK(near_first.rgb == far_first.rgb);
    CHECK(red(near_first.at(60, 45)));
    // Outside the near square but inside the far one: blue.
    const auto [bx, by] = pixel_of(camera, Vec3(0.96, 0, -1), 120, 90);
    CHECK(blue(near_first.at(bx, by)));

    // One mesh whose triangles come in either order, coloured per face.
    std::vector<Vec3> positions = near_square.positions;
    positions.insert(positions.end(), far_square.positions.begin(), far_square.positions.end());
    const std::vector<Triangle> forward{{0, 1, 2}, {0, 2, 3}, {4, 5, 6}, {4, 6, 7}};
    const std::vector<Triangle> backward{{4, 6, 7}, {4, 5, 6}, {0, 2, 3}, {0, 1, 2}};
    const std::vector<Colour> forward_colours{Colour(1, 0, 0), Colour(1, 0, 0), Colour(0, 0, 1), Colour(0, 0, 1)};
    const std::vector<Colour> backward_colours{Colour(0, 0, 1), Colour(0, 0, 1), Colour(1, 0, 0), Colour(1, 0, 0)};
    MeshView a, b;
    a.positions = b.positions = positions;
    a.triangles = forward;
    a.face_colours = forward_colours;
    b.triangles = backward;
    b.face_colours = backward_colours;
    const Image ia = render_panel(Panel{{a}, {}}, camera, 120, 90), ib = render_panel(Panel{{b}, {}}, camera, 120, 90);
    CHECK(ia.rgb == ib.rgb);
    CHECK(ia.rgb == near_first.rgb);
}

TEST_CASE("REN-7: the checkerboard alternates its two colours across cells", "[unit][render]") {
    Checkerboard checker;
    checker.cells = 8;
    checker.light = Colour(1, 0, 0);
    checker.dark = Colour(0, 1, 0);
    CHECK(checker_colour(checker, 0.01, 0.01) == checker.light);
    CHECK(checker_colour(checker, 0.13, 0.01) == checker.dark);   // cell (1, 0)
    CHECK(checker_colour(checker, 0.13, 0.13) == checker.light);  // cell (1, 1)
    CHECK(checker_colour(checker, 0.99, 0.01) == checker.dark);   // cell (7, 0)

    // A textured square shows both colours, each on about half of it.
    const Square square(1, 0);
    MeshView view = square.view();
    view.corner_uv = square.uv;
    RenderStyle style;
    style.checker = checker;
    const Camera camera = front_camera(4);
    const Image image = render_panel(Panel{{view}, {}}, camera, 200, 200, style);
    int reds = 0, greens = 0, covered = 0;
    for (int y = 0; y < 200; ++y)
        for (int x = 0; x < 200; ++x) {
            const Rgb8 c = image.at(x, y);
            covered += !white(c);
            reds += red(c);
            greens += green(c);
        }
    INFO(reds << " red, " << greens << " green of " << covered << " covered pixels");
    CHECK(covered > 10000);
    CHECK(reds > 0.4 * covered);
    CHECK(greens > 0.4 * covered);
}

TEST_CASE("REN-4: texture coordinates are interpolated perspective-correctly", "[unit][render]") {
    // A square tilted 70° away from a close camera: affine interpolation in screen space would
    // move the cells' centres by more than a quarter of a cell.
    const Square square(1, 0, 70 * pi / 180);
    MeshView view = square.view();
    view.corner_uv = square.uv;
    RenderStyle style;
    style.checker.cells = 8;
    style.checker.light = Colour(1, 0, 0);
    style.checker.dark = Colour(0, 1, 0);
    Camera camera = front_camera(2.5);
    camera.eye = Vec3(0, -0.3, 2.5);
    camera.fov_y_degrees = 80;  // wide: the whole square in view from close by
    const int size = 400;
    const Image image = render_panel(Panel{{view}, {}}, camera, size, size, style);
    int checked = 0;
    for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j)
            for (const double du : {-0.25, 0.0, 0.25})
                for (const double dv : {-0.25, 0.0, 0.25}) {
                    const double u = (i + 0.5 + du) / 8, v = (j + 0.5 + dv) / 8;
                    const double y = -1 + 2 * v;
                    const Vec3 p(-1 + 2 * u, y * std::cos(70 * pi / 180), y * std::sin(70 * pi / 180));
                    const auto [px, py] = pixel_of(camera, p, size, size);
                    const Rgb8 c = image.at(px, py);
                    INFO("cell (" << i << ", " << j << ") at u = " << u << ", v = " << v << ": rgb " << int(c.r) << " "
                                  << int(c.g) << " " << int(c.b));
                    CHECK(((i + j) % 2 == 0 ? red(c) : green(c)));
                    ++checked;
                }
    CHECK(checked == 576);
}

TEST_CASE("REN-6: flat shading is constant on a triangle, Gouraud varies, both two-sided", "[unit][render]") {
    // An octahedron seen at an angle: its faces have different normals.
    const std::vector<Vec3> positions{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    const std::vector<Triangle> triangles{{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                          {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    Camera camera;
    camera.eye = Vec3(3, 2.5, 4);
    camera.target = Vec3::Zero();
    camera.depth_bias = 0.01;
    MeshView flat;
    flat.positions = positions;
    flat.triangles = triangles;
    MeshView gouraud = flat;
    gouraud.shading = Shading::gouraud;
    const int size = 300;
    const Image flat_image = render_panel(Panel{{flat}, {}}, camera, size, size);
    const Image gouraud_image = render_panel(Panel{{gouraud}, {}}, camera, size, size);
    // Face {0, 2, 4} faces the camera: its centroid and a point towards corner 0.
    const Vec3 centroid = (positions[0] + positions[2] + positions[4]) / 3;
    const Vec3 towards_corner = centroid + 0.6 * (positions[0] - centroid);
    const Vec3 towards_other = centroid + 0.6 * (positions[4] - centroid);
    const auto at = [&](const Image& image, const Vec3& p) {
        const auto [x, y] = pixel_of(camera, p, size, size);
        return image.at(x, y);
    };
    CHECK(at(flat_image, centroid) == at(flat_image, towards_corner));
    CHECK(at(flat_image, centroid) == at(flat_image, towards_other));
    CHECK_FALSE(at(gouraud_image, towards_corner) == at(gouraud_image, towards_other));
    // Neighbouring faces differ under flat shading.
    const Vec3 other_face = (positions[2] + positions[1] + positions[4]) / 3;
    CHECK_FALSE(at(flat_image, centroid) == at(flat_image, other_face));

    // Two-sided: the reversed mesh looks the same.
    std::vector<Triangle> reversed = triangles;
    for (Triangle& t : reversed) std::swap(t[1], t[2]);
    MeshView flipped = flat;
    flipped.triangles = reversed;
    CHECK(render_panel(Panel{{flipped}, {}}, camera, size, size).rgb == flat_image.rgb);

    // The headlight: a square facing the camera is brighter than one turned 70° away.
    const Square facing(1, 0), turned(1, 0, 70 * pi / 180);
    const Image a = render_panel(Panel{{facing.view()}, {}}, front_camera(), 100, 100);
    const Image b = render_panel(Panel{{turned.view()}, {}}, front_camera(), 100, 100);
    CHECK(a.at(50, 50).r > b.at(50, 50).r + 40);
}

TEST_CASE("REN-9: polylines on the surface show over it; behind it they are hidden", "[unit][render]") {
    const Square square(1, 0, 60 * pi / 180);  // tilted: the surface's depth varies across a line's width
    const std::vector<Vec3> points{{-0.8, 0, 0},
                                   {0.8, 0, 0},
                                   {0, -0.8 * std::cos(60 * pi / 180), -0.8 * std::sin(60 * pi / 180)},
                                   {0, 0.8 * std::cos(60 * pi / 180), 0.8 * std::sin(60 * pi / 180)},
                                   {0.5, 0.3, -1.5},
                                   {0.5, -0.3, -1.5},
                                   {1.6, 0.3, -1.5},
                                   {1.6, -0.3, -1.5}};
    const std::vector<std::vector<std::uint32_t>> on_surface{{0, 1}, {2, 3}};
    const std::vector<std::vector<std::uint32_t>> behind{{4, 5}, {6, 7}};
    PolylineView green_lines, blue_lines;
    green_lines.points = blue_lines.points = points;
    green_lines.paths = on_surface;
    green_lines.colour = Colour(0, 1, 0);
    green_lines.width_pixels = 3;
    blue_lines.paths = behind;
    blue_lines.colour = Colour(0, 0, 1);
    blue_lines.width_pixels = 3;
    const Camera camera = front_camera();
    const int size = 400;
    const Image image = render_panel(Panel{{square.view()}, {green_lines, blue_lines}}, camera, size, size);
    // Every point along the on-surface lines is green.
    int visible = 0, total = 0;
    for (int k = 1; k < 40; ++k) {
        const double t = k / 40.0;
        for (const auto& [p, q] : {std::pair{points[0], points[1]}, std::pair{points[2], points[3]}}) {
            const auto [x, y] = pixel_of(camera, p + t * (q - p), size, size);
            visible += green(image.at(x, y));
            ++total;
        }
    }
    CHECK(visible == total);
    // The line behind the square is hidden; the one beside it (nothing in front) shows.
    const auto [hx, hy] = pixel_of(camera, Vec3(0.5, 0, -1.5), size, size);
    CHECK_FALSE(blue(image.at(hx, hy)));
    const auto [sx, sy] = pixel_of(camera, Vec3(1.6, 0, -1.5), size, size);
    CHECK(blue(image.at(sx, sy)));

    // Outlines: the square's diagonal (an edge) shows over the square.
    MeshView outlined = square.view();
    outlined.outline = true;
    RenderStyle style;
    style.outline_colour = Colour(1, 0, 0);
    style.outline_width_pixels = 2;
    const Image with_outline = render_panel(Panel{{outlined}, {}}, camera, size, size, style);
    const auto [dx, dy] = pixel_of(camera, (square.positions[0] + square.positions[2]) / 2, size, size);
    CHECK(red(with_outline.at(dx, dy)));
}

TEST_CASE("REN-4: geometry crossing the near plane is clipped, not mirrored", "[unit][render]") {
    // A ground plane reaching behind the camera, which stands above it looking at the horizon.
    const std::vector<Vec3> positions{{-100, 0, -100}, {100, 0, -100}, {100, 0, 100}, {-100, 0, 100}};
    const std::vector<Triangle> triangles{{0, 1, 2}, {0, 2, 3}};
    MeshView ground;
    ground.positions = positions;
    ground.triangles = triangles;
    Camera camera;
    camera.eye = Vec3(0, 1, 0);
    camera.target = Vec3(0, 1, -1);
    camera.near = 0.01;
    const Image image = render_panel(Panel{{ground}, {}}, camera, 80, 60);
    for (int x = 0; x < 80; ++x) {
        CHECK(white(image.at(x, 2)));         // sky
        CHECK_FALSE(white(image.at(x, 57)));  // ground up to the bottom edge
    }
}

TEST_CASE("REN-8: camera_for puts every corner of the box inside the central 90 % of the view", "[property][render]") {
    rc::prop("corners project into [-0.9, 0.9]² and in front of the near plane", [] {
        const auto coordinate = [] { return *rc::gen::inRange(-1000, 1001) / 10.0; };
        const auto extent = [] { return std::pow(10.0, *rc::gen::inRange(-30, 31) / 10.0); };
        const Vec3 lo(coordinate(), coordinate(), coordinate());
        const Vec3 size(extent(), extent(), extent());
        const double aspect = std::pow(10.0, *rc::gen::inRange(-5, 6) / 10.0);
        ViewDirection view;
        view.azimuth_degrees = *rc::gen::inRange(-180, 181);
        view.elevation_degrees = *rc::gen::inRange(-80, 81);
        view.up_axis = *rc::gen::inRange(0, 3);
        const Bounds box{lo, lo + size};
        const Camera camera = camera_for(box, aspect, view);
        for (int k = 0; k < 8; ++k) {
            const Vec3 corner((k & 1) ? box.max.x() : box.min.x(), (k & 2) ? box.max.y() : box.min.y(),
                              (k & 4) ? box.max.z() : box.min.z());
            const Projected p = project(camera, corner, aspect);
            RC_ASSERT(p.w >= camera.near);
            RC_ASSERT(std::abs(p.nx) <= 0.9 + 1e-9);
            RC_ASSERT(std::abs(p.ny) <= 0.9 + 1e-9);
        }
        const Bounds halves = merged(Bounds{lo, lo + size / 2}, Bounds{lo + size / 2, lo + size});
        RC_ASSERT(halves.min == box.min);
        RC_ASSERT(halves.max == box.max);
        RC_ASSERT(std::abs(camera.depth_bias - 0.005 * size.norm()) <= 1e-12 * size.norm());
    });
}

TEST_CASE("REN-8: a rendered mesh stays inside the image with a 5 % margin", "[unit][render]") {
    for (const std::uint64_t seed : {1, 2, 3}) {
        const TriMesh mesh = generate::random_closed_mesh({static_cast<int>(seed % 2), 800, seed, 0.2});
        const std::vector<Triangle> triangles = mesh.triangles();
        MeshView view;
        view.positions = mesh.positions();
        view.triangles = triangles;
        const int width = 300, height = 200;
        const Camera camera = camera_for(bounds_of(mesh.positions()), double(width) / height);
        const Image image = render_panel(Panel{{view}, {}}, camera, width, height);
        int lo_x = width, hi_x = -1, lo_y = height, hi_y = -1;
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                if (!white(image.at(x, y))) {
                    lo_x = std::min(lo_x, x);
                    hi_x = std::max(hi_x, x);
                    lo_y = std::min(lo_y, y);
                    hi_y = std::max(hi_y, y);
                }
        INFO("seed " << seed << ": drawn in x " << lo_x << ".." << hi_x << ", y " << lo_y << ".." << hi_y);
        CHECK(lo_x >= 0.05 * width - 1);
        CHECK(hi_x <= 0.95 * width);
        CHECK(lo_y >= 0.05 * height - 1);
        CHECK(hi_y <= 0.95 * height);
        // … and it is framed, not lost in the middle: it spans at least half the image one way.
        CHECK((hi_x - lo_x > width / 2 || hi_y - lo_y > height / 2));
    }
}

TEST_CASE("REN-10: the same scene renders to the same bytes", "[unit][render]") {
    const TriMesh mesh = generate::random_closed_mesh({1, 2000, 17, 0.3});
    const std::vector<Triangle> triangles = mesh.triangles();
    std::vector<Eigen::Vector2d> uv;
    for (std::size_t f = 0; f < triangles.size(); ++f) uv.insert(uv.end(), {{0, 0}, {1, 0}, {0, 1}});
    const std::vector<std::vector<std::uint32_t>> paths{{0, 1, 2, 3, 4, 5}, {7}};
    MeshView textured;
    textured.positions = mesh.positions();
    textured.triangles = triangles;
    textured.corner_uv = uv;
    textured.shading = Shading::gouraud;
    MeshView outlined = textured;
    outlined.corner_uv = {};
    outlined.outline = true;
    PolylineView lines;
    lines.points = mesh.positions();
    lines.paths = paths;
    const Camera camera = camera_for(bounds_of(mesh.positions()), 1.0);
    const Panel left{{textured}, {lines}}, right{{outlined}, {lines}};
    const std::string a = fhr::test::temp_path("det-a.png"), b = fhr::test::temp_path("det-b.png");
    write_two_panel_png(a, camera, left, right, 320, 160);
    write_two_panel_png(b, camera, left, right, 320, 160);
    CHECK(fhr::test::read_file(a) == fhr::test::read_file(b));
    const reader::DecodedPng decoded = reader::decode_png(fhr::test::read_file(a));
    CHECK(decoded.image.width == 320);
    CHECK(decoded.image.height == 160);
}

TEST_CASE("REN-13: two panels share one camera, and Figures 6–9 are written as valid PNGs", "[unit][render]") {
    const TriMesh t = generate::random_closed_mesh({0, 1200, 5, 0.2});
    const TriMesh d = generate::random_closed_mesh({0, 60, 5, 0.0});
    const std::vector<Triangle> t_triangles = t.triangles(), d_triangles = d.triangles();
    const MeshData t_data{t.positions(), t_triangles}, d_data{d.positions(), d_triangles};
    const FigureSize size{240, 120};
    const Camera camera = figure_camera(t.positions(), size);

    // The same panel on both sides gives two identical halves.
    MeshView view;
    view.positions = t.positions();
    view.triangles = t_triangles;
    const Image same = render_two_panels(camera, Panel{{view}, {}}, Panel{{view}, {}}, size.width, size.height);
    for (int y = 0; y < size.height; ++y)
        for (int x = 0; x < size.width / 2; ++x) REQUIRE(same.at(x, y) == same.at(x + size.width / 2, y));

    std::vector<Eigen::Vector2d> uv;
    for (std::size_t f = 0; f < t_triangles.size(); ++f) uv.insert(uv.end(), {{0, 0}, {1, 0}, {0, 1}});
    const std::vector<std::vector<std::uint32_t>> paths{{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10}},
        restricted_paths{{300, 301, 302, 303, 304, 305, 306, 307}};
    const PathData network{t.positions(), paths}, restricted{t.positions(), restricted_paths}, no_boundary{};
    const std::string dir = fhr::test::temp_path("figures");
    std::filesystem::create_directories(dir);
    write_fig6(dir + "/fig6.png", camera, t_data, d_data, size);
    write_fig7(dir + "/fig7.png", camera, t_data, network, restricted, no_boundary, t_data, uv, size);
    write_fig8(dir + "/fig8.png", camera, d_data, t_data, size);
    write_fig9(dir + "/fig9.png", camera, d_data, t_data, size);
    for (const char* name : {"fig6", "fig7", "fig8", "fig9"}) {
        INFO(name);
        reader::DecodedPng decoded;
        REQUIRE_NOTHROW(decoded = reader::decode_png(fhr::test::read_file(dir + "/" + name + ".png")));
        CHECK(decoded.image.width == size.width);
        CHECK(decoded.image.height == size.height);
    }
    // Fig. 7: the geodesics (red) and the restricted curves (gold) on the left, the checkerboard's
    // dark cells (blue) on the right.
    const Image fig7 = reader::decode_png(fhr::test::read_file(dir + "/fig7.png")).image;
    int red_left = 0, red_right = 0, gold_left = 0, gold_right = 0, dark_right = 0;
    for (int y = 0; y < size.height; ++y)
        for (int x = 0; x < size.width; ++x) {
            const Rgb8 c = fig7.at(x, y);
            const bool is_red =
                c.r > 150 && c.g < 90 && c.b<90, is_gold = c.r> 150 && c.g > 110 && c.b<60, is_dark = c.b> c.r + 40;
            (x < size.width / 2 ? red_left : red_right) += is_red;
            (x < size.width / 2 ? gold_left : gold_right) += is_gold;
            dark_right += x >= size.width / 2 && is_dark;
        }
    CHECK(red_left > 0);
    CHECK(red_right == 0);
    CHECK(gold_left > 0);
    CHECK(gold_right == 0);
    CHECK(dark_right > 0);
}

TEST_CASE("REN-15: the boundary edges are drawn in the boundary colour where they project, and only they",
          "[unit][render]") {
    // The square [−1, 1]² seen from the front: its four sides are boundary edges, its diagonal is not.
    const Square square(1, 0);
    const Camera camera = front_camera();
    const int size = 200;
    MeshView with_boundary = square.view();
    with_boundary.boundary = true;
    const Image image = render_panel(Panel{{with_boundary}, {}}, camera, size, size);
    for (int side = 0; side < 4; ++side) {
        const auto [x, y] =
            pixel_of(camera, (square.positions[side] + square.positions[(side + 1) % 4]) / 2, size, size);
        CHECK(green(image.at(x, y)));
    }
    const auto [dx, dy] = pixel_of(camera, Vec3(0.3, 0.3, 0), size, size);  // on the diagonal
    CHECK_FALSE(green(image.at(dx, dy)));
    // Every green pixel lies within 2 pixels of the square's projected outline.
    const auto [x0, y1] = pixel_of(camera, square.positions[0], size, size);
    const auto [x1, y0] = pixel_of(camera, square.positions[2], size, size);
    int greens = 0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            if (!green(image.at(x, y))) continue;
            ++greens;
            const int to_outline = std::min({std::abs(x - x0), std::abs(x - x1), std::abs(y - y0), std::abs(y - y1)});
            const bool in_band = x >= x0 - 2 && x <= x1 + 2 && y >= y0 - 2 && y <= y1 + 2;
            REQUIRE((in_band && to_outline <= 2));
        }
    CHECK(greens > 4 * (x1 - x0));  // all four sides, end to end
    // Without the flag, no green at all.
    const Image plain = render_panel(Panel{{square.view()}, {}}, camera, size, size);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) REQUIRE_FALSE(green(plain.at(x, y)));

    // Behind a surface: the boundary's hidden part in the hidden style, the visible part over it.
    const std::vector<Vec3> occluder_positions{{-0.4, 0.6, 1}, {0.4, 0.6, 1}, {0.4, 1.4, 1}, {-0.4, 1.4, 1}};
    MeshView occluder = square.view();
    occluder.positions = occluder_positions;
    occluder.colour = Colour(0, 0, 1);
    RenderStyle style;
    style.supersample = 1;
    style.boundary_colour = Colour(0, 1, 0);
    style.hidden_boundary_colour = Colour(1, 0, 1);
    style.hidden_boundary_width_pixels = 3;
    const Image behind = render_panel(Panel{{with_boundary, occluder}, {}}, camera, size, size, style);
    const auto [hx, hy] = pixel_of(camera, Vec3(0, 1, 0), size, size);    // the top side, behind the occluder
    const auto [vx, vy] = pixel_of(camera, Vec3(0.8, 1, 0), size, size);  // the top side, in view
    CHECK(behind.at(hx, hy) == (Rgb8{255, 0, 255}));
    CHECK(behind.at(vx, vy) == (Rgb8{0, 255, 0}));
    style.hidden_boundary_width_pixels = 0;  // no hidden part: the occluder shows
    CHECK(blue(render_panel(Panel{{with_boundary, occluder}, {}}, camera, size, size, style).at(hx, hy)));

    // A closed mesh has no boundary edge: the flag changes no pixel.
    const TriMesh closed = generate::random_closed_mesh({1, 600, 3, 0.1});
    const std::vector<Triangle> closed_triangles = closed.triangles();
    MeshView closed_view;
    closed_view.positions = closed.positions();
    closed_view.triangles = closed_triangles;
    const Camera closed_camera = camera_for(bounds_of(closed.positions()), 1.0);
    const Image closed_plain = render_panel(Panel{{closed_view}, {}}, closed_camera, 160, 160);
    closed_view.boundary = true;
    CHECK(render_panel(Panel{{closed_view}, {}}, closed_camera, 160, 160).rgb == closed_plain.rgb);
}

TEST_CASE("REN-15: Figures 6–9 draw the boundary of a surface with holes, and none of a closed one", "[unit][render]") {
    // Counts the boundary-coloured pixels of each half of a figure.
    const auto greens = [](const std::string& file) {
        const Image image = reader::decode_png(fhr::test::read_file(file)).image;
        std::pair<int, int> count{0, 0};
        for (int y = 0; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x)
                if (green(image.at(x, y))) ++(x < image.width / 2 ? count.first : count.second);
        return count;
    };
    const std::string dir = fhr::test::temp_path("boundary-figures");
    std::filesystem::create_directories(dir);
    const FigureSize size{320, 160};
    for (const int holes : {0, 3}) {
        INFO("holes " << holes);
        const TriMesh t = generate::random_mesh({0, 800, 7, 0.1, holes});
        const std::vector<Triangle> triangles = t.triangles();
        const MeshData data{t.positions(), triangles};
        const Camera camera = figure_camera(t.positions(), size);
        // Fig. 7's boundary curves: here each boundary edge of T as a path of two points.
        std::vector<std::vector<std::uint32_t>> arcs;
        for (EdgeId e : t.edges())
            if (t.is_boundary(e))
                arcs.push_back({t.from(TriMesh::halfedge(e, 0)).idx(), t.to(TriMesh::halfedge(e, 0)).idx()});
        CHECK(arcs.empty() == (holes == 0));
        std::vector<Eigen::Vector2d> uv(3 * triangles.size(), Eigen::Vector2d(0.5, 0.5));
        const PathData none{}, boundary{t.positions(), arcs};
        write_fig6(dir + "/fig6.png", camera, data, data, size);
        write_fig7(dir + "/fig7.png", camera, data, none, none, boundary, data, uv, size);
        write_fig8(dir + "/fig8.png", camera, data, data, size);
        write_fig9(dir + "/fig9.png", camera, data, data, size);
        for (const char* name : {"fig6", "fig7", "fig8", "fig9"}) {
            INFO(name);
            const auto [left, right] = greens(dir + "/" + name + ".png");
            if (holes == 0) {
                CHECK(left == 0);
                CHECK(right == 0);
            } else {
                CHECK(left > 20);
                CHECK(right > 20);
            }
        }
    }
}

TEST_CASE("REN-4: bad input is refused with InvalidInput", "[unit][render]") {
    const Square square(1, 0);
    const Camera camera = front_camera();
    const auto refused = [&](const MeshView& mesh) {
        CHECK_THROWS_AS(render_panel(Panel{{mesh}, {}}, camera, 10, 10), InvalidInput);
    };
    MeshView bad_index = square.view();
    const std::vector<Triangle> out_of_range{{0, 1, 4}};
    bad_index.triangles = out_of_range;
    refused(bad_index);
    MeshView bad_uv = square.view();
    bad_uv.corner_uv = std::span(square.uv).first(5);
    refused(bad_uv);
    MeshView bad_colours = square.view();
    const std::vector<Colour> one_colour{Colour(1, 0, 0)};
    bad_colours.face_colours = one_colour;
    refused(bad_colours);
    std::vector<Vec3> nan_positions = square.positions;
    nan_positions[2].x() = std::nan("");
    MeshView bad_position = square.view();
    bad_position.positions = nan_positions;
    refused(bad_position);

    const std::vector<std::vector<std::uint32_t>> bad_path{{0, 9}};
    PolylineView lines;
    lines.points = square.positions;
    lines.paths = bad_path;
    CHECK_THROWS_AS(render_panel(Panel{{}, {lines}}, camera, 10, 10), InvalidInput);

    CHECK_THROWS_AS(render_panel(Panel{}, camera, 0, 10), InvalidInput);
    RenderStyle no_samples;
    no_samples.supersample = 0;
    CHECK_THROWS_AS(render_panel(Panel{}, camera, 10, 10, no_samples), InvalidInput);
    Camera degenerate = camera;
    degenerate.target = degenerate.eye;
    CHECK_THROWS_AS(render_panel(Panel{}, degenerate, 10, 10), InvalidInput);
    Camera parallel_up = camera;
    parallel_up.up = Vec3::UnitZ();
    CHECK_THROWS_AS(render_panel(Panel{}, parallel_up, 10, 10), InvalidInput);

    CHECK_THROWS_AS(bounds_of({}), InvalidInput);
    CHECK_THROWS_AS(camera_for(Bounds{Vec3::Zero(), Vec3::Ones()}, 0.0), InvalidInput);
    CHECK_THROWS_AS(camera_for(Bounds{Vec3::Ones(), Vec3::Zero()}, 1.0), InvalidInput);
    CHECK_THROWS_AS(camera_for(Bounds{Vec3::Zero(), Vec3::Zero()}, 1.0), InvalidInput);
}
