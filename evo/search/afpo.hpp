#pragma once
// Age-Fitness Pareto Optimisation (Schmidt & Lipson 2010) selection: objectives are fitness (up),
// age (down) and optionally active voxel count (down, fitness.minimize_active_voxels). Novelty
// search (evo/search/novelty_selection.hpp) puts novelty in the first objective's place and may add the
// fitness as a second maximised one (AfpoOptions::second_objective).
//
// Selection rule (deterministic): non-dominated sorting into layers (rank 0 = nobody dominates
// it); whole layers are taken in rank order while they fit; the layer that overflows is taken in
// the order fitness desc, second desc (only when that objective is on), age asc, active voxels
// asc (only when that objective is on), id asc. The best fitness (first objective) is always in
// layer 0, so it is never lost.
#include <cstdint>
#include <vector>

namespace bhm::evo {

struct AfpoObjectives {
    double fitness = 0.0;  //!< the first maximised objective (novelty under novelty search)
    int age = 0;
    int active_voxels = 0;
    std::int64_t id = 0;  //!< tie-break only, never an objective
    double second = 0.0;  //!< a second maximised objective, when AfpoOptions::second_objective
};

struct AfpoOptions {
    bool minimize_active = false;   //!< active voxels (down) is an objective
    bool second_objective = false;  //!< AfpoObjectives::second (up) is an objective
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
