// FHR exchange — reading and writing `fhr-param 1` files (spec/param.md).
//
// Reader (PARAM-1, the grammar): the input is a stream of tokens separated by any whitespace,
// `#` starting a comment to the end of the line. It reads
//   fhr-param 1
//   domain_vertices N   N × (x y z)
//   domain_faces M      M × (i j k)
//   surface_vertices P  P × (x y z)
//   surface_faces Q     Q × (a b c d  β_a0 β_a1 β_a2  β_b0 β_b1 β_b2  β_c0 β_c1 β_c2)
// and nothing after. Each count is checked against the bytes left before anything is reserved
// (a record of k tokens needs at least 2k bytes: k one-character tokens and k separators), so a
// forged count cannot make it allocate more than the file size justifies (CLI-ERR-1). Numbers
// follow the rules of every fhr reader (src/fhr/io/detail/text_scanner.hpp, FMT-NUM-1); what they mean
// (finite, in range) is checked by the oracle, PARAM-2.
//
// Writer: shortest round-trip decimals (std::to_chars), so read(write(p)) is bit-identical, and
// one fixed layout, so equal files give equal bytes; written atomically (FMT-WRITE-1), in parts formatted at once on the executor's threads
// (io::FileParts).
#include <fhr/exchange/fhr_param.hpp>

#include <limits>

#include <fhr/io/detail/atomic_file.hpp>
#include <fhr/io/detail/number_text.hpp>
#include <fhr/io/detail/text_scanner.hpp>
#include <fhr/io/read.hpp>

namespace fhr::exchange {

namespace {

using io::detail::Where;

/// A whitespace-separated token stream over the whole input that knows the line of each token.
class Tokens {
public:
    Tokens(std::string_view bytes, const std::string& name) : bytes_(bytes), name_(name) {}

    /// The next token, or "" at the end of the input. Messages then name the token's line (at
    /// the end of the input: the line of the last token).
    std::string_view next() {
        while (pos_ < bytes_.size()) {
            const char c = bytes_[pos_];
            if (c == '\n') {
                ++line_;
                ++pos_;
            } else if (c == '#') {
                const std::size_t nl = bytes_.find('\n', pos_);
                pos_ = nl == std::string_view::npos ? bytes_.size() : nl;
            } else if (is_blank(c)) {
                ++pos_;
            } else {
                break;
            }
        }
        const std::size_t begin = pos_;
        if (begin < bytes_.size()) token_line_ = line_;
        while (pos_ < bytes_.size() && !is_blank(bytes_[pos_]) && bytes_[pos_] != '\n' && bytes_[pos_] != '#') ++pos_;
        return bytes_.substr(begin, pos_ - begin);
    }

    /// The next token; fails naming `what` at the end of the input.
    std::string_view next(Where where, std::string_view what) {
        const std::string_view t = next();
        if (t.empty()) fail(where, "unexpected end of file: expected " + std::string(what));
        return t;
    }

    double real(Where where) {
        const std::string_view t = next(where, "a number");
        double v = 0;
        const io::detail::NumberStatus s = io::detail::parse_double(t, v);
        if (s == io::detail::NumberStatus::out_of_range)
            fail(where, "number " + io::detail::quoted(t) + " is out of double range");
        if (s != io::detail::NumberStatus::ok) fail(where, "expected a number, found " + io::detail::quoted(t));
        return v;
    }

    /// An integer in [0, 2^32): a count or an index (PARAM-1: every index fits 32 bits).
    std::uint32_t unsigned32(Where where, std::string_view what) {
        const std::string_view t = next(where, what);
        std::int64_t v = 0;
        const io::detail::NumberStatus s = io::detail::parse_int64(t, v);
        if (s == io::detail::NumberStatus::not_a_number)
            fail(where, "expected " + std::string(what) + ", found " + io::detail::quoted(t));
        if (s == io::detail::NumberStatus::out_of_range || v < 0 || v > std::numeric_limits<std::uint32_t>::max())
            fail(where, std::string(what) + " " + io::detail::quoted(t) + " is not in [0, 2^32)");
        return static_cast<std::uint32_t>(v);
    }

    void keyword(std::string_view expected) {
        const Where where{};
        const std::string name = io::detail::quoted(expected);
        const std::string_view t = next(where, name);
        if (t != expected) fail(where, "PARAM-1: expected the section " + name + ", found " + io::detail::quoted(t));
    }

    /// PARAM-1: `count` records of `tokens_each` tokens need at least 2·tokens_each bytes each.
    std::uint32_t count(std::string_view section, std::uint64_t tokens_each) {
        const Where where{section};
        const std::uint32_t n = unsigned32(where, "a count");
        const std::uint64_t need = io::detail::add_min_bytes(0, n, 2 * tokens_each);
        const std::uint64_t left = bytes_.size() - pos_ + 1;  // the last record may lack its newline
        if (need > left)
            fail(where, "PARAM-1: the file declares " + std::to_string(n) + " records (at least " +
                            std::to_string(need) + " bytes), but only " + std::to_string(left - 1) +
                            " bytes follow (truncated file?)");
        return n;
    }

    [[noreturn]] void fail(Where where, std::string_view problem) const {
        io::detail::fail(name_, token_line_, where, problem);
    }

private:
    static bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

