// FHR core (beyond the paper) — the one clock of the stage timers (timings.json, spec/cli.md
// CLI-RUN-3): wall seconds on std::chrono::steady_clock. Internal: never installed.
#pragma once

#include <chrono>

namespace fhr::detail {

using Clock = std::chrono::steady_clock;

/// Seconds from `start` to now.
inline double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace fhr::detail
