#pragma once
// The calibration behind the Calibrate tab (docs/calibration.md, issue 28): one job at a time on
// its own thread (which fans the scan and the uncertainty out to evo's worker pool), reporting
// through a LatestSlot<CalibrationSnapshot> as the evolution session does: the worker publishes
// an immutable snapshot after every simulation, the UI takes the newest at the start of a frame
// and never waits. A job first simulates the body as given at the track's times (the preview the
// plots and the 3D marker use), then, when parameters are named, fits them (evo::calibrate).
// Cancel aborts the simulations in flight within one track row.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "app/gui/session/latest_slot.hpp"
#include "evo/calibrate/calibrator.hpp"

namespace bhm::app::gui {

enum class CalibrationPhase { Idle, Running, Finished, Cancelled, Failed };

struct CalibrationJob {
    evo::Experiment experiment;                    //!< the body's experiment
    std::shared_ptr<const evo::Body> framed_body;  //!< apply_frame_and_overrides output
    std::shared_ptr<const evo::MeasuredTrack> track;
    std::vector<evo::FitParameter> parameters;  //!< empty: the preview simulation only
    int threads = 0;
    int max_simulations = 200;
};

struct CalibrationSnapshot {
    std::uint64_t job = 0;  //!< increases with every start
    CalibrationPhase phase = CalibrationPhase::Idle;
    bool fitting = false;   //!< the job fits parameters (else: preview only)
    int simulations = 0;    //!< of the scan and the optimiser so far
    int budget = 0;         //!< max_simulations of the job
    double best_misfit_m = 0.0;  //!< best so far (+infinity before the first)
    std::chrono::steady_clock::time_point started{};
    double elapsed_s = 0.0;  //!< at publication (the UI adds the time since, while running)
    std::vector<evo::FitParameter> parameters;
    std::shared_ptr<const evo::MeasuredTrack> track;
    //! The body simulated at the track's times as given (null until simulated).
    std::shared_ptr<const evo::SimulatedTrack> preview;
    std::shared_ptr<const evo::CalibrationResult> result;  //!< once Finished with parameters
    std::string error;  //!< Failed: the one-line reason
};

class CalibrationSession {
  public:
    CalibrationSession() = default;
    ~CalibrationSession();  //!< cancels the job in progress and joins
    CalibrationSession(const CalibrationSession&) = delete;
    CalibrationSession& operator=(const CalibrationSession&) = delete;

    //! Starts a job; throws std::runtime_error while one is running.
    void start(CalibrationJob job);
    //! Aborts the job in progress (its snapshot then says Cancelled); nothing when idle.
    void cancel();
    bool running() const { return running_.load(); }
    std::shared_ptr<const CalibrationSnapshot> snapshot() const { return slot_.take(); }
    std::uint64_t version() const { return slot_.version(); }

  private:
    void join();
    LatestSlot<CalibrationSnapshot> slot_;
    std::atomic<bool> cancel_{false};
    std::atomic<bool> running_{false};
    std::uint64_t jobs_ = 0;
    std::thread thread_;
};

}  // namespace bhm::app::gui
