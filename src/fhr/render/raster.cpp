// FHR §6 figures — the CPU z-buffer rasterizer (see raster.hpp for the pipeline).
#include <fhr/render/raster.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <utility>

#include <fhr/core/errors.hpp>

namespace fhr::render {
namespace {

constexpr double degrees = std::numbers::pi / 180;

[[noreturn]] void refuse(const std::string& what) { throw InvalidInput("render: " + what); }

bool finite(const Vec3& p) { return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()); }

// The camera's orthonormal frame and its projection onto a viewport of sample_width ×
// sample_height samples (step 1 and 3 of raster.hpp).
struct View {
    Vec3 eye, right, up, forward;
    double near = 0, depth_bias = 0;
    double scale_x = 0, scale_y = 0;  // samples per unit of x/w and y/w
    double centre_x = 0, centre_y = 0;

    View(const Camera& camera, int sample_width, int sample_height) {
        const Vec3 towards_target = camera.target - camera.eye;
        forward = towards_target / towards_target.norm();
        const Vec3 side = forward.cross(camera.up);
        right = side / side.norm();
        up = right.cross(forward);
        if (!finite(forward) || !finite(right) || !(camera.near > 0) || !std::isfinite(camera.near) ||
            !(camera.fov_y_degrees > 0 && camera.fov_y_degrees < 180) || !(camera.depth_bias >= 0) ||
            !std::isfinite(camera.depth_bias))
            refuse(
                "degenerate camera (eye = target, up parallel to the view, near ≤ 0, fov_y not in (0°, 180°) "
                "or depth_bias < 0)");
        eye = camera.eye;
        near = camera.near;
        depth_bias = camera.depth_bias;
        const double tan_half_y = std::tan(camera.fov_y_degrees * degrees / 2);
        const double aspect = double(sample_width) / double(sample_height);
        centre_x = sample_width / 2.0;
        centre_y = sample_height / 2.0;
        scale_x = centre_x / (tan_half_y * aspect);
        scale_y = centre_y / tan_half_y;
    }
    Vec3 to_view(const Vec3& p) const {
        const Vec3 v = p - eye;
        return {v.dot(right), v.dot(up), v.dot(forward)};
    }
};

// A vertex in view space with the attributes interpolated across a triangle: texture
// coordinates and the two light terms (diffuse factor, specular).
struct ClipVertex {
    Vec3 view;
    double u = 0, v = 0, diffuse = 0, specular = 0;
};

ClipVertex lerp(const ClipVertex& a, const ClipVertex& b, double t) {
    return {a.view + t * (b.view - a.view), a.u + t * (b.u - a.u), a.v + t * (b.v - a.v),
            a.diffuse + t * (b.diffuse - a.diffuse), a.specular + t * (b.specular - a.specular)};
}

// Step 2: Sutherland–Hodgman against the plane w = near; 0, 3 or 4 vertices remain.
int clip_near(const std::array<ClipVertex, 3>& in, double near, std::array<ClipVertex, 4>& out) {
    int count = 0;
    for (int k = 0; k < 3; ++k) {
        const ClipVertex& a = in[k];
        const ClipVertex& b = in[(k + 1) % 3];
        const bool a_in = a.view.z() >= near, b_in = b.view.z() >= near;
        if (a_in) out[count++] = a;
        if (a_in != b_in) out[count++] = lerp(a, b, (near - a.view.z()) / (b.view.z() - a.view.z()));
    }
    return count;
}

// A vertex in sample space: position, q = 1/w, and the attributes times q.
struct ScreenVertex {
    double x = 0, y = 0, q = 0;
    double uq = 0, vq = 0, diffuse_q = 0, specular_q = 0;
};

std::uint32_t pack(const Colour& c) {
    const auto channel = [](double x) { return std::uint32_t(std::lround(std::clamp(x, 0.0, 1.0) * 255)); };
    return channel(c.x()) | (channel(c.y()) << 8) | (channel(c.z()) << 16);
}

// The supersampled colour and depth buffers (depth = w, +∞ where nothing was drawn).
class Canvas {
public:
    Canvas(int width, int height, const Colour& background)
        : width_(width),
          height_(height),
          colour_(std::size_t(width) * std::size_t(height), pack(background)),
          depth_(colour_.size(), std::numeric_limits<float>::infinity()) {}

