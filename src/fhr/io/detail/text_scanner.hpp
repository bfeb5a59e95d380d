// FHR io — the machinery shared by every strict reader (spec/formats.md): a line/token scanner
// for the text formats (OFF, OBJ, PLY ascii, STL ascii) and the checks every format applies to
// sizes, counts and coordinates (FMT-SIZE-1, FMT-NUM-*). Internal to src/fhr/io.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>

#include <fhr/core/errors.hpp>
#include <fhr/core/polygon_soup.hpp>

namespace fhr::io::detail {

/// Names the element a value belongs to in messages: `vertex 5`, `face 17`, `header`.
/// Built lazily (only when a message is composed), so it costs nothing on the happy path.
struct Where {
    static constexpr std::uint64_t no_index = std::numeric_limits<std::uint64_t>::max();
    std::string_view element;
    std::uint64_t index = no_index;
    std::string str() const;
};

/// `'token'` for messages: at most 40 characters, non-printable bytes escaped as \xHH.
std::string quoted(std::string_view token);

enum class NumberStatus { ok, not_a_number, out_of_range };

/// FMT-NUM-1: the whole token must be the number. A leading '+' is accepted (text mesh files do
/// write "+1.5"; std::from_chars refuses it).
NumberStatus parse_double(std::string_view token, double& out);

/// How far the numbers of a text file may lie from the values their writer meant (spec/atlas.md
/// ATLAS-8), from the digits it printed. A fixed-point writer (every number with a decimal point,
/// no exponent, the same number d of decimals: `%.6f`) rounds by half a unit in the d-th decimal.
/// Any other writer (`%g`, `%e`, shortest round-trip) drops trailing zeros, so a number's own digits
/// understate its precision: it rounds by half a unit in the P-th significant digit, P the most
/// significant digits of any number in the file (`%g`: 6; shortest round-trip: up to 17). A writer
/// of at most 8 significant digits may have held float32 values: half a float32 ulp of the largest
/// number is added.
class PrintedDigits {
public:
    /// One number as written. \pre parse_double(token) gave `value`.
    void add(std::string_view token, double value);
    /// The largest rounding of any number added (0 when none was).
    double rounding() const;

private:
    bool any_ = false, fixed_ = true;
    int decimals_ = -1, significant_ = 0;
    double max_abs_ = 0;
};

/// FMT-NUM-1: `[+-]digits`, exactly; out_of_range beyond int64. A plain digit loop: readers
/// parse hundreds of thousands of indices, and this is several times cheaper than the general
/// std::from_chars (the tests check that both agree).
inline NumberStatus parse_int64(std::string_view token, std::int64_t& out) {
    const bool negative = !token.empty() && token[0] == '-';
    if (!token.empty() && (token[0] == '-' || token[0] == '+')) token.remove_prefix(1);
    if (token.empty()) return NumberStatus::not_a_number;
    std::uint64_t v = 0;  // wraps for more than 19 significant digits, which are refused below
    for (const char c : token) {
        const unsigned digit = static_cast<unsigned char>(c) - static_cast<unsigned>('0');
        if (digit > 9) return NumberStatus::not_a_number;
        v = 10 * v + digit;
    }
    const std::size_t leading_zeros = std::min(token.find_first_not_of('0'), token.size());
    const std::uint64_t limit = (std::uint64_t{1} << 63) - (negative ? 0 : 1);  // |INT64_MIN| or INT64_MAX
    if (token.size() - leading_zeros > 19 || v > limit) return NumberStatus::out_of_range;
    out = negative ? static_cast<std::int64_t>(0 - v) : static_cast<std::int64_t>(v);
    return NumberStatus::ok;
}

/// FMT-NUM-2/3: fails (naming `where` and `line`) unless every coordinate of `p` is finite and
/// at most max_coordinate in magnitude, so that squared lengths cannot overflow.
void check_point(const Vec3& p, const std::string& name, std::uint64_t line, Where where);

/// FMT-SIZE-0: refuses empty inputs and inputs of 4 GiB or more (so that every index count fits
/// the soup's 32-bit offsets). Called first by every parse_*.
void check_input_size(std::string_view bytes, const std::string& name);

/// FMT-SIZE-1: refuses a declared count that the remaining bytes cannot hold, before anything is
/// reserved. `need` is the total minimum number of bytes, computed by the caller with
/// add_min_bytes (saturating, so absurd counts never overflow).
std::uint64_t add_min_bytes(std::uint64_t total, std::uint64_t count, std::uint64_t bytes_each);

/// Throws InvalidInput(name, line, problem): the one way readers report errors.
[[noreturn]] void fail(const std::string& name, std::uint64_t line, Where where, std::string_view problem);

/// A line-oriented scanner over a text file held in memory. `next_line()` moves to the next line
/// that holds a token (blank lines and comment-only lines are skipped; "\r\n" and "\n" both end a
/// line; everything from `comment` to the end of the line is ignored unless `comment` is '\0').
/// Tokens are separated by blanks (space, tab, \r, \v, \f). Every error names the current line.
class TextScanner {
public:
    TextScanner(std::string_view bytes, const std::string& name, char comment = '#');

