// Test helper of the io suite: capture the InvalidInput a reader throws, so that a test can check
// both the line and the problem it names (spec/formats.md: every refusal names file, line and
// element).
#pragma once

#include <stdexcept>

#include <catch2/catch.hpp>

#include <fhr/core/errors.hpp>

namespace fhr::test {

/// The fhr::InvalidInput thrown by `f()`. The test fails when nothing is thrown; any other
/// exception propagates and fails it too.
template <class F>
fhr::InvalidInput refusal(F&& f) {
    try {
        f();
    } catch (const fhr::InvalidInput& e) {
        return e;
    }
    FAIL("expected fhr::InvalidInput, but nothing was thrown");
    throw std::logic_error("unreachable");
}

}  // namespace fhr::test
