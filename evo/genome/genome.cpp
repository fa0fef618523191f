#include "evo/genome/genome.hpp"

#include <algorithm>
#include <cmath>
#include <queue>
#include <stdexcept>

namespace bhm::evo {

double activate(Activation function, double x) {
    switch (function) {
        case Activation::Sin:
            return std::sin(x);
        case Activation::Abs:
            return std::fabs(x);
        case Activation::NegAbs:
            return -std::fabs(x);
        case Activation::Square:
            return x * x;
        case Activation::NegSquare:
            return -x * x;
        case Activation::SqrtAbs:
            return std::sqrt(std::fabs(x));
        case Activation::NegSqrtAbs:
            return -std::sqrt(std::fabs(x));
    }
    return 0.0;
}

bool has_edge(const Genome& genome, int from, int to) {
    return std::any_of(genome.edges.begin(), genome.edges.end(),
                       [&](const CppnEdge& e) { return e.from == from && e.to == to; });
}

namespace {

//! Successor lists per node.
std::vector<std::vector<int>> successors(const Genome& genome) {
    std::vector<std::vector<int>> out(static_cast<std::size_t>(genome.node_count()));
    for (const auto& e : genome.edges)
        out[static_cast<std::size_t>(e.from)].push_back(e.to);
    return out;
}

}  // namespace

bool edge_keeps_acyclic(const Genome& genome, int from, int to) {
    if (from == to) return false;
    // A cycle appears exactly when `from` is reachable from `to`.
    const auto next = successors(genome);
    std::vector<char> seen(next.size(), 0);
    std::vector<int> stack{to};
    seen[static_cast<std::size_t>(to)] = 1;
    while (!stack.empty()) {
        const int node = stack.back();
        stack.pop_back();
        if (node == from) return false;
        for (int n : next[static_cast<std::size_t>(node)]) {
            if (!seen[static_cast<std::size_t>(n)]) {
                seen[static_cast<std::size_t>(n)] = 1;
                stack.push_back(n);
            }
        }
    }
    return true;
}

std::vector<int> topological_order(const Genome& genome) {
    const int n = genome.node_count();
    std::vector<int> in_degree(static_cast<std::size_t>(n), 0);
    for (const auto& e : genome.edges)
        ++in_degree[static_cast<std::size_t>(e.to)];
    const auto next = successors(genome);
    std::priority_queue<int, std::vector<int>, std::greater<>> ready;
    for (int i = 0; i < n; ++i)
        if (in_degree[static_cast<std::size_t>(i)] == 0) ready.push(i);
    std::vector<int> order;
    order.reserve(static_cast<std::size_t>(n));
    while (!ready.empty()) {
        const int node = ready.top();
        ready.pop();
        order.push_back(node);
        for (int m : next[static_cast<std::size_t>(node)])
            if (--in_degree[static_cast<std::size_t>(m)] == 0) ready.push(m);
    }
    if (static_cast<int>(order.size()) != n) throw std::invalid_argument("CPPN genome has a cycle");
    return order;
}

std::string genome_problem(const Genome& genome, double weight_range) {
    const int n = genome.node_count();
    for (std::size_t i = 0; i < genome.edges.size(); ++i) {
        const auto& e = genome.edges[i];
        const std::string where = "edges[" + std::to_string(i) + "]: ";
        if (e.from < 0 || e.from >= n || e.to < 0 || e.to >= n)
            return where + "node index out of range";
        if (genome.is_output(e.from)) return where + "edge leaves an output node";
        if (genome.is_input(e.to)) return where + "edge enters an input node";
        if (e.from == e.to) return where + "self loop";
        if (!std::isfinite(e.weight) || std::fabs(e.weight) > weight_range)
            return where + "weight outside [-range, range]";
        for (std::size_t j = 0; j < i; ++j)
            if (genome.edges[j].from == e.from && genome.edges[j].to == e.to)
                return where + "duplicate edge";
    }
    for (std::size_t h = 0; h < genome.hidden.size(); ++h)
        if (static_cast<int>(genome.hidden[h]) >= kActivationCount)
            return "hidden[" + std::to_string(h) + "]: unknown function";
    if (genome.has_history()) {
        if (genome.hidden_ids.size() != genome.hidden.size())
            return "hidden_ids: one id per hidden node expected";
        for (std::size_t h = 0; h < genome.hidden_ids.size(); ++h) {
            if (genome.hidden_ids[h] < genome.first_hidden())
                return "hidden_ids[" + std::to_string(h) +
                       "]: ids of hidden nodes follow the outputs";
            for (std::size_t k = 0; k < h; ++k)
                if (genome.hidden_ids[k] == genome.hidden_ids[h])
                    return "hidden_ids[" + std::to_string(h) + "]: duplicate id";
        }
        for (std::size_t i = 0; i < genome.edges.size(); ++i) {
            const std::string where = "edges[" + std::to_string(i) + "]: ";
            if (genome.edges[i].innovation < 0) return where + "innovation number missing";
            for (std::size_t j = 0; j < i; ++j)
                if (genome.edges[j].innovation == genome.edges[i].innovation)
                    return where + "duplicate innovation number";
        }
    }
    try {
        topological_order(genome);
    } catch (const std::invalid_argument&) {
        return "edges: the graph has a cycle";
    }
    return {};
}

Genome random_genome(const CppnSettings& settings, Rng& rng, int output_count, int input_count) {
    Genome genome;
    genome.output_count = output_count;
    genome.input_count = input_count;
    const int inputs = input_count;
    const int first_hidden = genome.first_hidden();
    const int hidden = rng.uniform_int(
        settings.min_hidden_nodes, std::max(settings.min_hidden_nodes, settings.max_hidden_nodes));
    auto random_weight = [&] { return rng.uniform(-settings.weight_range, settings.weight_range); };
    auto random_function = [&] { return static_cast<Activation>(rng.index(kActivationCount)); };
    auto add_edge = [&](int from, int to) {
        if (!has_edge(genome, from, to)) genome.edges.push_back({from, to, random_weight()});
    };

    // Sources available to hidden node h: the inputs and the hidden nodes created before it.
    for (int h = 0; h < hidden; ++h) {
        genome.hidden.push_back(random_function());
        const int node = first_hidden + h;
        const int source_count = inputs + h;
        for (int k = 0; k < 2; ++k) {
            const int pick = rng.index(source_count);
            add_edge(pick < inputs ? pick : first_hidden + (pick - inputs), node);
        }
    }
    for (int output = inputs; output < first_hidden; ++output) {
        if (hidden == 0) {
            for (int i = 0; i < inputs; ++i)
                add_edge(i, output);
            continue;
        }
        const int count = std::min(3, hidden);
        for (int k = 0; k < count; ++k)
            add_edge(first_hidden + rng.index(hidden), output);
    }
    // A hidden node nobody reads is dead weight; give it a consumer so every node matters.
    for (int h = 0; h < hidden; ++h) {
        const int node = first_hidden + h;
        const bool consumed = std::any_of(genome.edges.begin(), genome.edges.end(),
                                          [&](const CppnEdge& e) { return e.from == node; });
        if (!consumed) add_edge(node, inputs + rng.index(output_count));
    }
    return genome;
}

nlohmann::json genome_to_json(const Genome& genome, int fibre_outputs) {
    nlohmann::json hidden = nlohmann::json::array();
    for (auto f : genome.hidden)
        hidden.push_back(kActivationNames[static_cast<std::size_t>(f)]);
    nlohmann::json edges = nlohmann::json::array();
    for (const auto& e : genome.edges) {
        if (e.innovation >= 0)
            edges.push_back({e.from, e.to, e.weight, e.innovation});
        else
            edges.push_back({e.from, e.to, e.weight});
    }
    const int fibres =
        std::clamp(fibre_outputs, 0, std::max(0, genome.output_count - kOutputCount));
    const int material_outputs = genome.output_count - fibres;
    nlohmann::json outputs = {"material", "active"};
    if (material_outputs != kOutputCount) {
        outputs = {"material"};
        for (int k = 1; k < material_outputs; ++k)
            outputs.push_back("material_" + std::to_string(k));
    }
    for (int k = 0; k < fibres; ++k)
        outputs.push_back(std::string("fibre_") + "xyz"[k % 3]);
    if (genome.input_count ==
        kHyperNeatInputCount) {  // substrate weights (hyperneat_substrate.hpp)
        outputs = {"w_input_hidden", "w_hidden_hidden"};
        for (int k = 2; k < genome.output_count; ++k)
            outputs.push_back("w_hidden_output_" + std::to_string(k - 2));
    }
    const nlohmann::json inputs =
        genome.input_count == kHyperNeatInputCount
            ? nlohmann::json{"xa", "ya", "za", "xb", "yb", "zb", "d", "bias"}
            : nlohmann::json{"x", "y", "z", "d", "bias"};
    nlohmann::json out = {
        {"inputs", inputs}, {"outputs", outputs}, {"hidden", hidden}, {"edges", edges}};
    if (!genome.hidden_ids.empty()) out["hidden_ids"] = genome.hidden_ids;
    return out;
}

Genome genome_from_json(const nlohmann::json& json, double weight_range) {
    auto fail = [](const std::string& field, const std::string& message) {
        throw std::invalid_argument("genome" + (field.empty() ? "" : "." + field) + ": " + message);
    };
    if (!json.is_object()) fail("", "expected an object");
    Genome genome;
    if (json.contains("inputs")) {  // absent: the lattice CPPN's five
        if (!json["inputs"].is_array() ||
            (json["inputs"].size() != kInputCount && json["inputs"].size() != kHyperNeatInputCount))
            fail("inputs",
                 "expected an array of 5 (x, y, z, d, bias) or 8 (HyperNEAT's xa, ya, "
                 "za, xb, yb, zb, d, bias) input names");
        genome.input_count = static_cast<int>(json["inputs"].size());
    }
    if (json.contains("outputs")) {  // absent: the paper's two outputs
        if (!json["outputs"].is_array() || json["outputs"].size() < 2 ||
            json["outputs"].size() > 256)
            fail("outputs", "expected an array of 2 to 256 output names");
        genome.output_count = static_cast<int>(json["outputs"].size());
    }
    if (!json.contains("hidden") || !json["hidden"].is_array()) fail("hidden", "expected an array");
    for (std::size_t i = 0; i < json["hidden"].size(); ++i) {
        const auto& name = json["hidden"][i];
        const auto found = name.is_string()
                               ? std::find(kActivationNames.begin(), kActivationNames.end(),
                                           name.get<std::string>())
                               : kActivationNames.end();
        if (found == kActivationNames.end())
            fail("hidden[" + std::to_string(i) + "]", "unknown function " + name.dump());
        genome.hidden.push_back(static_cast<Activation>(found - kActivationNames.begin()));
    }
    if (!json.contains("edges") || !json["edges"].is_array()) fail("edges", "expected an array");
    for (std::size_t i = 0; i < json["edges"].size(); ++i) {
        const auto& e = json["edges"][i];
        // A fourth entry, the innovation number, in NEAT genomes.
        if (!e.is_array() || (e.size() != 3 && e.size() != 4) || !e[0].is_number_integer() ||
            !e[1].is_number_integer() || !e[2].is_number() ||
            (e.size() == 4 && !e[3].is_number_unsigned()))
            fail("edges[" + std::to_string(i) + "]", "expected [from, to, weight(, innovation)]");
        genome.edges.push_back({e[0].get<int>(), e[1].get<int>(), e[2].get<double>(),
                                e.size() == 4 ? e[3].get<std::int64_t>() : std::int64_t{-1}});
    }
    if (json.contains("hidden_ids")) {
        const auto& ids = json["hidden_ids"];
        if (!ids.is_array()) fail("hidden_ids", "expected an array of node ids");
        for (const auto& id : ids) {
            if (!id.is_number_unsigned()) fail("hidden_ids", "expected non-negative integers");
            genome.hidden_ids.push_back(id.get<std::int64_t>());
        }
    }
    if (auto problem = genome_problem(genome, weight_range); !problem.empty()) fail("", problem);
    return genome;
}

}  // namespace bhm::evo
