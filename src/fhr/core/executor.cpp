// FHR core — the default executor (core/executor.hpp): threads started per call, tasks handed out
// in index order through one atomic counter.
#include <fhr/core/executor.hpp>

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace fhr {

void ThreadsPerCall::for_each(std::size_t n, std::size_t grain, const std::function<void(std::size_t)>& task) {
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
    const std::size_t threads = threads_ != 0 ? threads_ : std::max(1u, std::thread::hardware_concurrency());
    const std::size_t helpers = std::min(threads, n / std::max<std::size_t>(grain, 1) + 1) - 1;
    std::vector<std::thread> started;
    for (std::size_t t = 0; t < helpers; ++t) started.emplace_back(work);
    work();
    for (std::thread& t : started) t.join();
    if (error) std::rethrow_exception(error);
}

Executor& default_executor() {
    static ThreadsPerCall all_hardware_threads;  // stateless: shared by every caller
    return all_hardware_threads;
}

}  // namespace fhr
