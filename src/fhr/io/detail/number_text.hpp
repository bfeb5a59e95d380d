// FHR io — numbers as text in the shortest form that reads back to the same value (spec/formats.md
// FMT-WRITE-2): shared by every text writer (OFF, OBJ, JSON, fhr-param).
#pragma once

#include <array>
#include <bit>
#include <charconv>
#include <cstdint>
#include <string>
#include <vector>

#include <fhr/core/polygon_soup.hpp>

namespace fhr::io {

/// Appends x (an integer or a double) in its shortest round-trip decimal form.
template <class T>
void append_number(std::string& out, T x) {
    char buffer[32];
    const auto r = std::to_chars(buffer, buffer + sizeof buffer, x);
    out.append(buffer, r.ptr);
}

/// Appends `x y z` of one point and a newline.
inline void append_point(std::string& out, const Vec3& p) {
    for (int c = 0; c < 3; ++c) {
        append_number(out, p[c]);
        out += c < 2 ? ' ' : '\n';
    }
}

/// Appends N doubles separated by single spaces, each as append_number writes it. A tuple whose
/// bits came recently (a table of 4,096 tuples, placed by a hash of the bits) is copied from the
/// text made then instead of formatted again: the same bytes (a vertex's β in its patch,
/// and its place in the atlas, are written once per face around it, six times on average:
/// formatting the horse's param.fhrp 120 → 86–102 ms, the 10⁶ mesh's 1.04 → 0.71 s).
template <std::size_t N>
class RecentNumbers {
public:
    void append(std::string& out, const std::array<double, N>& x) {
        std::array<std::uint64_t, N> bits;
        std::uint64_t hash = 0;
        for (std::size_t i = 0; i < N; ++i) {
            bits[i] = std::bit_cast<std::uint64_t>(x[i]);
            hash = (hash ^ bits[i]) * 0x9e3779b97f4a7c15u;
        }
        Entry& e = table_[hash >> 52];  // the top 12 bits
        if (e.length == 0 || e.bits != bits) {
            char* at = e.text;
            for (std::size_t i = 0; i < N; ++i) {
                if (i > 0) *at++ = ' ';
                at = std::to_chars(at, e.text + sizeof e.text, x[i]).ptr;
            }
            e.bits = bits;
            e.length = static_cast<std::uint8_t>(at - e.text);
        }
        out.append(e.text, e.length);
    }

private:
    struct Entry {
        std::array<std::uint64_t, N> bits{};
        std::uint8_t length = 0;  // 0: empty (a number has at least one character)
        char text[25 * N];        // a shortest double has at most 24 characters
    };
    std::vector<Entry> table_ = std::vector<Entry>(4096);
};

}  // namespace fhr::io
