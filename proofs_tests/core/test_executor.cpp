// The default executor (src/fhr/core/executor.hpp): every task exactly once, whatever the number
// of threads and the grain, and a task's exception rethrown to the caller only after all tasks
// have run (what lets each stage keep its results bit-identical on any executor, LIB-3).
#include <catch2/catch.hpp>

#include <atomic>
#include <memory>
#include <stdexcept>
#include <string>

#include <fhr/core/executor.hpp>

using fhr::Executor;
using fhr::ThreadsPerCall;

TEST_CASE("ThreadsPerCall calls every task exactly once, on any threads and grain (grain 0 counts as 1)", "[unit][executor]") {
    for (unsigned threads : {0u, 1u, 3u})
        for (std::size_t grain : {0u, 1u, 100u})
            for (std::size_t n : {0u, 1u, 50u}) {
                INFO(threads << " threads, grain " << grain << ", " << n << " tasks");
                const auto calls = std::make_unique<std::atomic<int>[]>(n + 1);
                ThreadsPerCall(threads).for_each(n, grain, [&](std::size_t i) { ++calls[i]; });
                int wrong = 0;
                for (std::size_t i = 0; i < n; ++i) wrong += calls[i] != 1;
                CHECK(wrong == 0);
                CHECK(calls[n] == 0);
            }
}

TEST_CASE("ThreadsPerCall rethrows the first exception after every task has run", "[unit][executor]") {
    // On one thread the tasks run in index order: task 3 throws first, task 7 second.
    std::atomic<int> ran{0};
    ThreadsPerCall one(1);
    try {
        one.for_each(10, 1, [&](std::size_t i) {
            ++ran;
            if (i == 3 || i == 7) throw std::runtime_error("task " + std::to_string(i));
        });
        FAIL("no exception reached the caller");
    } catch (const std::runtime_error& e) {
        CHECK(std::string(e.what()) == "task 3");
    }
    CHECK(ran == 10);
}

TEST_CASE("executor_or_default: the given executor, else the one shared default", "[unit][executor]") {
    ThreadsPerCall mine(2);
    CHECK(&fhr::executor_or_default(&mine) == &mine);
    Executor& shared = fhr::default_executor();
    CHECK(&fhr::executor_or_default(nullptr) == &shared);
    CHECK(&fhr::default_executor() == &shared);
}
