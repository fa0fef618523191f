#pragma once
// The run loop, shared by `bhm evolve`, MPI and the studio, whatever the algorithm
// (evolution.algorithm: AFPO, NEAT, novelty search; evo/search/search_algorithm.hpp). A
// generation is a list of stages: apply pending rule changes (re-score), breed (the algorithm),
// evaluate the new individuals (evo/run/cached_evaluation.hpp: cache first, then simulations on
// the evaluator: the worker pool or MPI ranks), select (the algorithm), commit (state, history,
// files, checkpoint) and publish the report (evo/run/generation_report.hpp).
//
// Determinism: all random draws happen on the calling thread in a fixed order; workers only run
// pure evaluations into pre-sized slots. The same seed gives the same history and champion
// whatever the thread count or evaluator, and a resumed run continues exactly as an uninterrupted
// one.
//
// Control (thread-safe, for a UI thread or a signal handler): request_stop() aborts the simulations
// in flight within milliseconds (evo::kControlCheckSteps), abandons the current generation and
// returns from run() with the last completed generation's checkpoint on disk (checkpoint_path();
// empty when no generation has completed); an abandoned generation is simply computed again on
// resume, so stop + resume == an uninterrupted run. set_paused(true) freezes the simulations in
// flight where they are and holds the loop between generations; paused time does not count
// against the wall-time budget; pause_between_generations(true) lets the generation finish first.
// request_fitness_change() swaps the fitness rules before the next generation and re-scores the
// population under them (all measures are kept, so no new simulation is needed; members that now
// break a constraint get kInvalidFitness); change_fitness_now() also abandons the generation in
// flight, which run() computes again under the new rules. request_physics_change() (a
// calibration applied to the live run, evo/run/physics_rules.hpp) is a rule change too: from the
// generation it applies to, every member of the population is simulated again under the new
// physics before breeding (no fitness measured under the old physics is compared with a new
// one) and the fitness cache, keyed by phenotype alone, starts afresh. Reports are immutable snapshots handed
// to a callback and kept as latest_report(); run() also tells an event callback when it holds,
// goes on and restarts a generation, so a UI follows the run's own loop instead of a copy of it;
// progress() says how far the generation in progress is.
#include <atomic>
#include <chrono>
#include <utility>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "evo/evaluate/evaluator.hpp"
#include "evo/genome/phenotype.hpp"
#include "evo/run/generation_report.hpp"
#include "evo/run/loop_check.hpp"
#include "evo/run/physics_rules.hpp"
#include "evo/run/run_output.hpp"
#include "evo/run/run_state.hpp"

namespace bhm::evo {

class RunDirectoryLock;

struct RunOptions {
    std::string out_dir;                  //!< empty: keep everything in memory, write no files
    std::optional<int> generations;       //!< total generations, generation 0 included
    std::optional<double> wall_budget_h;  //!< wall-time budget across resumes
    std::optional<int> threads;           //!< 0 = all hardware threads
    std::optional<std::uint64_t> seed;    //!< new runs only; must match the checkpoint on resume
    //! Named in out_dir's lock file (evo/run/run_lock.hpp) for anyone refused while this run owns it.
    std::string writer = "bhm";
    //! Where simulations run; null: a ThreadEvaluator with `threads` threads in this process.
    std::shared_ptr<Evaluator> evaluator;
    //! The continuum checks of evolution.verify (evo/run/loop_check.hpp; the CalculiX one is
    //! evo/verify/continuum_checker.hpp). Needed only when the experiment asks for checks: a run
    //! that does and has none, or one that cannot run here, is refused with the reason.
    std::shared_ptr<ContinuumChecker> checker;
};

//! How far the generation in progress is: a consistent snapshot, cheap enough to poll every frame.
struct GenerationProgress {
    bool running = false;       //!< inside run_generation()
    int generation = -1;        //!< the generation in progress, else the last one started
    int simulations_done = 0;   //!< finished simulations of that generation
    int simulations_total = 0;  //!< its simulations (0 until its individuals exist; cache hits
                                //!< and clones need none)
    double elapsed_s = 0.0;     //!< wall time in that generation so far, paused time excluded
    //! Wall time of earlier attempts at that generation, abandoned for new rules (paused time
    //! excluded): spent, so it counts in the run's elapsed time (RunState::elapsed_s) once the
    //! generation is complete, and a live clock that left it out would jump back.
    double abandoned_s = 0.0;
};

using ReportCallback = std::function<void(std::shared_ptr<const GenerationReport>)>;

enum class StopReason { GenerationBudget, WallBudget, StopRequested };

//! What run() tells an observer between generations (the studio draws its phase from these).
enum class RunEvent {
    Paused,     //!< the loop holds between generations (set_paused or pause_between_generations)
    Resumed,    //!< it goes on after a pause
    Restarted,  //!< the generation in progress was abandoned for new rules; it is run again
};
//! generation: the one that runs next; restarted: a pause began right after a restart, so that
//! generation is computed again when the run goes on.
using EventCallback = std::function<void(RunEvent event, int generation, bool restarted)>;

class EvolutionRun {
  public:
    //! A new run. With an out_dir: creates it, takes its lock for the run's lifetime (a directory
    //! another writer owns throws RunDirectoryBusy naming it), refuses a directory that already
    //! holds a checkpoint (resume it instead) and writes run.json. Throws std::invalid_argument /
    //! std::runtime_error.
    EvolutionRun(const Experiment& experiment, RunOptions options);
    //! Continues the run in options.out_dir from its checkpoint (or the previous one), after
    //! taking the directory's lock. A missing or damaged run.json is rewritten (with a warning).
    static std::unique_ptr<EvolutionRun> resume(RunOptions options);
    ~EvolutionRun();
    EvolutionRun(const EvolutionRun&) = delete;
    EvolutionRun& operator=(const EvolutionRun&) = delete;

