#include "evo/search/novelty.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace bhm::evo {

double behaviour_distance(const BehaviourDescriptor& a, const BehaviourDescriptor& b) {
    if (a.size() != b.size())
        throw std::invalid_argument("behaviour descriptors of different lengths");
    double sum = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i)
        sum += (a[i] - b[i]) * (a[i] - b[i]);
    return std::sqrt(sum);
}

std::vector<double> novelty_scores(const std::vector<const BehaviourDescriptor*>& pool,
                                   const std::deque<BehaviourDescriptor>& archive, int k) {
    std::vector<double> novelty(pool.size(), kNoNovelty);
    std::vector<double> distances;
    distances.reserve(pool.size() + archive.size());
    for (std::size_t i = 0; i < pool.size(); ++i) {
        if (!pool[i]) continue;
        distances.clear();
        for (std::size_t j = 0; j < pool.size(); ++j)
            if (j != i && pool[j]) distances.push_back(behaviour_distance(*pool[i], *pool[j]));
        for (const auto& a : archive)
            distances.push_back(behaviour_distance(*pool[i], a));
        const auto nearest = std::min(distances.size(), static_cast<std::size_t>(std::max(k, 1)));
        if (nearest == 0) {
            novelty[i] = 0.0;
            continue;
        }
        std::partial_sort(distances.begin(), distances.begin() + static_cast<long>(nearest),
                          distances.end());
        // Summed smallest first: the same order whatever the pool order, so ties stay bit-equal.
        novelty[i] = std::accumulate(distances.begin(),
                                     distances.begin() + static_cast<long>(nearest), 0.0) /
                     static_cast<double>(nearest);
    }
    return novelty;
}

}  // namespace bhm::evo
