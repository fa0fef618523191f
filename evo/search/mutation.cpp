#include "evo/search/mutation.hpp"

#include <algorithm>
#include <utility>
#include <vector>

#include "evo/evaluate/constraints.hpp"

namespace bhm::evo {

namespace {

Activation random_function(Rng& rng) {
    return static_cast<Activation>(rng.index(kActivationCount));
}

bool add_node(Genome& g, const CppnSettings& s, Rng& rng) {
    if (g.edges.empty()) return false;
    const auto e = static_cast<std::size_t>(rng.index(static_cast<int>(g.edges.size())));
    const CppnEdge split = g.edges[e];
    g.edges.erase(g.edges.begin() + static_cast<std::ptrdiff_t>(e));
    const int h = g.node_count();
    g.hidden.push_back(random_function(rng));
    g.edges.push_back({split.from, h, std::min(1.0, s.weight_range)});
    g.edges.push_back({h, split.to, split.weight});
    return true;
}

bool modify_node(Genome& g, Rng& rng) {
    if (g.hidden.empty()) return false;
    auto& f = g.hidden[static_cast<std::size_t>(rng.index(g.hidden_count()))];
    // Any of the six other functions, uniformly.
    f = static_cast<Activation>((static_cast<int>(f) + 1 + rng.index(kActivationCount - 1)) %
                                kActivationCount);
    return true;
}

bool remove_node(Genome& g, Rng& rng) {
    if (g.hidden.empty()) return false;
    const int h = rng.index(g.hidden_count());
    const int node = g.first_hidden() + h;
    g.hidden.erase(g.hidden.begin() + h);
    if (!g.hidden_ids.empty()) g.hidden_ids.erase(g.hidden_ids.begin() + h);  // NEAT genomes
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

bool add_edge(Genome& g, const CppnSettings& s, Rng& rng) {
    const int n = g.node_count();
    std::vector<std::vector<int>> next(static_cast<std::size_t>(n));
    for (const auto& e : g.edges)
        next[static_cast<std::size_t>(e.from)].push_back(e.to);
    std::vector<std::pair<int, int>> candidates;
    std::vector<char> reachable(static_cast<std::size_t>(n));
    std::vector<int> stack;
    for (int to = g.input_count; to < n; ++to) {
        // Nodes reachable from `to`: an edge from any of them into `to` would close a cycle.
        std::fill(reachable.begin(), reachable.end(), 0);
        reachable[static_cast<std::size_t>(to)] = 1;
        stack.assign(1, to);
        while (!stack.empty()) {
            const int v = stack.back();
            stack.pop_back();
            for (int w : next[static_cast<std::size_t>(v)])
                if (!reachable[static_cast<std::size_t>(w)]) {
                    reachable[static_cast<std::size_t>(w)] = 1;
                    stack.push_back(w);
                }
        }
        for (int from = 0; from < n; ++from) {
            if (g.is_output(from) || reachable[static_cast<std::size_t>(from)]) continue;
            if (has_edge(g, from, to)) continue;
            candidates.emplace_back(from, to);
        }
    }
    if (candidates.empty()) return false;
    const auto [from, to] =
        candidates[static_cast<std::size_t>(rng.index(static_cast<int>(candidates.size())))];
    g.edges.push_back({from, to, rng.uniform(-s.weight_range, s.weight_range)});
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

bool apply_mutation(Genome& genome, MutationKind kind, const CppnSettings& settings, Rng& rng) {
    switch (kind) {
        case MutationKind::AddNode:
            return add_node(genome, settings, rng);
        case MutationKind::ModifyNode:
            return modify_node(genome, rng);
        case MutationKind::RemoveNode:
            return remove_node(genome, rng);
        case MutationKind::AddEdge:
            return add_edge(genome, settings, rng);
        case MutationKind::ModifyEdge:
            return modify_edge(genome, settings, rng);
        case MutationKind::RemoveEdge:
            return remove_edge(genome, rng);
    }
    return false;
}

MutationKind random_mutation_kind(Rng& rng) {
    return static_cast<MutationKind>(rng.index(kMutationKindCount));
}

MutationOutcome mutate_until_new(const Genome& parent, const Phenotype& parent_phenotype,
                                 const Developer& developer, const Constraints& constraints,
                                 const CppnSettings& settings, int max_retries, Rng& rng) {
    return mutate_until_new(parent, parent_phenotype, developer, constraints, max_retries, rng,
                            [&](Genome& child, MutationKind kind) {
                                return apply_mutation(child, kind, settings, rng);
                            });
}

MutationOutcome mutate_until_new(const Genome& parent, const Phenotype& parent_phenotype,
                                 const Developer& developer, const Constraints& constraints,
                                 int max_retries, Rng& rng,
                                 const std::function<bool(Genome&, MutationKind)>& mutate) {
    MutationOutcome out;
    for (int attempt = 1; attempt <= max_retries; ++attempt) {
        Genome child = parent;
        if (!mutate(child, random_mutation_kind(rng))) continue;
        Phenotype phenotype = developer.develop(child);
        if (phenotype == parent_phenotype) continue;
        if (!constraint_violation(constraints, developer.experiment().boundary, developer.space(),
                                  phenotype)
                 .empty())
            continue;
        out.genome = std::move(child);
        out.phenotype = std::move(phenotype);
        out.attempts = attempt;
        return out;
    }
    out.genome = parent;
    out.phenotype = parent_phenotype;
    out.attempts = max_retries;
    out.cloned = true;
    return out;
}

}  // namespace bhm::evo
