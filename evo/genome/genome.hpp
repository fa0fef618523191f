#pragma once
// The genotype: a CPPN (Stanley 2007) as paper Table 2 specifies it. Five input nodes (x, y, z,
// d = distance from the centre, bias 1), two output nodes (material present, active or passive;
// with evolution.cppn.material_outputs = "per_material": presence then one output per material),
// hidden nodes each applying one of seven functions, weighted edges in [-1, 1]. The graph is any
// acyclic graph (not layered): node values are computed in topological order, each value used by
// every consumer.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "evo/experiment/experiment.hpp"
#include "evo/genome/rng.hpp"

namespace bhm::evo {

//! Hidden-node functions of paper Table 2.
enum class Activation : std::uint8_t { Sin, Abs, NegAbs, Square, NegSquare, SqrtAbs, NegSqrtAbs };
inline constexpr int kActivationCount = 7;
inline constexpr std::array<const char*, kActivationCount> kActivationNames = {
    "sin", "abs", "neg_abs", "square", "neg_square", "sqrt_abs", "neg_sqrt_abs"};

double activate(Activation function, double x);

//! Node layout: inputs first, then outputs, then hidden nodes. Inputs take no edges in and
//! outputs send no edges out, so the graph's sources and sinks are fixed. The constants below are
//! the paper's two-output layout; a per-material genome has 1 + materials outputs (output 0 =
//! presence at node kInputCount, output 1 + k = material k + 1) and its hidden nodes start later.
enum InputNode : int { kInputX = 0, kInputY, kInputZ, kInputD, kInputBias };
enum OutputNode : int { kOutputMaterial = 5, kOutputActive = 6 };
inline constexpr int kInputCount = 5;
inline constexpr int kOutputCount = 2;
inline constexpr int kFirstHidden = kInputCount + kOutputCount;
//! HyperNEAT's CPPN (evolution.algorithm = "hyperneat", evo/genome/hyperneat_substrate.hpp) is
//! queried with a pair of substrate nodes: xa, ya, za, xb, yb, zb, d = |b - a|, bias.
inline constexpr int kHyperNeatInputCount = 8;

struct CppnEdge {
    int from = 0;  //!< node index (an input or a hidden node)
    int to = 0;    //!< node index (a hidden or an output node)
    double weight = 0.0;
    //! NEAT's historical marking of this connection gene (evo/genome/neat_innovation.hpp); -1 in
    //! genomes that carry no history (AFPO's, novelty's).
    std::int64_t innovation = -1;
    bool operator==(const CppnEdge&) const = default;
};

struct Genome {
    //! Function of each hidden node; hidden node h is node first_hidden() + h.
    std::vector<Activation> hidden;
    std::vector<CppnEdge> edges;
    //! 2 (the paper's) or 1 + materials (per_material), plus 3 with fibre_outputs
    int output_count = kOutputCount;
    //! 5 (x, y, z, d, bias: a CPPN painting the lattice directly) or kHyperNeatInputCount (a
    //! HyperNEAT CPPN painting a substrate's connections); the inputs are nodes 0 .. input_count-1.
    int input_count = kInputCount;
    //! NEAT only: the run-wide id of each hidden node (hidden_ids[h] for node first_hidden() + h),
    //! so genes of two genomes can be aligned; inputs and outputs are their own ids. Empty in
    //! genomes without history.
    std::vector<std::int64_t> hidden_ids;

    int first_hidden() const { return input_count + output_count; }
    int node_count() const { return first_hidden() + static_cast<int>(hidden.size()); }
    int hidden_count() const { return static_cast<int>(hidden.size()); }
    bool is_input(int node) const { return node < input_count; }
    bool is_output(int node) const { return node >= input_count && node < first_hidden(); }
    bool is_hidden(int node) const { return node >= first_hidden(); }
    //! True for a NEAT genome: hidden node ids or innovation numbers present.
    bool has_history() const {
        if (!hidden_ids.empty()) return true;
        for (const auto& e : edges)
            if (e.innovation >= 0) return true;
        return false;
    }
    //! The run-wide id of node index `node` (NEAT); the index itself without history.
    std::int64_t node_id(int node) const {
        return is_hidden(node) && !hidden_ids.empty()
                   ? hidden_ids[static_cast<std::size_t>(node - first_hidden())]
                   : node;
    }
    bool operator==(const Genome&) const = default;
};

//! Empty when the genome is well formed: node indices in range, no edge into an input or out of an
//! output, no self loop or duplicate edge, weights finite and within +-weight_range, acyclic; with
//! NEAT history: one id per hidden node, unique and above the outputs, and every edge with a
//! unique innovation number.
std::string genome_problem(const Genome& genome, double weight_range);

//! True when adding from -> to keeps the graph acyclic (to does not already reach from).
bool edge_keeps_acyclic(const Genome& genome, int from, int to);
bool has_edge(const Genome& genome, int from, int to);

//! Nodes in an order where every edge goes forward (Kahn's algorithm, smallest index first, so
//! the order is deterministic). Throws std::invalid_argument if the graph has a cycle.
std::vector<int> topological_order(const Genome& genome);

//! A new random genome (paper Table 2): hidden node count uniform in [min, max]; each hidden node
//! takes two edges from inputs or earlier hidden nodes; each output takes edges from up to three
//! hidden nodes; every hidden node left without a consumer feeds a random output. Acyclic by
//! construction (edges only go from earlier to later nodes). output_count, input_count as Genome's.
Genome random_genome(const CppnSettings& settings, Rng& rng, int output_count = kOutputCount,
                     int input_count = kInputCount);

//! fibre_outputs: how many of the last outputs are the fibre axis ones (3 under
//! evolution.cppn.fibre_outputs, else 0): "outputs" then names them fibre_x, fibre_y, fibre_z
//! (names are for the reader; genome_from_json takes only their count).
nlohmann::json genome_to_json(const Genome& genome, int fibre_outputs = 0);
//! Throws std::invalid_argument naming the field when the JSON is not a well-formed genome.
Genome genome_from_json(const nlohmann::json& json, double weight_range);

}  // namespace bhm::evo
