#pragma once
// The novelty archive (Lehman & Stanley 2011): behaviours worth remembering, so that search keeps
// moving away from where it has already been rather than only from the current population.
//
// Rule (our documented choice, after the paper's adaptive threshold): after each generation's
// novelty is computed (against the pool and the archive as it was), every *new* individual of that
// generation (in creation order) whose novelty is strictly above the threshold enters the archive.
// Then the threshold adapts: more than kArchiveBusyAdditions entries this generation multiply it
// by kThresholdRaise; none multiply it by kThresholdLower. Beyond archive_capacity the
// oldest entries leave (first in, first out; capacity 0 keeps no archive). The threshold starts at
// evolution.novelty.archive_threshold. Everything here is deterministic and lives in checkpoints,
// so a resumed run continues exactly.
#include <deque>
#include <vector>

#include "evo/search/novelty.hpp"

namespace bhm::evo {

inline constexpr int kArchiveBusyAdditions = 4;  //!< more than this a generation: raise
inline constexpr double kThresholdRaise = 1.2;
inline constexpr double kThresholdLower = 0.95;  //!< after a generation that added nothing

struct NoveltyArchive {
    std::deque<BehaviourDescriptor> entries;  //!< oldest first
    double threshold = 0.0;                   //!< novelty needed to enter (voxel lengths)
    bool operator==(const NoveltyArchive&) const = default;
};

//! Adds the candidates (null = no descriptor, never added) whose novelty is above the threshold,
//! adapts the threshold and trims to capacity. Returns how many entered.
int update_archive(NoveltyArchive& archive,
                   const std::vector<const BehaviourDescriptor*>& candidates,
                   const std::vector<double>& novelty, int capacity);

}  // namespace bhm::evo
