#include "evo/search/neat_species.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "evo/genome/neat_genes.hpp"

namespace bhm::evo {

namespace {

//! Best first: valid, then fitness desc, then id asc (as the run's champion is chosen).
bool better(const Individual& a, const Individual& b) {
    if (a.valid != b.valid) return a.valid;
    if (a.report.fitness != b.report.fitness) return a.report.fitness > b.report.fitness;
    return a.id < b.id;
}

}  // namespace

void speciate(const std::vector<Individual>& population, const NeatSettings& settings,
              int generation, NeatState& state) {
    for (auto& s : state.species)
        s.members.clear();
    for (std::size_t i = 0; i < population.size(); ++i) {
        bool placed = false;
        for (auto& s : state.species) {
            if (compatibility_distance(population[i].genome, s.representative, settings) <
                state.threshold) {
                s.members.push_back(static_cast<int>(i));
                placed = true;
                break;
            }
        }
        if (placed) continue;
        NeatSpecies founded;
        founded.id = state.next_species_id++;
        founded.representative = population[i].genome;
        founded.best_fitness = -std::numeric_limits<double>::infinity();
        founded.created = generation;
        founded.last_improved = generation;
        founded.members = {static_cast<int>(i)};
        state.species.push_back(std::move(founded));
    }
    std::erase_if(state.species, [](const NeatSpecies& s) { return s.members.empty(); });
    for (auto& s : state.species) {
        std::stable_sort(s.members.begin(), s.members.end(), [&](int a, int b) {
            return better(population[static_cast<std::size_t>(a)],
                          population[static_cast<std::size_t>(b)]);
        });
        const Individual& best = population[static_cast<std::size_t>(s.members.front())];
        s.representative = best.genome;
        if (best.report.fitness > s.best_fitness) {
            s.best_fitness = best.report.fitness;
            s.last_improved = generation;
        }
    }
    if (settings.target_species > 0) {
        const int count = static_cast<int>(state.species.size());
        if (count < settings.target_species)
            state.threshold =
                std::max(settings.threshold_step, state.threshold - settings.threshold_step);
        else if (count > settings.target_species)
            state.threshold += settings.threshold_step;
    }
}

void restart_species_records(const std::vector<Individual>& population, int generation,
                             NeatState& state) {
    for (auto& s : state.species) {
        std::stable_sort(s.members.begin(), s.members.end(), [&](int a, int b) {
            return better(population[static_cast<std::size_t>(a)],
                          population[static_cast<std::size_t>(b)]);
        });
        s.best_fitness = population[static_cast<std::size_t>(s.members.front())].report.fitness;
        s.last_improved = generation;
    }
}

std::vector<int> species_of_members(const NeatState& state, std::size_t population_size) {
    std::vector<int> of(population_size, -1);
    for (std::size_t s = 0; s < state.species.size(); ++s)
        for (int m : state.species[s].members)
            if (m >= 0 && static_cast<std::size_t>(m) < population_size)
                of[static_cast<std::size_t>(m)] = static_cast<int>(s);
    return of;
}

std::vector<double> adjusted_fitness(const std::vector<Individual>& population,
                                     const NeatState& state) {
    std::vector<double> out(population.size(), 0.0);
    if (population.empty()) return out;
    double lowest = std::numeric_limits<double>::infinity();
    for (const auto& m : population)
        lowest = std::min(lowest, m.report.fitness);
    for (const auto& s : state.species)
        for (int m : s.members) {
            const auto& ind = population[static_cast<std::size_t>(m)];
            const double shifted = ind.valid ? ind.report.fitness - lowest : 0.0;
            out[static_cast<std::size_t>(m)] = shifted / static_cast<double>(s.members.size());
        }
    return out;
}

std::vector<int> allot_offspring(const std::vector<Individual>& population, const NeatState& state,
                                 const NeatSettings& settings, int generation, int total) {
    const std::size_t n = state.species.size();
    std::vector<int> counts(n, 0);
    if (n == 0 || total <= 0) return counts;
    // The species holding the population's best member is never retired for stagnation.
    std::size_t best_species = 0;
    const Individual* best = nullptr;
    for (std::size_t s = 0; s < n; ++s) {
        const auto& top = population[static_cast<std::size_t>(state.species[s].members.front())];
        if (!best || better(top, *best)) {
            best = &top;
            best_species = s;
        }
    }
    const auto adjusted = adjusted_fitness(population, state);
    std::vector<double> share(n, 0.0);
    std::vector<char> breeds(n, 0);
    double sum = 0.0;
    for (std::size_t s = 0; s < n; ++s) {
        const auto& sp = state.species[s];
        const bool stagnant = generation - 1 - sp.last_improved >= settings.stagnation_generations;
        breeds[s] = !stagnant || s == best_species;
        if (!breeds[s]) continue;
        for (int m : sp.members)
            share[s] += adjusted[static_cast<std::size_t>(m)];
        sum += share[s];
    }
    if (!(sum > 0.0)) {  // everybody equally fit: shares by size
        sum = 0.0;
        for (std::size_t s = 0; s < n; ++s) {
            share[s] = breeds[s] ? static_cast<double>(state.species[s].members.size()) : 0.0;
            sum += share[s];
        }
    }
    // Largest remainder: floors first, then one more to the largest fractional parts.
    std::vector<double> remainder(n, 0.0);
    int given = 0;
    for (std::size_t s = 0; s < n; ++s) {
        const double exact = total * share[s] / sum;
        counts[s] = static_cast<int>(std::floor(exact));
        remainder[s] = exact - counts[s];
        given += counts[s];
    }
    std::vector<std::size_t> order(n);
    for (std::size_t s = 0; s < n; ++s)
        order[s] = s;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return remainder[a] > remainder[b]; });
    for (std::size_t k = 0; given < total; k = (k + 1) % n) {
        if (!breeds[order[k]]) continue;
        ++counts[order[k]];
        ++given;
    }
    // The population's best member must survive (elitism keeps it only if its species breeds):
    // a species with a low mean can round to no offspring, so it takes one from the largest.
    if (counts[best_species] == 0) {
        const auto largest = static_cast<std::size_t>(
            std::max_element(counts.begin(), counts.end()) - counts.begin());
        --counts[largest];
        ++counts[best_species];
    }
    return counts;
}

}  // namespace bhm::evo
