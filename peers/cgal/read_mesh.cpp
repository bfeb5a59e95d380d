// cgal_uv's mesh reader: OFF, OBJ and PLY (ascii and binary), chosen by the file's extension,
// into a triangle soup in file order. It is small and strict, after fhr's own readers
// (spec/formats.md), because an adapter that guesses would hand CGAL a different mesh than the one
// the oracle compares the atlas with.
//
// Decisions:
// - Numbers are whole tokens read by std::from_chars (a leading '+' allowed); a coordinate must be
//   finite and at most 1e150 in magnitude (squared lengths stay finite); anything else is refused.
// - Faces must be triangles: CGAL's parameterizers take triangle meshes, and triangulating here
//   would make the atlas's faces differ from the file's.
// - Indices must be in range; OBJ's negative (relative) indices are resolved as OBJ defines them.
// - OFF: [ST][C][N]OFF, one vertex or face per line, a face line may end in up to 4 colour
//   numbers, vertex lines carry extras only when the keyword has a prefix. OBJ: `v` and `f` are
//   read; the statements fhr's reader ignores (texture, normals, groups, materials, lines,
//   points, free-form geometry) are ignored; any other statement is refused. PLY: element `vertex` with x, y, z, element
//   `face` with a list `vertex_indices` (or `vertex_index`); other properties and elements are
//   read past.
// - Every refusal is one line: FILE[:LINE]: problem.
#include "uv_job.hpp"

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string_view>

