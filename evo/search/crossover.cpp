#include "evo/search/crossover.hpp"

#include <stdexcept>

#include "evo/evaluate/constraints.hpp"

namespace bhm::evo {

Genome crossover(const Genome& primary, const Genome& mate, Rng& rng) {
    Genome child;
    child.output_count = primary.output_count;
    child.input_count = primary.input_count;
    if (mate.output_count != primary.output_count || mate.input_count != primary.input_count)
        throw std::invalid_argument("crossover of genomes with different input or output counts");
    child.hidden = primary.hidden;
    for (std::size_t h = 0; h < child.hidden.size() && h < mate.hidden.size(); ++h)
        if (rng.uniform() < 0.5) child.hidden[h] = mate.hidden[h];

    const auto find = [](const Genome& g, int from, int to) -> const CppnEdge* {
        for (const auto& e : g.edges)
            if (e.from == from && e.to == to) return &e;
        return nullptr;
    };
    const auto add = [&](CppnEdge e) {
        if (!has_edge(child, e.from, e.to) && edge_keeps_acyclic(child, e.from, e.to))
            child.edges.push_back(e);
    };
    for (const auto& e : primary.edges) {
        if (const CppnEdge* other = find(mate, e.from, e.to)) {
            CppnEdge kept = e;
            if (rng.uniform() < 0.5) kept.weight = other->weight;
            add(kept);
        } else if (rng.uniform() < 0.5) {
            add(e);
        }
    }
    const int nodes = child.node_count();
    for (const auto& e : mate.edges) {
        if (find(primary, e.from, e.to)) continue;  // matched above
        if (e.from >= nodes || e.to >= nodes) continue;
        if (rng.uniform() < 0.5) add(e);
    }
    return child;
}

MutationOutcome cross_then_mutate(const Genome& parent, const Genome& mate,
                                  const Phenotype& parent_phenotype, const Developer& developer,
                                  const Constraints& constraints, const CppnSettings& settings,
                                  int max_retries, Rng& rng) {
    Genome child = crossover(parent, mate, rng);
    Phenotype phenotype = developer.develop(child);
    if (!(phenotype == parent_phenotype) &&
        constraint_violation(constraints, developer.experiment().boundary, developer.space(),
                             phenotype)
            .empty()) {
        MutationOutcome out;
        out.genome = std::move(child);
        out.phenotype = std::move(phenotype);
        out.attempts = 1;
        return out;
    }
    MutationOutcome out = mutate_until_new(child, parent_phenotype, developer, constraints,
                                           settings, max_retries, rng);
    if (out.cloned) {  // mutate_until_new's clone is of the crossed genome: clone the parent
        out.genome = parent;
        out.phenotype = parent_phenotype;
    }
    return out;
}

}  // namespace bhm::evo
