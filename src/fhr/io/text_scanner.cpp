// FHR io — shared reader machinery: the text scanner and the number, coordinate, index and size
// checks of spec/formats.md (FMT-NUM-*, FMT-IDX-1, FMT-POLY-1, FMT-SIZE-*). Every reader goes
// through these, so each refusal is decided and worded in exactly one place.
#include <fhr/io/detail/text_scanner.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>

namespace fhr::io::detail {

std::string Where::str() const {
    std::string s(element);
    if (index != no_index) {
        s += ' ';
        s += std::to_string(index);
    }
    return s;
}

std::string quoted(std::string_view token) {
    constexpr std::size_t max_shown = 40;
    std::string s = "'";
    for (std::size_t i = 0; i < token.size() && i < max_shown; ++i) {
        const auto c = static_cast<unsigned char>(token[i]);
        if (c >= 0x20 && c < 0x7f) {
            s += static_cast<char>(c);
        } else {
            constexpr char hex[] = "0123456789abcdef";
            s += "\\x";
            s += hex[c >> 4];
            s += hex[c & 15];
        }
    }
    if (token.size() > max_shown) s += "...";
    return s + "'";
}

namespace {

/// The common short decimals `[-]digits[.digits]` with at most 19 digits: the digits as an
/// integer m and the number k ≤ 19 of fraction digits give m / 10^k. When m ≤ 2^53 both are
/// exact doubles (10^k is exact up to k = 22), and IEEE division rounds their quotient correctly, so the result equals
/// std::from_chars' (Clinger 1990, "How to read floating point numbers accurately", fast path).
/// Returns false for anything else, which then goes to std::from_chars.
bool parse_short_decimal(std::string_view token, double& out) {
    static constexpr double powers_of_ten[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,
                                               1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19};
    const bool negative = !token.empty() && token[0] == '-';
    if (negative) token.remove_prefix(1);
    std::uint64_t m = 0;
    int digits = 0, fraction_digits = -1;  // -1: no decimal point yet
    for (const char c : token) {
        if (c == '.' && fraction_digits < 0) {
            fraction_digits = 0;
            continue;
        }
        const unsigned digit = static_cast<unsigned char>(c) - static_cast<unsigned>('0');
        if (digit > 9 || ++digits > 19) return false;
        m = 10 * m + digit;
        if (fraction_digits >= 0) ++fraction_digits;
    }
    if (digits == 0 || m > (std::uint64_t{1} << 53)) return false;
    const double v = static_cast<double>(m) / powers_of_ten[fraction_digits < 0 ? 0 : fraction_digits];
    out = negative ? -v : v;
    return true;
}

/// nullptr when `v` may be a coordinate, otherwise what is wrong with it.
const char* coordinate_problem(double v) {
    if (std::isnan(v)) return "coordinate is NaN";
    if (std::isinf(v)) return "coordinate is infinite";
    // FMT-NUM-3: squared edge lengths must stay finite: (2e150)^2 · 3 < DBL_MAX ≈ 1.8e308.
    if (std::fabs(v) > max_coordinate) return "coordinate too large: lengths would overflow (|x| > 1e150)";
    return nullptr;
}

std::string index_range(std::uint64_t size) {
    return size == 0 ? std::string("(there are no vertices)") : "(0.." + std::to_string(size - 1) + ")";
}

}  // namespace

NumberStatus parse_double(std::string_view token, double& out) {
    if (token.size() > 1 && token[0] == '+' && token[1] != '-' && token[1] != '+') token.remove_prefix(1);
    if (parse_short_decimal(token, out)) return NumberStatus::ok;
    const char* end = token.data() + token.size();
    const auto [ptr, ec] = std::from_chars(token.data(), end, out);
    if (ec == std::errc::result_out_of_range && ptr == end) return NumberStatus::out_of_range;
    if (ec != std::errc() || ptr != end || token.empty()) return NumberStatus::not_a_number;
    return NumberStatus::ok;
}

void PrintedDigits::add(std::string_view token, double value) {
    any_ = true;
    max_abs_ = std::max(max_abs_, std::fabs(value));
    const std::size_t e = token.find_first_of("eE");
    const std::string_view mantissa = token.substr(0, e);
    const std::size_t dot = mantissa.find('.');
    const int decimals = dot == std::string_view::npos ? -1 : static_cast<int>(mantissa.size() - dot - 1);
    if (e != std::string_view::npos || decimals < 0 || (decimals_ >= 0 && decimals != decimals_)) fixed_ = false;
    decimals_ = std::max(decimals_, decimals);
    int digits = 0;  // significant: from the first non-zero digit on
    for (const char c : mantissa)
        if (c >= '0' && c <= '9' && (digits > 0 || c != '0')) ++digits;
    significant_ = std::max(significant_, digits);
}

double PrintedDigits::rounding() const {
    if (!any_) return 0;
    // A writer that prints at most 8 significant digits may have held its numbers in float32
    // (MeshLab does): half a float32 ulp of the largest number is added to the printing's rounding.
    const double float32 = significant_ <= 8 ? max_abs_ * 0x1p-24 : 0.0;
    if (fixed_) return 0.5 * std::pow(10.0, -decimals_) + float32;
    if (max_abs_ == 0) return 0;
    const double place = std::floor(std::log10(max_abs_)) - std::max(significant_, 1) + 1;
    return 0.5 * std::pow(10.0, std::max(place, -400.0)) + float32;
}

void check_point(const Vec3& p, const std::string& name, std::uint64_t line, Where where) {
    for (int c = 0; c < 3; ++c)
        if (const char* problem = coordinate_problem(p[c])) fail(name, line, where, problem);
}

void check_input_size(std::string_view bytes, const std::string& name) {
    if (bytes.empty()) fail(name, 0, {}, "empty file");
    if (bytes.size() > std::numeric_limits<std::uint32_t>::max())
        fail(name, 0, {}, "file too large (" + std::to_string(bytes.size()) + " bytes; at most 4 GiB - 1)");
}

std::uint64_t add_min_bytes(std::uint64_t total, std::uint64_t count, std::uint64_t bytes_each) {
    constexpr auto max = std::numeric_limits<std::uint64_t>::max();
    if (bytes_each != 0 && count > (max - total) / bytes_each) return max;
    return total + count * bytes_each;
}

void fail(const std::string& name, std::uint64_t line, Where where, std::string_view problem) {
    std::string what = where.element.empty() ? std::string() : where.str() + ": ";
    throw InvalidInput(name, line, what.append(problem));
}

void fail_index(std::int64_t value, std::uint64_t size, const std::string& name, std::uint64_t line, Where where) {
    if (value < 0) fail(name, line, where, "negative index " + std::to_string(value));
    fail(name, line, where, "index " + std::to_string(value) + " out of range " + index_range(size));
}

void check_polygon_size(std::uint64_t n, const std::string& name, std::uint64_t line, Where where) {
    if (n < 3) fail(name, line, where, "has " + std::to_string(n) + " vertices (a polygon needs at least 3)");
}

// ---- TextScanner -------------------------------------------------------------------------------

TextScanner::TextScanner(std::string_view bytes, const std::string& name, char comment)
    : bytes_(bytes), name_(name), comment_(comment) {}

bool TextScanner::next_line() {
    while (next_ < bytes_.size()) {
        const char* begin = bytes_.data() + next_;
        const std::size_t left = bytes_.size() - next_;
        const void* nl = std::memchr(begin, '\n', left);
        const std::size_t length = nl ? static_cast<std::size_t>(static_cast<const char*>(nl) - begin) : left;
        next_ += nl ? length + 1 : length;
        ++line_;
        text_ = std::string_view(begin, length);
        if (comment_ != '\0') {
            const std::size_t c = text_.find(comment_);
            if (c != std::string_view::npos) text_ = text_.substr(0, c);
        }
        pos_ = 0;
        if (has_token()) return true;
    }
    text_ = {};
    pos_ = 0;
    return false;
}

double TextScanner::real(Where where) {
    const std::string_view t = token(where, "a number");
    double v = 0;
    if (const NumberStatus s = parse_double(t, v); s != NumberStatus::ok) fail_number(where, t, s);
    return v;
}

double TextScanner::real(Where where, PrintedDigits& digits) {
    const std::string_view t = token(where, "a number");
    double v = 0;
    if (const NumberStatus s = parse_double(t, v); s != NumberStatus::ok) fail_number(where, t, s);
    digits.add(t, v);
    return v;
}

std::int64_t TextScanner::integer(Where where) {
    const std::string_view t = token(where, "an integer");
    std::int64_t v = 0;
    if (const NumberStatus s = parse_int64(t, v); s != NumberStatus::ok) fail_number(where, t, s, "64-bit integer");
    return v;
}

std::uint64_t TextScanner::count(Where where) {
    const std::int64_t v = integer(where);
    if (v < 0) fail(where, "negative count " + std::to_string(v));
    return static_cast<std::uint64_t>(v);
}

std::uint32_t TextScanner::index(Where where, std::uint64_t size) {
    const std::string_view t = token(where, "a vertex index");
    std::int64_t v = 0;
    const NumberStatus status = parse_int64(t, v);
    if (status == NumberStatus::not_a_number) fail(where, "expected a vertex index, found " + quoted(t));
    if (status == NumberStatus::out_of_range) {  // beyond 64 bits
        if (t[0] == '-') fail(where, "negative index " + quoted(t));
        fail(where, "index " + quoted(t) + " out of range " + index_range(size));
    }
    return checked_index(v, size, name_, line_, where);
}

Vec3 TextScanner::point(Where where, PrintedDigits* digits) {
    Vec3 p;
    for (int k = 0; k < 3; ++k) p[k] = digits ? real(where, *digits) : real(where);
    check_point(p, name_, line_, where);
    return p;
}

void TextScanner::expect_end_of_line(Where where) {
    if (const std::string_view t = token(); !t.empty()) fail(where, "unexpected " + quoted(t) + " at end of line");
}

void TextScanner::fail(Where where, std::string_view problem) const { detail::fail(name_, line_, where, problem); }

void TextScanner::fail_number(Where where, std::string_view token, NumberStatus status, std::string_view range) const {
    if (status == NumberStatus::out_of_range)
        fail(where, "number " + quoted(token) + " is out of " + std::string(range) + " range");
    fail(where, "expected a number, found " + quoted(token));
}

}  // namespace fhr::io::detail
