// FHR core (beyond the paper) — checked preconditions. A documented `\pre` that is cheap to test
// is written FHR_DCHECK(condition) at the top of the function. In builds with dchecks (meson
// option `dchecks`: on by default in debug builds and in builds with the tests, such as ./run's)
// a false condition throws ContractViolation (a std::logic_error) naming the condition, the file and the line: the
// caller broke the contract (spec/library.md LIB-2). Without dchecks the condition is not even
// evaluated: release builds pay nothing.
#pragma once

#include <string>

#include <fhr/core/errors.hpp>

namespace fhr::detail {

[[noreturn]] inline void dcheck_failed(const char* condition, const char* file, int line) {
    throw ContractViolation(std::string("precondition violated: ") + condition + " (" + file + ":" +
                            std::to_string(line) + ")");
}

}  // namespace fhr::detail

#if defined(FHR_DCHECKS)
#define FHR_DCHECK(condition) \
    ((condition) ? static_cast<void>(0) : ::fhr::detail::dcheck_failed(#condition, __FILE__, __LINE__))
#else
#define FHR_DCHECK(condition) static_cast<void>(sizeof((condition) ? 1 : 0))
#endif