namespace cgal_uv {

namespace {

// A refusal; `line` 0 means no line (binary data or the whole file).
struct Refusal {
    std::size_t line;
    std::string what;
};

[[noreturn]] void refuse(std::size_t line, std::string what) { throw Refusal{line, std::move(what)}; }

std::string quote(std::string_view token) {
    std::string q(1, '\'');
    q.append(token.substr(0, 40));
    q.append(token.size() > 40 ? "...'" : "'");
    return q;
}

double parse_coordinate(std::string_view token, std::size_t line) {
    std::string_view t = token;
    if (!t.empty() && t.front() == '+') t.remove_prefix(1);
    double value = 0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
    if (t.empty() || end != t.data() + t.size() || (ec != std::errc() && ec != std::errc::result_out_of_range))
        refuse(line, "expected a number, found " + quote(token));
    if (ec == std::errc::result_out_of_range) refuse(line, "number " + quote(token) + " is out of double range");
    if (std::isnan(value)) refuse(line, "coordinate is NaN");
    if (std::isinf(value)) refuse(line, "coordinate is infinite");
    if (std::fabs(value) > 1e150) refuse(line, "coordinate too large: lengths would overflow");
    return value;
}

long long parse_integer(std::string_view token, std::size_t line) {
    std::string_view t = token;
    if (!t.empty() && t.front() == '+') t.remove_prefix(1);
    long long value = 0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
    if (t.empty() || end != t.data() + t.size()) refuse(line, "expected an integer, found " + quote(token));
    if (ec != std::errc()) refuse(line, "integer " + quote(token) + " is out of range");
    return value;
}

std::uint32_t vertex_index(long long value, std::size_t vertex_count, std::size_t line) {
    if (value < 0) refuse(line, "negative index " + std::to_string(value));
    if (static_cast<unsigned long long>(value) >= vertex_count)
        refuse(line, "index " + std::to_string(value) +
                         (vertex_count == 0 ? " out of range (no vertices)"
                                            : " out of range (0.." + std::to_string(vertex_count - 1) + ")"));
    return static_cast<std::uint32_t>(value);
}

void check_triangle(std::size_t n, std::size_t face, std::size_t line) {
    if (n != 3)
        refuse(line,
               "face " + std::to_string(face) + " has " + std::to_string(n) + " vertices; only triangles are read");
}

// Text split into lines, comments (from '#') removed, each line into whitespace-separated tokens.
class TextLines {
public:
    explicit TextLines(std::string_view text) : text_(text) {}
    // The next line with at least one token; false at the end. line() is its 1-based number.
    bool next(std::vector<std::string_view>& tokens) {
        while (pos_ < text_.size()) {
            const std::size_t end = std::min(text_.find('\n', pos_), text_.size());
            std::string_view row = text_.substr(pos_, end - pos_);
            pos_ = end + 1;
            ++line_;
            if (const std::size_t hash = row.find('#'); hash != std::string_view::npos) row = row.substr(0, hash);
            tokens.clear();
            std::size_t i = 0;
            while (i < row.size()) {
                while (i < row.size() && std::isspace(static_cast<unsigned char>(row[i]))) ++i;
                std::size_t j = i;
                while (j < row.size() && !std::isspace(static_cast<unsigned char>(row[j]))) ++j;
                if (j > i) tokens.push_back(row.substr(i, j - i));
                i = j;
            }
            if (!tokens.empty()) return true;
        }
        return false;
    }
    std::size_t line() const { return line_; }

private:
    std::string_view text_;
    std::size_t pos_ = 0;
    std::size_t line_ = 0;
};

// --- OFF ------------------------------------------------------------------------------------------

void read_off(std::string_view text, TriangleSoup& soup) {
    TextLines lines(text);
    std::vector<std::string_view> tok;
    if (!lines.next(tok)) refuse(0, "empty file");
    std::string_view keyword = tok[0];
    bool prefixed = false;
    for (std::string_view prefix : {"ST", "C", "N"})
        if (keyword.substr(0, prefix.size()) == prefix) keyword.remove_prefix(prefix.size()), prefixed = true;
    if (keyword != "OFF") refuse(lines.line(), "expected the keyword OFF, found " + quote(tok[0]));
    std::vector<std::string_view> counts(tok.begin() + 1, tok.end());
    if (counts.empty()) {
        if (!lines.next(tok)) refuse(lines.line(), "header only");
        counts = tok;
    }
    if (counts.size() < 2 || counts.size() > 3) refuse(lines.line(), "expected the counts V F [E]");
    const long long nv = parse_integer(counts[0], lines.line()), nf = parse_integer(counts[1], lines.line());
    if (nv < 0 || nf < 0) refuse(lines.line(), "negative count");
    if (nf == 0) refuse(lines.line(), "no faces");
    // A vertex line needs at least 6 bytes and a face line at least 8: refuse counts the file cannot hold.
    if (static_cast<double>(nv) * 6 + static_cast<double>(nf) * 8 > static_cast<double>(text.size()))
        refuse(lines.line(), "the counts need more bytes than the file has (truncated file?)");
    soup.xyz.reserve(3 * static_cast<std::size_t>(nv));
    for (long long i = 0; i < nv; ++i) {
        if (!lines.next(tok))
            refuse(lines.line(),
                   "unexpected end of file: expected " + std::to_string(nv) + " vertices, found " + std::to_string(i));
        if (tok.size() < 3 || (tok.size() > 3 && !prefixed))
            refuse(lines.line(),
                   "vertex " + std::to_string(i) + ": expected 3 numbers, found " + std::to_string(tok.size()));
        for (int k = 0; k < 3; ++k) soup.xyz.push_back(parse_coordinate(tok[k], lines.line()));
    }
    soup.tri.reserve(3 * static_cast<std::size_t>(nf));
    for (long long f = 0; f < nf; ++f) {
        if (!lines.next(tok))
            refuse(lines.line(),
                   "unexpected end of file: expected " + std::to_string(nf) + " faces, found " + std::to_string(f));
        const long long n = parse_integer(tok[0], lines.line());
        if (n < 3)
            refuse(lines.line(), "face " + std::to_string(f) + " has " + std::to_string(n) +
                                     " vertices (a polygon needs at least 3)");
        check_triangle(static_cast<std::size_t>(n), static_cast<std::size_t>(f), lines.line());
        if (tok.size() < 4 || tok.size() > 4 + 4)
            refuse(lines.line(), "face " + std::to_string(f) + ": expected 3 indices and at most 4 colour numbers");
        for (int k = 1; k <= 3; ++k)
            soup.tri.push_back(
                vertex_index(parse_integer(tok[k], lines.line()), static_cast<std::size_t>(nv), lines.line()));
        for (std::size_t k = 4; k < tok.size(); ++k) {
            double colour = 0;
            const auto [end, ec] = std::from_chars(tok[k].data(), tok[k].data() + tok[k].size(), colour);
            if (ec != std::errc() || end != tok[k].data() + tok[k].size())
                refuse(lines.line(), "expected a colour number, found " + quote(tok[k]));
        }
    }
    if (lines.next(tok)) refuse(lines.line(), "unexpected data after face " + std::to_string(nf - 1));
}

// --- OBJ ------------------------------------------------------------------------------------------

void read_obj(std::string_view text, TriangleSoup& soup) {
    // fhr's OBJ reader ignores the same statements (spec/formats.md FMT-OBJ-1), so both read one mesh.
    static const char* const ignored[] = {
        "vt",     "vn",    "vp",       "g",        "o",          "s",         "mg",    "usemtl", "mtllib",
        "usemap", "maps",  "l",        "p",        "curv",       "curv2",     "surf",  "cstype", "deg",
        "bmat",   "step",  "parm",     "trim",     "hole",       "scrv",      "sp",    "end",    "con",
        "lod",    "bevel", "c_interp", "d_interp", "shadow_obj", "trace_obj", "ctech", "stech",  "call"};
    TextLines lines(text);
    std::vector<std::string_view> tok;
    std::vector<std::size_t> face_line;  // for the range check after the whole file
    while (lines.next(tok)) {
        const std::string_view word = tok[0];
        if (word == "v") {
            if (tok.size() != 4 && tok.size() != 5 && tok.size() != 7)
                refuse(lines.line(), "vertex " + std::to_string(soup.vertex_count()) + ": expected 3, 4 or 6 numbers");
            for (int k = 1; k <= 3; ++k) soup.xyz.push_back(parse_coordinate(tok[k], lines.line()));
            for (std::size_t k = 4; k < tok.size(); ++k) parse_coordinate(tok[k], lines.line());
        } else if (word == "f") {
            const std::size_t face = soup.face_count();
            if (tok.size() < 4)
                refuse(lines.line(), "face " + std::to_string(face) + " has " + std::to_string(tok.size() - 1) +
                                         " vertices (a polygon needs at least 3)");
            check_triangle(tok.size() - 1, face, lines.line());
            for (std::size_t k = 1; k < tok.size(); ++k) {
                const std::string_view corner = tok[k];
                const std::size_t slash = corner.find('/');
                const long long i = parse_integer(corner.substr(0, slash), lines.line());
                if (slash != std::string_view::npos) {
                    // i/t, i//n or i/t/n: t and n are non-zero integers, ignored.
                    const std::string_view rest = corner.substr(slash + 1);
                    const std::size_t slash2 = rest.find('/');
                    const std::string_view t = rest.substr(0, slash2);
                    const std::string_view n =
                        slash2 == std::string_view::npos ? std::string_view() : rest.substr(slash2 + 1);
                    const bool ok =
                        (slash2 == std::string_view::npos ? !t.empty()
                                                          : !n.empty() && n.find('/') == std::string_view::npos);
                    if (!ok) refuse(lines.line(), "malformed corner " + quote(corner));
                    if (!t.empty() && parse_integer(t, lines.line()) == 0)
                        refuse(lines.line(), "malformed corner " + quote(corner));
                    if (!n.empty() && parse_integer(n, lines.line()) == 0)
                        refuse(lines.line(), "malformed corner " + quote(corner));
                }
                if (i == 0) refuse(lines.line(), "OBJ indices are 1-based");
                long long index = i - 1;
                if (i < 0) {
                    index = static_cast<long long>(soup.vertex_count()) + i;
                    if (index < 0) refuse(lines.line(), "relative index " + std::to_string(i) + " out of range");
                }
                if (index > static_cast<long long>(std::numeric_limits<std::uint32_t>::max() - 1))
                    refuse(lines.line(), "index " + std::to_string(i) + " out of range");
                soup.tri.push_back(static_cast<std::uint32_t>(index));
            }
            face_line.push_back(lines.line());
        } else if (std::find(std::begin(ignored), std::end(ignored), word) == std::end(ignored)) {
            refuse(lines.line(), "unsupported OBJ statement " + quote(word));
        }
    }
    if (soup.face_count() == 0) refuse(0, "no faces");
    for (std::size_t c = 0; c < soup.tri.size(); ++c)
        if (soup.tri[c] >= soup.vertex_count())
            refuse(face_line[c / 3], "index " + std::to_string(soup.tri[c] + 1) + " out of range (1.." +
                                         std::to_string(soup.vertex_count()) + ")");
}

// --- PLY ------------------------------------------------------------------------------------------

enum class PlyType { i8, u8, i16, u16, i32, u32, f32, f64 };

std::optional<PlyType> ply_type(std::string_view name) {
    static const std::pair<const char*, PlyType> names[] = {
        {"char", PlyType::i8},   {"int8", PlyType::i8},     {"uchar", PlyType::u8},   {"uint8", PlyType::u8},
        {"short", PlyType::i16}, {"int16", PlyType::i16},   {"ushort", PlyType::u16}, {"uint16", PlyType::u16},
        {"int", PlyType::i32},   {"int32", PlyType::i32},   {"uint", PlyType::u32},   {"uint32", PlyType::u32},
        {"float", PlyType::f32}, {"float32", PlyType::f32}, {"double", PlyType::f64}, {"float64", PlyType::f64}};
    for (const auto& [n, t] : names)
        if (name == n) return t;
    return std::nullopt;
}

std::size_t type_size(PlyType t) {
    switch (t) {
        case PlyType::i8:
        case PlyType::u8: return 1;
        case PlyType::i16:
        case PlyType::u16: return 2;
        case PlyType::i32:
        case PlyType::u32:
        case PlyType::f32: return 4;
        case PlyType::f64: return 8;
    }
    return 0;
}

bool is_integer(PlyType t) { return t != PlyType::f32 && t != PlyType::f64; }

struct PlyProperty {
    std::string name;
    bool list = false;
    PlyType count_type = PlyType::u8;
    PlyType type = PlyType::f32;
};

struct PlyElement {
    std::string name;
    std::size_t count = 0;
    std::vector<PlyProperty> properties;
};

// Reads values of a PLY body, ascii or binary; each value comes back as a double (exact for every
// PLY integer type) and integers are checked against their type's range.
class PlyBody {
public:
    enum class Format { ascii, little, big };
    PlyBody(std::string_view body, Format format, std::size_t first_line)
        : body_(body), format_(format), lines_(body), line_offset_(first_line) {}

