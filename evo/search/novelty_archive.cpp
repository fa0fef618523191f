#include "evo/search/novelty_archive.hpp"

#include <stdexcept>

namespace bhm::evo {

int update_archive(NoveltyArchive& archive,
                   const std::vector<const BehaviourDescriptor*>& candidates,
                   const std::vector<double>& novelty, int capacity) {
    if (candidates.size() != novelty.size())
        throw std::invalid_argument("update_archive: one novelty per candidate expected");
    int added = 0;
    for (std::size_t i = 0; i < candidates.size(); ++i) {
        if (!candidates[i] || !(novelty[i] > archive.threshold)) continue;
        archive.entries.push_back(*candidates[i]);
        ++added;
    }
    if (added > kArchiveBusyAdditions) archive.threshold *= kThresholdRaise;
    if (added == 0) archive.threshold *= kThresholdLower;
    while (archive.entries.size() > static_cast<std::size_t>(capacity < 0 ? 0 : capacity))
        archive.entries.pop_front();
    return added;
}

}  // namespace bhm::evo
