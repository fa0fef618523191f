#pragma once
// NEAT speciation and explicit fitness sharing (Stanley & Miikkulainen 2002, section 3.3).
//
// Speciation: each genome, in population order, joins the first species whose representative is
// closer than the compatibility threshold (evo/genome/neat_genes.hpp compatibility_distance); otherwise it
// founds a new species and represents it. Representatives are each species' best member of the
// previous generation (the paper takes a random one; the best keeps the run free of extra draws).
// With target_species > 0 the threshold moves by threshold_step toward that many species after
// each speciation (never below threshold_step).
//
// Fitness sharing: adjusted fitness = fitness' / (members of its species), with fitness' the
// fitness shifted so that the population's lowest is 0 (sharing needs non-negative values; our
// fitness is -1 for a diverged and -2 for an invalid body). Each species is allotted offspring in
// proportion to the sum of its members' adjusted fitness (the largest-remainder method, so the
// counts add up to the population exactly; ties go to the older species); a species that has not
// improved its best fitness for stagnation_generations gets none, unless it holds the
// population's best member; that species always gets at least one offspring (taken from the
// species with the most), so with elitism >= 1 the population's best is never lost.
#include <cstdint>
#include <vector>

#include "evo/experiment/experiment.hpp"
#include "evo/genome/genome.hpp"
#include "evo/search/individual.hpp"

namespace bhm::evo {

struct NeatSpecies {
    int id = 0;
    Genome representative;
    double best_fitness = 0.0;  //!< the best fitness its members ever had
    int last_improved = 0;      //!< generation that set best_fitness
    int created = 0;            //!< generation it was founded
    std::vector<int> members;   //!< indices into the population, best first
    bool operator==(const NeatSpecies&) const = default;
};

//! NEAT's state between generations (stored in checkpoints).
struct NeatState {
    std::int64_t next_innovation = 0;
    std::int64_t next_node_id = 0;  //!< 0: not started (set from the genome layout)
    int next_species_id = 1;
    double threshold = 0.0;            //!< the current compatibility threshold
    std::vector<NeatSpecies> species;  //!< oldest first
    bool operator==(const NeatState&) const = default;
};

//! Assigns every member of population to a species (members lists rebuilt, species without
//! members dropped, new representatives = best members, best_fitness / last_improved updated for
//! `generation`, the threshold adjusted). population must be evaluated.
void speciate(const std::vector<Individual>& population, const NeatSettings& settings,
              int generation, NeatState& state);

//! After a change of fitness rules re-scored the population: each species' members re-sorted best
//! first, its record restarted from its best member's new fitness as of `generation` (records
//! under the old measure say nothing about stagnation under the new one).
void restart_species_records(const std::vector<Individual>& population, int generation,
                             NeatState& state);

//! Species index (into state.species) of each population member.
std::vector<int> species_of_members(const NeatState& state, std::size_t population_size);

//! Adjusted fitness of each member (fitness sharing above).
std::vector<double> adjusted_fitness(const std::vector<Individual>& population,
                                     const NeatState& state);

//! Offspring per species (indexed as state.species), summing to `total`, for the breeding of
//! generation `generation` (stagnation counted against it).
std::vector<int> allot_offspring(const std::vector<Individual>& population, const NeatState& state,
                                 const NeatSettings& settings, int generation, int total);

}  // namespace bhm::evo