    /// Moves to the next line with a token; false at the end of the input.
    bool next_line();
    /// 1-based number of the current line (0 before the first next_line()).
    std::uint64_t line() const { return line_; }
    /// The bytes after the current line (what a binary body starts with).
    std::string_view rest() const { return bytes_.substr(next_); }

    bool has_token() const {
        std::size_t p = pos_;
        while (p < text_.size() && is_blank(text_[p])) ++p;
        return p < text_.size();
    }
    /// The next token of the current line, or "" when the line has no more.
    std::string_view token() {
        while (pos_ < text_.size() && is_blank(text_[pos_])) ++pos_;
        const std::size_t begin = pos_;
        while (pos_ < text_.size() && !is_blank(text_[pos_])) ++pos_;
        return text_.substr(begin, pos_ - begin);
    }
    /// The next token; fails with "expected <what>" at the end of the line.
    std::string_view token(Where where, std::string_view what) {
        const std::string_view t = token();
        if (t.empty()) fail(where, "expected " + std::string(what) + ", found end of line");
        return t;
    }

    double real(Where where);
    /// real(), and the number added to `digits`.
    double real(Where where, PrintedDigits& digits);
    std::int64_t integer(Where where);
    /// A non-negative integer (a count).
    std::uint64_t count(Where where);
    /// A 0-based index into `size` points (OFF, PLY ascii).
    std::uint32_t index(Where where, std::uint64_t size);
    /// Three coordinates that pass check_point(); with `digits`, added to them.
    Vec3 point(Where where, PrintedDigits* digits = nullptr);
    /// Fails when the current line has tokens left.
    void expect_end_of_line(Where where);

    [[noreturn]] void fail(Where where, std::string_view problem) const;
    const std::string& name() const { return name_; }

private:
    /// "expected a number, found 'x'" or "number 'x' is out of range" as fits `status`.
    [[noreturn]] void fail_number(Where where, std::string_view token, NumberStatus status,
                                  std::string_view range = "double") const;
    /// Space, tab, \r, \v, \f separate tokens.
    static bool is_blank(char c) {
        constexpr std::uint64_t blanks = 1ULL << ' ' | 1ULL << '\t' | 1ULL << '\r' | 1ULL << '\v' | 1ULL << '\f';
        const auto u = static_cast<unsigned char>(c);
        return u <= ' ' && ((blanks >> u) & 1) != 0;
    }

    std::string_view bytes_;
    const std::string& name_;
    char comment_;
    std::size_t next_ = 0;    // start of the line after the current one
    std::uint64_t line_ = 0;  // number of the current line
    std::string_view text_;   // current line
    std::size_t pos_ = 0;     // position in text_
};

/// FMT-IDX-1: a 0-based index read from a file, checked against the point count.
/// Negative and out-of-range indices (including values that overflow 64 bits, reported by the
/// caller as out of range) are refused with the element named.
[[noreturn]] void fail_index(std::int64_t value, std::uint64_t size, const std::string& name, std::uint64_t line,
                             Where where);
inline std::uint32_t checked_index(std::int64_t value, std::uint64_t size, const std::string& name, std::uint64_t line,
                                   Where where) {
    if (value < 0 || static_cast<std::uint64_t>(value) >= size) fail_index(value, size, name, line, where);
    return static_cast<std::uint32_t>(value);
}

/// FMT-POLY-1: polygons with fewer than 3 vertices are refused by every reader.
void check_polygon_size(std::uint64_t n, const std::string& name, std::uint64_t line, Where where);

}  // namespace fhr::io::detail