    //! Runs generations until a budget is reached or a stop is requested.
    StopReason run();
    //! One generation; false when it was abandoned by a stop request (state unchanged).
    bool run_generation();

    void set_report_callback(ReportCallback callback) { callback_ = std::move(callback); }
    //! Called on run()'s thread; the state is committed and may be read from the callback.
    void set_event_callback(EventCallback callback) { events_ = std::move(callback); }
    //! Replaces where simulations run (RunOptions::evaluator; null: this process's threads).
    //! Only while run() is not executing.
    void set_evaluator(std::shared_ptr<Evaluator> evaluator) {
        evaluator_ = evaluator ? std::move(evaluator) : std::make_shared<ThreadEvaluator>(threads_);
    }
    void request_stop() {
        user_stop_.store(true);
        stop_.store(true);
    }
    //! After run() returned StopRequested: the time of the generation the stop abandoned counts
    //! in the run's elapsed time (as an attempt abandoned for new rules does) and the checkpoint
    //! is written again with it, so a resumed run's clock goes on from where this one stopped
    //! instead of going back. The live progress keeps its figures (a reader that adds them to an
    //! older snapshot stays right); the next generation starts from zero. Once per stop, on the
    //! thread that ran run(). Throws what writing the checkpoint throws.
    void keep_stopped_time();
    //! Lets run() go on after a stop request was honoured (the studio's "continue").
    void clear_stop() {
        user_stop_.store(false);
        stop_.store(false);
    }
    bool stop_requested() const { return stop_.load(); }
    //! The flag itself, for an async-signal-safe store from a signal handler.
    std::atomic<bool>& stop_flag() { return stop_; }
    void set_paused(bool paused);
    //! Lets the generation in progress finish, then holds run() until lowered (set_paused(false)
    //! lowers it too). The simulations in flight are not frozen.
    void pause_between_generations(bool hold);
    bool paused() const { return paused_.load(); }
    void request_fitness_change(const Fitness& fitness);
    //! As request_fitness_change, and a generation in progress is abandoned at once and run()
    //! computes it again under the new rules (its state is untouched, so the run stays what an
    //! uninterrupted run with the change at that generation would be).
    void change_fitness_now(const Fitness& fitness);
    //! New physics from the next generation on (recorded as a rule change with its physics):
    //! the population is simulated again under it and the cache cleared. Physics equal to the
    //! run's changes nothing. Throws std::invalid_argument (with_physics) for physics that would
    //! change the run's bodies or does not validate, before anything is queued.
    void request_physics_change(const PhysicsRules& physics);
    //! As request_physics_change, abandoning the generation in flight (as change_fitness_now).
    void change_physics_now(const PhysicsRules& physics);
    //! New continuum-check settings (evolution.verify: how often, how many, the policy) from the
    //! next generation on, recorded as a rule change: the population is re-scored under the new
    //! policy with the checks already made (no new simulation). Throws std::invalid_argument for
    //! settings out of range, or checks where the run has no usable checker.
    void request_verify_change(const LoopVerifySettings& settings);

    std::shared_ptr<const GenerationReport> latest_report() const;
    //! Thread-safe: from any thread at any time, also while run() executes.
    GenerationProgress progress() const;
    //! The state after the last completed generation. Only while run() is not executing.
    const RunState& state() const { return state_; }
    const Experiment& experiment() const { return state_.experiment; }
    //! The experiment as the run was started (run.json's), before any rule change. Immutable.
    const Experiment& started_experiment() const { return original_experiment_; }
    const Developer& developer() const { return developer_; }
    const std::vector<std::string>& resume_warnings() const { return resume_warnings_; }
    //! The checkpoint file that holds state(): the one loaded on resume or the last one written;
    //! empty while no generation is complete. Only while run() is not executing.
    const std::string& checkpoint_path() const { return checkpoint_path_; }
    int generation_budget() const { return generation_budget_; }
    double wall_budget_s() const { return wall_budget_s_; }
    int threads() const { return threads_; }

