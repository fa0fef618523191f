#pragma once
// AFPO selection with novelty as the objective (evolution.algorithm = "novelty"): the generation
// loop is AFPO's (evo/run/evolution_run.hpp), only what survives changes. Over the pool (the aged
// population followed by this generation's new individuals):
//  1. each member's novelty against the pool and the archive (evo/search/novelty.hpp);
//  2. Pareto selection (evo/search/afpo.hpp) on (novelty up, age down), plus fitness up as a second
//     objective when evolution.novelty.with_fitness, plus active voxels down when
//     fitness.minimize_active_voxels, plus the volume down or up by fitness.volume_objective;
//  3. the new individuals enter the archive by its rule (evo/search/novelty_archive.hpp).
// Fitness itself is still computed and kept: the run's champion is the best *fitness* seen.
#include <cstddef>
#include <vector>

#include "evo/experiment/experiment.hpp"
#include "evo/search/individual.hpp"
#include "evo/search/novelty_archive.hpp"

namespace bhm::evo {

struct NoveltySelection {
    std::vector<int> survivors;   //!< indices into the pool, in selection order
    std::vector<int> ranks;       //!< (pool) Pareto layer
    std::vector<double> novelty;  //!< (pool) novelty, kNoNovelty without a descriptor
    NoveltyArchive archive;       //!< after this generation's additions
    int added = 0;                //!< entries this generation added to the archive
};

//! A member's descriptor when it takes part in novelty: valid, not diverged, complete.
const BehaviourDescriptor* usable_behaviour(const Individual& member);

//! pool[first_new..] are this generation's new individuals (the archive's candidates).
NoveltySelection select_by_novelty(const std::vector<Individual>& pool, std::size_t first_new,
                                   const NoveltyArchive& archive, const Experiment& rules);

}  // namespace bhm::evo
