// FHR io — minimal JSON writer (see json.hpp).
#include <fhr/io/detail/json.hpp>

#include <cmath>

#include <fhr/io/detail/number_text.hpp>

namespace fhr::io {

void JsonWriter::newline() {
    out_ += '\n';
    out_.append(static_cast<std::size_t>(2 * depth_), ' ');
}

void JsonWriter::element_start() {
    if (after_key_) {
        after_key_ = false;
        return;
    }
    if (!first_) out_ += ',';
    if (depth_ > 0) newline();
    first_ = false;
}

JsonWriter& JsonWriter::begin_object() {
    element_start();
    out_ += '{';
    ++depth_;
    first_ = true;
    return *this;
}

JsonWriter& JsonWriter::end_object() {
    --depth_;
    if (!first_) newline();
    out_ += '}';
    first_ = false;
    return *this;
}

JsonWriter& JsonWriter::begin_array() {
    element_start();
    out_ += '[';
    ++depth_;
    first_ = true;
    return *this;
}

JsonWriter& JsonWriter::end_array() {
    --depth_;
    if (!first_) newline();
    out_ += ']';
    first_ = false;
    return *this;
}

JsonWriter& JsonWriter::key(std::string_view k) {
    element_start();
    write_string(k);
    out_ += ": ";
    after_key_ = true;
    return *this;
}

JsonWriter& JsonWriter::value(std::string_view s) {
    element_start();
    write_string(s);
    return *this;
}

void JsonWriter::write_string(std::string_view s) {
    out_ += '"';
    for (unsigned char c : s) {
        switch (c) {
            case '"': out_ += "\\\""; break;
            case '\\': out_ += "\\\\"; break;
            case '\n': out_ += "\\n"; break;
            case '\r': out_ += "\\r"; break;
            case '\t': out_ += "\\t"; break;
            default:
                if (c < 0x20) {
                    static const char* hex = "0123456789abcdef";
                    out_ += "\\u00";
                    out_ += hex[c >> 4];
                    out_ += hex[c & 15];
                } else {
                    out_ += static_cast<char>(c);
                }
        }
    }
    out_ += '"';
}

JsonWriter& JsonWriter::raw(std::string_view json) {
    element_start();
    out_ += json;
    return *this;
}

JsonWriter& JsonWriter::value(double x) {
    if (!std::isfinite(x)) return null();
    element_start();
    append_number(out_, x);
    return *this;
}

JsonWriter& JsonWriter::signed_value(std::int64_t x) {
    element_start();
    append_number(out_, x);
    return *this;
}

JsonWriter& JsonWriter::unsigned_value(std::uint64_t x) {
    element_start();
    append_number(out_, x);
    return *this;
}

JsonWriter& JsonWriter::value(bool b) {
    element_start();
    out_ += b ? "true" : "false";
    return *this;
}

JsonWriter& JsonWriter::null() {
    element_start();
    out_ += "null";
    return *this;
}

}  // namespace fhr::io
