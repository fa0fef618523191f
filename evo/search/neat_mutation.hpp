#pragma once
// NEAT's mutations (Stanley & Miikkulainen 2002, section 3.1) on CPPN genomes that carry history:
// the six operators of paper section 3 (evo/search/mutation.hpp), each with probability 1/6, with
// the structural ones numbered through the run's InnovationTable:
//  - AddNode splits a random connection u->v (weight w) into u->h (weight 1, clipped to the range)
//    and h->v (weight w); h, both connections' innovation numbers and h's id come from the table,
//    so the same split this generation gives the same genes. The split connection is dropped
//    (this project's CPPN has no disabled genes: an edge is either in the graph or not);
//  - AddEdge: uniformly among absent connections that keep the graph acyclic, numbered by the
//    table from its end nodes' ids;
//  - ModifyNode, RemoveNode, ModifyEdge, RemoveEdge as in evo/search/mutation.hpp (no new genes).
#include "evo/genome/neat_innovation.hpp"
#include "evo/search/mutation.hpp"

namespace bhm::evo {

//! The minimal NEAT genome: every input connected to every output, weights uniform in the range,
//! innovation numbers from the table (so all minimal genomes of a generation align), no hidden
//! node. input_count: kInputCount, or kHyperNeatInputCount for HyperNEAT's CPPN.
Genome neat_minimal_genome(int output_count, const CppnSettings& settings, Rng& rng,
                           InnovationTable& table, int input_count = kInputCount);

//! Applies one operator in place (false, genome unchanged: nothing to act on).
bool apply_neat_mutation(Genome& genome, MutationKind kind, const CppnSettings& settings, Rng& rng,
                         InnovationTable& table);

//! As mutate_until_new (evo/search/mutation.hpp) with NEAT's operators: mutates a copy of `base`
//! until the phenotype differs from `reference` and satisfies the constraints, at most max_retries
//! times; cloned = true (genome = base) when none did.
MutationOutcome neat_mutate_until_new(const Genome& base, const Phenotype& reference,
                                      const Developer& developer, const Constraints& constraints,
                                      const CppnSettings& settings, int max_retries, Rng& rng,
                                      InnovationTable& table);

}  // namespace bhm::evo
