// FHR core (beyond the paper) — the result of a step that may fail for a reason of the data, not a
// bug: a value, or one line saying why there is none. A strategy that can fail (the direct start of
// keeping the domain, replaying a domain's collapses) returns one, and its caller decides what to
// do next; exceptions stay for errors (core/errors.hpp). C++20 has no std::expected.
#pragma once

#include <optional>
#include <string>
#include <utility>

#include <fhr/core/errors.hpp>

namespace fhr {

template <class T>
class Outcome {
public:
    Outcome(T value) : value_(std::move(value)) {}  // NOLINT: a value converts to its outcome
    static Outcome failure(std::string why) { return Outcome(std::move(why), 0); }

    bool ok() const { return value_.has_value(); }
    explicit operator bool() const { return ok(); }
    /// Why there is no value (empty when there is one).
    const std::string& why() const { return why_; }
    /// \throws InternalError naming why there is none when !ok(): the caller promised a value.
    T& value() & {
        if (!ok()) throw InternalError("no value: " + why_);
        return *value_;
    }
    T&& value() && {
        if (!ok()) throw InternalError("no value: " + why_);
        return std::move(*value_);
    }
    T* operator->() { return &value(); }
    T& operator*() & { return value(); }

private:
    Outcome(std::string why, int) : why_(std::move(why)) {}
    std::optional<T> value_;
    std::string why_;
};

}  // namespace fhr