    int width() const { return width_; }
    int height() const { return height_; }
    std::uint32_t colour(int x, int y) const { return colour_[index(x, y)]; }

    // The inclusive sample range covered by [lo, hi] of sample-centre coordinates, clipped to the
    // buffer; empty (first > last) when outside.
    static std::pair<int, int> sample_range(double lo, double hi, int size) {
        const double first = std::max(0.0, std::ceil(lo - 0.5)),
                     last = std::min(double(size - 1), std::floor(hi - 0.5));
        if (!(first <= last)) return {1, 0};
        return {int(first), int(last)};
    }

    // Step 4 for one projected triangle; the albedo at a sample comes from `albedo(u, v)`.
    template <class Albedo>
    void fill_triangle(const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c, const Albedo& albedo) {
        const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
        if (area == 0 || !std::isfinite(area)) return;
        const double inverse_area = 1 / area;
        const auto [x0, x1] = sample_range(std::min({a.x, b.x, c.x}), std::max({a.x, b.x, c.x}), width_);
        const auto [y0, y1] = sample_range(std::min({a.y, b.y, c.y}), std::max({a.y, b.y, c.y}), height_);
        for (int y = y0; y <= y1; ++y) {
            const double sy = y + 0.5;
            for (int x = x0; x <= x1; ++x) {
                const double sx = x + 0.5;
                const double ba = ((c.x - b.x) * (sy - b.y) - (c.y - b.y) * (sx - b.x)) * inverse_area;
                const double bb = ((a.x - c.x) * (sy - c.y) - (a.y - c.y) * (sx - c.x)) * inverse_area;
                const double bc = ((b.x - a.x) * (sy - a.y) - (b.y - a.y) * (sx - a.x)) * inverse_area;
                if (ba < 0 || bb < 0 || bc < 0) continue;
                const double q = ba * a.q + bb * b.q + bc * c.q;
                const double w = 1 / q;
                const std::size_t i = index(x, y);
                if (!(w < double(depth_[i]))) continue;
                const double u = (ba * a.uq + bb * b.uq + bc * c.uq) * w;
                const double v = (ba * a.vq + bb * b.vq + bc * c.vq) * w;
                const double diffuse = (ba * a.diffuse_q + bb * b.diffuse_q + bc * c.diffuse_q) * w;
                const double specular = (ba * a.specular_q + bb * b.specular_q + bc * c.specular_q) * w;
                depth_[i] = float(w);
                colour_[i] = pack(albedo(u, v) * diffuse + Colour::Constant(specular));
            }
        }
    }

