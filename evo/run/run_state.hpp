#pragma once
// Everything an evolution run is at the end of a generation: exactly what a checkpoint stores, so
// a resumed run continues as if never interrupted.
#include <cstdint>
#include <optional>
#include <vector>

#include "evo/evaluate/fitness_cache.hpp"
#include "evo/experiment/experiment.hpp"
#include "evo/genome/rng.hpp"
#include "evo/search/individual.hpp"
#include "evo/search/neat_species.hpp"
#include "evo/search/novelty_archive.hpp"
#include "evo/run/loop_check.hpp"
#include "evo/run/physics_rules.hpp"

namespace bhm::evo {

//! Novelty search's figures of one generation (evolution.algorithm = "novelty"; fitness.csv's
//! extra columns).
struct NoveltyRow {
    double best_novelty = 0.0;  //!< highest novelty in the population after selection
    double median_novelty = 0.0;
    int archive_size = 0;            //!< after this generation's additions
    int archive_added = 0;           //!< entries this generation added
    double archive_threshold = 0.0;  //!< after this generation's adaptation
    double champion_fitness = 0.0;   //!< the best fitness seen so far: the run's champion
    bool operator==(const NoveltyRow&) const = default;
};

//! One row of fitness.csv. Counts are for that generation alone.
struct HistoryRow {
    int generation = 0;
    int evaluations = 0;  //!< new individuals that needed a result (mutants, newcomer)
    int simulations = 0;  //!< of those, the ones actually simulated (the rest came from the cache)
    double best_fitness = 0.0;
    double median_fitness = 0.0;
    int best_age = 0;
    std::int64_t best_id = 0;
    int diverged = 0;       //!< simulations that diverged
    double wall_s = 0.0;    //!< wall time since the run started (across resumes) at its end
    int rules_version = 0;  //!< bumped by every change of fitness rules between generations
    ExploitReport best_exploits;  //!< the flags of the best member
    int flagged_members = 0;      //!< population members raising any exploit flag
    int species = 0;              //!< NEAT: species after this generation (0 for other algorithms)
    //! Of this generation's simulations, those that ended early because the motion repeated
    //! (evo/evaluate/periodic_end.hpp), and their mean simulated time (where they stopped).
    int ended_early = 0;
    double mean_simulated_s = 0.0;
    double best_simulated_s = 0.0;        //!< where the best member's simulation stopped
    double best_periodic_residual = 0.0;  //!< its last period-to-period residual (voxels)
    std::optional<NoveltyRow> novelty;  //!< novelty search only
    //! Runs with continuum checks in the loop (evolution.verify) only.
    std::optional<LoopCheckRow> verify;
    bool operator==(const HistoryRow&) const = default;
};

//! The best individual seen so far under the current rules.
struct ChampionRecord {
    Individual individual;
    int generation_found = 0;
};

//! A change of the rules applied before `generation`: the fitness rules (measure, constraints,
//! objectives) in force from then on and, when the change also set the physics (a calibration
//! applied to the live run, evo/run/physics_rules.hpp), that physics: from that generation every
//! member was simulated again under it.
struct RuleChange {
    int generation = 0;
    Fitness fitness;
    std::optional<PhysicsRules> physics;
    //! Set when the change set the continuum checks' policy (evolution.verify).
    std::optional<LoopVerifySettings> verify;
    bool operator==(const RuleChange&) const = default;
};

struct RunState {
    Experiment experiment;  //!< the current rules (fitness as last changed)
    std::uint64_t seed = 0;
    int generation = -1;  //!< last completed generation (-1: none yet)
    std::int64_t next_id = 0;
    Rng::State rng{};
    int rules_version = 0;
    double elapsed_s = 0.0;  //!< wall time spent on completed generations, across resumes
    std::vector<Individual> population;  //!< in selection order
    std::vector<int> pareto_rank;        //!< per population member, from the last selection
    //! Per population member: its novelty in the last selection (evolution.algorithm = "novelty"
    //! only, else empty). Not in the checkpoint: empty after a resume until the next generation.
    std::vector<double> novelty;
    std::optional<ChampionRecord> champion;
    std::vector<HistoryRow> history;
    std::vector<RuleChange> rule_changes;
    FitnessCache cache;
    NeatState neat;  //!< evolution.algorithm = "neat" only: innovation counters, species
    NoveltyArchive novelty_archive;  //!< evolution.algorithm = "novelty" only
    //! Every continuum check applied so far (evolution.verify), in the order they landed.
    std::vector<LoopCheck> loop_checks;
    //! Bodies picked for checking whose results land in a later generation.
    std::optional<PendingChecks> pending_checks;
};

}  // namespace bhm::evo
