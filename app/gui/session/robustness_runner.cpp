// The Robustness tab's worker (robustness_runner.hpp).
#include "app/gui/session/robustness_runner.hpp"

#include <mutex>
#include <utility>

#include "evo/evaluate/fitness.hpp"

namespace bhm::app::gui {

RobustnessRunner::~RobustnessRunner() {
    cancel_ = true;
    if (worker_.joinable()) worker_.join();
}

bool RobustnessRunner::start(RobustnessRequest request) {
    if (running_.load()) return false;
    if (worker_.joinable()) worker_.join();  // the last one has ended: reap its thread
    RobustnessState state;
    state.job = ++jobs_;
    state.total = static_cast<int>(request.bodies.size() * request.controllers.size());
    state.started = std::chrono::steady_clock::now();
    state.request = std::make_shared<const RobustnessRequest>(std::move(request));
    cancel_ = false;
    running_ = true;
    states_.publish(std::make_shared<const RobustnessState>(state));
    worker_ = std::thread([this, state]() mutable { work(std::move(state)); });
    return true;
}

void RobustnessRunner::cancel() {
    if (running_.load()) cancel_ = true;
}

void RobustnessRunner::work(RobustnessState state) {
    const RobustnessRequest& r = *state.request;
    std::mutex progress;  // on_cell comes from any evaluation thread
    auto elapsed = [&] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - state.started)
            .count();
    };
    try {
        const int threads = r.threads > 0 ? r.threads : r.experiment.evolution.threads;
        auto table = std::make_shared<evo::RobustnessTable>(evo::evaluate_robustness(
            r.experiment, r.bodies, r.body_labels, r.controllers, threads,
            [&](int done, int) {
                const std::lock_guard lock(progress);
                if (done <= state.done) return;  // a later cell's report came first
                state.done = done;
                states_.publish(std::make_shared<const RobustnessState>(state));
            },
            &cancel_));
        const std::lock_guard lock(progress);
        state.table = std::move(table);
        state.phase = RobustnessPhase::Finished;
    } catch (const evo::EvaluationCancelled&) {
        state.phase = RobustnessPhase::Cancelled;
    } catch (const std::exception& e) {
        state.phase = cancel_.load() ? RobustnessPhase::Cancelled : RobustnessPhase::Failed;
        state.error = e.what();
    }
    state.elapsed_s = elapsed();
    states_.publish(std::make_shared<const RobustnessState>(state));
    running_ = false;
}

}  // namespace bhm::app::gui
