// NEAT (evolution.algorithm = "neat"; Stanley & Miikkulainen 2002) as a SearchAlgorithm: its
// breeding and selection are evo/search/neat_generation.hpp; here only the wiring and the
// species ids of the reports.
#include "evo/search/neat_generation.hpp"
#include "evo/search/search_algorithm.hpp"

namespace bhm::evo {
namespace {

class NeatSearch final : public SearchAlgorithm {
  public:
    void rules_changed(const GenerationContext& context, const std::vector<Individual>& population,
                       SearchState& state) const override {
        restart_species_records(population, context.generation - 1, state.neat);
    }

    Brood breed(const GenerationContext& context, std::vector<Individual> population,
                SearchState& state, Rng& rng, std::int64_t& next_id) const override {
        NeatBrood made;
        neat_breed(context.rules, context.developer, context.generation, population, state.neat,
                   rng, next_id, made);
        Brood brood;
        brood.carried = std::move(made.carried);
        brood.fresh = std::move(made.fresh);
        brood.clones = made.clones;
        return brood;
    }

    Selection select(const GenerationContext& context, std::vector<Individual> pool,
                     std::size_t /*first_new*/, SearchState& state) const override {
        Selection out;
        out.population =
            neat_select(context.rules, context.generation, std::move(pool), state.neat);
        out.ranks.assign(out.population.size(), 0);  // no Pareto layers in NEAT
        const auto species_of = species_of_members(state.neat, out.population.size());
        for (const int s : species_of)
            out.species.push_back(s >= 0 ? state.neat.species[static_cast<std::size_t>(s)].id : 0);
        return out;
    }
};

}  // namespace

std::unique_ptr<SearchAlgorithm> make_neat_search() {
    return std::make_unique<NeatSearch>();
}

}  // namespace bhm::evo
