// FHR io — strict Wavefront OBJ reader (spec/formats.md FMT-OBJ-*), polygonal subset: `v` and
// `f` statements make the triangulation T of the paper (§1); every other statement of the OBJ
// specification (texture coordinates, normals, groups, materials, free-form geometry, …) is
// recognised and ignored, an unknown statement is refused. Asked for texture coordinates (a UV
// atlas, spec/atlas.md ATLAS-1), it also reads `vt`, each corner's `t` and the `usemtl` groups.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include <fhr/io/detail/text_scanner.hpp>
#include <fhr/io/read.hpp>

namespace fhr::io {

namespace {

using detail::NumberStatus;
using detail::TextScanner;
using detail::Where;

/// FMT-OBJ-1: statements of the OBJ specification that carry nothing the paper's input needs.
constexpr std::string_view ignored_statements[] = {
    "vt",     "vn",    "vp",       "g",        "o",          "s",         "mg",    "usemtl", "mtllib",
    "usemap", "maps",  "l",        "p",        "curv",       "curv2",     "surf",  "cstype", "deg",
    "bmat",   "step",  "parm",     "trim",     "hole",       "scrv",      "sp",    "end",    "con",
    "lod",    "bevel", "c_interp", "d_interp", "shadow_obj", "trace_obj", "ctech", "stech",  "call"};

bool is_ignored(std::string_view keyword) {
    for (std::string_view s : ignored_statements)
        if (s == keyword) return true;
    return false;
}

/// An OBJ reference resolved to a 0-based index: positive ones are 1-based and checked against the
/// final count by the caller (OBJ allows them to refer forward), negative ones count back from the
/// `defined` records read so far (FMT-OBJ-4, FMT-OBJ-5).
std::uint32_t resolve(std::string_view token, std::uint64_t defined, const char* what, const char* plural,
                      TextScanner& in, Where where) {
    std::int64_t value = 0;
    const NumberStatus status = detail::parse_int64(token, value);
    if (status == NumberStatus::not_a_number)
        in.fail(where, std::string("expected a ") + what + " index, found " + detail::quoted(token));
    if (status == NumberStatus::out_of_range || value > std::numeric_limits<std::uint32_t>::max())
        in.fail(where, "index " + detail::quoted(token) + " out of range");
    if (value == 0) in.fail(where, "index 0 (OBJ indices are 1-based)");
    if (value > 0) return static_cast<std::uint32_t>(value - 1);
    if (value < -static_cast<std::int64_t>(defined))
        in.fail(where, "relative index " + std::to_string(value) + " out of range (only " + std::to_string(defined) +
                           " " + plural + " defined so far)");
    return static_cast<std::uint32_t>(static_cast<std::int64_t>(defined) + value);
}

/// FMT-OBJ-3: one `f` corner `i`, `i/t`, `i//n` or `i/t/n`. Returns the vertex index, 0-based
/// (resolve()); with `texture`, sets it to the corner's texture coordinate record, or none.
std::uint32_t parse_corner(std::string_view corner, std::uint64_t defined, TextScanner& in, Where where,
                           std::uint64_t defined_uv = 0, std::uint32_t* texture = nullptr) {
    std::array<std::string_view, 3> parts;  // vertex, texture, normal
    std::size_t last = 0;                   // index of the last part present
    for (std::string_view rest = corner;; ++last) {
        if (last == parts.size()) in.fail(where, "malformed corner " + detail::quoted(corner));
        const std::size_t slash = rest.find('/');
        parts[last] = rest.substr(0, slash);
        if (slash == std::string_view::npos) break;
        rest.remove_prefix(slash + 1);
    }
    // texture and normal references are ignored but must be well formed: non-zero integers, the
    // texture part empty only in `i//n`.
    const auto is_reference = [](std::string_view s) {
        std::int64_t v = 0;
        return detail::parse_int64(s, v) == NumberStatus::ok && v != 0;
    };
    const bool texture_ok = last < 1 || is_reference(parts[1]) || (parts[1].empty() && last == 2);
    const bool normal_ok = last < 2 || is_reference(parts[2]);
    if (!texture_ok || !normal_ok)
        in.fail(where, "malformed corner " + detail::quoted(corner) + " (expected i, i/t, i//n or i/t/n)");

    if (texture)
        *texture = last >= 1 && !parts[1].empty()
                       ? resolve(parts[1], defined_uv, "texture coordinate", "texture coordinates", in, where)
                       : SoupTexture::none;
    return resolve(parts[0], defined, "vertex", "vertices", in, where);
}

}  // namespace

PolygonSoup parse_obj(std::string_view bytes, const std::string& name, bool texture) {
    detail::check_input_size(bytes, name);
    TextScanner in(bytes, name);
    PolygonSoup soup;
    soup.source = name;
    SoupTexture& tex = soup.texture;
    std::uint32_t group = 0;       // the texture of the faces that follow: the last `usemtl`, 0 before any
    detail::PrintedDigits digits;  // of the coordinates x, y, z
    if (texture) tex.texture_names.emplace_back();

    while (in.next_line()) {
        const std::string_view keyword = in.token();
        if (keyword == "v") {
            // FMT-OBJ-2: `v x y z`, optionally followed by w (a weight for rational free-form
            // geometry, ignored) or by an r g b colour (a common extension, ignored).
            const Where where{"vertex", soup.points.size()};
            soup.points.push_back(in.point(where, texture ? &digits : nullptr));
            soup.point_line.push_back(in.line());
            int extra = 0;
            for (; in.has_token() && extra < 3; ++extra) in.real(where);
            if (extra == 2) in.fail(where, "expected x y z, x y z w or x y z r g b");
            in.expect_end_of_line(where);
        } else if (keyword == "f") {
            const Where where{"face", soup.polygon_count()};
            std::uint64_t n = 0;
            for (std::string_view corner = in.token(); !corner.empty(); corner = in.token(), ++n) {
                std::uint32_t t = SoupTexture::none;
                soup.indices.push_back(
                    parse_corner(corner, soup.points.size(), in, where, tex.uv.size(), texture ? &t : nullptr));
                if (texture) tex.corner_uv.push_back(t);
            }
            detail::check_polygon_size(n, name, in.line(), where);
            soup.offsets.push_back(static_cast<std::uint32_t>(soup.indices.size()));
            soup.polygon_line.push_back(in.line());
            if (texture) tex.polygon_texture.push_back(group);
        } else if (texture && keyword == "vt") {
            // `vt u v [w]`: w (a 3D texture's depth) is ignored; u and v must be finite.
            const Where where{"texture coordinate", tex.uv.size()};
            std::array<double, 2> uv{in.real(where), in.real(where)};
            for (double x : uv)
                if (!std::isfinite(x)) in.fail(where, "texture coordinate is not finite");
            if (in.has_token()) in.real(where);
            in.expect_end_of_line(where);
            tex.uv.push_back(uv);
        } else if (texture && keyword == "usemtl") {
            const std::string_view material = in.token({"usemtl"}, "a material name");
            const auto known = std::find(tex.texture_names.begin(), tex.texture_names.end(), material);
            group = static_cast<std::uint32_t>(known - tex.texture_names.begin());
            if (known == tex.texture_names.end()) tex.texture_names.emplace_back(material);
        } else if (!is_ignored(keyword)) {
            in.fail({}, "unknown OBJ statement " + detail::quoted(keyword));
        }
    }

    // FMT-OBJ-6
    if (soup.polygon_count() == 0) detail::fail(name, 0, {}, "no faces ('f' statements)");
    // FMT-OBJ-5: positive indices may refer forward; now that all vertices are known, check them.
    for (std::size_t p = 0; p < soup.polygon_count(); ++p)
        for (std::uint32_t k = soup.offsets[p]; k < soup.offsets[p + 1]; ++k)
            if (soup.indices[k] >= soup.points.size())
                detail::fail(name, soup.polygon_line[p], {"face", p},
                             "index " + std::to_string(std::uint64_t{soup.indices[k]} + 1) + " out of range (1.." +
                                 std::to_string(soup.points.size()) + ")");
    tex.rounding = digits.rounding();
    if (texture)
        for (std::size_t p = 0; p < soup.polygon_count(); ++p)
            for (std::uint32_t k = soup.offsets[p]; k < soup.offsets[p + 1]; ++k)
                if (tex.corner_uv[k] != SoupTexture::none && tex.corner_uv[k] >= tex.uv.size())
                    detail::fail(name, soup.polygon_line[p], {"face", p},
                                 "texture coordinate index " + std::to_string(std::uint64_t{tex.corner_uv[k]} + 1) +
                                     " out of range (1.." + std::to_string(tex.uv.size()) + ")");
    return soup;
}

}  // namespace fhr::io
