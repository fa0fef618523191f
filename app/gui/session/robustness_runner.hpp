#pragma once
// The studio's Robustness tab (issue 44) on a worker thread: a table of bodies against
// controllers, each cell one full evaluation by evo::evaluate_robustness (the function `bhm
// robustness` calls, so a cell here is the CLI's value bit for bit), on its own thread that
// never touches ImGui or GL. The worker publishes an immutable RobustnessState (progress, then
// the table or the error) into a LatestSlot; the UI takes the newest one at the start of a
// frame. Cancel stops every cell within milliseconds (evo's cancel flag) and keeps no table.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "app/gui/session/latest_slot.hpp"
#include "evo/evaluate/robustness.hpp"
#include "evo/experiment/experiment.hpp"

namespace bhm::app::gui {

//! What a table is made of: the experiment every cell is evaluated under, the bodies (as a body
//! file or a champion file holds them; robustness_cell_body frames them) with their row labels,
//! and the controllers (the columns, resolved as the CLI resolves --controllers).
struct RobustnessRequest {
    evo::Experiment experiment;
    std::vector<evo::Body> bodies;
    std::vector<std::string> body_labels;
    std::vector<evo::RobustnessController> controllers;
    int threads = 0;  //!< 0: the experiment's evolution.threads, else all cores (as the CLI)
};

enum class RobustnessPhase { Running, Finished, Failed, Cancelled };

//! What the worker publishes: immutable once published. The request rides along, so that a
//! click on a cell shows exactly the pair that was evaluated.
struct RobustnessState {
    std::uint64_t job = 0;  //!< 1 for the first start, then one more per start
    RobustnessPhase phase = RobustnessPhase::Running;
    int done = 0, total = 0;
    std::chrono::steady_clock::time_point started{};
    double elapsed_s = 0.0;  //!< at the end (running: the UI measures from `started`)
    std::string error;       //!< Failed: one line
    std::shared_ptr<const RobustnessRequest> request;
    std::shared_ptr<const evo::RobustnessTable> table;  //!< Finished
};

class RobustnessRunner {
  public:
    RobustnessRunner() = default;
    ~RobustnessRunner();  //!< cancels a table in progress and joins the worker
    RobustnessRunner(const RobustnessRunner&) = delete;
    RobustnessRunner& operator=(const RobustnessRunner&) = delete;

    //! Starts a table; false (nothing started) while one is running.
    bool start(RobustnessRequest request);
    //! The cells stop within milliseconds; the state becomes Cancelled. No-op when idle.
    void cancel();
    bool running() const { return running_.load(); }
    //! The newest state (null before the first start).
    std::shared_ptr<const RobustnessState> state() const { return states_.take(); }
    std::uint64_t version() const { return states_.version(); }

  private:
    void work(RobustnessState state);
    std::atomic<bool> cancel_{false};
    std::atomic<bool> running_{false};
    std::uint64_t jobs_ = 0;  //!< the UI thread's (start)
    LatestSlot<RobustnessState> states_;
    std::thread worker_;
};

}  // namespace bhm::app::gui
