#pragma once
// The six mutation operators of paper section 3 (add, modify or remove a node; add, modify or
// remove an edge), each drawn with probability 1/6, and the neutral-mutation retry: a child whose
// phenotype equals its parent's, or breaks a constraint, is redrawn from the parent.
#include <array>
#include <functional>

#include "evo/experiment/experiment.hpp"
#include "evo/genome/genome.hpp"
#include "evo/genome/phenotype.hpp"
#include "evo/genome/rng.hpp"

namespace bhm::evo {

enum class MutationKind { AddNode, ModifyNode, RemoveNode, AddEdge, ModifyEdge, RemoveEdge };
inline constexpr int kMutationKindCount = 6;
inline constexpr std::array<const char*, kMutationKindCount> kMutationNames = {
    "add_node", "modify_node", "remove_node", "add_edge", "modify_edge", "remove_edge"};

//! Applies one operator in place. Returns false, leaving the genome unchanged, when the operator
//! has nothing to act on (no edge to split or change, no hidden node, no edge that can be added).
//!  - AddNode splits a random edge u->v (weight w) into u->h (weight 1, clipped to the range) and
//!    h->v (weight w), h a new hidden node with a random function (NEAT's split, so the new path
//!    starts close to the old one);
//!  - ModifyNode gives a random hidden node a different function;
//!  - RemoveNode deletes a random hidden node and its edges;
//!  - AddEdge picks uniformly among all absent edges that keep the graph acyclic, weight uniform;
//!  - ModifyEdge adds sigma * N(0, 1) to a random edge's weight, clipped to [-range, range];
//!  - RemoveEdge deletes a random edge.
bool apply_mutation(Genome& genome, MutationKind kind, const CppnSettings& settings, Rng& rng);

//! Draws one of the six kinds uniformly.
MutationKind random_mutation_kind(Rng& rng);

struct MutationOutcome {
    Genome genome;
    Phenotype phenotype;
    int attempts = 0;     //!< mutations tried, this one included
    bool cloned = false;  //!< no new valid phenotype within max_retries: the child is the parent
};

//! Mutates a copy of the parent until the phenotype differs from the parent's and satisfies the
//! constraints, at most max_retries times (paper: 1500); after that the child is a clone.
MutationOutcome mutate_until_new(const Genome& parent, const Phenotype& parent_phenotype,
                                 const Developer& developer, const Constraints& constraints,
                                 const CppnSettings& settings, int max_retries, Rng& rng);

//! The same retry loop with another set of operators (NEAT's numbered genes): `mutate` applies
//! the drawn kind in place and returns false when it had nothing to act on.
MutationOutcome mutate_until_new(const Genome& parent, const Phenotype& parent_phenotype,
                                 const Developer& developer, const Constraints& constraints,
                                 int max_retries, Rng& rng,
                                 const std::function<bool(Genome&, MutationKind)>& mutate);

}  // namespace bhm::evo
