// Beyond the paper — the run's interactive page (see page.hpp, spec/page.md).
#include <fhr/app/page.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <initializer_list>
#include <span>
#include <string_view>
#include <unordered_map>

#include <fhr/core/errors.hpp>
#include <fhr/io/detail/atomic_file.hpp>
#include <fhr/io/detail/json.hpp>
#include <fhr/render/figures.hpp>
#include <fhr/render/svg.hpp>
#include <fhr/wavelet/refine.hpp>

namespace fhr::app {

namespace detail {
std::string_view page_script();  // the bundle of web/src (page_script.cpp, generated), or empty
}  // namespace detail

bool page_available() { return !detail::page_script().empty(); }

namespace {

static_assert(std::endian::native == std::endian::little, "the page's typed arrays are little-endian");

std::string base64(std::string_view bytes) {
    static constexpr char alphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    std::size_t i = 0;
    for (; i + 3 <= bytes.size(); i += 3) {
        const std::uint32_t v = static_cast<std::uint8_t>(bytes[i]) << 16 |
                                static_cast<std::uint8_t>(bytes[i + 1]) << 8 | static_cast<std::uint8_t>(bytes[i + 2]);
        for (int s = 18; s >= 0; s -= 6) out += alphabet[(v >> s) & 63];
    }
    if (const std::size_t rest = bytes.size() - i; rest > 0) {
        std::uint32_t v = static_cast<std::uint8_t>(bytes[i]) << 16;
        if (rest == 2) v |= static_cast<std::uint8_t>(bytes[i + 1]) << 8;
        out += alphabet[(v >> 18) & 63];
        out += alphabet[(v >> 12) & 63];
        out += rest == 2 ? alphabet[(v >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}

template <class T>
std::string_view bytes_of(std::span<const T> values) {
    return {reinterpret_cast<const char*>(values.data()), values.size_bytes()};
}

// The page's arrays, each an entry {"type", "count", "data"} (and "min", "max" for q16) of the
// JSON object "arrays" (spec/page.md PAGE-3).
class ArrayWriter {
public:
    explicit ArrayWriter(io::JsonWriter& j) : j_(j) {}
    void u32(std::string_view name, std::span<const std::uint32_t> values) {
        entry(name, "u32", values.size(), bytes_of(values));
    }
    void u8(std::string_view name, std::span<const std::uint8_t> values) {
        entry(name, "u8", values.size(), bytes_of(values));
    }
    void f32(std::string_view name, std::span<const float> values) {
        entry(name, "f32", values.size(), bytes_of(values));
    }
    void triangles(std::string_view name, std::span<const Triangle> faces) {
        std::vector<std::uint32_t> flat;
        flat.reserve(3 * faces.size());
        for (const Triangle& t : faces) flat.insert(flat.end(), t.begin(), t.end());
        u32(name, flat);
    }
    /// Points quantised to 16 bits per coordinate over their bounding box: coordinate c of point i
    /// is min_c + q·(max_c − min_c)/65535.
    void q16(std::string_view name, std::span<const Vec3> points) {
        Vec3 lo = Vec3::Constant(0), hi = Vec3::Constant(0);
        if (!points.empty()) lo = hi = points.front();
        for (const Vec3& x : points) {
            lo = lo.cwiseMin(x);
            hi = hi.cwiseMax(x);
        }
        std::vector<std::uint16_t> q;
        q.reserve(3 * points.size());
        for (const Vec3& x : points)
            for (int c = 0; c < 3; ++c)
                q.push_back(hi[c] > lo[c]
                                ? static_cast<std::uint16_t>(std::lround((x[c] - lo[c]) / (hi[c] - lo[c]) * 65535.0))
                                : 0);
        begin(name, "q16", 3 * points.size());
        j_.key("min").begin_array().value(lo[0]).value(lo[1]).value(lo[2]).end_array();
        j_.key("max").begin_array().value(hi[0]).value(hi[1]).value(hi[2]).end_array();
        j_.key("data").value(base64(bytes_of(std::span<const std::uint16_t>(q)))).end_object();
    }
    /// Values in [0, 1] to 16 bits (u16n: value = q / 65535).
    void unit16(std::string_view name, std::span<const double> values) {
        std::vector<std::uint16_t> q;
        q.reserve(values.size());
        for (const double x : values)
            q.push_back(static_cast<std::uint16_t>(std::lround(std::clamp(x, 0.0, 1.0) * 65535.0)));
        entry(name, "u16n", q.size(), bytes_of(std::span<const std::uint16_t>(q)));
    }

private:
    io::JsonWriter& j_;
    void begin(std::string_view name, std::string_view type, std::size_t count) {
        j_.key(name).begin_object().key("type").value(type).key("count").value(count);
    }
    void entry(std::string_view name, std::string_view type, std::size_t count, std::string_view bytes) {
        begin(name, type, count);
        j_.key("data").value(base64(bytes)).end_object();
    }
};

// T′ as the page draws it: the final T′ itself, or beyond `budget` faces a display copy made by
// clustering its vertices on a grid (each face whose corners fall into three different cells kept,
// standing for itself; PAGE-9), the cell grown by 10 % steps from the size where about `budget`
// faces would be left until at most `budget` are.
struct DisplayMesh {
    std::vector<Vec3> positions;
    std::vector<Triangle> faces;
    std::vector<std::uint32_t> original;  // per display face, its face of T′ (empty: T′ itself)
};

DisplayMesh display_mesh(const Parameterization& p, std::size_t budget) {
    DisplayMesh m;
    const std::size_t n = p.refined_faces.size();
    if (n <= budget) return m;
    Vec3 lo = p.refined_positions.front(), hi = lo;
    double area = 0;
    for (const Vec3& x : p.refined_positions) {
        lo = lo.cwiseMin(x);
        hi = hi.cwiseMax(x);
    }
    for (const Triangle& t : p.refined_faces)
        area += 0.5 * (p.refined_positions[t[1]] - p.refined_positions[t[0]])
                          .cross(p.refined_positions[t[2]] - p.refined_positions[t[0]])
                          .norm();
    // A surface of area A sampled on cells of side h has about 2A/h² faces left.
    for (double h = std::sqrt(2 * area / static_cast<double>(budget));; h *= 1.1) {
        std::unordered_map<std::uint64_t, std::uint32_t> cell_index;
        std::vector<std::uint32_t> cell(p.refined_positions.size());
        std::vector<Vec3> sum;
        std::vector<double> count;
        for (std::size_t v = 0; v < p.refined_positions.size(); ++v) {
            const Vec3 c = ((p.refined_positions[v] - lo) / h).array().floor();
            const std::uint64_t key = static_cast<std::uint64_t>(c[0]) << 42 | static_cast<std::uint64_t>(c[1]) << 21 |
                                      static_cast<std::uint64_t>(c[2]);
            const auto [it, added] = cell_index.try_emplace(key, static_cast<std::uint32_t>(sum.size()));
            if (added) {
                sum.emplace_back(Vec3::Zero());
                count.push_back(0);
            }
            cell[v] = it->second;
            sum[it->second] += p.refined_positions[v];
            count[it->second] += 1;
        }
        m.faces.clear();
        m.original.clear();
        for (std::size_t f = 0; f < n; ++f) {
            const Triangle& t = p.refined_faces[f];
            const Triangle c{cell[t[0]], cell[t[1]], cell[t[2]]};
            if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2]) continue;
            m.faces.push_back(c);
            m.original.push_back(static_cast<std::uint32_t>(f));
        }
        if (m.faces.size() > budget) continue;
        m.positions.resize(sum.size());
        for (std::size_t c = 0; c < sum.size(); ++c) m.positions[c] = sum[c] / count[c];
        return m;
    }
}

// The edges of T′ inside faces of T (their two faces lie in one face of T): what §3 added.
std::vector<std::uint32_t> added_edges(const Parameterization& p) {
    std::vector<std::array<std::uint32_t, 3>> sides;  // (lower end, upper end, face)
    sides.reserve(3 * p.refined_faces.size());
    for (std::uint32_t f = 0; f < p.refined_faces.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = p.refined_faces[f][k], b = p.refined_faces[f][(k + 1) % 3];
            sides.push_back({std::min(a, b), std::max(a, b), f});
        }
    std::sort(sides.begin(), sides.end());
    std::vector<std::uint32_t> edges;
    for (std::size_t i = 0; i + 1 < sides.size(); ++i)
        if (sides[i][0] == sides[i + 1][0] && sides[i][1] == sides[i + 1][1] &&
            p.face_t[RefinedFaceId(sides[i][2])] == p.face_t[RefinedFaceId(sides[i + 1][2])]) {
            edges.push_back(sides[i][0]);
            edges.push_back(sides[i][1]);
        }
    return edges;
}

// T (§2), D, and the network of curves (§3): each curve's vertices of T′, their offsets, its kind.
void write_domain_and_curves(ArrayWriter& a, const TriMesh& T, const Parameterization& p, bool decimated) {
    const partition::Partition& P = p.partition;
    if (!decimated) a.triangles("t_faces", T.triangles());
    a.q16("d_positions", P.domain.mesh.positions());
    a.triangles("d_faces", P.domain.mesh.triangles());
    std::vector<std::uint32_t> points, offsets{0};
    std::vector<std::uint8_t> kinds;
    for (DEdgeId e : P.network.path.ids()) {
        for (VertexId v : P.network.path[e]) points.push_back(v.idx());
        offsets.push_back(static_cast<std::uint32_t>(points.size()));
        kinds.push_back(static_cast<std::uint8_t>(P.curves[EdgeId(e)].kind));
    }
    std::vector<Vec3> xyz;
    xyz.reserve(points.size());
    for (const std::uint32_t v : points) xyz.push_back(p.refined_positions[v]);
    a.q16("curve_points", xyz);
    a.u32("curve_offsets", offsets);
    a.u8("curve_kinds", kinds);
}

// The colours of the distortion views are fhr's, not the page's (one ramp for the figure and the
// page): σ₁/σ₂ in render::anisotropy_colour (REN-16), and a face's L2 stretch s on a log scale
// from 1/4 (blue: the face has shrunk) through 1 (white) to 4 and more (red: it has grown).
render::Colour stretch_colour(double s) {
    if (!(s > 0) || !std::isfinite(s)) return render::Colour(0.6, 0.6, 0.6);
    const double t = std::clamp(std::log2(s) / 2, -1.0, 1.0);
    const render::Colour white(0.97, 0.97, 0.97), shrunk(0.19, 0.35, 0.80), grown(0.80, 0.10, 0.10);
    return t < 0 ? white + -t * (shrunk - white) : white + t * (grown - white);
}

template <class ColourOf>
std::vector<std::uint8_t> rgb(std::span<const float> values, ColourOf colour) {
    std::vector<std::uint8_t> out;
    out.reserve(3 * values.size());
    for (const float x : values) {
        const render::Colour c = colour(x);
        for (int k = 0; k < 3; ++k)
            out.push_back(static_cast<std::uint8_t>(std::lround(std::clamp(c[k], 0.0, 1.0) * 255)));
    }
    return out;
}

// How far a compressed surface lies from f^J at a vertex, as a share t of the largest such
// distance over every step of the curve: white (0) to dark red (1).
render::Colour error_colour(double t) {
    const render::Colour white(0.97, 0.97, 0.97), far(0.60, 0.05, 0.05);
    return white + std::clamp(t, 0.0, 1.0) * (far - white);
}

enum class Scale { linear, log };

// A legend: its colour bar as 64 CSS colours from `from` to `to` and its ticks.
template <class ColourOf>
void legend(io::JsonWriter& j, std::string_view name, double from, double to, std::initializer_list<double> ticks,
            Scale scale, ColourOf colour) {
    j.key(name).begin_object().key("from").value(from).key("to").value(to).key("ticks").begin_array();
    for (const double t : ticks) j.value(t);
    j.end_array().key("colours").begin_array();
    for (int i = 0; i < 64; ++i) {
        const double x = scale == Scale::log ? from * std::pow(to / from, i / 63.0) : from + (to - from) * i / 63.0;
        const std::vector<std::uint8_t> c =
            rgb(std::span<const float>(std::array<float, 1>{static_cast<float>(x)}), colour);
        char css[8];
        std::snprintf(css, sizeof css, "#%02x%02x%02x", c[0], c[1], c[2]);
        j.value(std::string_view(css));
    }
    j.end_array().end_object();
}

// T′ (or its display copy) with, per face, its patch, the β of its corners, its σ₁/σ₂ and its
// L2 stretch (DIST-1, DIST-3: normalised over T′), and the face of T′ it stands for.
void write_refined(ArrayWriter& a, const Parameterization& p, const DisplayMesh& display) {
    const bool decimated = !display.original.empty();
    const std::size_t n = decimated ? display.faces.size() : p.refined_faces.size();
    const auto original = [&](std::size_t f) { return decimated ? display.original[f] : f; };
    a.q16("tp_positions",
          decimated ? std::span<const Vec3>(display.positions) : std::span<const Vec3>(p.refined_positions));
    a.triangles("tp_faces",
                decimated ? std::span<const Triangle>(display.faces) : std::span<const Triangle>(p.refined_faces));
    if (decimated) a.u32("tp_original", display.original);
    std::vector<std::uint32_t> patch(n);
    std::vector<double> beta;
    beta.reserve(6 * n);
    for (std::size_t f = 0; f < n; ++f) {
        const RefinedFaceId face(static_cast<RefinedFaceId::Index>(original(f)));
        patch[f] = p.face_patch[face].idx();
        for (const auto& b : p.face_beta[face]) {
            beta.push_back(b[1]);
            beta.push_back(b[2]);
        }
    }
    a.u32("tp_patch", patch);
    a.unit16("tp_beta", beta);
    const std::vector<exchange::FaceStretch> s = face_stretches(p);
    double surface = 0, image = 0;
    for (const auto& x : s)
        if (!x.degenerate) {
            surface += x.surface_area;
            image += x.image_area;
        }
    const double k = image > 0 ? std::sqrt(surface / image) : 1;  // DIST-3
    std::vector<float> anisotropy(n, 0), stretch(n, 0);
    for (std::size_t f = 0; f < n; ++f) {
        const exchange::FaceStretch& x = s[original(f)];
        if (x.degenerate) continue;
        anisotropy[f] = static_cast<float>(x.sigma1 / x.sigma2);
        stretch[f] = static_cast<float>(std::sqrt((x.sigma1 * x.sigma1 + x.sigma2 * x.sigma2) / 2) / k);
    }
    a.f32("tp_anisotropy", anisotropy);
    a.f32("tp_stretch", stretch);
    a.u8("tp_anisotropy_rgb", rgb(std::span<const float>(anisotropy), render::anisotropy_colour));
    a.u8("tp_stretch_rgb", rgb(std::span<const float>(stretch), stretch_colour));
    if (!decimated) a.u32("tp_added_edges", added_edges(p));
}

// The largest distance from f^J of a compressed surface's vertex, over every step of the curve.
double largest_rate_error(const PageContent& content) {
    double far = 0;
    for (const RateStep& step : content.rate)
        for (std::size_t v = 0; v < step.positions.size(); ++v)
            far = std::max(far, (step.positions[v] - content.wavelets->remesh_positions[v]).norm());
    return far;
}

// §5: D^J laid in D (flat), f^J, the faces of each D^j, and each rate step's reconstruction with
// its vertices coloured by their distance from f^J (error_colour, over the largest).
void write_levels(ArrayWriter& a, const Parameterization& p, const PageContent& content) {
    const wavelet::WaveletResult& w = *content.wavelets;
    const wavelet::Refinement r = wavelet::refine(p.partition.domain.mesh, w.levels);
    a.q16("dj_positions", r.levels.back().positions());
    a.q16("fj_positions", w.remesh_positions);
    for (std::size_t j = 0; j < w.remesh_level_faces.size(); ++j)
        a.triangles("level_faces_" + std::to_string(j), w.remesh_level_faces[j]);
    const double far = largest_rate_error(content);
    for (std::size_t i = 0; i < content.rate.size(); ++i) {
        const std::vector<Vec3>& x = content.rate[i].positions;
        a.q16("rate_" + std::to_string(i), x);
        std::vector<float> share(x.size());
        for (std::size_t v = 0; v < x.size(); ++v)
            share[v] = far > 0 ? static_cast<float>((x[v] - w.remesh_positions[v]).norm() / far) : 0.0f;
        a.u8("rate_rgb_" + std::to_string(i), rgb(std::span<const float>(share), error_colour));
    }
}

// JSON inside <script>: "</" only occurs in its strings, where "<\/" means the same.
std::string script_safe(std::string_view json) {
    std::string out;
    out.reserve(json.size());
    for (std::size_t i = 0; i < json.size(); ++i) {
        out += json[i];
        if (json[i] == '<' && i + 1 < json.size() && json[i + 1] == '/') out += '\\';
    }
    return out;
}

}  // namespace

void write_page(const std::string& path, const TriMesh& T, const Parameterization& p, const PageContent& content) {
    if (!page_available())
        throw InvalidInput(path, 0,
                           "this fhr was built without its page: install web/'s npm packages (npm ci --prefix web, "
                           "as ./run does) and configure with -Dpage=enabled");
    if (content.display_faces < 1000) throw InvalidInput(path, 0, "a page draws at least 1000 faces of T′");
    const DisplayMesh display = display_mesh(p, content.display_faces);
    io::JsonWriter j;
    j.begin_object();
    j.key("format").value("fhr-page 1").key("title").value(content.title).key("up").value(content.up_axis);
    j.key("decimated").value(!display.original.empty()).key("refined_faces").value(p.refined_faces.size());
    j.key("report").raw(content.report_json.substr(0, content.report_json.find_last_not_of('\n') + 1));
    j.key("timings").raw(content.timings_json.substr(0, content.timings_json.find_last_not_of('\n') + 1));
    j.key("rate").begin_array();
    for (const RateStep& s : content.rate)
        j.begin_object()
            .key("percent")
            .value(s.percent)
            .key("count")
            .value(s.count)
            .key("l2")
            .value(s.l2)
            .key("hausdorff")
            .value(s.hausdorff)
            .end_object();
    j.end_array();
    j.key("levels").value(content.wavelets ? content.wavelets->levels : 0);
    j.key("legends").begin_object();
    legend(j, "anisotropy", 1, 1000, {1, 10, 100, 1000}, Scale::log, render::anisotropy_colour);
    legend(j, "stretch", 0.25, 4, {0.25, 0.5, 1, 2, 4}, Scale::log, stretch_colour);
    if (content.wavelets) {
        const double far = largest_rate_error(content);
        legend(j, "error", 0, far, {0, far / 2, far}, Scale::linear,
               [far](double d) { return error_colour(far > 0 ? d / far : 0); });
    }
    j.end_object();
    j.key("arrays").begin_object();
    ArrayWriter a(j);
    write_domain_and_curves(a, T, p, !display.original.empty());
    write_refined(a, p, display);
    if (content.wavelets) write_levels(a, p, content);
    j.end_object().end_object();

    std::string html =
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
        "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>fhr — " +
        render::xml_escaped(content.title) +
        "</title>\n</head>\n<body>\n<script id=\"fhr-data\" type=\"application/json\">";
    html += script_safe(j.str());
    html += "</script>\n<script>";
    html += detail::page_script();
    html += "</script>\n</body>\n</html>\n";
    io::write_file_atomically(path, html);
}

}  // namespace fhr::app
