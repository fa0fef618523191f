#pragma once
// What the evolution worker publishes for the UI after every generation (and on every change of
// state): immutable, taken by the UI thread at the start of a frame (latest_slot.hpp).
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "evo/evaluate/exploit_flags.hpp"
#include "evo/experiment/experiment.hpp"
#include "evo/run/member_summary.hpp"
#include "evo/run/run_state.hpp"

namespace bhm::app::gui {

enum class RunPhase { Idle, Running, Pausing, Paused, Stopping, Finished, Stopped, Failed };
const char* run_phase_name(RunPhase phase);
//! A run thread exists (running, pausing, paused or stopping).
inline bool run_is_live(RunPhase p) {
    return p == RunPhase::Running || p == RunPhase::Pausing || p == RunPhase::Paused ||
           p == RunPhase::Stopping;
}

struct GenerationRecord {
    int generation = 0;
    double best_fitness = 0.0;     //!< best of the population under the rules of that generation
    double median_fitness = 0.0;   //!< over evaluated, valid members
    double elapsed_s = 0.0;        //!< wall time since the run started
    std::int64_t evaluations = 0;  //!< simulations so far
};

//! A change of rules (constraints, fitness measure, boundary) between generations: the population
//! was re-evaluated under the new rules from `generation` on.
struct RuleChangeNote {
    int generation = 0;
    std::string description;
    evo::FitnessMeasure measure = evo::FitnessMeasure::ComFinal3d;  //!< from `generation` on
};

//! A member as the studio shows it: evo's summary (the same shape the generation report and the
//! run directory's champion files have) and the body, shared between snapshots and the views.
struct PopulationMember : evo::MemberSummary {
    std::shared_ptr<const evo::Body> body;  //!< framed phenotype (what is simulated)
    //! Its phenotype's hash: what a continuum check in the loop applies to (a twin checked
    //! under another id counts, as it does for the run's policy).
    std::uint64_t hash = 0;
};

struct EvolutionSnapshot {
    RunPhase phase = RunPhase::Idle;
    std::string message;  //!< last event or error, one line
    std::string run_dir;
    //! The run is built (a resumed one has loaded its checkpoint): the fields below are its own.
    //! False only while a checkpoint loads; the panels then say so instead of showing defaults.
    bool loaded = false;
    evo::Experiment experiment;  //!< the rules in force
    int generation = 0;          //!< generations completed
    int generation_budget = 0;
    double best_fitness = 0.0;
    double simulations_per_s = 0.0;
    double elapsed_s = 0.0;
    double eta_s = -1.0;  //!< negative while unknown
    std::int64_t evaluations = 0;
    int species = 0;  //!< NEAT: species in the population (0 for other algorithms)
    std::optional<evo::NoveltyRow> novelty;  //!< novelty search: novelty and archive figures
    //! Stopped: the abandoned generation's time is in elapsed_s (EvolutionRun::keep_stopped_time),
    //! so the live progress, which still holds it, is not added again.
    bool stopped_time_kept = false;
    std::vector<GenerationRecord> history;
    std::vector<RuleChangeNote> rule_changes;
    evo::FitnessMeasure initial_measure = evo::FitnessMeasure::ComFinal3d;  //!< before any change
    std::vector<PopulationMember> population;  //!< sorted by fitness, best first
    bool has_champion = false;
    PopulationMember champion;  //!< best so far under the current rules
    int champion_generation = 0;
    //! Continuum checks in the loop (evolution.verify; the settings in force are
    //! experiment.evolution.verify): every check applied so far, in the order they landed. The
    //! members' check and check_worst are their bodies' (evo::index_checks: a later check of
    //! the same body wins). Empty for a watched run directory (its files do not hold them).
    std::vector<evo::LoopCheck> loop_checks;
};

//! The continuum check that applies to individual `id` of `run`: its body's (by phenotype hash)
//! where it is the champion or in the population, else the last check made of that id (an
//! earlier champion that left the population); null when none.
const evo::LoopCheck* loop_check_of(const EvolutionSnapshot& run, std::int64_t id);

//! How far the generation in progress is, read live every frame (evo::EvolutionRun::progress,
//! thread-safe): the Run panel's per-simulation progress, elapsed time, simulations/s and ETA
//! move inside a generation instead of waiting for its end.
struct LiveProgress {
    bool running = false;       //!< a generation is being evaluated
    int generation = -1;        //!< the one in progress
    int simulations_done = 0;   //!< finished simulations of it
    int simulations_total = 0;  //!< its simulations (0 until its individuals exist)
    double generation_s = 0.0;  //!< wall time in it so far, paused time excluded
    //! Earlier attempts at it abandoned for new rules: spent time, so elapsed counts it
    //! (evo::GenerationProgress::abandoned_s).
    double abandoned_s = 0.0;
};

//! Live figures from the last completed generation's snapshot and the progress of the next.
struct LiveFigures {
    double elapsed_s = 0.0;          //!< completed generations + the one in progress
    double simulations_per_s = 0.0;  //!< in the generation in progress once it has results
    double eta_s = -1.0;             //!< to the generation budget; -1 unknown
    std::int64_t simulations = 0;    //!< completed + finished in the generation in progress
};
//! `phase` is the run's phase now: only a running run has an ETA (a stopped, paused, finished
//! or failed one is going nowhere, so its last estimate would mislead).
LiveFigures live_figures(const EvolutionSnapshot& run, const LiveProgress& progress,
                         RunPhase phase);

//! "measure com_final_3d, min fill 0.2, reject tentacle": what changes from `before` to `after`
//! ("rules re-applied" when nothing does), for the plots' markers and the Run panel.
std::string describe_fitness_change(const evo::Fitness& before, const evo::Fitness& after);
//! "CalculiX checks every 2 generations, top 1, policy penalise, tolerance 0.1" (or "CalculiX
//! checks off"): the continuum checks' settings, for the Run panel and the plots' markers.
std::string describe_verify_settings(const evo::LoopVerifySettings& settings);
//! The note of changes[i] (its fitness change against the one before, or `initial` for the
//! first; where it set physics, what changed in it against the physics in force before:
//! `started`'s or an earlier change's; where it set the continuum checks, their new settings).
std::string describe_rule_change(const evo::Experiment& started, const evo::Fitness& initial,
                                 const std::vector<evo::RuleChange>& changes, std::size_t i);

//! "escaped (12 % unanchored), tentacle (thin share 0.62)"; "" when nothing is flagged or the
//! result predates exploit detection.
std::string exploit_summary(const evo::ExploitReport& report);
//! "E", "D", "T" letters of the flags set ("" when none), for tables.
std::string exploit_letters(const evo::ExploitReport& report);

//! The measure generation g was scored under: the last rule change at or before g, else the
//! run's first measure. Fitness values of different measures have different units (voxels,
//! degrees), so plots keep them apart.
inline evo::FitnessMeasure measure_at(const EvolutionSnapshot& run, int generation) {
    evo::FitnessMeasure measure = run.initial_measure;
    for (const auto& change : run.rule_changes)
        if (change.generation <= generation) measure = change.measure;
    return measure;
}

}  // namespace bhm::app::gui
