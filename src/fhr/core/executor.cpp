// FHR core — the thread pool (core/executor.hpp): a call is posted with the number of helpers
// worth having (n / grain, at most the workers); the caller and the helpers that take it hand out
// the indices through one atomic counter; the call returns when its indices are used up and every
// helper that joined has left. Exceptions are kept per call with their index: the lowest index
// wins, so the error a caller sees does not depend on which thread ran what.
#include <fhr/core/executor.hpp>

#include <algorithm>
#include <atomic>
#include <exception>

namespace fhr {

struct ThreadPool::Call {
    std::size_t n;
    const std::function<void(std::size_t)>* task;
    std::atomic<std::size_t> next{0};
    std::size_t places;      // helpers that may still join (under lock_)
    std::size_t inside = 0;  // helpers working on it (under lock_)
    std::mutex error_lock;
    std::exception_ptr error;
    std::size_t error_index = 0;

    /// Runs tasks until the indices are used up.
    void run() {
        for (std::size_t i; (i = next++) < n;) {
            try {
                (*task)(i);
            } catch (...) {
                const std::lock_guard<std::mutex> hold(error_lock);
                if (!error || i < error_index) {
                    error = std::current_exception();
                    error_index = i;
                }
            }
        }
    }
};

ThreadPool::ThreadPool(unsigned threads) {
    const unsigned total = threads != 0 ? threads : std::max(1u, std::thread::hardware_concurrency());
    workers_.reserve(total - 1);
    for (unsigned t = 1; t < total; ++t) workers_.emplace_back([this] { work(); });
}

ThreadPool::~ThreadPool() {
    {
        const std::lock_guard<std::mutex> hold(lock_);
        stopping_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : workers_) t.join();
}

void ThreadPool::work() {
    std::unique_lock<std::mutex> hold(lock_);
    for (;;) {
        wake_.wait(hold, [&] { return stopping_ || !calls_.empty(); });
        if (stopping_) return;
        help(hold);
    }
}

void ThreadPool::help(std::unique_lock<std::mutex>& hold) {
    Call* call = calls_.front();
    if (--call->places == 0) calls_.pop_front();
    ++call->inside;
    hold.unlock();
    call->run();
    hold.lock();
    if (--call->inside == 0) wake_.notify_all();  // its caller waits on wake_
}

void ThreadPool::for_each(std::size_t n, std::size_t grain, const std::function<void(std::size_t)>& task) {
    const std::size_t helpers = std::min<std::size_t>(workers_.size(), n / std::max<std::size_t>(grain, 1));
    Call call;
    call.n = n;
    call.task = &task;
    call.places = helpers;
    if (helpers > 0) {
        {
            const std::lock_guard<std::mutex> hold(lock_);
            calls_.push_back(&call);
        }
        if (helpers == 1)
            wake_.notify_one();
        else
            wake_.notify_all();
    }
    call.run();
    if (helpers > 0) {
        std::unique_lock<std::mutex> hold(lock_);
        if (call.places > 0) calls_.erase(std::find(calls_.begin(), calls_.end(), &call));  // places nobody took
        // While its helpers finish, the caller helps with calls posted meanwhile (those of a task
        // still running, say) instead of idling: an oracle beside §5 on two threads leaves §5's
        // own calls a thread when it ends.
        for (;;) {
            wake_.wait(hold, [&] { return call.inside == 0 || !calls_.empty(); });
            if (call.inside == 0) break;
            help(hold);
        }
    }
    if (call.error) std::rethrow_exception(call.error);
}

Executor& default_executor() {
    static ThreadPool all_hardware_threads;  // shared by every caller that names no executor
    return all_hardware_threads;
}

}  // namespace fhr
