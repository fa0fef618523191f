// The worker pool runs every job once, writes results by index and reports the first failure.
#include <doctest/doctest.h>

#include <atomic>
#include <stdexcept>
#include <vector>

#include "evo/evaluate/worker_pool.hpp"

using namespace bhm::evo;

TEST_CASE("parallel_for runs each index exactly once into its own slot") {
    for (int threads : {1, 2, 5}) {
        std::vector<int> slots(37, 0);
        std::atomic<int> calls{0};
        parallel_for(37, threads, [&](int i) {
            slots[static_cast<std::size_t>(i)] += i * i;
            ++calls;
        });
        CHECK(calls == 37);
        for (int i = 0; i < 37; ++i)
            CHECK(slots[static_cast<std::size_t>(i)] == i * i);
    }
    parallel_for(0, 4, [](int) { FAIL("no job expected"); });
}

TEST_CASE("parallel_for rethrows the failure of the lowest index") {
    CHECK_THROWS_WITH(parallel_for(10, 3,
                                   [](int i) {
                                       if (i == 4 || i == 7)
                                           throw std::runtime_error("job " + std::to_string(i));
                                   }),
                      "job 4");
    CHECK(resolve_thread_count(3) == 3);
    CHECK(resolve_thread_count(0) >= 1);
}
