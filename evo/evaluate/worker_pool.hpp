#pragma once
// A minimal fork-join worker pool: runs job(i) for i in [0, count) on `threads` threads that take
// the next index from a shared counter. Each job writes only its own pre-sized result slot, so the
// results are in index order whatever the thread count or timing.
#include <functional>

namespace bhm::evo {

//! Number of worker threads to use: `requested` if > 0, else the hardware's (at least 1).
int resolve_thread_count(int requested);

//! Runs every job; the calling thread works too. If jobs throw, the remaining ones are skipped and
//! the exception of the lowest index that threw is rethrown after all threads have joined.
void parallel_for(int count, int threads, const std::function<void(int)>& job);

}  // namespace bhm::evo
