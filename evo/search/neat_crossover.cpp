#include "evo/search/neat_crossover.hpp"

#include <algorithm>
#include <stdexcept>
#include <unordered_map>

#include "evo/genome/neat_genes.hpp"

namespace bhm::evo {

namespace {

//! Builds the child gene by gene in id space (node ids, innovation numbers) over positional nodes.
class ChildBuilder {
  public:
    ChildBuilder(int input_count, int output_count) {
        child_.input_count = input_count;
        child_.output_count = output_count;
    }

    //! Index of node `id` in the child, adding hidden node (id, function) when absent.
    int node(std::int64_t id, Activation function) {
        if (id < child_.first_hidden()) return static_cast<int>(id);
        if (const auto it = index_.find(id); it != index_.end()) return it->second;
        const int index = child_.node_count();
        child_.hidden.push_back(function);
        child_.hidden_ids.push_back(id);
        index_.emplace(id, index);
        return index;
    }
    bool has_node(std::int64_t id) const {
        return id < child_.first_hidden() || index_.count(id) > 0;
    }
    bool keeps_acyclic(int from, int to) const {
        return !has_edge(child_, from, to) && edge_keeps_acyclic(child_, from, to);
    }
    //! Adds the gene from -> to when that keeps the child a well-formed acyclic genome.
    void edge(int from, int to, double weight, std::int64_t innovation) {
        if (has_edge(child_, from, to) || !edge_keeps_acyclic(child_, from, to)) return;
        child_.edges.push_back({from, to, weight, innovation});
    }
    Genome take() { return std::move(child_); }

  private:
    Genome child_;
    std::unordered_map<std::int64_t, int> index_;
};

Activation function_of(const Genome& g, int node) {
    return g.is_hidden(node) ? g.hidden[static_cast<std::size_t>(node - g.first_hidden())]
                             : Activation::Sin;  // unused for inputs and outputs
}

}  // namespace

Genome neat_crossover(const Genome& primary, const Genome& mate, Fitter fitter, Rng& rng) {
    if (mate.output_count != primary.output_count || mate.input_count != primary.input_count)
        throw std::invalid_argument("crossover of genomes with different input or output counts");
    // The structure comes from the fitter parent ("base"); with equal fitness from the primary,
    // plus the mate's unmatched genes with probability 1/2.
    const bool mate_fitter = fitter == Fitter::Mate;
    const Genome& base = mate_fitter ? mate : primary;
    const Genome& other = mate_fitter ? primary : mate;
    const auto al = mate_fitter ? align_genes(mate, primary) : align_genes(primary, mate);

    ChildBuilder child(primary.input_count, primary.output_count);
    // Every node of the base parent, in its order; matching node genes take either function.
    std::unordered_map<std::int64_t, int> other_index;
    for (int h = 0; h < other.hidden_count(); ++h)
        other_index.emplace(other.hidden_ids[static_cast<std::size_t>(h)],
                            other.first_hidden() + h);
    for (int h = 0; h < base.hidden_count(); ++h) {
        const std::int64_t id = base.hidden_ids[static_cast<std::size_t>(h)];
        Activation f = base.hidden[static_cast<std::size_t>(h)];
        if (const auto it = other_index.find(id); it != other_index.end())
            if (rng.uniform() < 0.5) f = function_of(other, it->second);
        child.node(id, f);
    }
    // Genes in the base parent's order: matching ones with either weight, its unmatched ones
    // always (fitter) or with probability 1/2 (equal fitness).
    std::unordered_map<std::size_t, std::size_t> match_of;
    for (const auto& [x, y] : al.matching)
        match_of.emplace(x, y);
    const bool equal = fitter == Fitter::Equal;
    auto node_in_child = [&](const Genome& g, int node) {
        return child.node(g.node_id(node), function_of(g, node));
    };
    for (std::size_t i = 0; i < base.edges.size(); ++i) {
        const CppnEdge& e = base.edges[i];
        double weight = e.weight;
        if (const auto it = match_of.find(i); it != match_of.end()) {
            if (rng.uniform() < 0.5) weight = other.edges[it->second].weight;
        } else if (equal && rng.uniform() >= 0.5) {
            continue;
        }
        child.edge(node_in_child(base, e.from), node_in_child(base, e.to), weight, e.innovation);
    }
    if (equal) {
        std::vector<std::size_t> unmatched = al.disjoint_b;
        unmatched.insert(unmatched.end(), al.excess_b.begin(), al.excess_b.end());
        std::sort(unmatched.begin(), unmatched.end());  // the mate's own gene order
        for (const std::size_t i : unmatched) {
            if (rng.uniform() >= 0.5) continue;
            const CppnEdge& e = other.edges[i];
            // An edge touching a node new to the child cannot close a cycle; between two nodes
            // the child has, it is checked first so that no node is brought over for nothing.
            if (child.has_node(other.node_id(e.from)) && child.has_node(other.node_id(e.to)) &&
                !child.keeps_acyclic(node_in_child(other, e.from), node_in_child(other, e.to)))
                continue;
            child.edge(node_in_child(other, e.from), node_in_child(other, e.to), e.weight,
                       e.innovation);
        }
    }
    return child.take();
}

}  // namespace bhm::evo
