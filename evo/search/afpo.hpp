#pragma once
// Age-Fitness Pareto Optimisation (Schmidt & Lipson 2010) selection: objectives are fitness (up),
// age (down), optionally active voxel count (down, fitness.minimize_active_voxels) and optionally
// the body's volume, its filled voxel count (down or up, fitness.volume_objective). Novelty
// search (evo/search/novelty_selection.hpp) puts novelty in the first objective's place and may add
// the fitness as a second maximised one (AfpoOptions::second_objective).
//
// Selection rule (deterministic): non-dominated sorting into layers (rank 0 = nobody dominates
// it); whole layers are taken in rank order while they fit; the layer that overflows is taken in
// the order fitness desc, second desc (only when that objective is on), age asc, active voxels
// asc (only when that objective is on), volume asc or desc (only when that objective is on), id
// asc. The best fitness (first objective) is always in layer 0, so it is never lost. With the
// optional objectives off the order is the one it was before they existed (bit-identical runs).
#include <cstdint>
#include <vector>

#include "evo/experiment/experiment.hpp"

namespace bhm::evo {

struct AfpoObjectives {
    double fitness = 0.0;  //!< the first maximised objective (novelty under novelty search)
    int age = 0;
    int active_voxels = 0;
    std::int64_t id = 0;  //!< tie-break only, never an objective
    double second = 0.0;  //!< a second maximised objective, when AfpoOptions::second_objective
    int voxels = 0;       //!< the body's volume (filled cells), when AfpoOptions::volume is on
};

struct AfpoOptions {
    bool minimize_active = false;                   //!< active voxels (down) is an objective
    bool second_objective = false;                  //!< AfpoObjectives::second (up) is an objective
    VolumeObjective volume = VolumeObjective::Off;  //!< AfpoObjectives::voxels (down or up)
};

//! a dominates b: no worse in every objective and strictly better in at least one.
bool dominates(const AfpoObjectives& a, const AfpoObjectives& b, const AfpoOptions& options);
bool dominates(const AfpoObjectives& a, const AfpoObjectives& b, bool minimize_active);

//! Pareto layer of each entry (0 = non-dominated).
std::vector<int> pareto_ranks(const std::vector<AfpoObjectives>& pool, const AfpoOptions& options);
std::vector<int> pareto_ranks(const std::vector<AfpoObjectives>& pool, bool minimize_active);

//! Indices into pool of the `count` survivors, in selection order (rank, then the tie order).
std::vector<int> select_survivors(const std::vector<AfpoObjectives>& pool, int count,
                                  const AfpoOptions& options);
std::vector<int> select_survivors(const std::vector<AfpoObjectives>& pool, int count,
                                  bool minimize_active);

}  // namespace bhm::evo