    // Step 5 for one segment of half-width `radius` samples: a sample within `radius` of the
    // segment takes `colour` when its depth (1/w interpolated along the segment) is at most the
    // buffer's depth + bias — or, with `hidden`, when it is more (the part behind the surface).
    void draw_segment(const ScreenVertex& a, const ScreenVertex& b, double radius, double bias, std::uint32_t colour,
                      bool hidden) {
        const auto [x0, x1] = sample_range(std::min(a.x, b.x) - radius, std::max(a.x, b.x) + radius, width_);
        const auto [y0, y1] = sample_range(std::min(a.y, b.y) - radius, std::max(a.y, b.y) + radius, height_);
        const double dx = b.x - a.x, dy = b.y - a.y, length2 = dx * dx + dy * dy;
        const double inverse_length2 = length2 > 0 ? 1 / length2 : 0;
        for (int y = y0; y <= y1; ++y) {
            const double sy = y + 0.5;
            for (int x = x0; x <= x1; ++x) {
                const double sx = x + 0.5;
                const double t = std::clamp(((sx - a.x) * dx + (sy - a.y) * dy) * inverse_length2, 0.0, 1.0);
                const double ex = sx - (a.x + t * dx), ey = sy - (a.y + t * dy);
                if (ex * ex + ey * ey > radius * radius) continue;
                const double w = 1 / (a.q + t * (b.q - a.q));
                const std::size_t i = index(x, y);
                if ((w - bias <= double(depth_[i])) != hidden) colour_[i] = colour;
            }
        }
    }

private:
    std::size_t index(int x, int y) const { return std::size_t(y) * std::size_t(width_) + std::size_t(x); }
    int width_, height_;
    std::vector<std::uint32_t> colour_;
    std::vector<float> depth_;
};

// The headlight (REN-6), in view coordinates (x right, y up, z along the viewing direction, the
// frame normals are computed in): the direction towards the light, from the viewer raised and
// moved to the left, and the half vector between it and the direction towards the viewer.
struct Light {
    Vec3 to_light = Vec3(-0.30, 0.35, -1).normalized();
    Vec3 half = (to_light + Vec3(0, 0, -1)).normalized();
    // (diffuse factor, specular term) for normal n (any length; zero gives ambient only).
    std::pair<double, double> terms(const Vec3& n) const {
        const double length = n.norm();
        if (!(length > 0)) return {0.3, 0.0};
        const Vec3 unit = n / length;
        double s = std::abs(unit.dot(half));
        for (int k = 0; k < 5; ++k) s *= s;  // s^32
        return {0.3 + 0.6 * std::abs(unit.dot(to_light)), 0.15 * s};
    }
};

ScreenVertex project(const View& view, const ClipVertex& c) {
    const double q = 1 / c.view.z();
    return {view.centre_x + c.view.x() * q * view.scale_x,
            view.centre_y - c.view.y() * q * view.scale_y,
            q,
            c.u * q,
            c.v * q,
            c.diffuse * q,
            c.specular * q};
}

void check_mesh(const MeshView& mesh, std::size_t m) {
    const std::string name = "mesh " + std::to_string(m);
    for (std::size_t i = 0; i < mesh.positions.size(); ++i)
        if (!finite(mesh.positions[i])) refuse(name + ": position " + std::to_string(i) + " is not finite");
    for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
        for (const std::uint32_t v : mesh.triangles[f])
            if (v >= mesh.positions.size())
                refuse(name + ": triangle " + std::to_string(f) + " has vertex " + std::to_string(v) + " ≥ " +
                       std::to_string(mesh.positions.size()));
    if (!mesh.corner_uv.empty() && mesh.corner_uv.size() != 3 * mesh.triangles.size())
        refuse(name + ": " + std::to_string(mesh.corner_uv.size()) + " corner uv for " +
               std::to_string(mesh.triangles.size()) + " triangles (expected 3 per triangle)");
    for (std::size_t i = 0; i < mesh.corner_uv.size(); ++i)
        if (!mesh.corner_uv[i].allFinite()) refuse(name + ": corner uv " + std::to_string(i) + " is not finite");
    if (!mesh.face_colours.empty() && mesh.face_colours.size() != mesh.triangles.size())
        refuse(name + ": " + std::to_string(mesh.face_colours.size()) + " face colours for " +
               std::to_string(mesh.triangles.size()) + " triangles");
    for (std::size_t f = 0; f < mesh.face_colours.size(); ++f)
        if (!mesh.face_colours[f].allFinite()) refuse(name + ": face colour " + std::to_string(f) + " is not finite");
    if (!mesh.colour.allFinite()) refuse(name + ": colour is not finite");
}

// The undirected edges of a mesh's triangles, each once, sorted (REN-9); with only_boundary,
// those of exactly one triangle (REN-15). Also a polyline's segments (indices into its points).
using Edge = std::pair<std::uint32_t, std::uint32_t>;
std::vector<Edge> edges_of(const MeshView& mesh, bool only_boundary) {
    std::vector<Edge> all;
    all.reserve(3 * mesh.triangles.size());
    for (const Triangle& t : mesh.triangles)
        for (int k = 0; k < 3; ++k) all.emplace_back(std::minmax(t[k], t[(k + 1) % 3]));
    std::sort(all.begin(), all.end());
    std::vector<Edge> out;
    for (std::size_t i = 0; i < all.size();) {
        std::size_t j = i + 1;
        while (j < all.size() && all[j] == all[i]) ++j;
        if (!only_boundary || j - i == 1) out.push_back(all[i]);
        i = j;
    }
    return out;
}

void check_polylines(const PolylineView& lines, std::size_t l) {
    const std::string name = "polylines " + std::to_string(l);
    for (std::size_t i = 0; i < lines.points.size(); ++i)
        if (!finite(lines.points[i])) refuse(name + ": point " + std::to_string(i) + " is not finite");
    for (std::size_t p = 0; p < lines.paths.size(); ++p)
        for (const std::uint32_t v : lines.paths[p])
            if (v >= lines.points.size())
                refuse(name + ": path " + std::to_string(p) + " has point " + std::to_string(v) + " ≥ " +
                       std::to_string(lines.points.size()));
    if (!lines.colour.allFinite() || !(lines.width_pixels > 0) || !std::isfinite(lines.width_pixels) ||
        !lines.hidden_colour.allFinite() || !(lines.hidden_width_pixels >= 0) ||
        !std::isfinite(lines.hidden_width_pixels))
        refuse(name + ": colour not finite, width not positive or hidden width negative");
}

void draw_mesh(Canvas& canvas, const View& view, const Light& light, const MeshView& mesh, const RenderStyle& style) {
    std::vector<Vec3> in_view(mesh.positions.size());
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) in_view[i] = view.to_view(mesh.positions[i]);
    const auto face_normal = [&](const Triangle& t) {
        return Vec3((in_view[t[1]] - in_view[t[0]]).cross(in_view[t[2]] - in_view[t[0]]));
    };
    // Gouraud: area-weighted vertex normals (sum of the unnormalized face normals, in face order).
    std::vector<std::pair<double, double>> vertex_light;
    if (mesh.shading == Shading::gouraud) {
        std::vector<Vec3> normal(mesh.positions.size(), Vec3::Zero());
        for (const Triangle& t : mesh.triangles) {
            const Vec3 n = face_normal(t);
            for (const std::uint32_t v : t) normal[v] += n;
        }
        vertex_light.resize(normal.size());
        for (std::size_t v = 0; v < normal.size(); ++v) vertex_light[v] = light.terms(normal[v]);
    }
    for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
        const Triangle& t = mesh.triangles[f];
        const std::pair<double, double> flat =
            mesh.shading == Shading::flat ? light.terms(face_normal(t)) : std::pair{0.0, 0.0};
        std::array<ClipVertex, 3> corners;
        for (int k = 0; k < 3; ++k) {
            const auto [diffuse, specular] = mesh.shading == Shading::flat ? flat : vertex_light[t[k]];
            const Eigen::Vector2d uv = mesh.corner_uv.empty() ? Eigen::Vector2d::Zero() : mesh.corner_uv[3 * f + k];
            corners[k] = {in_view[t[k]], uv.x(), uv.y(), diffuse, specular};
        }
        std::array<ClipVertex, 4> clipped;
        const int count = clip_near(corners, view.near, clipped);
        std::array<ScreenVertex, 4> screen;
        for (int k = 0; k < count; ++k) screen[k] = project(view, clipped[k]);
        const Colour base = mesh.face_colours.empty() ? mesh.colour : mesh.face_colours[f];
        for (int k = 1; k + 1 < count; ++k) {
            if (mesh.corner_uv.empty())
                canvas.fill_triangle(screen[0], screen[k], screen[k + 1], [&](double, double) { return base; });
            else
                canvas.fill_triangle(screen[0], screen[k], screen[k + 1],
                                     [&](double u, double v) { return checker_colour(style.checker, u, v); });
        }
    }
}

