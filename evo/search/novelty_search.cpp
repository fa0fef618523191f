// Novelty search (evolution.algorithm = "novelty"; Lehman & Stanley 2011) as a SearchAlgorithm:
// it breeds as AFPO (afpo_breed) and selects on novelty (evo/search/novelty_selection.hpp).
#include "evo/search/novelty_selection.hpp"
#include "evo/search/search_algorithm.hpp"

namespace bhm::evo {
namespace {

class NoveltySearch final : public SearchAlgorithm {
  public:
    bool champion_from_pool() const override { return true; }

    Brood breed(const GenerationContext& context, std::vector<Individual> population,
                SearchState& /*state*/, Rng& rng, std::int64_t& next_id) const override {
        return afpo_breed(context, std::move(population), rng, next_id);
    }

    Selection select(const GenerationContext& context, std::vector<Individual> pool,
                     std::size_t first_new, SearchState& state) const override {
        const NoveltyArchive archive =
            context.generation == 0
                ? NoveltyArchive{{}, context.rules.evolution.novelty.archive_threshold}
                : state.novelty_archive;
        NoveltySelection chosen = select_by_novelty(pool, first_new, archive, context.rules);
        Selection out;
        for (int index : chosen.survivors) {
            const auto i = static_cast<std::size_t>(index);
            out.population.push_back(pool[i]);
            out.ranks.push_back(chosen.ranks[i]);
            out.novelty.push_back(chosen.novelty[i]);
        }
        out.species.assign(out.population.size(), 0);
        out.archive_added = chosen.added;
        state.novelty_archive = std::move(chosen.archive);
        return out;
    }
};

}  // namespace

std::unique_ptr<SearchAlgorithm> make_novelty_search() {
    return std::make_unique<NoveltySearch>();
}

}  // namespace bhm::evo
