// The thread pool (src/fhr/core/executor.hpp; spec/library.md LIB-3): every task exactly once,
// whatever the number of threads and the grain; the exception of the lowest index rethrown to the
// caller only after all tasks have run (what lets each stage keep its results and its errors
// bit-identical on any executor); the same threads for every call (none started per
// call); several callers at once and calls from inside a task.
#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <fhr/core/executor.hpp>

using fhr::Executor;
using fhr::ThreadPool;

TEST_CASE("ThreadPool calls every task exactly once, on any threads and grain (grain 0 counts as 1)",
          "[unit][executor]") {
    for (unsigned threads : {0u, 1u, 3u}) {
        ThreadPool pool(threads);
        CHECK(pool.threads() == (threads == 0 ? std::max(1u, std::thread::hardware_concurrency()) : threads));
        for (std::size_t grain : {0u, 1u, 100u})
            for (std::size_t n : {0u, 1u, 50u}) {
                INFO(threads << " threads, grain " << grain << ", " << n << " tasks");
                const auto calls = std::make_unique<std::atomic<int>[]>(n + 1);
                pool.for_each(n, grain, [&](std::size_t i) { ++calls[i]; });
                int wrong = 0;
                for (std::size_t i = 0; i < n; ++i) wrong += calls[i] != 1;
                CHECK(wrong == 0);
                CHECK(calls[n] == 0);
            }
    }
}

TEST_CASE("ThreadPool: n tasks of grain g get min(workers, n / g) helpers", "[unit][executor]") {
    ThreadPool pool(3);
    // Grain 1: 3 tasks, 2 helpers: the three run at once (each waits until all three have started).
    std::mutex lock;
    std::condition_variable started_one;
    int started = 0;
    std::atomic<int> met{0};
    pool.for_each(3, 1, [&](std::size_t) {
        std::unique_lock<std::mutex> hold(lock);
        ++started;
        started_one.notify_all();
        if (started_one.wait_for(hold, std::chrono::seconds(5), [&] { return started == 3; })) ++met;
    });
    CHECK(met == 3);
    // Grain 2: 3 tasks, 1 helper: never more than two at once.
    std::atomic<int> running{0}, most{0};
    pool.for_each(3, 2, [&](std::size_t) {
        const int now = ++running;
        for (int seen = most; now > seen && !most.compare_exchange_weak(seen, now);) {}
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        --running;
    });
    CHECK(most <= 2);
}

TEST_CASE("ThreadPool rethrows the exception of the lowest index, after every task has run", "[unit][executor]") {
    for (unsigned threads : {1u, 2u, 4u}) {
        INFO(threads << " threads");
        ThreadPool pool(threads);
        for (int round = 0; round < 20; ++round) {
            std::atomic<int> ran{0};
            try {
                // Task 7 throws at once, task 3 only after a while: on several threads 7 usually
                // throws first, and still 3's exception is the one the caller sees.
                pool.for_each(10, 1, [&](std::size_t i) {
                    ++ran;
                    if (i == 3) {
                        std::this_thread::sleep_for(std::chrono::microseconds(200));
                        throw std::runtime_error("task 3");
                    }
                    if (i == 7) throw std::runtime_error("task 7");
                });
                FAIL("no exception reached the caller");
            } catch (const std::runtime_error& e) {
                CHECK(std::string(e.what()) == "task 3");
            }
            CHECK(ran == 10);
        }
    }
}

TEST_CASE("ThreadPool starts its threads once: every call runs on the same threads", "[unit][executor]") {
    ThreadPool pool(3);
    std::mutex lock;
    std::set<std::thread::id> seen;
    for (int call = 0; call < 200; ++call)
        pool.for_each(64, 1, [&](std::size_t) {
            std::this_thread::sleep_for(std::chrono::microseconds(5));
            const std::lock_guard<std::mutex> hold(lock);
            seen.insert(std::this_thread::get_id());
        });
    // The caller and the two workers; a pool that started threads per call would show hundreds.
    CHECK(seen.size() <= 3);
    CHECK(seen.count(std::this_thread::get_id()) == 1);
}

TEST_CASE("ThreadPool serves several callers at once, and calls made from inside a task", "[unit][executor]") {
    ThreadPool pool(2);
    std::atomic<long> sum{0};
    std::vector<std::thread> callers;
    for (int c = 0; c < 4; ++c)
        callers.emplace_back([&] {
            for (int round = 0; round < 50; ++round)
                pool.for_each(8, 1, [&](std::size_t i) {
                    // Nested: each outer task runs an inner call of 8 tasks on the same pool.
                    pool.for_each(8, 1, [&](std::size_t j) { sum += static_cast<long>(i * 8 + j); });
                });
        });
    for (std::thread& t : callers) t.join();
    // Each outer call adds 0 + 1 + ... + 63 = 2016; 4 callers × 50 rounds.
    CHECK(sum == 4L * 50 * 2016);
}

TEST_CASE("executor_or_default: the given executor, else the one shared default", "[unit][executor]") {
    ThreadPool mine(2);
    CHECK(&fhr::executor_or_default(&mine) == &mine);
    Executor& shared = fhr::default_executor();
    CHECK(&fhr::executor_or_default(nullptr) == &shared);
    CHECK(&fhr::default_executor() == &shared);
}

TEST_CASE("ThreadPool: a caller whose tasks are done helps the calls its helpers post while it waits",
          "[unit][executor]") {
    // Two threads, two tasks: a task on the calling thread ends soon; a task on the worker posts
    // a call of two tasks that must run at once (each waits until both have started). Its only
    // possible helper is the caller, waiting for the outer call: without its help they never meet.
    ThreadPool pool(2);
    const std::thread::id caller = std::this_thread::get_id();
    int nested_rounds = 0;
    for (int round = 0; round < 20; ++round) {
        std::atomic<int> met{0}, nested{0};
        pool.for_each(2, 1, [&](std::size_t) {
            if (std::this_thread::get_id() == caller) {  // long enough for the worker to take the other task
                std::this_thread::sleep_for(std::chrono::milliseconds(20));
                return;
            }
            ++nested;
            std::mutex lock;
            std::condition_variable started_one;
            int started = 0;
            pool.for_each(2, 1, [&](std::size_t) {
                std::unique_lock<std::mutex> hold(lock);
                ++started;
                started_one.notify_all();
                if (started_one.wait_for(hold, std::chrono::seconds(2), [&] { return started == 2; })) ++met;
            });
        });
        INFO("round " << round);
        CHECK(met == 2 * nested);
        nested_rounds += nested;
    }
    CHECK(nested_rounds > 0);  // the worker took a task in some round (it takes one in nearly every)
}
