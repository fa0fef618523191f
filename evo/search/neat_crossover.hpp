#pragma once
// NEAT crossover (Stanley & Miikkulainen 2002, section 3.2, Fig. 4): genes are aligned by
// innovation number. Matching genes take their weight from either parent (1/2 each); disjoint and
// excess genes come from the fitter parent. When both are equally fit, disjoint and excess genes
// of both are each kept with probability 1/2 (the paper's rule), the primary parent's first, and
// one is added only if the graph stays acyclic and its nodes can be brought over (a hidden node of
// the other parent joins the child with its id and function). Node genes (hidden nodes, aligned by
// id) present in both take the function of either parent (1/2 each). The child is well formed
// (evo/genome/genome.hpp genome_problem) by construction.
#include "evo/genome/genome.hpp"
#include "evo/genome/rng.hpp"

namespace bhm::evo {

//! The child of primary and mate (both with history, same output count). primary_fitter: the
//! primary is strictly fitter; equal_fitness: neither is (then genes of both may be inherited).
//! With neither flag the mate is the fitter one.
enum class Fitter { Primary, Mate, Equal };
Genome neat_crossover(const Genome& primary, const Genome& mate, Fitter fitter, Rng& rng);

}  // namespace bhm::evo
