#pragma once
// What a completed generation says, in its two shapes: the row of fitness.csv kept in the run's
// history (HistoryRow, run_state.hpp) and the immutable snapshot handed to the run's report
// callback and the studio (GenerationReport), built here from the state after the generation.
#include <cstdint>
#include <optional>
#include <vector>

#include "evo/evaluate/exploit_flags.hpp"
#include "evo/experiment/experiment.hpp"
#include "evo/run/cached_evaluation.hpp"
#include "evo/run/member_summary.hpp"
#include "evo/run/run_state.hpp"
#include "evo/search/search_algorithm.hpp"

namespace bhm::evo {

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
    std::vector<MemberSummary> population;  //!< in selection order
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
    //! Continuum checks in the loop: the settings in force and every check made so far (the
    //! champion's is the one whose hash is its phenotype's; members carry theirs).
    LoopVerifySettings verify;
    std::vector<LoopCheck> loop_checks;
};

//! The best member: valid first, then fitness desc, age asc, id asc.
const Individual& best_member(const std::vector<Individual>& population);

//! What the run loop knows of the generation it just ran, besides the new state.
struct GenerationTally {
    int generation = 0;
    int rules_version = 0;
    int evaluations = 0;  //!< new individuals that needed a result
    const CachedEvaluation* evaluation = nullptr;
    //! After a physics change: the population simulated again before breeding (null otherwise);
    //! its simulations count in the generation's simulations and diverged.
    const CachedEvaluation* reevaluation = nullptr;
    int clones = 0;
    int newcomers_skipped = 0;
    double generation_wall_s = 0.0;  //!< this generation, paused time excluded
    double wall_s = 0.0;             //!< elapsed across resumes at the generation's end
    //! The continuum checks that landed in this generation (evolution.verify; null: none ran).
    const std::vector<LoopCheck>* checks_landed = nullptr;
    bool verify_changed = false;  //!< a rule change set the checks' settings
    //! The checks still to land after this generation (null: none).
    const PendingChecks* pending_checks = nullptr;
};

//! fitness.csv's row for the selected population (species and novelty from the search state and
//! the selection; champion_fitness from the champion).
HistoryRow make_history_row(const GenerationTally& tally, const Selection& selection,
                            const SearchState& search, double champion_fitness);

//! The snapshot of the state after a generation (state.history.back() is its row).
GenerationReport make_generation_report(const RunState& state, const Selection& selection,
                                        const GenerationTally& tally, bool rules_changed,
                                        bool new_champion);

}  // namespace bhm::evo
