// FHR io — numbers as text in the shortest form that reads back to the same value (spec/formats.md
// FMT-WRITE-2): shared by every text writer (OFF, OBJ, JSON, fhr-param).
#pragma once

#include <charconv>
#include <string>

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

}  // namespace fhr::io
