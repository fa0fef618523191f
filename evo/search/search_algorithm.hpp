#pragma once
// The algorithm-specific half of a generation (evolution.algorithm). A generation is
//   breed    which members carry over into the pool, which new individuals to make;
//   evaluate the new ones: the same for every algorithm (evo/run/cached_evaluation.hpp);
//   select   the next population, in selection order, from the pool.
// EvolutionRun::run_generation (evo/run/evolution_run.hpp) calls these stages and nothing else of
// an algorithm, so adding one is a class implementing SearchAlgorithm (one file) and its case in
// make_search_algorithm.
//
// Determinism: breed draws every random number on the calling thread from the Rng it is handed,
// in a fixed order; select draws none.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "evo/experiment/experiment.hpp"
#include "evo/genome/phenotype.hpp"
#include "evo/genome/rng.hpp"
#include "evo/search/individual.hpp"
#include "evo/search/neat_species.hpp"
#include "evo/search/novelty_archive.hpp"

namespace bhm::evo {

//! What an algorithm carries from one generation to the next besides the population (stored in
//! checkpoints with the rest of the run's state).
struct SearchState {
    NeatState neat;                  //!< "neat": innovation counters, species
    NoveltyArchive novelty_archive;  //!< "novelty": the archive of behaviours
};

//! What every stage sees: the rules of this generation and its number.
struct GenerationContext {
    const Experiment& rules;
    const Developer& developer;
    int generation = 0;
};

struct Brood {
    std::vector<Individual> carried;  //!< members kept into the pool, already evaluated
    std::vector<Individual> fresh;    //!< new individuals (clones carry their parent's result)
    int clones = 0;                   //!< fresh members that copy a parent's result
    int newcomers_skipped = 0;        //!< no valid random newcomer found
};

struct Selection {
    std::vector<Individual> population;  //!< the next population, in selection order
    std::vector<int> ranks;              //!< per member: Pareto layer (0 without layers)
    std::vector<int> species;            //!< per member: species id (0 without species)
    std::vector<double> novelty;         //!< per member: novelty ("novelty" only, else empty)
    int archive_added = 0;               //!< "novelty": entries this generation added
};

class SearchAlgorithm {
  public:
    virtual ~SearchAlgorithm() = default;
    //! The fitness rules changed before this generation and the population was re-scored.
    virtual void rules_changed(const GenerationContext& /*context*/,
                               const std::vector<Individual>& /*population*/,
                               SearchState& /*state*/) const {}
    //! The champion is sought in the whole pool, not only in the selected population: "novelty"
    //! selects on novelty, so it can drop the fittest new individual.
    virtual bool champion_from_pool() const { return false; }
    //! population: the last generation's, empty for generation 0.
    virtual Brood breed(const GenerationContext& context, std::vector<Individual> population,
                        SearchState& state, Rng& rng, std::int64_t& next_id) const = 0;
    //! pool = brood.carried followed by the evaluated brood.fresh (from index first_new).
    virtual Selection select(const GenerationContext& context, std::vector<Individual> pool,
                             std::size_t first_new, SearchState& state) const = 0;
};

//! Throws std::invalid_argument for an algorithm that is not built.
std::unique_ptr<SearchAlgorithm> make_search_algorithm(Algorithm algorithm);
// One per algorithm, each defined in its own file (afpo_search.cpp, neat_search.cpp,
// novelty_search.cpp, ga_search.cpp).
std::unique_ptr<SearchAlgorithm> make_afpo_search();
std::unique_ptr<SearchAlgorithm> make_neat_search();
std::unique_ptr<SearchAlgorithm> make_novelty_search();
std::unique_ptr<SearchAlgorithm> make_ga_search();         // ga_search.cpp
std::unique_ptr<SearchAlgorithm> make_hyperneat_search();  // hyperneat_search.cpp
//! The experiment's algorithm, wrapped for evolution.controller = "coevolve"
//! (evo/search/coevolve_search.hpp).
std::unique_ptr<SearchAlgorithm> make_search_algorithm(const Evolution& evolution);

//! AFPO's breeding (paper section 3), which novelty search shares: generation 0 is
//! random_population; after it every member ages by one and makes one child (a mutant, or with
//! evolution.crossover_rate a crossover then mutant) that inherits its age, and one random
//! newcomer of age 0 joins. The pool is the aged population plus the new individuals.
Brood afpo_breed(const GenerationContext& context, std::vector<Individual> population, Rng& rng,
                 std::int64_t& next_id);

//! A random valid individual (random CPPN, developed, within the constraints), drawn up to
//! max(100, max_neutral_retries) times; false when none was valid.
bool draw_random_individual(const GenerationContext& context, Rng& rng, std::int64_t id,
                            Individual& out);
//! population-many random valid individuals; throws std::runtime_error when one cannot be found.
std::vector<Individual> random_population(const GenerationContext& context, Rng& rng,
                                          std::int64_t& next_id);

}  // namespace bhm::evo