  private:
    struct Start {
        Experiment original;  //!< as the run was started (run.json)
        RunState state;
        std::vector<std::string> warnings;
        std::string checkpoint_path;
        bool resumed = false;
        bool rewrite_run_info = false;  //!< run.json was missing or damaged
        std::shared_ptr<RunDirectoryLock> lock;
    };
    static Start fresh_start(const Experiment& experiment, const RunOptions& options);
    EvolutionRun(Start start, RunOptions options);
    //! The rules of the next generation (a pending fitness change applied) and the population and
    //! champion re-scored under them; copies, so an abandoned generation changes nothing.
    struct Rescored {
        Experiment rules;
        std::vector<Individual> population;
        std::optional<ChampionRecord> champion;
        int rules_version = 0;
        bool changed = false;
        bool physics_changed = false;  //!< every member must be simulated again
        bool verify_changed = false;   //!< the continuum checks' settings changed
    };
    Rescored rescore_for_pending_rules(std::uint64_t& applied_serial) const;
    //! m's fitness, validity and exploit rejection under rules (its report's measures kept).
    void rescore_member(Individual& m, const Experiment& rules,
                        const LoopCheckIndex& checks) const;
    //! Refuses checks in the loop that this run cannot make (no checker, or it cannot run here).
    void require_checker(const LoopVerifySettings& settings) const;
    //! The generation's results become the run's state: history, cache, checkpoint and files,
    //! then the report is published.
    //! physics_cache: after a physics change, the cache that replaces the run's (the
    //! re-evaluated population's results); null otherwise.
    void commit_generation(const Experiment& rules, bool rules_changed, std::uint64_t applied_serial,
                           const FitnessCache* physics_cache, bool physics_changed,
                           std::int64_t next_id, const Rng& rng, Selection selection,
                           SearchState search, ChampionRecord champion,
                           const GenerationTally& tally, bool new_champion);
    void publish(std::shared_ptr<const GenerationReport> report);
    //! Seconds spent paused since the run was made (the current pause included).
    double paused_seconds() const;
    //! The same, with the instant it holds for (read under the same lock).
    std::pair<double, std::chrono::steady_clock::time_point> paused_seconds_now() const;
    void progress_begin(int generation);
    void progress_set_total(int simulations);
    void progress_count_one();
    void progress_end();
    //! The generation just ended was abandoned: its time joins progress_.abandoned_s.
    void progress_abandoned();

    RunOptions options_;
    std::shared_ptr<RunDirectoryLock> lock_;  //!< held for the run's lifetime (null: no out_dir)
    Experiment original_experiment_;
    RunState state_;
    Developer developer_;
    std::optional<RunOutput> output_;
    int generation_budget_ = 0;
    double wall_budget_s_ = 0.0;
    int threads_ = 1;
    std::shared_ptr<Evaluator> evaluator_;
    std::shared_ptr<ContinuumChecker> checker_;
    //! The checks of state_.pending_checks (or of the generation in progress's picks), running
    //! beside the generations until they land; kept across generations, cancelled by a change
    //! of rules or when the run is destroyed.
    std::unique_ptr<LoopCheckJob> check_job_;
    std::vector<std::string> resume_warnings_;
    std::string checkpoint_path_;

    //! Raised to abandon the generation in flight: by a stop (user_stop_), a signal handler
    //! (stop_flag) or a restart for new rules (restart_).
    std::atomic<bool> stop_{false};
    std::atomic<bool> user_stop_{false};
    std::atomic<bool> restart_{false};
    std::atomic<bool> hold_{false};
    EventCallback events_;
    std::atomic<bool> paused_{false};
    mutable std::mutex control_mutex_;
    std::condition_variable control_changed_;
    std::chrono::steady_clock::time_point pause_began_;  //!< under control_mutex_
    double paused_s_ = 0.0;                              //!< completed pauses, under control_mutex_
    std::optional<Fitness> pending_fitness_;
    std::optional<PhysicsRules> pending_physics_;
    std::optional<LoopVerifySettings> pending_verify_;
    std::uint64_t pending_serial_ = 0;

    mutable std::mutex report_mutex_;
    std::shared_ptr<const GenerationReport> latest_;
    ReportCallback callback_;

    mutable std::mutex progress_mutex_;
    GenerationProgress progress_;  //!< elapsed_s unused while running: from the two below
    std::chrono::steady_clock::time_point progress_start_;
    double progress_paused_at_start_s_ = 0.0;
    bool abandoned_time_kept_ = false;  //!< keep_stopped_time: progress_.abandoned_s is in state_

    std::chrono::steady_clock::time_point session_start_;
    int session_generations_ = 0;
};

}  // namespace bhm::evo
