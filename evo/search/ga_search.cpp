// A plain generational genetic algorithm (evolution.algorithm = "ga"; issue 44): the baseline the
// controller studies compare NEAT and HyperNEAT against. Generation 0 is random_population. After
// it: elitism 1 (the fittest member is carried over unchanged), and population - 1 children, each
// from a parent chosen by a binary tournament (two members drawn with replacement, the fitter
// wins, the lower index on a tie); a child is mutate_until_new of its parent, or with
// evolution.crossover_rate the positional crossover of two tournament winners then mutation
// (evo/search/crossover.hpp). Selection is generational replacement: the elite and the children
// are the next population, fittest first. No ages, species or archive.
#include <algorithm>
#include <numeric>

#include "evo/search/crossover.hpp"
#include "evo/search/mutation.hpp"
#include "evo/search/search_algorithm.hpp"

namespace bhm::evo {
namespace {

bool fitter(const Individual& a, const Individual& b) {
    if (a.report.fitness != b.report.fitness) return a.report.fitness > b.report.fitness;
    return a.id < b.id;
}

std::size_t tournament(const std::vector<Individual>& population, Rng& rng) {
    const int n = static_cast<int>(population.size());
    const auto a = static_cast<std::size_t>(rng.index(n));
    const auto b = static_cast<std::size_t>(rng.index(n));
    return fitter(population[b], population[a]) ? b : a;
}

class GaSearch final : public SearchAlgorithm {
  public:
    Brood breed(const GenerationContext& context, std::vector<Individual> population,
                SearchState& /*state*/, Rng& rng, std::int64_t& next_id) const override {
        Brood brood;
        const Experiment& rules = context.rules;
        if (context.generation == 0 || population.empty()) {
            brood.fresh = random_population(context, rng, next_id);
            return brood;
        }
        std::sort(population.begin(), population.end(), fitter);
        const double crossover_rate = rules.evolution.crossover_rate;
        const int children = std::max(0, rules.evolution.population - 1);
        for (int k = 0; k < children; ++k) {
            const Individual& parent = population[tournament(population, rng)];
            const Individual* mate = nullptr;
            if (crossover_rate > 0.0 && population.size() > 1 && rng.uniform() < crossover_rate)
                mate = &population[tournament(population, rng)];
            auto out = mate ? cross_then_mutate(parent.genome, mate->genome, parent.phenotype,
                                                context.developer, rules.fitness.constraints,
                                                rules.evolution.cppn,
                                                rules.evolution.max_neutral_retries, rng)
                            : mutate_until_new(parent.genome, parent.phenotype, context.developer,
                                               rules.fitness.constraints, rules.evolution.cppn,
                                               rules.evolution.max_neutral_retries, rng);
            Individual child;
            child.id = next_id++;
            child.parent_id = parent.id;
            child.born_generation = context.generation;
            child.genome = std::move(out.genome);
            child.phenotype = std::move(out.phenotype);
            if (out.cloned) {
                child.report = parent.report;
                child.evaluated = parent.evaluated;
                child.valid = parent.valid;
                ++brood.clones;
            }
            brood.fresh.push_back(std::move(child));
        }
        Individual elite = std::move(population.front());
        ++elite.age;  // generations survived, for the reports
        brood.carried.push_back(std::move(elite));
        return brood;
    }

    Selection select(const GenerationContext& /*context*/, std::vector<Individual> pool,
                     std::size_t /*first_new*/, SearchState& /*state*/) const override {
        std::sort(pool.begin(), pool.end(), fitter);
        Selection out;
        out.population = std::move(pool);
        out.ranks.assign(out.population.size(), 0);
        out.species.assign(out.population.size(), 0);
        return out;
    }
};

}  // namespace

std::unique_ptr<SearchAlgorithm> make_ga_search() {
    return std::make_unique<GaSearch>();
}

}  // namespace bhm::evo
