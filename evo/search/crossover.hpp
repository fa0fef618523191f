#pragma once
// Crossover for AFPO (paper section 3: "future versions will test the crossover contribution";
// evolution.crossover_rate, default 0 = the paper's mutation-only AFPO).
//
// AFPO genomes descend from unrelated random newcomers and carry no innovation numbers, so genes
// are aligned by position, the one correspondence two CPPNs of this layout share: inputs and
// outputs are the same nodes in both, hidden node k of one is matched with hidden node k of the
// other. The child has the primary parent's hidden node count; each matched hidden node takes its
// function from either parent with probability 1/2. Edges: an edge present in both parents (same
// from, same to) is kept with the weight of either parent (1/2 each); an edge of one parent only is
// kept with probability 1/2, the primary parent's first, then the mate's (whose endpoints must
// exist in the child). Every edge is added only if it keeps the graph acyclic, so the child is a
// well-formed genome by construction.
#include "evo/genome/genome.hpp"
#include "evo/genome/rng.hpp"
#include "evo/search/mutation.hpp"

namespace bhm::evo {

//! The child of primary and mate (both well-formed, same output count). Deterministic given rng.
Genome crossover(const Genome& primary, const Genome& mate, Rng& rng);

//! AFPO's child with crossover: the crossover of parent and mate, kept when its phenotype is new
//! and valid; otherwise mutate_until_new from that crossed genome (new = differs from the
//! parent's phenotype); when that also fails, a clone of the parent (cloned = true).
MutationOutcome cross_then_mutate(const Genome& parent, const Genome& mate,
                                  const Phenotype& parent_phenotype, const Developer& developer,
                                  const Constraints& constraints, const CppnSettings& settings,
                                  int max_retries, Rng& rng);

}  // namespace bhm::evo