    std::string_view bytes_;
    const std::string& name_;
    std::size_t pos_ = 0;
    std::uint64_t line_ = 1;        // line of bytes_[pos_]
    std::uint64_t token_line_ = 0;  // line of the last token returned
};

Vec3 read_point(Tokens& in, Where where) {
    Vec3 p;
    for (int c = 0; c < 3; ++c) p[c] = in.real(where);
    return p;
}

void append_section(std::string& out, const char* keyword, std::size_t count) {
    out += keyword;
    out += ' ';
    io::append_number(out, std::uint64_t{count});
    out += '\n';
}

}  // namespace

ParamFile parse_param(std::string_view bytes, const std::string& name) {
    io::detail::check_input_size(bytes, name);
    Tokens in(bytes, name);
    const std::string_view magic = in.next();
    if (magic.empty()) io::detail::fail(name, 0, {}, "PARAM-1: empty file (only blank lines and comments)");
    if (magic != "fhr-param")
        in.fail({"header"}, "PARAM-1: not a fhr-param file: the first token is " + io::detail::quoted(magic) +
                                " (expected 'fhr-param 1')");
    const std::string_view version = in.next({"header"}, "the version '1'");
    if (version != "1")
        in.fail({"header"}, "PARAM-1: unsupported version " + io::detail::quoted(version) + " (expected 1)");

    ParamFile file;
    in.keyword("domain_vertices");
    file.domain_vertices.resize(in.count("domain_vertices", 3));
    for (std::size_t i = 0; i < file.domain_vertices.size(); ++i)
        file.domain_vertices[i] = read_point(in, {"domain vertex", i});

    in.keyword("domain_faces");
    file.domain_faces.resize(in.count("domain_faces", 3));
    for (std::size_t f = 0; f < file.domain_faces.size(); ++f)
        for (auto& v : file.domain_faces[f]) v = in.unsigned32({"domain face", f}, "a vertex index");

    in.keyword("surface_vertices");
    file.surface_vertices.resize(in.count("surface_vertices", 3));
    for (std::size_t i = 0; i < file.surface_vertices.size(); ++i)
        file.surface_vertices[i] = read_point(in, {"surface vertex", i});

    in.keyword("surface_faces");
    file.surface_faces.resize(in.count("surface_faces", 13));
    for (std::size_t f = 0; f < file.surface_faces.size(); ++f) {
        const Where where{"surface face", f};
        ParamFace& face = file.surface_faces[f];
        for (auto& v : face.v) v = in.unsigned32(where, "a vertex index");
        face.patch = in.unsigned32(where, "a domain face index");
        for (Beta& beta : face.beta)
            for (double& x : beta) x = in.real(where);
    }

    if (const std::string_view extra = in.next(); !extra.empty())
        in.fail({}, "PARAM-1: unexpected " + io::detail::quoted(extra) + " after the last surface face");
    return file;
}

ParamFile read_param(const std::string& path) { return parse_param(io::read_bytes(path), path); }

namespace {

/// The parts of `file`'s text (io::FileParts): its four sections, each a heading and its records.
io::FileParts param_parts(const ParamFile& file) {
    auto heading = [](const char* keyword, std::size_t count) {
        std::string out;
        append_section(out, keyword, count);
        return out;
    };
    io::FileParts parts;
    parts.text("fhr-param 1\n" + heading("domain_vertices", file.domain_vertices.size()));
    parts.elements(file.domain_vertices.size(), [&](std::size_t first, std::size_t end, std::string& out) {
        for (std::size_t i = first; i < end; ++i) io::append_point(out, file.domain_vertices[i]);
    });
    parts.text(heading("domain_faces", file.domain_faces.size()));
    parts.elements(file.domain_faces.size(), [&](std::size_t first, std::size_t end, std::string& out) {
        for (std::size_t f = first; f < end; ++f)
            for (int c = 0; c < 3; ++c) {
                io::append_number(out, std::uint64_t{file.domain_faces[f][c]});
                out += c < 2 ? ' ' : '\n';
            }
    });
    parts.text(heading("surface_vertices", file.surface_vertices.size()));
    parts.elements(file.surface_vertices.size(), [&](std::size_t first, std::size_t end, std::string& out) {
        for (std::size_t i = first; i < end; ++i) io::append_point(out, file.surface_vertices[i]);
    });
    parts.text(heading("surface_faces", file.surface_faces.size()));
    parts.elements(file.surface_faces.size(), [&](std::size_t first, std::size_t end, std::string& out) {
        io::RecentNumbers<3> betas;  // a vertex's β in a patch is written with each face around it
        for (std::size_t f = first; f < end; ++f) {
            const ParamFace& face = file.surface_faces[f];
            for (const std::uint32_t v : face.v) {
                io::append_number(out, std::uint64_t{v});
                out += ' ';
            }
            io::append_number(out, std::uint64_t{face.patch});
            for (const Beta& beta : face.beta) {
                out += ' ';
                betas.append(out, beta);
            }
            out += '\n';
        }
    });
    return parts;
}

}  // namespace

std::string format_param(const ParamFile& file) { return param_parts(file).joined(); }

void write_param(const std::string& path, const ParamFile& file, Executor* executor) {
    param_parts(file).write(path, executor);
}

}  // namespace fhr::exchange
