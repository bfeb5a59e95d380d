// FHR core (beyond the paper) — where fhr runs its independent tasks: one geodesic per domain edge
// (§3), one patch map per domain face (§4), one reconstruction per kept percentage (§5). Each task
// writes only its own result slot, so every result is bit-identical whatever runs the tasks, on
// how many threads (CLI-RUN-4, spec/library.md LIB-3). A caller that owns threads (a pool, a
// scheduler) passes its own Executor in the options; without one, fhr uses ThreadsPerCall.
#pragma once

#include <cstddef>
#include <functional>

namespace fhr {

class Executor {
public:
    virtual ~Executor() = default;
    /// Calls task(i) exactly once for every i in [0, n), possibly concurrently, and returns when
    /// all calls have finished. When tasks throw, the first exception is rethrown here after all
    /// calls have finished. `grain`: how many tasks make one more thread worthwhile (a hint).
    virtual void for_each(std::size_t n, std::size_t grain, const std::function<void(std::size_t)>& task) = 0;
};

/// Starts up to `threads` threads for each for_each (the caller's being one of them) and joins them
/// before returning; 0 means std::thread::hardware_concurrency(). Holds no other state: one object
/// may serve any number of callers at once.
class ThreadsPerCall final : public Executor {
public:
    explicit ThreadsPerCall(unsigned threads = 0) : threads_(threads) {}
    void for_each(std::size_t n, std::size_t grain, const std::function<void(std::size_t)>& task) override;

private:
    unsigned threads_;
};

/// The executor of options that name none: a ThreadsPerCall on all hardware threads.
Executor& default_executor();

/// `executor` when it is given, else default_executor().
inline Executor& executor_or_default(Executor* executor) { return executor ? *executor : default_executor(); }

}  // namespace fhr
