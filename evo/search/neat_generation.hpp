#pragma once
// One NEAT generation (evolution.algorithm = "neat"; Stanley & Miikkulainen 2002) in the two
// algorithm-specific steps of EvolutionRun::run_generation (evo/run/evolution_run.hpp).
//
// Breed, generation 0: population-many minimal genomes (every input to every output), each grown
// by k node splits, k uniform in [cppn.min_hidden_nodes, cppn.max_hidden_nodes] (paper Table 2's
// initial hidden nodes), redrawn until the body is valid. All splits of one generation go through
// one InnovationTable, so the same split in two genomes is the same gene.
// Breed, generation g > 0: offspring per species by explicit fitness sharing and stagnation
// (evo/search/neat_species.hpp allot_offspring). A species with n offspring copies its best `elitism`
// members unchanged (they carry their result over, age + 1); the others are children of its best
// survival_fraction (at least one): with probability neat.crossover_rate the NEAT crossover of two
// different survivors (evo/search/neat_crossover.hpp; kept when its body is new and valid, else mutated
// from), otherwise a mutant of one survivor (evo/search/neat_mutation.hpp, redrawn until new and valid
// for max_neutral_retries, then a clone). Children have age 0.
// Select: the whole brood is the next population (generational replacement); it is speciated
// (evo/search/neat_species.hpp speciate) and ordered by species, oldest species first, best member
// first.
#include <cstdint>
#include <vector>

#include "evo/genome/phenotype.hpp"
#include "evo/genome/rng.hpp"
#include "evo/search/individual.hpp"
#include "evo/search/neat_species.hpp"

namespace bhm::evo {

struct NeatBrood {
    std::vector<Individual> carried;  //!< elites, already evaluated
    std::vector<Individual> fresh;    //!< children to evaluate (clones carry their parent's result)
    int clones = 0;
};

//! The breeding step of generation g (state: the NEAT state after generation g - 1; updated with
//! the innovation counters). Throws std::runtime_error when generation 0 finds no valid body.
void neat_breed(const Experiment& rules, const Developer& developer, int g,
                const std::vector<Individual>& population, NeatState& state, Rng& rng,
                std::int64_t& next_id, NeatBrood& out);

//! The selection step: next population = pool, speciated and ordered (above).
std::vector<Individual> neat_select(const Experiment& rules, int g, std::vector<Individual> pool,
                                    NeatState& state);

}  // namespace bhm::evo
