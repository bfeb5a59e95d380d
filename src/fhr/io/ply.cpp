// FHR io — strict PLY reader (spec/formats.md FMT-PLY-*): ascii, binary_little_endian and
// binary_big_endian bodies. The triangulation T of the paper (§1) is taken from element `vertex`
// (properties x, y, z found by name, of any scalar type) and element `face` (list property
// `vertex_indices` or `vertex_index` of any integer types); every other property and element is
// read past — its size still checked — and ignored. Asked for texture coordinates (a UV atlas,
// spec/atlas.md ATLAS-1), it also reads per-vertex `u v`, `s t` or `texture_u texture_v`, the
// per-face list `texcoord` (u, v of each corner; it wins over per-vertex ones) and `texnumber`.
#include <array>
#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <fhr/io/detail/text_scanner.hpp>
#include <fhr/io/read.hpp>

namespace fhr::io {

namespace {

using detail::TextScanner;
using detail::Where;

enum class Scalar : std::uint8_t { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

struct ScalarInfo {
    std::string_view name, alias;
    unsigned size;
    bool integer;
    std::int64_t min, max;  // range of an integer type
};

constexpr std::array<ScalarInfo, 8> scalar_info = {{
    {"char", "int8", 1, true, -128, 127},
    {"uchar", "uint8", 1, true, 0, 255},
    {"short", "int16", 2, true, -32768, 32767},
    {"ushort", "uint16", 2, true, 0, 65535},
    {"int", "int32", 4, true, -2147483648LL, 2147483647},
    {"uint", "uint32", 4, true, 0, 4294967295LL},
    {"float", "float32", 4, false, 0, 0},
    {"double", "float64", 8, false, 0, 0},
}};

const ScalarInfo& info(Scalar t) { return scalar_info[static_cast<std::size_t>(t)]; }

struct Property {
    std::string name;
    Scalar type{};
    bool is_list = false;
    Scalar count_type{};  // of a list
};

struct Element {
    std::string name;
    std::uint64_t count = 0;
    std::vector<Property> properties;
};

enum class Encoding { ascii, little_endian, big_endian };

/// The header, and where the triangulation is in it.
struct Header {
    Encoding encoding{};
    std::vector<Element> elements;
    std::size_t vertex = 0, face = 0;  // element indices
    std::array<std::size_t, 3> xyz{};  // property indices in the vertex element
    std::size_t face_list = 0;         // property index in the face element
    // Texture coordinates (absent: absent): per-vertex u and v, the face list texcoord, texnumber.
    static constexpr std::size_t absent = std::numeric_limits<std::size_t>::max();
    std::array<std::size_t, 2> vertex_uv{absent, absent};
    std::size_t face_texcoord = absent, face_texnumber = absent;
};

Scalar parse_scalar(std::string_view token, TextScanner& in) {
    for (std::size_t t = 0; t < scalar_info.size(); ++t)
        if (token == scalar_info[t].name || token == scalar_info[t].alias) return static_cast<Scalar>(t);
    in.fail({"header"}, "unknown property type " + detail::quoted(token));
}

/// FMT-PLY-1: `ply`, `format`, `comment`, `obj_info`, `element`, `property`, `end_header`.
Header parse_header_lines(std::string_view bytes, TextScanner& in) {
    const Where where{"header"};
    if (bytes.substr(0, 4) != "ply\n" && bytes.substr(0, 5) != "ply\r\n")
        detail::fail(in.name(), 1, where, "missing the 'ply' magic line");
    in.next_line();
    Header h;
    bool has_format = false;
    while (true) {
        if (!in.next_line()) detail::fail(in.name(), in.line(), where, "no 'end_header' line");
        const std::string_view keyword = in.token();
        if (keyword == "comment" || keyword == "obj_info") continue;
        if (keyword == "end_header") {
            in.expect_end_of_line(where);
            break;
        }
        if (keyword == "format") {
            const std::string_view encoding = in.token(where, "an encoding");
            if (encoding == "ascii")
                h.encoding = Encoding::ascii;
            else if (encoding == "binary_little_endian")
                h.encoding = Encoding::little_endian;
            else if (encoding == "binary_big_endian")
                h.encoding = Encoding::big_endian;
            else
                in.fail(where, "unknown encoding " + detail::quoted(encoding));
            if (in.token(where, "a version") != "1.0") in.fail(where, "unsupported PLY version (expected 1.0)");
            has_format = true;
        } else if (keyword == "element") {
            Element e;
            e.name = in.token(where, "an element name");
            for (const Element& other : h.elements)
                if (other.name == e.name) in.fail(where, "element " + detail::quoted(e.name) + " declared twice");
            e.count = in.count(where);
            h.elements.push_back(std::move(e));
        } else if (keyword == "property") {
            if (h.elements.empty()) in.fail(where, "property before any element");
            Property p;
            const std::string_view type = in.token(where, "a property type");
            if (type == "list") {
                p.is_list = true;
                p.count_type = parse_scalar(in.token(where, "a list count type"), in);
                if (!info(p.count_type).integer) in.fail(where, "list count type must be an integer type");
                p.type = parse_scalar(in.token(where, "a list value type"), in);
            } else {
                p.type = parse_scalar(type, in);
            }
            p.name = in.token(where, "a property name");
            std::vector<Property>& properties = h.elements.back().properties;
            for (const Property& other : properties)
                if (other.name == p.name) in.fail(where, "property " + detail::quoted(p.name) + " declared twice");
            properties.push_back(std::move(p));
        } else {
            in.fail(where, "unknown header line " + detail::quoted(keyword));
        }
        in.expect_end_of_line(where);
    }
    if (!has_format) in.fail(where, "no 'format' line");
    return h;
}

std::size_t find_element(const Header& h, std::string_view name, const std::string& file) {
    for (std::size_t e = 0; e < h.elements.size(); ++e)
        if (h.elements[e].name == name) return e;
    detail::fail(file, 0, {"header"}, "no " + detail::quoted(name) + " element");
}

/// FMT-PLY-2: locates x, y, z and the face index list.
Header parse_header(std::string_view bytes, TextScanner& in) {
    Header h = parse_header_lines(bytes, in);
    const std::string& file = in.name();
    for (const Element& e : h.elements)
        if (e.properties.empty())
            detail::fail(file, 0, {"header"}, "element " + detail::quoted(e.name) + " has no properties");

    h.vertex = find_element(h, "vertex", file);
    const std::vector<Property>& vertex = h.elements[h.vertex].properties;
    constexpr std::array<std::string_view, 3> axes = {"x", "y", "z"};
    for (std::size_t c = 0; c < 3; ++c) {
        std::size_t k = 0;
        while (k < vertex.size() && vertex[k].name != axes[c]) ++k;
        if (k == vertex.size())
            detail::fail(file, 0, {"header"}, "element 'vertex' has no property '" + std::string(axes[c]) + "'");
        if (vertex[k].is_list)
            detail::fail(file, 0, {"header"}, "vertex property '" + std::string(axes[c]) + "' is a list");
        h.xyz[c] = k;
    }

    h.face = find_element(h, "face", file);
    const std::vector<Property>& face = h.elements[h.face].properties;
    std::size_t k = 0;
    while (k < face.size() && face[k].name != "vertex_indices" && face[k].name != "vertex_index") ++k;
    if (k == face.size()) detail::fail(file, 0, {"header"}, "element 'face' has no property 'vertex_indices'");
    if (!face[k].is_list || !info(face[k].type).integer)
        detail::fail(file, 0, {"header"}, "face property '" + face[k].name + "' must be a list of integers");
    h.face_list = k;
    // Texture coordinates, used only when asked for: the first pair of names present, as scalars.
    const auto scalar = [](const std::vector<Property>& ps, std::string_view name) {
        for (std::size_t j = 0; j < ps.size(); ++j)
            if (ps[j].name == name && !ps[j].is_list) return j;
        return Header::absent;
    };
    constexpr std::array<std::array<std::string_view, 2>, 3> uv_names = {
        {{"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}}};
    for (const auto& names : uv_names)
        if (h.vertex_uv[0] == Header::absent && scalar(vertex, names[0]) != Header::absent &&
            scalar(vertex, names[1]) != Header::absent)
            h.vertex_uv = {scalar(vertex, names[0]), scalar(vertex, names[1])};
    for (std::size_t j = 0; j < face.size(); ++j)
        if (face[j].name == "texcoord" && face[j].is_list) h.face_texcoord = j;
    h.face_texnumber = scalar(face, "texnumber");
    if (h.elements[h.face].count == 0) detail::fail(file, 0, {"header"}, "no faces (the header declares 0)");
    return h;
}

/// FMT-SIZE-1: the fewest bytes the body can take (a face list holds at least 3 indices; an ascii
/// value takes at least 2 bytes, a digit and a separator).
std::uint64_t min_body_bytes(const Header& h) {
    std::uint64_t total = 0;
    for (std::size_t e = 0; e < h.elements.size(); ++e) {
        std::uint64_t record = 0;
        for (std::size_t k = 0; k < h.elements[e].properties.size(); ++k) {
            const Property& p = h.elements[e].properties[k];
            const std::uint64_t min_values = (e == h.face && k == h.face_list) ? 3 : 0;
            if (h.encoding == Encoding::ascii)
                record += p.is_list ? 2 + 2 * min_values : 2;
            else
                record += p.is_list ? info(p.count_type).size + min_values * info(p.type).size : info(p.type).size;
        }
        total = detail::add_min_bytes(total, h.elements[e].count, record);
    }
    return total;
}

/// An ascii body: one element per line.
class AsciiBody {
public:
    explicit AsciiBody(TextScanner& in) : in_(in) {}
    void begin(Where where, std::uint64_t declared) {
        if (!in_.next_line())
            in_.fail(where, "unexpected end of file (the header declares " + std::to_string(declared) + ")");
    }
    void end(Where where) { in_.expect_end_of_line(where); }
    void finish() {
        if (in_.next_line()) in_.fail({}, "unexpected data after the last element");
    }
    std::uint64_t line() const { return in_.line(); }
    std::int64_t integer(Scalar t, Where where) {
        const std::int64_t v = in_.integer(where);
        if (v < info(t).min || v > info(t).max)
            in_.fail(where, "value " + std::to_string(v) + " out of range for " + std::string(info(t).name));
        return v;
    }
    double real(Scalar t, Where where) {
        return info(t).integer ? static_cast<double>(integer(t, where)) : in_.real(where);
    }
    /// real(), and the number added to the printed digits (an integer type is exact).
    double real(Scalar t, Where where, detail::PrintedDigits& digits, double&) {
        return info(t).integer ? static_cast<double>(integer(t, where)) : in_.real(where, digits);
    }
    void skip(Scalar t, Where where, std::uint64_t n) {
        for (std::uint64_t k = 0; k < n; ++k) real(t, where);
    }

private:
    TextScanner& in_;
};

/// A binary body, little or big endian.
class BinaryBody {
public:
    BinaryBody(std::string_view data, bool big_endian, const std::string& name)
        : data_(data), big_endian_(big_endian), name_(name) {}
    void begin(Where, std::uint64_t) {}
    void end(Where) {}
    void finish() {
        if (pos_ != data_.size())
            detail::fail(name_, 0, {},
                         "unexpected data after the last element (" + std::to_string(data_.size() - pos_) + " bytes)");
    }
    std::uint64_t line() const { return 0; }
    std::int64_t integer(Scalar t, Where where) {
        const std::uint64_t r = raw(t, where);
        switch (t) {
            case Scalar::int8: return static_cast<std::int8_t>(r);
            case Scalar::int16: return static_cast<std::int16_t>(r);
            case Scalar::int32: return static_cast<std::int32_t>(r);
            default: return static_cast<std::int64_t>(r);
        }
    }
    double real(Scalar t, Where where) {
        if (t == Scalar::float32) return std::bit_cast<float>(static_cast<std::uint32_t>(raw(t, where)));
        if (t == Scalar::float64) return std::bit_cast<double>(raw(t, where));
        return static_cast<double>(integer(t, where));
    }
    /// real(), and `rounding` raised to half an ulp of the stored type at the value (0 for integers).
    double real(Scalar t, Where where, detail::PrintedDigits&, double& rounding) {
        const double v = real(t, where);
        const double half_ulp = t == Scalar::float32 ? 0x1p-24 : t == Scalar::float64 ? 0x1p-53 : 0.0;
        rounding = std::max(rounding, half_ulp * std::fabs(v));
        return v;
    }
    void skip(Scalar t, Where where, std::uint64_t n) {
        if (n > (data_.size() - pos_) / info(t).size) truncated(where);
        pos_ += n * info(t).size;
    }

private:
    [[noreturn]] void truncated(Where where) const {
        detail::fail(name_, 0, where, "unexpected end of data (truncated file?)");
    }
    std::uint64_t raw(Scalar t, Where where) {
        const unsigned size = info(t).size;
        if (data_.size() - pos_ < size) truncated(where);
        std::uint64_t r = 0;
        for (unsigned b = 0; b < size; ++b) {
            const auto byte = static_cast<unsigned char>(data_[pos_ + (big_endian_ ? b : size - 1 - b)]);
            r = (r << 8) | byte;
        }
        pos_ += size;
        return r;
    }
    std::string_view data_;
    std::size_t pos_ = 0;
    bool big_endian_;
    const std::string& name_;
};

/// FMT-PLY-3: every element in header order; x y z and the face lists go into the soup, and with
/// `texture` the texture coordinates into soup.texture (ATLAS-1).
template <class Body>
void read_body(Body& body, const Header& h, PolygonSoup& soup, bool text, bool texture) {
    const std::uint64_t vertex_count = h.elements[h.vertex].count;
    SoupTexture& tex = soup.texture;
    const bool per_vertex_uv = texture && h.vertex_uv[0] != Header::absent;
    const bool per_corner_uv = texture && h.face_texcoord != Header::absent;
    std::vector<double> corner_uv;  // the current face's texcoord list
    detail::PrintedDigits digits;   // of the coordinates, in an ascii body
    for (std::size_t e = 0; e < h.elements.size(); ++e) {
        const Element& element = h.elements[e];
        const bool is_vertex = e == h.vertex, is_face = e == h.face;
        for (std::uint64_t i = 0; i < element.count; ++i) {
            const Where where{element.name, i};
            body.begin(where, element.count);
            Vec3 p = Vec3::Zero();
            std::array<double, 2> uv{};
            std::uint32_t texnumber = 0;
            std::int64_t polygon_size = -1;
            corner_uv.clear();
            for (std::size_t k = 0; k < element.properties.size(); ++k) {
                const Property& prop = element.properties[k];
                if (!prop.is_list) {
                    const bool coordinate = is_vertex && (k == h.xyz[0] || k == h.xyz[1] || k == h.xyz[2]);
                    const double v = texture && coordinate ? body.real(prop.type, where, digits, tex.rounding)
                                                           : body.real(prop.type, where);
                    for (int c = 0; c < 3; ++c)
                        if (is_vertex && k == h.xyz[c]) p[c] = v;
                    for (int c = 0; c < 2; ++c)
                        if (per_vertex_uv && is_vertex && k == h.vertex_uv[c]) uv[c] = v;
                    if (texture && is_face && k == h.face_texnumber) {
                        if (!(v >= 0 && v < 4294967296.0 && v == std::floor(v)))
                            detail::fail(soup.source, body.line(), where, "texnumber is not an integer in [0, 2^32)");
                        texnumber = static_cast<std::uint32_t>(v);
                    }
                    continue;
                }
                const std::int64_t n = body.integer(prop.count_type, where);
                if (n < 0) detail::fail(soup.source, body.line(), where, "negative list length " + std::to_string(n));
                if (per_corner_uv && is_face && k == h.face_texcoord) {
                    for (std::int64_t j = 0; j < n; ++j) corner_uv.push_back(body.real(prop.type, where));
                    continue;
                }
                if (!is_face || k != h.face_list) {
                    body.skip(prop.type, where, static_cast<std::uint64_t>(n));
                    continue;
                }
                detail::check_polygon_size(static_cast<std::uint64_t>(n), soup.source, body.line(), where);
                for (std::int64_t j = 0; j < n; ++j)
                    soup.indices.push_back(detail::checked_index(body.integer(prop.type, where), vertex_count,
                                                                 soup.source, body.line(), where));
                soup.offsets.push_back(static_cast<std::uint32_t>(soup.indices.size()));
                if (text) soup.polygon_line.push_back(body.line());
                polygon_size = n;
            }
            body.end(where);
            if (texture && is_face) {
                tex.polygon_texture.push_back(texnumber);
                if (per_corner_uv) {
                    if (static_cast<std::int64_t>(corner_uv.size()) != 2 * polygon_size)
                        detail::fail(soup.source, body.line(), where,
                                     "texcoord has " + std::to_string(corner_uv.size()) + " values, expected " +
                                         std::to_string(2 * polygon_size) + " (u v per corner)");
                    for (std::size_t j = 0; j < corner_uv.size(); j += 2) {
                        if (!std::isfinite(corner_uv[j]) || !std::isfinite(corner_uv[j + 1]))
                            detail::fail(soup.source, body.line(), where, "texture coordinate is not finite");
                        tex.corner_uv.push_back(static_cast<std::uint32_t>(tex.uv.size()));
                        tex.uv.push_back({corner_uv[j], corner_uv[j + 1]});
                    }
                } else {
                    const std::uint32_t* corners = soup.polygon(soup.polygon_count() - 1);
                    for (std::int64_t j = 0; j < polygon_size; ++j)
                        tex.corner_uv.push_back(per_vertex_uv ? corners[j] : SoupTexture::none);
                }
            }
            if (!is_vertex) continue;
            detail::check_point(p, soup.source, body.line(), where);
            soup.points.push_back(p);
            if (text) soup.point_line.push_back(body.line());
            if (per_vertex_uv) {
                if (!std::isfinite(uv[0]) || !std::isfinite(uv[1]))
                    detail::fail(soup.source, body.line(), where, "texture coordinate is not finite");
                tex.uv.push_back(uv);
            }
        }
    }
    body.finish();
    tex.rounding = std::max(tex.rounding, digits.rounding());
}

}  // namespace

PolygonSoup parse_ply(std::string_view bytes, const std::string& name, bool texture) {
    detail::check_input_size(bytes, name);
    TextScanner in(bytes, name, '\0');
    const Header h = parse_header(bytes, in);
    const bool text = h.encoding == Encoding::ascii;
    const std::string_view body_bytes = in.rest();

    // FMT-SIZE-1: checked before anything is reserved (an ascii file may lack its last newline).
    const std::uint64_t need = min_body_bytes(h);
    if (need > body_bytes.size() + (text ? 1 : 0))
        detail::fail(name, 0, {"header"},
                     "the declared elements need at least " + std::to_string(need) + " bytes, but only " +
                         std::to_string(body_bytes.size()) + " bytes follow the header (truncated file?)");

    PolygonSoup soup;
    soup.source = name;
    const std::uint64_t vertex_count = h.elements[h.vertex].count;
    const std::uint64_t face_count = h.elements[h.face].count;
    soup.points.reserve(vertex_count);
    soup.offsets.reserve(face_count + 1);
    soup.indices.reserve(3 * face_count);
    if (text) {
        soup.point_line.reserve(vertex_count);
        soup.polygon_line.reserve(face_count);
        AsciiBody body(in);
        read_body(body, h, soup, true, texture);
    } else {
        BinaryBody body(body_bytes, h.encoding == Encoding::big_endian, name);
        read_body(body, h, soup, false, texture);
    }
    return soup;
}

}  // namespace fhr::io
