// FHR core — the one form of parallelism fhr uses: independent tasks (one geodesic per domain
// edge, one patch per domain face) spread over the hardware threads. Each task writes only its
// own result slot, so the output is bit-identical to a single-threaded run (CLI-RUN-4).
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace fhr {

/// Calls task(i) for every i in [0, n), on up to std::thread::hardware_concurrency() threads
/// (one more thread per `grain` tasks). The first exception thrown by a task is rethrown here
/// after all threads have stopped.
template <class Task>
void parallel_for(std::size_t n, std::size_t grain, Task&& task) {
    std::atomic<std::size_t> next{0};
    std::exception_ptr error;
    std::mutex error_lock;
    auto work = [&] {
        for (std::size_t i; (i = next++) < n;) {
            try {
                task(i);
            } catch (...) {
                const std::lock_guard<std::mutex> lock(error_lock);
                if (!error) error = std::current_exception();
            }
        }
    };
    const std::size_t cores = std::max(1u, std::thread::hardware_concurrency());
    const std::size_t helpers = std::min(cores, n / std::max<std::size_t>(grain, 1) + 1) - 1;
    std::vector<std::thread> threads;
    for (std::size_t t = 0; t < helpers; ++t) threads.emplace_back(work);
    work();
    for (std::thread& t : threads) t.join();
    if (error) std::rethrow_exception(error);
}

}  // namespace fhr
