#pragma once
// The evolution behind the Run panel: one run on its own thread (which fans simulations out to
// evo's worker pool), controlled with atomics and a small command queue, reporting through a
// LatestSlot<EvolutionSnapshot> after every generation. The UI never waits for it: pause and stop
// abandon the generation in progress (its simulations are cancelled; a paused one is re-run on
// resume), rule changes take effect before the next generation, and the thread is only joined in
// the destructor or when a new run starts.
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "app/gui/session/evolution_snapshot.hpp"
#include "app/gui/session/latest_slot.hpp"
#include "evo/experiment/experiment.hpp"

namespace bhm::evo {
class EvolutionRun;
}

namespace bhm::app::gui {

class EvolutionSession {
  public:
    EvolutionSession();
    ~EvolutionSession();  //!< stops the run (abandoning the generation in progress) and joins
    EvolutionSession(const EvolutionSession&) = delete;
    EvolutionSession& operator=(const EvolutionSession&) = delete;

    //! Starts a new run of `experiment` writing run_dir (created; the same files and checkpoints
    //! as `bhm evolve`). Throws std::runtime_error when a run is live or the folder is unusable.
    void start(const evo::Experiment& experiment, const std::string& run_dir);
    //! Continues the run saved in run_dir from its last checkpoint (loaded on the run thread;
    //! a failure shows in the snapshot).
    void resume_from(const std::string& run_dir);
    //! Holds the run. By default the simulations in flight freeze where they are (within
    //! milliseconds, evo::EvolutionRun::set_paused) and go on at resume; between_generations
    //! lets the generation in progress finish and be saved first (then the loop waits).
    void pause(bool between_generations = false);
    void resume();
    void stop();
    //! New fitness rules (measure, constraints, objectives) for the next generation: the run
    //! re-scores the population under them (evo::EvolutionRun::request_fitness_change) and the
    //! history marks the change. The boundary cannot change within a run (it changes the bodies).
    void change_rules(const evo::Experiment& experiment);
    //! New physics (a calibration applied to the live run) from the next generation on, recorded
    //! as a rule change: every member is simulated again under it
    //! (evo::EvolutionRun::request_physics_change). Throws std::runtime_error when no run is
    //! live or loaded, std::invalid_argument for physics the run cannot take.
    void change_physics(const evo::PhysicsRules& physics);
    //! New continuum-check settings (evolution.verify: how often, how many, the policy) from the
    //! next generation on, recorded as a rule change (evo::EvolutionRun::request_verify_change;
    //! the generation in flight finishes under the old ones). Throws std::runtime_error when no
    //! run is live or loaded, std::invalid_argument for settings the run refuses (out of range,
    //! or checks where CalculiX cannot run), before anything is queued.
    void change_verify(const evo::LoopVerifySettings& settings);
    //! The settings last sent by change_verify to this run (null before any). UI thread only.
    const evo::LoopVerifySettings* sent_verify() const {
        return sent_verify_ ? &*sent_verify_ : nullptr;
    }
    //! The rules last sent by change_rules to this run (null before any): in force from the next
    //! generation, while the snapshot still shows the old ones. UI thread only.
    const evo::Experiment* sent_rules() const { return sent_rules_ ? &*sent_rules_ : nullptr; }

    //! Once the run has ended (its last snapshot is out, the thread returns right after): joins
    //! the thread and tidies (discard_unstarted_folder). Cheap to call every frame.
    void collect_ended();

    std::shared_ptr<const EvolutionSnapshot> snapshot() const { return slot_.take(); }
    //! The generation in progress, now (lock-free for the UI but for the run's own short lock).
    LiveProgress progress() const;
    std::uint64_t version() const { return slot_.version(); }
    RunPhase phase() const { return phase_.load(); }

    struct Shared;  //!< state shared with the run thread (evolution_session.cpp)

  private:
    void join_finished();
    //! A run stopped before its first generation leaves no checkpoint: the folder start() made
    //! for it (run.json, an empty champions/) is removed once its thread is joined, so quitting
    //! in generation 0 leaves no empty run behind. UI thread only.
    void discard_unstarted_folder();
    //! Runs `ready` (a new run) or what `make` returns on the run thread (a resumed one).
    void launch(std::unique_ptr<evo::EvolutionRun> ready,
                std::function<std::unique_ptr<evo::EvolutionRun>()> make,
                const std::string& run_dir, const std::string& first_message);
    LatestSlot<EvolutionSnapshot> slot_;
    std::atomic<RunPhase> phase_{RunPhase::Idle};
    std::shared_ptr<Shared> shared_;
    std::optional<evo::Experiment> sent_rules_;
    std::optional<evo::LoopVerifySettings> sent_verify_;
    std::thread thread_;
};

}  // namespace bhm::app::gui
