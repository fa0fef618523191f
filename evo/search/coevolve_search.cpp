// evolution.controller = "coevolve" (issue 44): any algorithm's breeding, then a controller for
// every new individual (coevolve_search.hpp).
#include "evo/search/coevolve_search.hpp"

#include <unordered_map>

#include "evo/genome/controller.hpp"
#include "evo/search/mutation.hpp"

namespace bhm::evo {

namespace {

// One operator of the six that acts (evo/search/mutation.hpp), tried up to 32 draws.
void mutate_once(Genome& controller, const CppnSettings& settings, Rng& rng) {
    for (int attempt = 0; attempt < 32; ++attempt)
        if (apply_mutation(controller, random_mutation_kind(rng), settings, rng)) return;
}

class CoevolveSearch final : public SearchAlgorithm {
  public:
    explicit CoevolveSearch(std::unique_ptr<SearchAlgorithm> inner) : inner_(std::move(inner)) {}

    void rules_changed(const GenerationContext& context, const std::vector<Individual>& population,
                       SearchState& state) const override {
        inner_->rules_changed(context, population, state);
    }
    bool champion_from_pool() const override { return inner_->champion_from_pool(); }

    Brood breed(const GenerationContext& context, std::vector<Individual> population,
                SearchState& state, Rng& rng, std::int64_t& next_id) const override {
        std::unordered_map<std::int64_t, Genome> controller_of;
        for (const Individual& m : population)
            controller_of.emplace(m.id, m.controller);
        Brood brood = inner_->breed(context, std::move(population), state, rng, next_id);
        give_controllers(context, controller_of, brood, rng);
        return brood;
    }

    Selection select(const GenerationContext& context, std::vector<Individual> pool,
                     std::size_t first_new, SearchState& state) const override {
        return inner_->select(context, std::move(pool), first_new, state);
    }

  private:
    std::unique_ptr<SearchAlgorithm> inner_;
};

}  // namespace

void give_controllers(const GenerationContext& context,
                      const std::unordered_map<std::int64_t, Genome>& controller_of, Brood& brood,
                      Rng& rng) {
    const CppnSettings& settings = context.rules.evolution.cppn;
    for (Individual& child : brood.fresh) {
        const auto parent = controller_of.find(child.parent_id);
        if (parent == controller_of.end()) {
            child.controller = random_controller(settings, rng);
        } else {
            child.controller = parent->second;
            mutate_once(child.controller, settings, rng);
        }
        child.phenotype = context.developer.develop(child.genome, child.controller);
        if (child.evaluated) {  // a clone of its parent's body, but not of its controller
            child.evaluated = false;
            child.report = FitnessReport{};
            child.valid = true;
            --brood.clones;
        }
    }
}

std::unique_ptr<SearchAlgorithm> make_coevolve_search(std::unique_ptr<SearchAlgorithm> inner) {
    return std::make_unique<CoevolveSearch>(std::move(inner));
}

}  // namespace bhm::evo
