#include "evo/run/generation_report.hpp"

#include <algorithm>

namespace bhm::evo {
namespace {

double median(std::vector<double> values) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace

const Individual& best_member(const std::vector<Individual>& population) {
    return *std::min_element(population.begin(), population.end(),
                             [](const Individual& a, const Individual& b) {
                                 if (a.valid != b.valid) return a.valid;
                                 if (a.report.fitness != b.report.fitness)
                                     return a.report.fitness > b.report.fitness;
                                 if (a.age != b.age) return a.age < b.age;
                                 return a.id < b.id;
                             });
}

HistoryRow make_history_row(const GenerationTally& tally, const Selection& selection,
                            const SearchState& search, double champion_fitness) {
    const std::vector<Individual>& population = selection.population;
    const Individual& best = best_member(population);
    HistoryRow row;
    row.generation = tally.generation;
    row.evaluations = tally.evaluations;
    row.simulations = tally.evaluation->simulations() +
                      (tally.reevaluation ? tally.reevaluation->simulations() : 0);
    row.best_fitness = best.report.fitness;
    std::vector<double> fitness;
    for (const auto& m : population)
        fitness.push_back(m.report.fitness);
    row.median_fitness = median(fitness);
    row.best_age = best.age;
    row.best_id = best.id;
    row.diverged = tally.evaluation->diverged +
                   (tally.reevaluation ? tally.reevaluation->diverged : 0);
    // Where the simulations stopped (evaluations that end when the motion repeats).
    const auto& simulated = tally.evaluation->simulated_reports;
    double simulated_s = 0.0;
    for (const auto& r : simulated) {
        row.ended_early += r.ended_early ? 1 : 0;
        simulated_s += r.simulated_s;
    }
    row.mean_simulated_s =
        simulated.empty() ? 0.0 : simulated_s / static_cast<double>(simulated.size());
    row.best_simulated_s = best.report.simulated_s;
    row.best_periodic_residual = best.report.periodic_residual;
    row.wall_s = tally.wall_s;
    row.rules_version = tally.rules_version;
    row.best_exploits = best.report.exploits;
    for (const auto& m : population)
        row.flagged_members += m.report.exploits.any() ? 1 : 0;
    row.species = static_cast<int>(search.neat.species.size());
    if (!selection.novelty.empty()) {
        NoveltyRow n;
        n.best_novelty = *std::max_element(selection.novelty.begin(), selection.novelty.end());
        n.median_novelty = median(selection.novelty);
        n.archive_size = static_cast<int>(search.novelty_archive.entries.size());
        n.archive_added = selection.archive_added;
        n.archive_threshold = search.novelty_archive.threshold;
        n.champion_fitness = champion_fitness;
        row.novelty = n;
    }
    return row;
}

GenerationReport make_generation_report(const RunState& state, const Selection& selection,
                                        const GenerationTally& tally, bool rules_changed,
                                        bool new_champion) {
    const HistoryRow& row = state.history.back();
    GenerationReport report;
    report.generation = tally.generation;
    report.measure = state.experiment.fitness.measure;
    report.rules_version = tally.rules_version;
    report.rules_changed = rules_changed;
    report.best_fitness = row.best_fitness;
    report.median_fitness = row.median_fitness;
    report.champion = *state.champion;
    report.new_champion = new_champion;
    report.species = row.species;
    report.novelty = row.novelty;
    report.verify = state.experiment.evolution.verify;
    report.loop_checks = state.loop_checks;
    const LoopCheckIndex checks = index_checks(report.loop_checks);
    for (std::size_t k = 0; k < state.population.size(); ++k) {
        const auto& m = state.population[k];
        MemberSummary entry = summary_of(m);
        if (const auto it = checks.find(m.phenotype.hash); it != checks.end()) {
            entry.check = it->second->outcome;
            entry.check_worst = it->second->worst;
        }
        entry.pareto_rank = state.pareto_rank[k];
        entry.species = k < selection.species.size() ? selection.species[k] : 0;
        if (k < selection.novelty.size()) entry.novelty = selection.novelty[k];
        report.population.push_back(std::move(entry));
    }
    report.evaluations = row.evaluations;
    report.simulations = row.simulations;
    report.cache_hits = tally.evaluation->cache_hits;
    report.clones = tally.clones;
    report.diverged = row.diverged;
    report.newcomers_skipped = tally.newcomers_skipped;
    return report;
}

}  // namespace bhm::evo
