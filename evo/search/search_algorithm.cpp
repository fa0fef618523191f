#include "evo/search/search_algorithm.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "evo/evaluate/constraints.hpp"
#include "evo/search/coevolve_search.hpp"

namespace bhm::evo {

std::unique_ptr<SearchAlgorithm> make_search_algorithm(Algorithm algorithm) {
    switch (algorithm) {
        case Algorithm::Afpo:
            return make_afpo_search();
        case Algorithm::Neat:
            return make_neat_search();
        case Algorithm::Novelty:
            return make_novelty_search();
        case Algorithm::Ga:
            return make_ga_search();
        case Algorithm::HyperNeat:
            return make_hyperneat_search();
    }
    throw std::invalid_argument("evolution.algorithm " +
                                std::to_string(static_cast<int>(algorithm)) + " is not built");
}

std::unique_ptr<SearchAlgorithm> make_search_algorithm(const Evolution& evolution) {
    auto algorithm = make_search_algorithm(evolution.algorithm);
    if (evolution.controller.mode == ControllerMode::Coevolve)
        return make_coevolve_search(std::move(algorithm));
    return algorithm;
}

bool draw_random_individual(const GenerationContext& context, Rng& rng, std::int64_t id,
                            Individual& out) {
    const Experiment& e = context.rules;
    const Developer& developer = context.developer;
    const int attempts = std::max(100, e.evolution.max_neutral_retries);
    for (int attempt = 0; attempt < attempts; ++attempt) {
        Genome genome = random_genome(e.evolution.cppn, rng, developer.cppn_output_count(),
                                      developer.cppn_input_count());
        Phenotype phenotype = developer.develop(genome);
        if (!constraint_violation(e.fitness.constraints, e.boundary, developer.space(), phenotype)
                 .empty())
            continue;
        out = Individual{};
        out.id = id;
        out.born_generation = context.generation;
        out.genome = std::move(genome);
        out.phenotype = std::move(phenotype);
        return true;
    }
    return false;
}

std::vector<Individual> random_population(const GenerationContext& context, Rng& rng,
                                          std::int64_t& next_id) {
    std::vector<Individual> population;
    for (int i = 0; i < context.rules.evolution.population; ++i) {
        Individual ind;
        if (!draw_random_individual(context, rng, next_id, ind))
            throw std::runtime_error(
                "no valid random individual in " +
                std::to_string(std::max(100, context.rules.evolution.max_neutral_retries)) +
                " draws: the constraints may be too strict for this workspace");
        ++next_id;
        population.push_back(std::move(ind));
    }
    return population;
}

}  // namespace bhm::evo
