#include "app/gui/session/calibration_session.hpp"

#include <exception>
#include <limits>
#include <stdexcept>

#include "evo/evaluate/fitness.hpp"

namespace bhm::app::gui {

CalibrationSession::~CalibrationSession() {
    cancel();
    join();
}

void CalibrationSession::join() {
    if (thread_.joinable()) thread_.join();
}

void CalibrationSession::cancel() { cancel_.store(true); }

void CalibrationSession::start(CalibrationJob job) {
    if (running_.load()) throw std::runtime_error("a calibration is already running: cancel it first");
    join();  // the last job's thread has published its end and is returning
    cancel_.store(false);
    running_.store(true);
    auto first = std::make_shared<CalibrationSnapshot>();
    first->job = ++jobs_;
    first->phase = CalibrationPhase::Running;
    first->fitting = !job.parameters.empty();
    first->budget = job.max_simulations;
    first->best_misfit_m = std::numeric_limits<double>::infinity();
    first->started = std::chrono::steady_clock::now();
    first->parameters = job.parameters;
    first->track = job.track;
    slot_.publish(first);
    thread_ = std::thread([this, job = std::move(job), first] {
        // Each publication is a fresh copy of the last one with what changed: the UI holds
        // the older ones as long as it draws them.
        CalibrationSnapshot now = *first;
        auto publish = [&] {
            now.elapsed_s =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - now.started)
                    .count();
            slot_.publish(std::make_shared<const CalibrationSnapshot>(now));
        };
        try {
            now.preview = std::make_shared<const evo::SimulatedTrack>(evo::simulate_track(
                evo::FitPoint{job.experiment, 0.0}, *job.framed_body, *job.track, &cancel_));
            if (!job.parameters.empty()) {
                publish();
                evo::CalibrationOptions options;
                options.threads = job.threads;
                options.max_simulations = job.max_simulations;
                options.cancel = &cancel_;
                options.progress = [&](int simulations, double best) {
                    now.simulations = simulations;
                    now.best_misfit_m = best;
                    publish();
                };
                now.result = std::make_shared<const evo::CalibrationResult>(evo::calibrate(
                    job.experiment, *job.framed_body, *job.track, job.parameters, options));
                now.best_misfit_m = now.result->misfit_after_m;
            } else {
                now.best_misfit_m = evo::track_misfit(*job.track, *now.preview);
            }
            now.phase = CalibrationPhase::Finished;
        } catch (const evo::EvaluationCancelled&) {
            now.phase = CalibrationPhase::Cancelled;
        } catch (const std::exception& e) {
            now.phase = cancel_.load() ? CalibrationPhase::Cancelled : CalibrationPhase::Failed;
            now.error = e.what();
        }
        // running() turns false only once the final snapshot is out.
        publish();
        running_.store(false);
    });
}

}  // namespace bhm::app::gui
