#include "evo/search/neat_generation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "evo/evaluate/constraints.hpp"
#include "evo/search/neat_crossover.hpp"
#include "evo/search/neat_mutation.hpp"

namespace bhm::evo {

namespace {

void breed_initial(const Experiment& rules, const Developer& developer, int g,
                   InnovationTable& table, Rng& rng, std::int64_t& next_id, NeatBrood& out) {
    const auto& cppn = rules.evolution.cppn;
    const auto& constraints = rules.fitness.constraints;
    const int attempts = std::max(100, rules.evolution.max_neutral_retries);
    for (int i = 0; i < rules.evolution.population; ++i) {
        bool found = false;
        for (int attempt = 0; attempt < attempts && !found; ++attempt) {
            Genome genome = neat_minimal_genome(developer.cppn_output_count(), cppn, rng, table,
                                                developer.cppn_input_count());
            const int splits = rng.uniform_int(
                cppn.min_hidden_nodes, std::max(cppn.min_hidden_nodes, cppn.max_hidden_nodes));
            for (int k = 0; k < splits; ++k)
                apply_neat_mutation(genome, MutationKind::AddNode, cppn, rng, table);
            Phenotype phenotype = developer.develop(genome);
            if (!constraint_violation(constraints, rules.boundary, developer.space(), phenotype)
                     .empty())
                continue;
            Individual ind;
            ind.id = next_id++;
            ind.born_generation = g;
            ind.genome = std::move(genome);
            ind.phenotype = std::move(phenotype);
            out.fresh.push_back(std::move(ind));
            found = true;
        }
        if (!found)
            throw std::runtime_error(
                "no valid random individual in " + std::to_string(attempts) +
                " draws: the constraints may be too strict for this workspace");
    }
}

Fitter fitter_of(const Individual& a, const Individual& b) {
    if (a.report.fitness > b.report.fitness) return Fitter::Primary;
    if (b.report.fitness > a.report.fitness) return Fitter::Mate;
    return Fitter::Equal;
}

}  // namespace

void neat_breed(const Experiment& rules, const Developer& developer, int g,
                const std::vector<Individual>& population, NeatState& state, Rng& rng,
                std::int64_t& next_id, NeatBrood& out) {
    const auto& settings = rules.evolution.neat;
    if (g == 0) {
        state = NeatState{};
        state.threshold = settings.compatibility_threshold;
        state.next_node_id = developer.cppn_input_count() + developer.cppn_output_count();
    }
    // A new table every generation: the same mutation is the same gene within one generation.
    InnovationTable table(state.next_innovation, state.next_node_id);
    if (g == 0) {
        breed_initial(rules, developer, g, table, rng, next_id, out);
    } else {
        const auto& cppn = rules.evolution.cppn;
        const auto& constraints = rules.fitness.constraints;
        const int retries = rules.evolution.max_neutral_retries;
        const auto counts =
            allot_offspring(population, state, settings, g, rules.evolution.population);
        for (std::size_t s = 0; s < state.species.size(); ++s) {
            const auto& members = state.species[s].members;  // best first
            const int n = counts[s];
            const int size = static_cast<int>(members.size());
            const int elites = std::min({settings.elitism, n, size});
            for (int k = 0; k < elites; ++k) {
                Individual elite =
                    population[static_cast<std::size_t>(members[static_cast<std::size_t>(k)])];
                ++elite.age;
                out.carried.push_back(std::move(elite));
            }
            const int parents =
                std::clamp(static_cast<int>(std::ceil(settings.survival_fraction * size)), 1, size);
            for (int c = elites; c < n; ++c) {
                const int first = rng.index(parents);
                const Individual& parent =
                    population[static_cast<std::size_t>(members[static_cast<std::size_t>(first)])];
                MutationOutcome made;
                if (parents > 1 && rng.uniform() < settings.crossover_rate) {
                    int second = rng.index(parents - 1);
                    if (second >= first) ++second;  // a different survivor
                    const Individual& mate = population[static_cast<std::size_t>(
                        members[static_cast<std::size_t>(second)])];
                    Genome crossed =
                        neat_crossover(parent.genome, mate.genome, fitter_of(parent, mate), rng);
                    Phenotype phenotype = developer.develop(crossed);
                    if (!(phenotype == parent.phenotype) &&
                        constraint_violation(constraints, rules.boundary, developer.space(),
                                             phenotype)
                            .empty()) {
                        made.genome = std::move(crossed);
                        made.phenotype = std::move(phenotype);
                    } else {
                        made = neat_mutate_until_new(crossed, parent.phenotype, developer,
                                                     constraints, cppn, retries, rng, table);
                        if (made.cloned) {
                            made.genome = parent.genome;
                            made.phenotype = parent.phenotype;
                        }
                    }
                } else {
                    made = neat_mutate_until_new(parent.genome, parent.phenotype, developer,
                                                 constraints, cppn, retries, rng, table);
                }
                Individual child;
                child.id = next_id++;
                child.parent_id = parent.id;
                child.born_generation = g;
                child.genome = std::move(made.genome);
                child.phenotype = std::move(made.phenotype);
                if (made.cloned) {  // the parent's body: the parent's result
                    child.report = parent.report;
                    child.evaluated = parent.evaluated;
                    child.valid = parent.valid;
                    ++out.clones;
                }
                out.fresh.push_back(std::move(child));
            }
        }
    }
    state.next_innovation = table.next_innovation();
    state.next_node_id = table.next_node_id();
}

std::vector<Individual> neat_select(const Experiment& rules, int g, std::vector<Individual> pool,
                                    NeatState& state) {
    speciate(pool, rules.evolution.neat, g, state);
    std::vector<Individual> next;
    next.reserve(pool.size());
    for (auto& s : state.species) {
        for (int& m : s.members) {
            next.push_back(std::move(pool[static_cast<std::size_t>(m)]));
            m = static_cast<int>(next.size()) - 1;
        }
    }
    return next;
}

}  // namespace bhm::evo