// A segment clipped against w ≥ near, projected; false when all of it is nearer than the near plane.
bool project_segment(const View& view, const Vec3& p, const Vec3& q, ScreenVertex& a, ScreenVertex& b) {
    ClipVertex s{view.to_view(p)}, e{view.to_view(q)};
    const bool s_in = s.view.z() >= view.near, e_in = e.view.z() >= view.near;
    if (!s_in && !e_in) return false;
    if (!s_in) s = lerp(s, e, (view.near - s.view.z()) / (e.view.z() - s.view.z()));
    if (!e_in) e = lerp(e, s, (view.near - e.view.z()) / (s.view.z() - e.view.z()));
    a = project(view, s);
    b = project(view, e);
    return true;
}

}  // namespace

Bounds bounds_of(std::span<const Vec3> points) {
    if (points.empty()) refuse("bounding box of no points");
    Bounds b{points[0], points[0]};
    for (const Vec3& p : points) {
        if (!finite(p)) refuse("bounding box of a point that is not finite");
        b.min = b.min.cwiseMin(p);
        b.max = b.max.cwiseMax(p);
    }
    return b;
}

Bounds merged(const Bounds& a, const Bounds& b) { return {a.min.cwiseMin(b.min), a.max.cwiseMax(b.max)}; }

Camera camera_for(const Bounds& bounds, double aspect, const ViewDirection& view) {
    if (!(aspect > 0) || !std::isfinite(aspect)) refuse("camera: aspect ratio must be finite and positive");
    if (view.up_axis < 0 || view.up_axis > 2) refuse("camera: up_axis must be 0, 1 or 2");
    if (!finite(bounds.min) || !finite(bounds.max) || !(bounds.min.array() <= bounds.max.array()).all())
        refuse("camera: the bounding box is empty or not finite");
    const Vec3 centre = (bounds.min + bounds.max) / 2;
    const double diagonal = (bounds.max - bounds.min).norm();
    // The horizontal basis (e_a, e_b, up) is right-handed; azimuth 0 looks from e_a.
    const Vec3 up = Vec3::Unit(view.up_axis), e_a = Vec3::Unit((view.up_axis + 1) % 3),
               e_b = Vec3::Unit((view.up_axis + 2) % 3);
    const double az = view.azimuth_degrees * degrees, el = view.elevation_degrees * degrees;
    const Vec3 towards_eye = std::cos(el) * (std::cos(az) * e_a + std::sin(az) * e_b) + std::sin(el) * up;
    Camera camera;
    camera.fov_y_degrees = 30;
    camera.up = up;
    camera.target = centre;
    // Corner c at lateral offsets (x, y) and height z towards the eye projects inside the central
    // 90 % when |x| ≤ 0.9 tan(half_x) (d − z) and |y| ≤ 0.9 tan(half_y) (d − z).
    const Vec3 forward = -towards_eye, right = forward.cross(up).normalized(), cam_up = right.cross(forward);
    const double tan_y = 0.9 * std::tan(camera.fov_y_degrees * degrees / 2), tan_x = tan_y * aspect;
    double distance = 0, highest = -std::numeric_limits<double>::infinity();
    for (int k = 0; k < 8; ++k) {
        const Vec3 corner((k & 1) ? bounds.max.x() : bounds.min.x(), (k & 2) ? bounds.max.y() : bounds.min.y(),
                          (k & 4) ? bounds.max.z() : bounds.min.z());
        const Vec3 c = corner - centre;
        const double z = c.dot(towards_eye);
        distance = std::max({distance, z + std::abs(c.dot(right)) / tan_x, z + std::abs(c.dot(cam_up)) / tan_y});
        highest = std::max(highest, z);
    }
    // A box seen edge-on along the view (no lateral extent) still gets its nearest corner in front.
    distance = std::max(distance, highest + 0.1 * diagonal);
    if (!(distance > 0)) refuse("camera: the bounding box is a single point");
    camera.eye = centre + distance * towards_eye;
    camera.near = 0.01 * (distance - highest);
    camera.depth_bias = 0.005 * diagonal;
    return camera;
}

