#include "evo/search/novelty_selection.hpp"

#include "evo/evaluate/behaviour.hpp"
#include "evo/search/afpo.hpp"

namespace bhm::evo {

const BehaviourDescriptor* usable_behaviour(const Individual& member) {
    const bool usable =
        member.evaluated && member.valid && !member.report.diverged &&
        member.report.behaviour.size() == static_cast<std::size_t>(kBehaviourLength);
    return usable ? &member.report.behaviour : nullptr;
}

NoveltySelection select_by_novelty(const std::vector<Individual>& pool, std::size_t first_new,
                                   const NoveltyArchive& archive, const Experiment& rules) {
    const auto& settings = rules.evolution.novelty;
    std::vector<const BehaviourDescriptor*> behaviours;
    behaviours.reserve(pool.size());
    for (const auto& m : pool)
        behaviours.push_back(usable_behaviour(m));

    NoveltySelection out;
    out.novelty = novelty_scores(behaviours, archive.entries, settings.k);
    std::vector<AfpoObjectives> objectives;
    objectives.reserve(pool.size());
    for (std::size_t i = 0; i < pool.size(); ++i) {
        const auto& m = pool[i];
        objectives.push_back({out.novelty[i], m.age, m.phenotype.active_voxels, m.id,
                              m.report.fitness, m.phenotype.voxels});
    }
    const AfpoOptions options{rules.fitness.minimize_active_voxels, settings.with_fitness,
                              rules.fitness.volume_objective};
    out.survivors = select_survivors(objectives, rules.evolution.population, options);
    out.ranks = pareto_ranks(objectives, options);

    out.archive = archive;
    const std::size_t first = std::min(first_new, pool.size());
    const std::vector<const BehaviourDescriptor*> candidates(
        behaviours.begin() + static_cast<long>(first), behaviours.end());
    const std::vector<double> candidate_novelty(out.novelty.begin() + static_cast<long>(first),
                                                out.novelty.end());
    out.added =
        update_archive(out.archive, candidates, candidate_novelty, settings.archive_capacity);
    return out;
}

}  // namespace bhm::evo
