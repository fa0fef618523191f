#include "evo/search/neat_mutation.hpp"

#include <algorithm>
#include <utility>
#include <vector>

namespace bhm::evo {

namespace {

Activation random_function(Rng& rng) {
    return static_cast<Activation>(rng.index(kActivationCount));
}

bool add_node(Genome& g, const CppnSettings& s, Rng& rng, InnovationTable& table) {
    if (g.edges.empty()) return false;
    const auto e = static_cast<std::size_t>(rng.index(static_cast<int>(g.edges.size())));
    const CppnEdge split = g.edges[e];
    const auto made = table.split(split.innovation, g.node_id(split.from), g.node_id(split.to));
    // Only possible if this genome split the same connection this generation already: it no
    // longer holds that connection then, so this is a guard, never the normal path.
    if (std::find(g.hidden_ids.begin(), g.hidden_ids.end(), made.node_id) != g.hidden_ids.end())
        return false;
    g.edges.erase(g.edges.begin() + static_cast<std::ptrdiff_t>(e));
    const int h = g.node_count();
    g.hidden.push_back(random_function(rng));
    g.hidden_ids.push_back(made.node_id);
    g.edges.push_back({split.from, h, std::min(1.0, s.weight_range), made.in_innovation});
    g.edges.push_back({h, split.to, split.weight, made.out_innovation});
    return true;
}

bool add_edge(Genome& g, const CppnSettings& s, Rng& rng, InnovationTable& table) {
    const int n = g.node_count();
    std::vector<std::pair<int, int>> candidates;
    for (int to = g.input_count; to < n; ++to)
        for (int from = 0; from < n; ++from) {
            if (g.is_output(from) || from == to || has_edge(g, from, to)) continue;
            if (edge_keeps_acyclic(g, from, to)) candidates.emplace_back(from, to);
        }
    if (candidates.empty()) return false;
    const auto [from, to] =
        candidates[static_cast<std::size_t>(rng.index(static_cast<int>(candidates.size())))];
    g.edges.push_back({from, to, rng.uniform(-s.weight_range, s.weight_range),
                       table.connection(g.node_id(from), g.node_id(to))});
    return true;
}

}  // namespace

Genome neat_minimal_genome(int output_count, const CppnSettings& settings, Rng& rng,
                           InnovationTable& table, int input_count) {
    Genome g;
    g.output_count = output_count;
    g.input_count = input_count;
    for (int out = input_count; out < g.first_hidden(); ++out)
        for (int in = 0; in < input_count; ++in)
            g.edges.push_back({in, out, rng.uniform(-settings.weight_range, settings.weight_range),
                               table.connection(in, out)});
    return g;
}

bool apply_neat_mutation(Genome& genome, MutationKind kind, const CppnSettings& settings, Rng& rng,
                         InnovationTable& table) {
    switch (kind) {
        case MutationKind::AddNode:
            return add_node(genome, settings, rng, table);
        case MutationKind::AddEdge:
            return add_edge(genome, settings, rng, table);
        default:  // changing or removing genes needs no new innovation number: AFPO's operators
            return apply_mutation(genome, kind, settings, rng);
    }
}

MutationOutcome neat_mutate_until_new(const Genome& base, const Phenotype& reference,
                                      const Developer& developer, const Constraints& constraints,
                                      const CppnSettings& settings, int max_retries, Rng& rng,
                                      InnovationTable& table) {
    return mutate_until_new(base, reference, developer, constraints, max_retries, rng,
                            [&](Genome& child, MutationKind kind) {
                                return apply_neat_mutation(child, kind, settings, rng, table);
                            });
}

}  // namespace bhm::evo
