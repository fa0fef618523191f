// AFPO (evolution.algorithm = "afpo"; paper section 3, Schmidt & Lipson 2010): breed as
// afpo_breed (search_algorithm.hpp), select by Pareto layers on (fitness up, age down[, active
// voxels down][, volume down or up]) back to population-many (evo/search/afpo.hpp).
#include <algorithm>

#include "evo/search/afpo.hpp"
#include "evo/search/crossover.hpp"
#include "evo/search/mutation.hpp"
#include "evo/search/search_algorithm.hpp"

namespace bhm::evo {

Brood afpo_breed(const GenerationContext& context, std::vector<Individual> population, Rng& rng,
                 std::int64_t& next_id) {
    Brood brood;
    const Experiment& rules = context.rules;
    if (context.generation == 0) {
        brood.fresh = random_population(context, rng, next_id);
        return brood;
    }
    const auto& constraints = rules.fitness.constraints;
    for (auto& m : population)
        ++m.age;
    const double crossover_rate = rules.evolution.crossover_rate;
    for (std::size_t p = 0; p < population.size(); ++p) {
        const Individual& parent = population[p];
        // Rate 0 draws nothing, so mutation-only runs keep the paper's random stream.
        const Individual* mate = nullptr;
        if (crossover_rate > 0.0 && population.size() > 1 && rng.uniform() < crossover_rate) {
            auto m = static_cast<std::size_t>(rng.index(static_cast<int>(population.size()) - 1));
            mate = &population[m >= p ? m + 1 : m];  // any member but the parent
        }
        auto out =
            mate ? cross_then_mutate(parent.genome, mate->genome, parent.phenotype,
                                     context.developer, constraints, rules.evolution.cppn,
                                     rules.evolution.max_neutral_retries, rng)
                 : mutate_until_new(parent.genome, parent.phenotype, context.developer, constraints,
                                    rules.evolution.cppn, rules.evolution.max_neutral_retries, rng);
        Individual child;
        child.id = next_id++;
        child.parent_id = parent.id;
        // AFPO: an offspring is as old as its oldest parent.
        child.age = mate && !out.cloned ? std::max(parent.age, mate->age) : parent.age;
        child.born_generation = context.generation;
        child.genome = std::move(out.genome);
        child.phenotype = std::move(out.phenotype);
        if (out.cloned) {  // same phenotype as the parent: same result
            child.report = parent.report;
            child.evaluated = parent.evaluated;
            child.valid = parent.valid;
            ++brood.clones;
        }
        brood.fresh.push_back(std::move(child));
    }
    Individual newcomer;
    if (draw_random_individual(context, rng, next_id, newcomer)) {
        ++next_id;
        brood.fresh.push_back(std::move(newcomer));
    } else {
        ++brood.newcomers_skipped;
    }
    brood.carried = std::move(population);
    return brood;
}

namespace {

class AfpoSearch final : public SearchAlgorithm {
  public:
    Brood breed(const GenerationContext& context, std::vector<Individual> population,
                SearchState& /*state*/, Rng& rng, std::int64_t& next_id) const override {
        return afpo_breed(context, std::move(population), rng, next_id);
    }

    Selection select(const GenerationContext& context, std::vector<Individual> pool,
                     std::size_t /*first_new*/, SearchState& /*state*/) const override {
        std::vector<AfpoObjectives> objectives;
        objectives.reserve(pool.size());
        for (const auto& m : pool)
            objectives.push_back({m.report.fitness, m.age, m.phenotype.active_voxels, m.id, 0.0,
                                  m.phenotype.voxels});
        const AfpoOptions options{.minimize_active = context.rules.fitness.minimize_active_voxels,
                                  .volume = context.rules.fitness.volume_objective};
        const auto survivors =
            select_survivors(objectives, context.rules.evolution.population, options);
        const auto ranks = pareto_ranks(objectives, options);
        Selection out;
        for (int index : survivors) {
            out.population.push_back(pool[static_cast<std::size_t>(index)]);
            out.ranks.push_back(ranks[static_cast<std::size_t>(index)]);
        }
        out.species.assign(out.population.size(), 0);
        return out;
    }
};

}  // namespace

std::unique_ptr<SearchAlgorithm> make_afpo_search() {
    return std::make_unique<AfpoSearch>();
}

}  // namespace bhm::evo