    // Ascii: moves to the next line and makes its tokens current. Binary: nothing.
    void begin_record(const std::string& element, std::size_t index) {
        element_ = element;
        index_ = index;
        if (format_ != Format::ascii) return;
        if (!lines_.next(tokens_)) refuse(0, element + " " + std::to_string(index) + ": unexpected end of data");
        next_token_ = 0;
    }
    void end_record() {
        if (format_ == Format::ascii && next_token_ != tokens_.size())
            refuse(line(), element_ + " " + std::to_string(index_) + ": more values than its properties");
    }
    double value(PlyType t) {
        if (format_ == Format::ascii) {
            if (next_token_ >= tokens_.size())
                refuse(line(), element_ + " " + std::to_string(index_) + ": fewer values than its properties");
            const std::string_view token = tokens_[next_token_++];
            if (is_integer(t)) {
                const long long v = parse_integer(token, line());
                check_range(static_cast<double>(v), t, token);
                return static_cast<double>(v);
            }
            std::string_view s = token;
            if (!s.empty() && s.front() == '+') s.remove_prefix(1);
            double v = 0;
            const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
            if (s.empty() || end != s.data() + s.size() || (ec != std::errc() && ec != std::errc::result_out_of_range))
                refuse(line(), "expected a number, found " + quote(token));
            if (ec == std::errc::result_out_of_range)
                refuse(line(), "number " + quote(token) + " is out of double range");
            return v;
        }
        const std::size_t n = type_size(t);
        if (body_.size() - pos_ < n) refuse(0, element_ + " " + std::to_string(index_) + ": unexpected end of data");
        unsigned char b[8];
        std::memcpy(b, body_.data() + pos_, n);
        pos_ += n;
        const bool swap = (format_ == Format::big) == (std::endian::native == std::endian::little);
        if (swap) std::reverse(b, b + n);
        switch (t) {
            case PlyType::i8: {
                std::int8_t v;
                std::memcpy(&v, b, 1);
                return v;
            }
            case PlyType::u8: {
                std::uint8_t v;
                std::memcpy(&v, b, 1);
                return v;
            }
            case PlyType::i16: {
                std::int16_t v;
                std::memcpy(&v, b, 2);
                return v;
            }
            case PlyType::u16: {
                std::uint16_t v;
                std::memcpy(&v, b, 2);
                return v;
            }
            case PlyType::i32: {
                std::int32_t v;
                std::memcpy(&v, b, 4);
                return v;
            }
            case PlyType::u32: {
                std::uint32_t v;
                std::memcpy(&v, b, 4);
                return v;
            }
            case PlyType::f32: {
                float v;
                std::memcpy(&v, b, 4);
                return v;
            }
            case PlyType::f64: {
                double v;
                std::memcpy(&v, b, 8);
                return v;
            }
        }
        return 0;
    }
    void finish() {
        std::vector<std::string_view> rest;
        if (format_ == Format::ascii ? lines_.next(rest) : pos_ != body_.size())
            refuse(line(), "unexpected data after the last element");
    }
    std::size_t line() const { return format_ == Format::ascii ? line_offset_ + lines_.line() : 0; }

private:
    void check_range(double v, PlyType t, std::string_view token) const {
        double lo = 0, hi = 0;
        switch (t) {
            case PlyType::i8: lo = -128, hi = 127; break;
            case PlyType::u8: lo = 0, hi = 255; break;
            case PlyType::i16: lo = -32768, hi = 32767; break;
            case PlyType::u16: lo = 0, hi = 65535; break;
            case PlyType::i32: lo = -2147483648.0, hi = 2147483647.0; break;
            case PlyType::u32: lo = 0, hi = 4294967295.0; break;
            default: return;
        }
        if (v < lo || v > hi) refuse(line(), "value " + std::string(token) + " out of range for its type");
    }

