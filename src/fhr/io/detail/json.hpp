// FHR io — a minimal JSON writer for reports (`--json`, report.json). Numbers are written in
// shortest round-trip form, so a reader gets back the exact doubles; non-finite numbers become null.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <type_traits>

namespace fhr::io {

class JsonWriter {
public:
    JsonWriter& begin_object();
    JsonWriter& end_object();
    JsonWriter& begin_array();
    JsonWriter& end_array();
    JsonWriter& key(std::string_view k);
    JsonWriter& value(std::string_view s);
    JsonWriter& value(const char* s) { return value(std::string_view(s)); }
    JsonWriter& value(double x);
    JsonWriter& value(bool b);
    template <class T>
    requires(std::is_integral_v<T> && !std::is_same_v<T, bool>) JsonWriter& value(T x) {
        if constexpr (std::is_signed_v<T>)
            return signed_value(x);
        else
            return unsigned_value(x);
    }
    JsonWriter& null();
    /// A value written elsewhere as JSON text (such as report.json's document), put here as is.
    JsonWriter& raw(std::string_view json);
    /// The document, pretty-printed with two-space indentation and a final newline.
    std::string str() const { return out_ + "\n"; }

private:
    std::string out_;
    int depth_ = 0;
    bool first_ = true;  // no element yet at this depth
    bool after_key_ = false;
    void element_start();
    void newline();
    void write_string(std::string_view s);
    JsonWriter& signed_value(std::int64_t x);
    JsonWriter& unsigned_value(std::uint64_t x);
};

}  // namespace fhr::io
