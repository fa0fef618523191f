#pragma once
// The evaluation stage of a generation, the same for every algorithm: each new individual gets
// its result from its parent (a clone), the run's cache (a phenotype seen before), an earlier twin
// of this generation, or else one simulation per distinct new phenotype on the evaluator (the
// worker pool or MPI ranks). Results depend on the phenotypes alone, so this stage is where the
// thread count and the evaluator can never change a run.
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "evo/evaluate/evaluator.hpp"
#include "evo/evaluate/fitness_cache.hpp"
#include "evo/search/individual.hpp"

namespace bhm::evo {

struct CachedEvaluation {
    int cache_hits = 0;  //!< results from a clone's parent, the cache or a twin
    int diverged = 0;    //!< simulations that diverged
    //! The simulated phenotypes (hash) and their reports, in simulation order: for the cache.
    std::vector<std::uint64_t> simulated_hashes;
    std::vector<FitnessReport> simulated_reports;
    int simulations() const { return static_cast<int>(simulated_reports.size()); }
};

//! evolution.controller fixed_controllers (issue 44): one body's reports, one per controller of
//! the set, as one: every measure the mean over the controllers (so fitness is the mean of the
//! controllers' fitness under any measure), diverged when any diverged, ended early when all did,
//! time and steps summed. Exploit flags: each raised when any controller's run raised it (a body
//! that exploits under one controller of the set is suspect), with the measure of the first run
//! that raised it, motion_voxels the largest; behaviour (novelty search): the element-wise mean
//! of the descriptors, empty when any run has none. With one controller: that run's report.
FitnessReport mean_over_controllers(std::span<const FitnessReport> reports, const Fitness& rules);

//! With evolution.controller fixed_controllers each distinct body is simulated once per
//! controller and its result is mean_over_controllers (on_total counts the simulations).
//! Gives every member of fresh its result (report, evaluated, valid under rules' constraints).
//! batch_controls: cancel, pause and on_result as the evaluator should see them (rules and bodies
//! are filled here); on_total(n) is told how many simulations are about to run. Throws
//! EvaluationCancelled (fresh then partly filled) when the cancel flag is raised.
CachedEvaluation evaluate_fresh(std::vector<Individual>& fresh, const Experiment& rules,
                                const FitnessCache& cache, Evaluator& evaluator,
                                EvaluationBatch batch_controls,
                                const std::function<void(int)>& on_total);

}  // namespace bhm::evo
