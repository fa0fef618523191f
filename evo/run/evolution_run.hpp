#pragma once
// The AFPO run loop (paper section 3; Schmidt & Lipson 2010), shared by `bhm evolve` and the
// studio.
//
// Generation 0: P random valid individuals. Generation g > 0: every member ages by one; each makes
// one mutant (mutate_until_new) that inherits its age; one random newcomer of age 0 joins
// (2P + 1 in the pool); the new ones are evaluated (cache first, then simulations on the
// evaluator: the worker pool, or MPI ranks, evo/evaluate/evaluator.hpp); Pareto selection on (fitness up,
// age down[, active voxels down]) cuts the pool back to P.
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
// against the wall-time budget. request_fitness_change() swaps the fitness rules before the next
// generation and re-scores the population under them (all measures are kept, so no new
// simulation is needed; members that now break a constraint get kInvalidFitness). Reports are
// immutable snapshots handed to a callback and kept as latest_report(); progress() says how far
// the generation in progress is.
#include <atomic>
#include <chrono>
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
};

struct PopulationEntry {
    std::int64_t id = 0;
    double fitness = 0.0;
    int age = 0;
    int voxels = 0;
    double active_fraction = 0.0;
    int pareto_rank = 0;
    bool diverged = false;
    bool valid = true;
    ExploitReport exploits;  //!< escaped / detached_motion / tentacle and their measures
    int species = 0;         //!< NEAT: the member's species id (0 for other algorithms)
    double novelty = 0.0;    //!< novelty search: the member's novelty (0 for other algorithms)
};

//! An immutable snapshot of one completed generation.
struct GenerationReport {
    int generation = 0;
    int generation_budget = 0;
    FitnessMeasure measure = FitnessMeasure::ComFinal3d;
    int rules_version = 0;
    bool rules_changed = false;  //!< the rules changed just before this generation
    double best_fitness = 0.0;
    double median_fitness = 0.0;
    ChampionRecord champion;  //!< champion.individual.report.exploits: the champion's flags
    bool new_champion = false;
    std::vector<PopulationEntry> population;  //!< in selection order
    int evaluations = 0;
    int simulations = 0;
    int cache_hits = 0;  //!< evaluations served by the cache, a clone's parent or a twin
    int clones = 0;      //!< mutants that found no new valid phenotype in max_neutral_retries
    int diverged = 0;
    int newcomers_skipped = 0;  //!< no valid random newcomer found (over-strict constraints)
    int species = 0;            //!< NEAT: species in the population (0 for other algorithms)
    std::optional<NoveltyRow> novelty;  //!< novelty search: novelty and archive figures
    double generation_wall_s = 0.0;
    double elapsed_s = 0.0;          //!< across resumes
    double simulations_per_s = 0.0;  //!< this generation
    double eta_s = -1.0;             //!< to the generation or wall budget; -1 unknown
};

//! How far the generation in progress is: a consistent snapshot, cheap enough to poll every frame.
struct GenerationProgress {
    bool running = false;       //!< inside run_generation()
    int generation = -1;        //!< the generation in progress, else the last one started
    int simulations_done = 0;   //!< finished simulations of that generation
    int simulations_total = 0;  //!< its simulations (0 until its individuals exist; cache hits
                                //!< and clones need none)
    double elapsed_s = 0.0;     //!< wall time in that generation so far, paused time excluded
};

using ReportCallback = std::function<void(std::shared_ptr<const GenerationReport>)>;

enum class StopReason { GenerationBudget, WallBudget, StopRequested };

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
    //! Replaces where simulations run (RunOptions::evaluator; null: this process's threads).
    //! Only while run() is not executing.
    void set_evaluator(std::shared_ptr<Evaluator> evaluator) {
        evaluator_ = evaluator ? std::move(evaluator) : std::make_shared<ThreadEvaluator>(threads_);
    }
    void request_stop() { stop_.store(true); }
    //! Lets run() go on after a stop request was honoured (the studio's "continue").
    void clear_stop() { stop_.store(false); }
    bool stop_requested() const { return stop_.load(); }
    //! The flag itself, for an async-signal-safe store from a signal handler.
    std::atomic<bool>& stop_flag() { return stop_; }
    void set_paused(bool paused);
    bool paused() const { return paused_.load(); }
    void request_fitness_change(const Fitness& fitness);

    std::shared_ptr<const GenerationReport> latest_report() const;
    //! Thread-safe: from any thread at any time, also while run() executes.
    GenerationProgress progress() const;
    //! The state after the last completed generation. Only while run() is not executing.
    const RunState& state() const { return state_; }
    const Experiment& experiment() const { return state_.experiment; }
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
    bool draw_random_individual(Individual& out, Rng& rng, std::int64_t id, int generation,
                                const Constraints& constraints) const;

    // The algorithm-specific steps of run_generation (evolution.algorithm). A generation is:
    // breed (which members carry over into the pool, which new individuals to make), evaluate the
    // new ones (shared by every algorithm: cache, then the evaluator), select (the next
    // population, in selection order, from the pool). A new algorithm adds its breed_* and
    // select_* and one case in each of run_generation's two switches.
    struct Brood {
        std::vector<Individual> carried;  //!< members kept into the pool, already evaluated
        std::vector<Individual> fresh;    //!< new individuals, evaluated by run_generation
        int clones = 0;                   //!< fresh members that copy a parent's result
        int newcomers_skipped = 0;
    };
    //! Generation 0 of AFPO: population-many random valid individuals.
    void breed_random(const Experiment& rules, int g, Rng& rng, std::int64_t& next_id,
                      Brood& brood) const;
    //! AFPO (paper section 3): every member ages and makes one child; one random newcomer.
    void breed_afpo(const Experiment& rules, int g, std::vector<Individual> population, Rng& rng,
                    std::int64_t& next_id, Brood& brood) const;
    //! AFPO's Pareto selection on (fitness, age[, active voxels]) back to population-many.
    void select_afpo(const Experiment& rules, std::vector<Individual> pool,
                     std::vector<Individual>& next_population, std::vector<int>& next_ranks) const;
    void publish(std::shared_ptr<const GenerationReport> report);
    //! Seconds spent paused since the run was made (the current pause included).
    double paused_seconds() const;
    void progress_begin(int generation);
    void progress_set_total(int simulations);
    void progress_count_one();
    void progress_end();

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
    std::vector<std::string> resume_warnings_;
    std::string checkpoint_path_;

    std::atomic<bool> stop_{false};
    std::atomic<bool> paused_{false};
    mutable std::mutex control_mutex_;
    std::condition_variable control_changed_;
    std::chrono::steady_clock::time_point pause_began_;  //!< under control_mutex_
    double paused_s_ = 0.0;                              //!< completed pauses, under control_mutex_
    std::optional<Fitness> pending_fitness_;
    std::uint64_t pending_serial_ = 0;

    mutable std::mutex report_mutex_;
    std::shared_ptr<const GenerationReport> latest_;
    ReportCallback callback_;

    mutable std::mutex progress_mutex_;
    GenerationProgress progress_;  //!< elapsed_s unused: computed from the two below
    std::chrono::steady_clock::time_point progress_start_;
    double progress_paused_at_start_s_ = 0.0;

    std::chrono::steady_clock::time_point session_start_;
    int session_generations_ = 0;
};

}  // namespace bhm::evo
