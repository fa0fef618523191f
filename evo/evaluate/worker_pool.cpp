#include "evo/evaluate/worker_pool.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace bhm::evo {

int resolve_thread_count(int requested) {
    if (requested > 0) return requested;
    return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

void parallel_for(int count, int threads, const std::function<void(int)>& job) {
    if (count <= 0) return;
    std::atomic<int> next{0};
    std::atomic<bool> failed{false};
    std::mutex error_mutex;
    int error_index = count;
    std::exception_ptr error;

    auto worker = [&] {
        for (;;) {
            if (failed.load(std::memory_order_relaxed)) return;
            const int i = next.fetch_add(1, std::memory_order_relaxed);
            if (i >= count) return;
            try {
                job(i);
            } catch (...) {
                std::lock_guard lock(error_mutex);
                if (i < error_index) {
                    error_index = i;
                    error = std::current_exception();
                }
                failed.store(true, std::memory_order_relaxed);
            }
        }
    };
    const int helpers = std::min(std::max(threads, 1), count) - 1;
    std::vector<std::thread> pool;
    pool.reserve(static_cast<std::size_t>(helpers));
    for (int t = 0; t < helpers; ++t)
        pool.emplace_back(worker);
    worker();
    for (auto& t : pool)
        t.join();
    if (error) std::rethrow_exception(error);
}

}  // namespace bhm::evo
