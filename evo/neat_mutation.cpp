#include "evo/neat_mutation.hpp"

#include <algorithm>
#include <utility>
#include <vector>

#include "evo/constraints.hpp"

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

bool modify_node(Genome& g, Rng& rng) {
    if (g.hidden.empty()) return false;
    auto& f = g.hidden[static_cast<std::size_t>(rng.index(g.hidden_count()))];
    f = static_cast<Activation>((static_cast<int>(f) + 1 + rng.index(kActivationCount - 1)) %
                                kActivationCount);
    return true;
}

bool remove_node(Genome& g, Rng& rng) {
    if (g.hidden.empty()) return false;
    const int h = rng.index(g.hidden_count());
    const int node = g.first_hidden() + h;
    g.hidden.erase(g.hidden.begin() + h);
    g.hidden_ids.erase(g.hidden_ids.begin() + h);
    std::vector<CppnEdge> kept;
    kept.reserve(g.edges.size());
    for (auto e : g.edges) {
        if (e.from == node || e.to == node) continue;
        if (e.from > node) --e.from;  // later hidden nodes shift down by one
        if (e.to > node) --e.to;
        kept.push_back(e);
    }
    g.edges = std::move(kept);
    return true;
}

bool add_edge(Genome& g, const CppnSettings& s, Rng& rng, InnovationTable& table) {
    const int n = g.node_count();
    std::vector<std::pair<int, int>> candidates;
    for (int to = kInputCount; to < n; ++to)
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

bool modify_edge(Genome& g, const CppnSettings& s, Rng& rng) {
    if (g.edges.empty()) return false;
    auto& e = g.edges[static_cast<std::size_t>(rng.index(static_cast<int>(g.edges.size())))];
    e.weight = std::clamp(e.weight + s.mutation_weight_sigma * rng.normal(), -s.weight_range,
                          s.weight_range);
    return true;
}

bool remove_edge(Genome& g, Rng& rng) {
    if (g.edges.empty()) return false;
    g.edges.erase(g.edges.begin() + rng.index(static_cast<int>(g.edges.size())));
    return true;
}

}  // namespace

Genome neat_minimal_genome(int output_count, const CppnSettings& settings, Rng& rng,
                           InnovationTable& table) {
    Genome g;
    g.output_count = output_count;
    for (int out = kInputCount; out < g.first_hidden(); ++out)
        for (int in = 0; in < kInputCount; ++in)
            g.edges.push_back({in, out, rng.uniform(-settings.weight_range, settings.weight_range),
                               table.connection(in, out)});
    return g;
}

bool apply_neat_mutation(Genome& genome, MutationKind kind, const CppnSettings& settings, Rng& rng,
                         InnovationTable& table) {
    switch (kind) {
        case MutationKind::AddNode:
            return add_node(genome, settings, rng, table);
        case MutationKind::ModifyNode:
            return modify_node(genome, rng);
        case MutationKind::RemoveNode:
            return remove_node(genome, rng);
        case MutationKind::AddEdge:
            return add_edge(genome, settings, rng, table);
        case MutationKind::ModifyEdge:
            return modify_edge(genome, settings, rng);
        case MutationKind::RemoveEdge:
            return remove_edge(genome, rng);
    }
    return false;
}

MutationOutcome neat_mutate_until_new(const Genome& base, const Phenotype& reference,
                                      const Developer& developer, const Constraints& constraints,
                                      const CppnSettings& settings, int max_retries, Rng& rng,
                                      InnovationTable& table) {
    MutationOutcome out;
    for (int attempt = 1; attempt <= max_retries; ++attempt) {
        Genome child = base;
        if (!apply_neat_mutation(child, random_mutation_kind(rng), settings, rng, table)) continue;
        Phenotype phenotype = developer.develop(child);
        if (phenotype == reference) continue;
        if (!constraint_violation(constraints, developer.experiment().boundary, developer.space(),
                                  phenotype)
                 .empty())
            continue;
        out.genome = std::move(child);
        out.phenotype = std::move(phenotype);
        out.attempts = attempt;
        return out;
    }
    out.genome = base;
    out.phenotype = reference;
    out.attempts = max_retries;
    out.cloned = true;
    return out;
}

}  // namespace bhm::evo
