// FHR core (beyond the paper) — where fhr runs its independent tasks: one geodesic per domain edge
// (§3), one patch map per domain face (§4), one reconstruction per kept percentage (§5). Each task
// writes only its own result slot, so every result is bit-identical whatever runs the tasks, on
// how many threads (CLI-RUN-4, spec/library.md LIB-3). A caller that owns threads (a pool, a
// scheduler) passes its own Executor in the options; without one, fhr uses one ThreadPool shared
// by the process, started on first use.
//
// Why a pool: a run calls for_each dozens of times (every recovery round of §3, every
// level of §5), many of them on a few milliseconds of work; starting and joining threads on every
// call cost more than some of those calls' tasks. The pool's workers wait between calls.
#pragma once

#include <algorithm>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace fhr {

class Executor {
public:
    virtual ~Executor() = default;
    /// Calls task(i) exactly once for every i in [0, n), possibly concurrently, and returns when
    /// all calls have finished. When tasks throw, the exception of the lowest index is rethrown
    /// here after all calls have finished (the same one on any number of threads). `grain`: how
    /// many tasks make one more thread worthwhile (a hint).
    virtual void for_each(std::size_t n, std::size_t grain, const std::function<void(std::size_t)>& task) = 0;
};

/// `threads` − 1 worker threads, started by the constructor and joined by the destructor; the
/// thread calling for_each works as the last one. Any number of threads may call for_each at once,
/// and a task may itself call for_each on the same pool (the caller always works on its own
/// call's tasks, so every call finishes even when no worker is free). A caller whose indices are
/// used up helps with other posted calls while it waits for its helpers.
class ThreadPool final : public Executor {
public:
    /// threads = 0: std::thread::hardware_concurrency() (at least 1). 1: every task on the caller.
    explicit ThreadPool(unsigned threads = 0);
    ~ThreadPool() override;
    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    void for_each(std::size_t n, std::size_t grain, const std::function<void(std::size_t)>& task) override;
    /// The threads that work on one call: the workers and the caller.
    unsigned threads() const { return static_cast<unsigned>(workers_.size()) + 1; }

private:
    struct Call;
    void work();
    /// Joins the first posted call as a helper until its indices are used up. \pre lock_ held
    /// (released while working), calls_ not empty.
    void help(std::unique_lock<std::mutex>& hold);

    std::mutex lock_;
    std::condition_variable wake_;  // a call was posted, or the pool stops
    std::deque<Call*> calls_;       // calls with helper places left
    bool stopping_ = false;
    std::vector<std::thread> workers_;
};

/// The executor of options that name none: one ThreadPool on all hardware threads for the process.
Executor& default_executor();

/// `executor` when it is given, else default_executor().
inline Executor& executor_or_default(Executor* executor) { return executor ? *executor : default_executor(); }

/// [0, n) in consecutive blocks of `block` indices (the last may be shorter), one task each on
/// `executor`: range(first, end) for each block. \pre block > 0.
inline void for_each_block(Executor& executor, std::size_t n, std::size_t block, std::size_t grain,
                           const std::function<void(std::size_t, std::size_t)>& range) {
    executor.for_each((n + block - 1) / block, grain,
                      [&](std::size_t b) { range(b * block, std::min(n, (b + 1) * block)); });
}

}  // namespace fhr
