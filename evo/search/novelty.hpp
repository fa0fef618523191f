#pragma once
// Novelty (Lehman & Stanley 2011, "Abandoning objectives"): how far a behaviour lies from the
// behaviours already seen. The novelty of a pool member is the mean Euclidean distance between its
// behaviour descriptor (evo/evaluate/behaviour.hpp, voxel lengths) and its k nearest neighbours among the
// other pool members' descriptors and the archive's (evo/search/novelty_archive.hpp):
//     novelty(i) = (1 / k') sum_{j in kNN(i)} |b_i - b_j|,   k' = min(k, neighbours available).
// Members without a descriptor (diverged, rejected by a constraint, or from before descriptors)
// score kNoNovelty and are nobody's neighbour; a member with no neighbour at all scores 0.
// Twins (a clone and its parent) are neighbours at distance 0, as in the paper's population.
#include <deque>
#include <vector>

namespace bhm::evo {

using BehaviourDescriptor = std::vector<double>;

//! Below every real novelty (which is >= 0), so selection drops such members first.
inline constexpr double kNoNovelty = -1.0;

double behaviour_distance(const BehaviourDescriptor& a, const BehaviourDescriptor& b);

//! Novelty of each pool entry (null = no descriptor) against the others and the archive.
std::vector<double> novelty_scores(const std::vector<const BehaviourDescriptor*>& pool,
                                   const std::deque<BehaviourDescriptor>& archive, int k);

}  // namespace bhm::evo