    std::string_view body_;
    Format format_;
    std::size_t pos_ = 0;
    TextLines lines_;
    std::size_t line_offset_;
    std::vector<std::string_view> tokens_;
    std::size_t next_token_ = 0;
    std::string element_;
    std::size_t index_ = 0;
};

void read_ply(std::string_view text, TriangleSoup& soup) {
    // The header: lines up to and including "end_header".
    std::vector<PlyElement> elements;
    std::optional<PlyBody::Format> format;
    std::size_t pos = 0, line = 0;
    bool ended = false;
    while (pos < text.size() && !ended) {
        const std::size_t end = std::min(text.find('\n', pos), text.size());
        std::string_view row = text.substr(pos, end - pos);
        pos = end + 1;
        ++line;
        if (!row.empty() && row.back() == '\r') row.remove_suffix(1);
        std::istringstream words{std::string(row)};
        std::vector<std::string> owned;
        for (std::string w; words >> w;) owned.push_back(w);
        if (line == 1) {
            if (row != "ply") refuse(1, "expected the line 'ply'");
            continue;
        }
        if (owned.empty()) refuse(line, "blank header line");
        const std::string& word = owned[0];
        if (word == "comment" || word == "obj_info") continue;
        if (word == "format") {
            if (format || owned.size() != 3 || owned[2] != "1.0")
                refuse(line, "expected one line 'format ascii|binary_little_endian|binary_big_endian 1.0'");
            if (owned[1] == "ascii")
                format = PlyBody::Format::ascii;
            else if (owned[1] == "binary_little_endian")
                format = PlyBody::Format::little;
            else if (owned[1] == "binary_big_endian")
                format = PlyBody::Format::big;
            else
                refuse(line, "unknown PLY format " + quote(owned[1]));
        } else if (word == "element") {
            if (owned.size() != 3) refuse(line, "expected 'element NAME COUNT'");
            const long long count = parse_integer(owned[2], line);
            if (count < 0) refuse(line, "negative element count");
            for (const PlyElement& e : elements)
                if (e.name == owned[1]) refuse(line, "element " + quote(owned[1]) + " declared twice");
            elements.push_back({owned[1], static_cast<std::size_t>(count), {}});
        } else if (word == "property") {
            if (elements.empty()) refuse(line, "property before any element");
            PlyProperty p;
            if (owned.size() == 5 && owned[1] == "list") {
                const auto ct = ply_type(owned[2]), vt = ply_type(owned[3]);
                if (!ct || !vt || !is_integer(*ct)) refuse(line, "bad list property types");
                p = {owned[4], true, *ct, *vt};
            } else if (owned.size() == 3) {
                const auto t = ply_type(owned[1]);
                if (!t) refuse(line, "unknown property type " + quote(owned[1]));
                p = {owned[2], false, PlyType::u8, *t};
            } else {
                refuse(line, "expected 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME'");
            }
            for (const PlyProperty& q : elements.back().properties)
                if (q.name == p.name) refuse(line, "property " + quote(p.name) + " declared twice");
            elements.back().properties.push_back(p);
        } else if (word == "end_header") {
            if (owned.size() != 1) refuse(line, "expected 'end_header'");
            ended = true;
        } else {
            refuse(line, "unknown header line " + quote(row));
        }
    }
    if (!ended) refuse(line, "header without end_header");
    if (!format) refuse(line, "header without a format line");
    for (const PlyElement& e : elements)
        if (e.properties.empty()) refuse(0, "element " + quote(e.name) + " has no properties");

    const PlyElement* vertex = nullptr;
    const PlyElement* face = nullptr;
    for (const PlyElement& e : elements) {
        if (e.name == "vertex") vertex = &e;
        if (e.name == "face") face = &e;
    }
    if (!vertex) refuse(0, "no element 'vertex'");
    if (!face) refuse(0, "no element 'face'");
    int xyz_slot[3] = {-1, -1, -1};
    for (std::size_t k = 0; k < vertex->properties.size(); ++k)
        for (int c = 0; c < 3; ++c)
            if (vertex->properties[k].name == std::string(1, "xyz"[c])) {
                if (vertex->properties[k].list)
                    refuse(0, "vertex property " + quote(vertex->properties[k].name) + " is a list");
                xyz_slot[c] = static_cast<int>(k);
            }
    if (xyz_slot[0] < 0 || xyz_slot[1] < 0 || xyz_slot[2] < 0) refuse(0, "element vertex lacks x, y or z");
    int index_slot = -1;
    for (std::size_t k = 0; k < face->properties.size(); ++k) {
        const PlyProperty& p = face->properties[k];
        if (p.name == "vertex_indices" || p.name == "vertex_index") {
            if (index_slot >= 0) refuse(0, "face has both vertex_indices and vertex_index");
            if (!p.list || !is_integer(p.type))
                refuse(0, "face property " + quote(p.name) + " is not a list of integers");
            index_slot = static_cast<int>(k);
        }
    }
    if (index_slot < 0) refuse(0, "element face lacks a list vertex_indices");
    if (face->count == 0) refuse(0, "no faces");

    // Refuse counts the body cannot hold before reserving anything.
    const double body_bytes = static_cast<double>(text.size() - std::min(pos, text.size()));
    double need = 0;
    for (const PlyElement& e : elements) {
        double record = 0;
        for (const PlyProperty& p : e.properties)
            record +=
                *format == PlyBody::Format::ascii
                    ? 2.0 * (p.list ? 1 + (&e == face ? 3 : 0) : 1)
                    : static_cast<double>(p.list ? type_size(p.count_type) + (&e == face ? 3 * type_size(p.type) : 0)
                                                 : type_size(p.type));
        need += record * static_cast<double>(e.count);
    }
    if (need > body_bytes) refuse(0, "the element counts need more bytes than the file has (truncated file?)");

    PlyBody body(text.substr(std::min(pos, text.size())), *format, line);
    soup.xyz.assign(3 * vertex->count, 0.0);
    soup.tri.reserve(3 * face->count);
    for (const PlyElement& e : elements) {
        for (std::size_t i = 0; i < e.count; ++i) {
            body.begin_record(e.name, i);
            for (std::size_t k = 0; k < e.properties.size(); ++k) {
                const PlyProperty& p = e.properties[k];
                if (!p.list) {
                    const double v = body.value(p.type);
                    if (&e == vertex)
                        for (int c = 0; c < 3; ++c)
                            if (xyz_slot[c] == static_cast<int>(k)) {
                                if (std::isnan(v))
                                    refuse(body.line(), "vertex " + std::to_string(i) + ": coordinate is NaN");
                                if (std::isinf(v))
                                    refuse(body.line(), "vertex " + std::to_string(i) + ": coordinate is infinite");
                                if (std::fabs(v) > 1e150)
                                    refuse(body.line(), "vertex " + std::to_string(i) +
                                                            ": coordinate too large: lengths would overflow");
                                soup.xyz[3 * i + static_cast<std::size_t>(c)] = v;
                            }
                    continue;
                }
                const double n = body.value(p.count_type);
                if (n < 0) refuse(body.line(), e.name + " " + std::to_string(i) + ": negative list length");
                const bool indices = &e == face && static_cast<int>(k) == index_slot;
                if (indices) {
                    if (n < 3)
                        refuse(body.line(), "face " + std::to_string(i) + " has " +
                                                std::to_string(static_cast<long long>(n)) +
                                                " vertices (a polygon needs at least 3)");
                    check_triangle(static_cast<std::size_t>(n), i, body.line());
                }
                for (std::size_t j = 0; j < static_cast<std::size_t>(n); ++j) {
                    const double v = body.value(p.type);
                    if (indices)
                        soup.tri.push_back(vertex_index(static_cast<long long>(v), vertex->count, body.line()));
                }
            }
            body.end_record();
        }
    }
    body.finish();
}

std::string lower_extension(const std::string& path) {
    const std::size_t slash = path.find_last_of('/');
    const std::size_t dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string ext = path.substr(dot + 1);
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

}  // namespace

bool read_mesh(const std::string& path, TriangleSoup& soup, std::string& error) {
    soup = {};
    const std::string ext = lower_extension(path);
    void (*reader)(std::string_view, TriangleSoup&) = nullptr;
    if (ext == "off" || ext == "coff")
        reader = read_off;
    else if (ext == "obj")
        reader = read_obj;
    else if (ext == "ply")
        reader = read_ply;
    else {
        error = path + ": unknown format (cgal_uv reads .off, .obj and .ply)";
        return false;
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        error = path + ": cannot open: " + std::strerror(errno);
        return false;
    }
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) {
        error = path + ": cannot read: " + std::strerror(errno);
        return false;
    }
    if (text.empty()) {
        error = path + ": empty file";
        return false;
    }
    try {
        reader(text, soup);
    } catch (const Refusal& r) {
        error = path + (r.line ? ":" + std::to_string(r.line) : std::string()) + ": " + r.what;
        soup = {};
        return false;
    }
    return true;
}

}  // namespace cgal_uv
