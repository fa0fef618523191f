#include "evo/calibrate/track_batches.hpp"

#include <mutex>

#include "evo/evaluate/worker_pool.hpp"

namespace bhm::evo {

SimulatedTrack simulate_track_at(const TrackProblem& problem, const std::vector<double>& x,
                                 const std::atomic<bool>* cancel) {
    return simulate_track(apply_fit(*problem.experiment, *problem.parameters, x),
                          *problem.framed_body, *problem.track, cancel);
}

void ThreadTrackBatches::simulate(
    const TrackProblem& problem, const std::vector<std::vector<double>>& xs,
    std::vector<SimulatedTrack>& results, const std::atomic<bool>* cancel,
    const std::function<void(std::size_t, const SimulatedTrack&)>& on_result) {
    results.assign(xs.size(), SimulatedTrack{});
    std::mutex one_at_a_time;
    parallel_for(static_cast<int>(xs.size()), threads_, [&](int j) {
        const auto i = static_cast<std::size_t>(j);
        results[i] = simulate_track_at(problem, xs[i], cancel);
        if (!on_result) return;
        std::lock_guard lock(one_at_a_time);
        on_result(i, results[i]);
    });
}

}  // namespace bhm::evo