Colour checker_colour(const Checkerboard& checker, double u, double v) {
    const auto cell = [&](double t) { return static_cast<long long>(std::floor(t * checker.cells)); };
    return ((cell(u) + cell(v)) & 1) ? checker.dark : checker.light;
}

Image render_panel(const Panel& panel, const Camera& camera, int width, int height, const RenderStyle& style) {
    if (width < 1 || height < 1) refuse("image size " + std::to_string(width) + "×" + std::to_string(height));
    if (style.supersample < 1 || style.supersample > 8) refuse("supersample must be 1..8");
    if (style.checker.cells < 1) refuse("checkerboard needs at least one cell");
    for (std::size_t m = 0; m < panel.meshes.size(); ++m) check_mesh(panel.meshes[m], m);
    for (std::size_t l = 0; l < panel.polylines.size(); ++l) check_polylines(panel.polylines[l], l);

    const int ss = style.supersample;
    Canvas canvas(width * ss, height * ss, style.background);
    const View view(camera, canvas.width(), canvas.height());
    const Light light;
    for (const MeshView& mesh : panel.meshes) draw_mesh(canvas, view, light, mesh, style);

    // Step 5: every line as segments with its style — the outlines, the boundary edges, the
    // polylines, in this order; the hidden parts of all of them first, then the visible parts.
    struct Lines {
        std::span<const Vec3> points;
        std::vector<Edge> segments;
        Colour colour, hidden_colour;
        double width_pixels, hidden_width_pixels;
    };
    std::vector<Lines> lines;
    for (const MeshView& mesh : panel.meshes)
        if (mesh.outline)
            lines.push_back({mesh.positions, edges_of(mesh, false), style.outline_colour, style.outline_colour,
                             style.outline_width_pixels, 0.0});
    for (const MeshView& mesh : panel.meshes)
        if (mesh.boundary)
            lines.push_back({mesh.positions, edges_of(mesh, true), style.boundary_colour, style.hidden_boundary_colour,
                             style.boundary_width_pixels, style.hidden_boundary_width_pixels});
    for (const PolylineView& polyline : panel.polylines) {
        Lines& l = lines.emplace_back(Lines{polyline.points,
                                            {},
                                            polyline.colour,
                                            polyline.hidden_colour,
                                            polyline.width_pixels,
                                            polyline.hidden_width_pixels});
        for (const std::vector<std::uint32_t>& path : polyline.paths) {
            if (path.size() == 1) l.segments.emplace_back(path[0], path[0]);  // a dot
            for (std::size_t k = 0; k + 1 < path.size(); ++k) l.segments.emplace_back(path[k], path[k + 1]);
        }
    }
    ScreenVertex a, b;
    for (const bool hidden : {true, false})
        for (const Lines& l : lines) {
            const double width = hidden ? l.hidden_width_pixels : l.width_pixels;
            if (!(width > 0)) continue;
            const std::uint32_t colour = pack(hidden ? l.hidden_colour : l.colour);
            for (const auto& [p, q] : l.segments)
                if (project_segment(view, l.points[p], l.points[q], a, b))
                    canvas.draw_segment(a, b, width * ss / 2, view.depth_bias, colour, hidden);
        }

    // Step 6: the box filter over ss × ss samples, rounded to nearest.
    Image image(width, height, Rgb8{});
    const unsigned n = unsigned(ss * ss);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            unsigned sum[3] = {0, 0, 0};
            for (int j = 0; j < ss; ++j)
                for (int i = 0; i < ss; ++i) {
                    const std::uint32_t c = canvas.colour(x * ss + i, y * ss + j);
                    for (int ch = 0; ch < 3; ++ch) sum[ch] += (c >> (8 * ch)) & 0xFF;
                }
            image.set(x, y,
                      Rgb8{std::uint8_t((sum[0] + n / 2) / n), std::uint8_t((sum[1] + n / 2) / n),
                           std::uint8_t((sum[2] + n / 2) / n)});
        }
    return image;
}

}  // namespace fhr::render
